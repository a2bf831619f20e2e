#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test or benchmark fails
//! Shell integration: completion scripts and man pages generated from the command line's own
//! definitions, naming every command and flag.

use crate::common;
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

#[test]
fn completions_offer_presets_materials_paper_items_and_man_commands() {
    let (code, script, err) = thud(&["completions", "bash"]);
    assert_eq!(code, 0, "{err}");
    for name in ["paper-fig9", "paper-table3", "quiet-nylon", "steel-ball"] {
        assert!(script.contains(name), "preset {name}");
    }
    for name in ["tungsten-carbide", "stainless-steel", "acrylic", "nylon"] {
        assert!(script.contains(name), "material {name}");
    }
    for name in ["table3", "fig17", "table5"] {
        assert!(script.contains(name), "paper item {name}");
    }
    // `thud man COMMAND` completes the commands: bash's word list for `man` names them.
    let man_case = script.split("thud__subcmd__man)").nth(1).unwrap();
    let man_case = &man_case[..man_case.find(";;").unwrap()];
    assert!(man_case.contains("simulate") && man_case.contains("response") && man_case.contains("merge"), "{man_case}");
    let (code, fish, _) = thud(&["completions", "fish"]);
    assert_eq!(code, 0);
    assert!(fish.contains("paper-fig9") && fish.contains("tungsten-carbide"), "fish offers them too");
    // The parser still takes what it took (aliases the completion does not offer).
    let (code, _, err) = thud(&["simulate", "--sphere", "pmma", "--duration", "0.05"]);
    assert_eq!(code, 0, "{err}");
}

#[test]
fn man_all_writes_every_page_with_the_extra_sections_and_keeps_existing_ones() {
    let dir = tempfile::tempdir().unwrap();
    let folder = dir.path().join("man").join("man1");
    let f = folder.to_str().unwrap();
    let (code, out, err) = thud(&["man", "--all", f]);
    assert_eq!((code, out.as_str()), (0, ""), "{err}");
    let mut names: Vec<String> =
        std::fs::read_dir(&folder).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    names.sort();
    for want in COMMANDS.iter().map(|c| format!("thud-{c}.1")).chain(
        [
            "thud.1",
            "thud-merge.1",
            "thud-response.1",
            "thud-export-csv.1",
            "thud-export-svg.1",
            "thud-export-pdf.1",
            "thud-export-wav.1",
        ]
        .map(String::from),
    ) {
        assert!(names.contains(&want), "{want} not in {names:?}");
    }
    assert!(err.contains(&format!("wrote {} man pages", names.len())), "{err}");
    for name in &names {
        let page = std::fs::read_to_string(folder.join(name)).unwrap();
        assert!(page.starts_with(&format!(".TH {} 1 ", name.trim_end_matches(".1"))), "{name}");
        for section in
            [".SH \"EXIT STATUS\"", ".SH ENVIRONMENT", ".SH FILES", ".SH UNITS", ".SH \"SEE ALSO\"", ".SH OPTIONS"]
        {
            assert!(page.contains(section), "{name}: {section}");
        }
        for var in ["NO_COLOR", "RAYON_NUM_THREADS", "XDG_CONFIG_HOME", "XDG_DATA_HOME"] {
            assert!(page.contains(var), "{name}: {var}");
        }
        assert!(page.contains("thud(1)") || name == "thud.1", "{name}: SEE ALSO thud(1)");
        // The page printed alone is the page written.
        // A command whose own name has a hyphen (`impact-map`) is one word of the path.
        let stem = name.trim_end_matches(".1").trim_start_matches("thud");
        let args: Vec<&str> = match stem.strip_prefix('-') {
            Some(cmd @ "impact-map") => vec![cmd],
            _ => stem.split('-').skip(1).collect(),
        };
        let (code, alone, _) = thud(&[&["man"][..], &args].concat());
        assert_eq!((code, alone.as_str()), (0, page.as_str()), "{name}");
    }
    let sim = std::fs::read_to_string(folder.join("thud-simulate.1")).unwrap();
    assert!(sim.contains(".SH EXAMPLES") && sim.contains("paper\\-fig9"), "examples");
    assert!(sim.contains("paper\\-table3"), "the page lists the preset names");
    // A second run keeps every page and writes nothing; --force replaces them.
    let before = std::fs::metadata(folder.join("thud.1")).unwrap().modified().unwrap();
    let (code, _, err) = thud(&["man", "--all", f]);
    assert_eq!(code, 2, "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.starts_with("thud: invalid --all: ") && err.contains("exists") && err.contains("--force"), "{err}");
    assert_eq!(std::fs::metadata(folder.join("thud.1")).unwrap().modified().unwrap(), before);
    let (code, _, err) = thud(&["man", "--all", f, "--force"]);
    assert_eq!(code, 0, "{err}");
    if std::process::Command::new("man").arg("--version").output().is_ok_and(|o| o.status.success()) {
        let o = std::process::Command::new("man")
            .args(["--warnings", "-E", "UTF-8", "-l", folder.join("thud-simulate.1").to_str().unwrap()])
            .env("MANWIDTH", "100")
            .env("MAN_KEEP_FORMATTING", "0")
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        assert!(o.stderr.is_empty(), "man warns: {}", String::from_utf8_lossy(&o.stderr));
        let text = String::from_utf8_lossy(&o.stdout);
        assert!(text.contains("An I/O failure") && text.contains("docs/model.md"), "{text}");
    }
}

/// zsh's `_arguments` reads `--flag=[help]:MESSAGE:ACTION`: a value name with a colon
/// (`NAME=FROM:TO:N`) must have it escaped, or zsh runs its second part as a command
/// ("command not found: TO" on `thud sweep --vary <TAB>`).
#[test]
fn zsh_completion_specs_have_one_message_and_one_action() {
    let (code, script, err) = thud(&["completions", "zsh"]);
    assert_eq!(code, 0, "{err}");
    let mut checked = 0;
    for line in script.lines().map(str::trim).filter(|l| l.starts_with('\'') && l.contains("]:")) {
        let spec = line.trim_end_matches(" \\").trim_end_matches('\'');
        // (`::` is an optional value: one colon more, not a part more.)
        let tail = spec[spec.rfind("]:").unwrap() + 2..].trim_start_matches(':');
        let mut colons = 0;
        let mut prev = ' ';
        for c in tail.chars() {
            colons += usize::from(c == ':' && prev != '\\');
            prev = c;
        }
        assert_eq!(colons, 1, "message and action, no more: {line}");
        checked += 1;
    }
    assert!(checked > 50, "{checked} specs");
    assert!(script.contains(r"]:NAME=FROM\:TO\:N:"), "the --vary value name, escaped");
}
