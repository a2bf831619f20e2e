//! `thud pulse` takes its flags from the engine's impact table
//! (`params::PULSE`), as the design commands take theirs from `params::DESIGN`: each flag's
//! help, placeholder, choices and conflicts are its row's, so there is one place to define one.

use crate::common::thud;
use clap::CommandFactory;
use thud::params::{Accepts, PULSE};

/// Every row of the table is a flag of `pulse` with the row's help and placeholder, and a choice
/// row offers exactly the row's names.
#[test]
fn each_pulse_flag_carries_its_row_s_help_placeholder_and_choices() {
    let cmd = thud::cli::Cli::command();
    let pulse = cmd.find_subcommand("pulse").unwrap();
    for p in PULSE {
        let arg = pulse.get_arguments().find(|a| a.get_long() == Some(p.name)).unwrap();
        assert!(!p.help.is_empty(), "--{}: a row of the impact table has a help", p.name);
        assert_eq!(arg.get_help().map(ToString::to_string).as_deref(), Some(p.help), "--{}", p.name);
        let shown: Vec<String> = arg.get_value_names().unwrap_or_default().iter().map(ToString::to_string).collect();
        match &p.accepts {
            Accepts::Choice { names, .. } => {
                let offered: Vec<String> = arg.get_possible_values().iter().map(|v| v.get_name().to_string()).collect();
                assert_eq!(offered, names.iter().map(ToString::to_string).collect::<Vec<_>>(), "--{}", p.name);
            }
            _ => assert_eq!(shown, [p.value_name], "--{}", p.name),
        }
    }
}

/// K_HZ as a number conflicts with either material (the row's conflict, declared once), refused
/// by the command line before the engine whichever flag comes first.
#[test]
fn k_hz_is_refused_with_either_material_in_either_order() {
    for args in [
        ["--k-hz", "5e8", "--sphere", "steel"],
        ["--sphere", "steel", "--k-hz", "5e8"],
        ["--k-hz", "5e8", "--plate", "steel"],
        ["--plate", "steel", "--k-hz", "5e8"],
    ] {
        let (code, out, err) = thud(&[&["pulse"][..], &args[..]].concat());
        assert_eq!(code, 2, "{args:?}");
        assert!(out.is_empty(), "{args:?}: {out}");
        let line = err.trim_end();
        assert!(!line.contains('\n'), "one line: {err}");
        assert!(line.contains("cannot be used with") && line.contains("--k-hz <KH>"), "{args:?}: {err}");
        assert!(line.contains(&format!("'{} <MATERIAL>'", args[if args[0] == "--k-hz" { 2 } else { 0 }])), "{err}");
    }
}

/// A material may start with a dash (the engine names the flag), and a flag's value is what the
/// engine reads: the same impact from `--sound-speed 340` as from Python's `sound_speed=340`
/// (the table's row, not a hand-written field).
#[test]
fn pulse_flags_reach_the_engine_as_the_table_reads_them() {
    let (code, _, err) = thud(&["pulse", "--sphere", "-x"]);
    assert_eq!(code, 2);
    assert!(err.starts_with("thud: invalid --sphere: unknown material '-x'"), "{err}");
    let (code, out, err) = thud(&["pulse", "--sound-speed", "340", "--model", "paper", "--source", "single", "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!((v["c_m_s"].as_f64(), v["source"].as_str()), (Some(340.0), Some("single")));
}
