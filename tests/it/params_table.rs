#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test or benchmark fails
//! One table per parameter: every row of the engine's table (`thud_core::params::DESIGN`) is
//! exposed by every front end with the row's own range and help — the command line's flag on
//! each design command (so its completions and man page too), `thud limits`, an explorer field,
//! a key of `config.toml`'s `[design]`, and Python's keyword in the checked-in stub. A row a
//! front end misses fails here.

use std::path::{Path, PathBuf};

use clap::CommandFactory;
use thud::cli::Cli;
use thud::params::{self, Accepts, DESIGN};
use thud::tui::explain;
use thud::tui::fields::Knob;

/// The design commands, fit damper included.
const COMMANDS: [&[&str]; 6] =
    [&["simulate"], &["sweep"], &["response"], &["restitution"], &["export", "csv"], &["fit", "damper"]];

fn stub_path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("crates/thud-py/python/thud/__init__.pyi")
}

#[test]
fn every_row_is_a_flag_of_every_design_command_with_its_help() {
    for path in COMMANDS {
        let mut cmd = Cli::command();
        for sub in path {
            cmd = cmd.find_subcommand(sub).unwrap().clone();
        }
        for p in DESIGN {
            // A fit of c1 takes only the rows a fit reads; the others are no flag of it.
            if path == &["fit", "damper"][..] && !thud::cli::design_args::FIT_ROWS.contains(&p.name) {
                let long = thud::cli::design_args::flag_of(p.name);
                assert!(cmd.get_arguments().all(|a| a.get_long() != Some(long)), "fit damper takes --{long}");
                continue;
            }
            // The force amplitude is `--force-amplitude` on every command (`--force` replaces a file).
            let long = thud::cli::design_args::flag_of(p.name);
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
            let listed = params::listed_ranges()
                .into_iter()
                .find(|r| r.param == p.name)
                .unwrap_or_else(|| panic!("{} is not listed", p.name));
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
        if k.plain() {
            // A field made from the row: its name, help and range are the row's.
            assert!(p.label.chars().count() <= 10, "{}: the panel's label column is 10 wide", p.name);
            assert_eq!((k.label(), k.param()), (p.label, p.name));
            let hint = explain::field_hint(k, &thud::design::Design::default());
            assert!(hint.contains(p.help), "{hint}");
        }
    }
    // The parameters the explorer lacked before its fields came from the table.
    for name in ["density", "radius", "ball-velocity", "periods", "settle"] {
        assert!(Knob::ALL.iter().any(|k| k.plain() && k.rows() == [name]), "{name}");
    }
}

/// A quantity's type in a study's overload (`sweep(mass=[…], gap=[…])`).
const STUDY_QUANTITY: &str = "Union[Quantity, Sequence[Quantity], npt.ArrayLike, None]";

/// The line after which a stub function's keyword block starts.
const PRESET_LINE: &str = "    preset: Optional[str] = None,\n";

/// The next `def NAME(` in `text` of one of `blocks`' functions: its offset and its block.
fn next_def<'a>(text: &str, blocks: &'a [(&str, String)]) -> Option<(usize, &'a String)> {
    blocks
        .iter()
        .filter_map(|(function, block)| text.find(&format!("def {function}(")).map(|at| (at, block)))
        .min_by_key(|(at, _)| *at)
}

