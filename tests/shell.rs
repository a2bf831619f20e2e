#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test or benchmark fails
//! Shell integration: completion scripts and man pages generated from the command line's own
//! definitions, naming every command and flag.

mod common;
use common::thud;

const COMMANDS: [&str; 11] =
    ["pulse", "simulate", "sweep", "restitution", "paper", "export", "presets", "tui", "limits", "completions", "man"];

#[test]
fn bash_completions_name_every_command_and_the_design_flags() {
    let (code, script, err) = thud(&["completions", "bash"]);
    assert_eq!(code, 0, "{err}");
    assert!(script.contains("complete -F _thud"), "not a bash completion script");
    for c in COMMANDS {
        assert!(script.contains(&format!("thud__subcmd__{c})")), "{c}");
    }
    for flag in ["--mass", "--gap", "--main-mass", "--k-hz", "--quad-signs", "--masses", "--no-limit", "--json"] {
        assert!(script.contains(flag), "{flag}");
    }
    // Value enums are completed too.
    assert!(script.contains("half-sine") && script.contains("quadrupole") && script.contains("newmark"));
}

#[test]
fn every_shell_gets_a_script_of_its_own() {
    for (shell, marker) in
        [("zsh", "#compdef thud"), ("fish", "complete -c thud"), ("powershell", "Register-ArgumentCompleter")]
    {
        let (code, script, err) = thud(&["completions", shell]);
        assert_eq!(code, 0, "{shell}: {err}");
        assert!(script.contains(marker), "{shell}");
        assert!(script.contains("simulate") && script.contains("main-mass"), "{shell}");
    }
    let (code, _, err) = thud(&["completions", "tcsh"]);
    assert_eq!(code, 2);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("tcsh") && err.contains("bash"), "{err}");
}

#[test]
fn the_man_page_is_roff_and_names_the_commands() {
    let (code, page, err) = thud(&["man"]);
    assert_eq!(code, 0, "{err}");
    assert!(page.starts_with(".TH thud 1 "), "{}", &page[..page.len().min(80)]);
    for section in [".SH NAME", ".SH SYNOPSIS", ".SH OPTIONS", ".SH SUBCOMMANDS"] {
        assert!(page.contains(section), "{section}");
    }
    for c in COMMANDS {
        assert!(page.contains(&format!("thud\\-{c}(1)")), "{c}");
    }
    assert!(page.contains("\\-\\-no\\-limit"));
}

#[test]
fn a_command_has_its_own_page_and_an_unknown_one_is_one_line() {
    let (code, page, err) = thud(&["man", "simulate"]);
    assert_eq!(code, 0, "{err}");
    assert!(page.starts_with(".TH thud-simulate 1 "), "{}", &page[..page.len().min(80)]);
    for flag in ["\\-\\-mass", "\\-\\-main\\-mass", "\\-\\-samples", "\\-\\-json"] {
        assert!(page.contains(flag), "{flag}");
    }
    let (code, page, _) = thud(&["man", "export", "wav"]);
    assert_eq!(code, 0);
    assert!(page.starts_with(".TH thud-export-wav 1 "));
    let (code, out, err) = thud(&["man", "nonesuch"]);
    assert_eq!((code, out.as_str()), (2, ""));
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.starts_with("thud: invalid command: 'nonesuch' is not a command of `thud`; one of: pulse,"), "{err}");
}
