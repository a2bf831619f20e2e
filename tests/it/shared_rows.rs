#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test or benchmark fails
//! A row of the one parameter table (`thud::params::PARAMS`) that applies to both designs and
//! impacts reaches every front end, and its value changes what each builds: `thud pulse` and
//! `thud simulate` (a flag whose value changes the JSON record), the config file (a `[design]`
//! key whose value changes the design), the explorer (a field of its own) and Python (a keyword
//! of `pulse` and of `simulate` in the checked-in stub). A shared row one of them misses, or
//! reads and ignores, fails here.

use std::path::PathBuf;

use thud::design::Design;
use thud::params::{self, Accepts, Input, Param, Spelling, Where, PARAMS};
use thud::tui::fields::Knob;

use crate::common::thud;

type Row = Param<params::DesignDraft>;

/// Values to try for a row, as typed: inside its range and unlike any default.
fn candidates(p: &Row) -> Vec<String> {
    match (&p.accepts, p.range()) {
        (Accepts::Choice { names, .. }, _) => names.iter().map(ToString::to_string).collect(),
        (Accepts::Name { .. }, _) => vec!["steel".into(), "brass".into()],
        (Accepts::Switch { .. }, _) => vec![String::new()],
        (_, Some(r)) => {
            let mut v: Vec<f64> = [0.3, 0.6, 0.01].iter().map(|f| r.min + f * (r.max - r.min)).collect();
            if r.min > 0.0 {
                v.insert(0, (r.min * r.max).sqrt());
                v.push(r.min * 1.5);
            }
            v.push(r.max - 0.2 * (r.max - r.min));
            v.into_iter().map(|x| format!("{x}")).collect()
        }
        (_, None) => unreachable!("{}: a numeric row has a range", p.name),
    }
}

/// What else a row may need given with it: nothing, the physical model (the air's state), or
/// the row it requires (a design's plate needs its sphere).
fn extras(p: &Row) -> Vec<Vec<(&'static str, String)>> {
    let mut out = vec![vec![], vec![("model", "physical".to_string())]];
    if let Some(needed) = p.requires {
        out.push(vec![(needed, "steel".to_string())]);
    }
    out
}

fn input(p: &Row, value: &str) -> Input {
    match p.accepts {
        Accepts::Switch { .. } => Input::Switch(true),
        _ => Input::Text(value.to_string()),
    }
}

/// The first (extras, value) for which `build` succeeds with the row and gives another result
/// than with the extras alone.
fn first_change(
    p: &Row,
    build: impl Fn(&[(String, Input)]) -> Option<String>,
) -> Option<(Vec<(&'static str, String)>, String)> {
    for extra in extras(p) {
        let given: Vec<(String, Input)> = extra.iter().map(|(n, v)| (n.to_string(), Input::Text(v.clone()))).collect();
        let Some(without) = build(&given) else { continue };
        for value in candidates(p) {
            let mut with = given.clone();
            with.push((p.name.to_string(), input(p, &value)));
            if build(&with).is_some_and(|b| b != without) {
                return Some((extra, value));
            }
        }
    }
    None
}

/// The command line of `base` with `extra` and the row set to `value` (or without the row).
fn args<'a>(base: &[&'a str], extra: &'a [(&'static str, String)], row: Option<(&Row, &'a str)>) -> Vec<String> {
    let mut out: Vec<String> = base.iter().map(ToString::to_string).collect();
    let flag = |p: &Row| if p.name == "force" { "force-amplitude" } else { p.name };
    for (n, v) in extra {
        out.extend([format!("--{n}"), v.clone()]);
    }
    if let Some((p, value)) = row {
        out.push(format!("--{}", flag(p)));
        if !matches!(p.accepts, Accepts::Switch { .. }) {
            out.push(value.to_string());
        }
    }
    out
}

fn run(args: &[String]) -> String {
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let (code, out, err) = thud(&args);
    assert_eq!(code, 0, "thud {}: {err}", args.join(" "));
    out
}

fn shared() -> Vec<&'static Row> {
    PARAMS.iter().filter(|p| p.used_in == Where::Both).collect()
}

#[test]
fn every_shared_row_reaches_pulse_simulate_the_config_the_explorer_and_python() {
    let rows = shared();
    for name in ["mass", "radius", "k-hz", "sphere", "r", "source", "model", "air-temperature", "rho-c", "sound-speed"]
    {
        assert!(rows.iter().any(|p| p.name == name), "{name} applies to both designs and impacts");
    }
    let stub = std::fs::read_to_string(
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("crates/thud-py/python/thud/__init__.pyi"),
    )
    .unwrap();
    let block = |function: &str| {
        let at = stub.find(&format!("def {function}(")).unwrap();
        let body = &stub[at..];
        body[..body.find("\"\"\"").unwrap()].to_string()
    };
    let (pulse_stub, simulate_stub) = (block("pulse"), block("simulate"));
    for p in rows {
        // thud pulse: its value changes the impact the engine builds, and the command's record.
        let impact = |g: &[(String, Input)]| params::pulse(None, g, Spelling::Flag).ok().map(|i| format!("{i:?}"));
        let (extra, value) =
            first_change(p, impact).unwrap_or_else(|| panic!("{}: no value changes an impact", p.name));
        let pulse = ["pulse", "--json"];
        assert_ne!(
            run(&args(&pulse, &extra, Some((p, &value)))),
            run(&args(&pulse, &extra, None)),
            "thud pulse ignores --{} {value}",
            p.name
        );
        // thud simulate: the same for a design.
        let design =
            |g: &[(String, Input)]| params::design(Design::default(), g, Spelling::Flag).ok().map(|d| format!("{d:?}"));
        let (extra, value) = first_change(p, design).unwrap_or_else(|| panic!("{}: no value changes a design", p.name));
        let simulate = ["simulate", "--duration", "0.02", "--json"];
        assert_ne!(
            run(&args(&simulate, &extra, Some((p, &value)))),
            run(&args(&simulate, &extra, None)),
            "thud simulate ignores --{} {value}",
            p.name
        );
        // The config file: a [design] key whose value changes the design.
        let toml_value = |v: &str| if v.parse::<f64>().is_ok() { v.to_string() } else { format!("\"{v}\"") };
        let mut text = String::from("[design]\n");
        for (n, v) in &extra {
            text += &format!("{n} = {}\n", toml_value(v));
        }
        let config = |text: &str| {
            let config: thud::config::Config = toml::from_str(text).unwrap();
            format!("{:?}", config.design(Design::default()).unwrap())
        };
        let with = match p.accepts {
            Accepts::Switch { .. } => format!("{text}{} = true\n", p.name),
            _ => format!("{text}{} = {}\n", p.name, toml_value(&value)),
        };
        assert!(thud::config::check_text(std::path::Path::new("config.toml"), &with).is_empty(), "{with}");
        assert_ne!(config(&with), config(&text), "the config's {} changes nothing", p.name);
        // The explorer: a field sets the row.
        assert!(Knob::ALL.iter().any(|k| k.rows().contains(&p.name)), "the explorer has no field for {}", p.name);
        // Python: a keyword of pulse and of simulate.
        let keyword = format!("    {}: Optional[", Spelling::Keyword.spell(p.name));
        assert!(pulse_stub.contains(&keyword), "Python's pulse has no {keyword}");
        assert!(simulate_stub.contains(&keyword), "Python's simulate has no {keyword}");
    }
}