/// Python's keywords are the table's rows (the engine resolves them by name); the stub lists
/// each with its help and range. `THUD_BLESS=1` rewrites the stub's blocks from the table.
#[test]
fn the_python_stub_lists_every_row_as_the_table_says() {
    let text = std::fs::read_to_string(stub_path()).unwrap();
    let blocks = [
        ("simulate", params::stub_keywords(&[])),
        ("simulate_ensemble", params::stub_keywords(&["ball-position"])),
        ("sweep", params::stub_keywords(&[])),
        ("response", params::stub_keywords(&["freq"])),
        ("pulse", params::impact_stub_keywords()),
    ];
    if std::env::var_os("THUD_BLESS").is_some() {
        let mut out = String::new();
        let mut rest = text.as_str();
        while let Some((at, block)) = next_def(rest, &blocks) {
            let mut open = at + rest[at..].find(PRESET_LINE).unwrap() + PRESET_LINE.len();
            if rest[open..].starts_with("    design: ") {
                open += rest[open..].find('\n').unwrap() + 1;
            }
            // The block ends at its last row's line (`settle` for a design's).
            let last = block.lines().last().unwrap();
            let last = &last[..=last.find(':').unwrap()];
            let end = open + rest[open..].find(last).unwrap();
            let end = end + rest[end..].find('\n').unwrap() + 1;
            out += &rest[..open];
            // A study's overload keeps its sequences.
            out += &if rest[open..end].contains(STUDY_QUANTITY) {
                block.replace("Optional[Quantity]", STUDY_QUANTITY)
            } else {
                block.clone()
            };
            rest = &rest[end..];
        }
        out += rest;
        std::fs::write(stub_path(), out).unwrap();
        return;
    }
    // Every definition of each function (the overloads of `simulate` too) carries the block.
    let mut rest = text.as_str();
    let mut seen = 0;
    while let Some((at, block)) = next_def(rest, &blocks) {
        let body = &rest[at..];
        let body = &body[..body.find("\"\"\"").unwrap_or(body.len())];
        let name = &body[..body.find('(').unwrap()];
        // A study's overload (`sweep(mass=[…], gap=[…])`) takes a sequence for each quantity.
        let study = block.replace("Optional[Quantity]", STUDY_QUANTITY);
        assert!(
            body.contains(block.as_str()) || body.contains(study.as_str()),
            "the stub's {name} keywords differ from the table:\n{block}"
        );
        rest = &rest[at + 4..];
        seen += 1;
    }
    assert!(seen >= blocks.len(), "the stub defines {seen} of the table's functions");
    for p in DESIGN {
        let keyword = format!("    {}: Optional[", p.name.replace('-', "_"));
        assert!(text.contains(&keyword), "{}", p.name);
        assert!(text.contains(p.help), "{}", p.name);
    }
}

/// A value inside the row's range (the default design's, or the range's bound) as TOML, and
/// one outside it (none for rows without a range).
fn config_values(p: &params::Param<params::DesignDraft>) -> (String, Option<String>) {
    let d = thud::design::Design::default();
    match (&p.accepts, p.range()) {
        (Accepts::Choice { names, .. }, _) => (format!("\"{}\"", names[names.len() - 1]), None),
        (Accepts::Name { .. }, _) => ("\"steel\"".into(), None),
        (Accepts::Switch { .. }, _) => ("true".into(), None),
        (_, Some(r)) => {
            let inside = p.get.map(|g| g(&d)).filter(|v| r.contains(*v)).unwrap_or(r.max);
            let outside = if r.max.is_finite() { r.max.abs() * 2.0 + 1.0 } else { r.min - r.min.abs() - 1.0 };
            (format!("{inside:?}"), Some(format!("{outside:?}")))
        }
        (_, None) => unreachable!("{}: a numeric row has a range", p.name),
    }
}

