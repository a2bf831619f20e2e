#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test or benchmark fails
//! One table per parameter: every row of the engine's table (`thud_core::params::DESIGN`) is
//! exposed by every front end with the row's own range and help — the command line's flag on
//! each design command (so its completions and man page too), `thud limits`, an explorer field,
//! and Python's keyword in the checked-in stub. A row a front end misses fails here.

use std::path::PathBuf;

use clap::CommandFactory;
use thud::cli::Cli;
use thud::limits::RANGES;
use thud::params::{self, Accepts, DESIGN};
use thud::tui::explain;
use thud::tui::fields::Knob;

/// The design commands and the long flag the force amplitude has on each.
const COMMANDS: [(&[&str], &str); 5] = [
    (&["simulate"], "force"),
    (&["sweep"], "force-amplitude"),
    (&["response"], "force"),
    (&["restitution"], "force"),
    (&["export", "csv"], "force-amplitude"),
];

fn stub_path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("crates/thud-py/thud.pyi")
}

#[test]
fn every_row_is_a_flag_of_every_design_command_with_its_help() {
    for (path, force) in COMMANDS {
        let mut cmd = Cli::command();
        for sub in path {
            cmd = cmd.find_subcommand(sub).unwrap().clone();
        }
        for p in DESIGN {
            let long = if p.name == "force" { force } else { p.name };
            let arg = cmd.get_arguments().find(|a| a.get_long() == Some(long));
            let arg = arg.unwrap_or_else(|| panic!("{path:?} has no --{long}"));
            assert_eq!(arg.get_help().map(ToString::to_string).as_deref(), Some(p.help), "--{long}");
            if let Accepts::Choice { names, .. } = p.accepts {
                let values: Vec<String> = arg.get_possible_values().iter().map(|v| v.get_name().to_string()).collect();
                assert_eq!(values, names, "--{long}");
            }
        }
    }
}

#[test]
fn every_numeric_row_is_listed_by_thud_limits_with_its_range() {
    for p in DESIGN {
        if let Some(range) = p.range() {
            let listed =
                RANGES.iter().find(|r| r.param == p.name).unwrap_or_else(|| panic!("{} is not listed", p.name));
            assert_eq!(listed, range, "{}", p.name);
        }
    }
}

#[test]
fn every_row_has_an_explorer_field_with_its_range_and_help() {
    for p in DESIGN {
        let fields: Vec<Knob> = Knob::ALL.into_iter().filter(|k| k.rows().contains(&p.name)).collect();
        assert_eq!(fields.len(), 1, "{}: fields {fields:?}", p.name);
        let k = fields[0];
        if k.rows().len() == 1 {
            assert_eq!(k.range().as_ref(), p.range(), "{}", p.name);
        }
        if let Knob::Row(_) = k {
            // A field made from the row: its name, help and range are the row's.
            assert!(p.label.chars().count() <= 10, "{}: the panel's label column is 10 wide", p.name);
            assert_eq!((k.label(), k.param()), (p.label, p.name));
            let hint = explain::field_hint(k, &thud::design::Design::default());
            assert!(hint.contains(p.help), "{hint}");
        }
    }
    // The parameters the explorer lacked before its fields came from the table.
    for name in ["density", "radius", "ball-velocity", "periods", "settle"] {
        assert!(Knob::ALL.iter().any(|k| matches!(k, Knob::Row(_)) && k.rows() == [name]), "{name}");
    }
}

/// Python's keywords are the table's rows (the engine resolves them by name); the stub lists
/// each with its help and range. `THUD_BLESS=1` rewrites the stub's blocks from the table.
#[test]
fn the_python_stub_lists_every_row_as_the_table_says() {
    let text = std::fs::read_to_string(stub_path()).unwrap();
    let blocks = [
        ("simulate", params::stub_keywords(&[])),
        ("sweep", params::stub_keywords(&[])),
        ("response", params::stub_keywords(&["freq"])),
    ];
    if std::env::var_os("THUD_BLESS").is_some() {
        let mut out = String::new();
        let mut rest = text.as_str();
        for (function, block) in &blocks {
            let at = rest.find(&format!("def {function}(")).unwrap();
            let open = at
                + rest[at..].find("    preset: Optional[str] = None,\n").unwrap()
                + "    preset: Optional[str] = None,\n".len();
            let end = open + rest[open..].find("    settle: Optional[bool] = None,").unwrap();
            let end = end + rest[end..].find('\n').unwrap() + 1;
            out += &rest[..open];
            out += block;
            rest = &rest[end..];
        }
        out += rest;
        std::fs::write(stub_path(), out).unwrap();
        return;
    }
    for (function, block) in &blocks {
        let at = text.find(&format!("def {function}(")).unwrap();
        let body = &text[at..];
        let body = &body[..body.find("\"\"\"").unwrap()];
        assert!(body.contains(block.as_str()), "thud.pyi's {function} keywords differ from the table:\n{block}");
    }
    for p in DESIGN {
        let keyword = format!("    {}: Optional[", p.name.replace('-', "_"));
        assert!(text.contains(&keyword), "{}", p.name);
        assert!(text.contains(p.help), "{}", p.name);
    }
}