#[test]
fn every_row_is_a_config_key_with_its_range() {
    let path = Path::new("config.toml");
    for p in DESIGN {
        let (inside, outside) = config_values(p);
        // A row that needs another (`plate` needs `sphere`) comes with it, as on the command line.
        // So does `dt`, which only the Newmark solver has (as `--dt` needs `--solver newmark`).
        let needs = if p.name == "dt" {
            "solver = \"newmark\"\n".to_string()
        } else if p.name.starts_with("air-") {
            // The air's temperature and pressure are the physical model's (the paper model
            // refuses them).
            "model = \"physical\"\n".to_string()
        } else {
            p.requires
                .and_then(|r| DESIGN.iter().find(|q| q.name == r))
                .map(|q| format!("{} = {}\n", q.name, config_values(q).0))
                .unwrap_or_default()
        };
        let line = 2 + needs.lines().count();
        let text = format!("theme = \"mono\"\n[design]\n{needs}{} = {inside}\n", p.name);
        let problems = thud::config::check_text(path, &text);
        assert!(problems.is_empty(), "{text}: {problems:?}");
        let config: thud::config::Config = toml::from_str(&text).unwrap();
        assert!(config.validate().is_ok(), "{text}");
        if let (Some(outside), Some(range)) = (outside, p.range()) {
            let text = format!("[design]\n{needs}{} = {outside}\n", p.name);
            let problems = thud::config::check_text(path, &text);
            assert_eq!(problems.len(), 1, "{text}: {problems:?}");
            let shown = problems[0].to_string();
            assert!(
                shown.starts_with(&format!("config.toml:{line}:{}: invalid {}: ", p.name.len() + 4, p.name)),
                "{shown}"
            );
            assert!(shown.contains(&range.describe()), "{shown}: the range's line");
            let config: thud::config::Config = toml::from_str(&text).unwrap();
            assert!(config.validate().is_err(), "{text}");
        }
    }
    // A key that is no row is reported at the key, naming the nearest row.
    let problems = thud::config::check_text(path, "[design]\nmain_mas = 1\nstifness = 2\n");
    let shown: Vec<String> = problems.iter().map(ToString::to_string).collect();
    assert_eq!(shown.len(), 2, "{shown:?}");
    assert!(
        shown[0].starts_with("config.toml:2:1: invalid main_mas: unknown design parameter; did you mean 'main-mass'?"),
        "{shown:?}"
    );
    assert!(shown[1].starts_with("config.toml:3:1: invalid stifness: unknown design parameter"), "{shown:?}");
}

/// Runs the built binary with HOME and the XDG folders in `home`: exit code, stdout, stderr.
fn thud_in(home: &Path, args: &[&str]) -> (i32, String, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_thud"))
        .args(args)
        .env("HOME", home)
        .env("XDG_CONFIG_HOME", home.join("config"))
        .env("XDG_DATA_HOME", home.join("data"))
        .env_remove("XDG_CONFIG_DIRS")
        .stdin(std::process::Stdio::null())
        .output()
        .unwrap();
    let text = |b: &[u8]| String::from_utf8_lossy(b).into_owned();
    (out.status.code().unwrap_or(-1), text(&out.stdout), text(&out.stderr))
}

#[test]
fn config_design_keys_set_the_preset_before_the_flags_and_config_check_lists_them() {
    let home = tempfile::tempdir().unwrap();
    let dir = home.path().join("config/thud");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("config.toml"), "[design]\nmass = \"50g\"\nmain-mass = 0.6\n").unwrap();
    let mass = |args: &[&str]| {
        let (code, out, err) =
            thud_in(home.path(), &[&["simulate", "--duration", "0.05", "--json"][..], args].concat());
        assert_eq!(code, 0, "{err}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        (
            v["design"]["damper"]["impact_mass_kg"].as_f64().unwrap(),
            v["design"]["damper"]["main_mass_kg"].as_f64().unwrap(),
        )
    };
    assert_eq!(mass(&[]), (0.05, 0.6));
    assert_eq!(mass(&["--mass", "60g"]), (0.06, 0.6), "a flag overrides the config");
    assert_eq!(thud_in(home.path(), &["config", "check"]).0, 0);
    std::fs::write(dir.join("config.toml"), "[design]\nmass = 1e9\nmian-mass = 1\n").unwrap();
    let (code, out, err) = thud_in(home.path(), &["config", "check"]);
    assert_eq!(code, 2, "{err}");
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 2, "{out}");
    assert!(lines[0].contains("config.toml:2:8: invalid mass: 1e9 kg is out of range"), "{out}");
    assert!(lines[0].contains(&thud::limits::MASS.describe()), "{out}");
    assert!(
        lines[1].contains("config.toml:3:1: invalid mian-mass: unknown design parameter; did you mean 'main-mass'?"),
        "{out}"
    );
}
