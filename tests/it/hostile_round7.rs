#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! Hostile round 7: a design file's every table refuses a key it does not know (a misspelt
//! `gap_m` used to be dropped without a word), while every file thud writes, and the files of
//! its first release, still load.
//!
//! Runs of the built binary, with HOME and the XDG folders in a temporary folder, each killed
//! after 60 s of CPU time (a failure).

use std::fs;
use std::path::Path;
use std::process::Stdio;
use std::time::Duration;

use thud::damper::Solver;
use thud::design::{Atmosphere, Design, Materials, Model};
use thud::store::DesignFile;

use crate::support::{home, wait};
use home::in_home;
use wait::wait_within_cpu;

const BIN: &str = env!("CARGO_BIN_EXE_thud");

/// Runs thud with `args` in `home` to completion: (code, stdout, stderr).
fn thud(home: &Path, args: &[&str]) -> (i32, String, String) {
    let child = in_home(BIN, args, home, &[]).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().unwrap();
    let out = wait_within_cpu(child, Duration::from_secs(60), Duration::from_secs(600), &format!("{args:?}"));
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

/// A refusal: exit 2, nothing on stdout, one line on stderr holding every one of `words`.
fn assert_refused(home: &Path, args: &[&str], words: &[&str]) {
    let (code, out, err) = thud(home, args);
    assert_eq!(code, 2, "{args:?}: {err}");
    assert!(out.is_empty(), "{args:?} printed: {out}");
    assert_eq!(err.lines().count(), 1, "{args:?}: one line: {err}");
    for w in words {
        assert!(err.contains(w), "{args:?}: {w:?} missing from {err}");
    }
}

/// A design file as the explorer's save writes it, with every table a design file can hold:
/// materials, the physical model's air, the Newmark solver, an ensemble size and uncertainties.
fn every_table() -> String {
    let design = Design {
        materials: Some(Materials::new("steel", "steel")),
        model: Model::Physical,
        atmosphere: Atmosphere { temperature_c: 25.0, pressure_pa: 100_000.0 },
        solver: Solver::Newmark { dt_s: 1e-6 },
        ..Design::default()
    };
    let file = DesignFile {
        description: "every table".into(),
        ensemble: Some(3),
        uncertainty: [("main-mass".to_string(), 0.05), ("k".to_string(), 0.02)].into_iter().collect(),
        design,
    };
    file.to_toml().unwrap()
}

/// The tables of `text` (its `[header]` lines).
fn tables(text: &str) -> Vec<&str> {
    text.lines().filter(|l| l.starts_with('[')).collect()
}

/// `text` with `line` added after the table header `table` (or first, for the top level).
fn with_line_in(text: &str, table: Option<&str>, line: &str) -> String {
    let Some(table) = table else { return format!("{line}\n{text}") };
    let mut out = String::new();
    for l in text.lines() {
        out.push_str(l);
        out.push('\n');
        if l == table {
            out.push_str(line);
            out.push('\n');
        }
    }
    out
}

#[test]
fn a_key_no_table_of_a_design_file_knows_is_refused_naming_the_key_and_the_file() {
    let home = tempfile::tempdir().unwrap();
    let text = every_table();
    let good = home.path().join("good.toml");
    fs::write(&good, &text).unwrap();
    let (code, _, err) = thud(home.path(), &["simulate", "--design", good.to_str().unwrap(), "--duration", "0.01"]);
    assert_eq!(code, 0, "the file as written loads: {err}\n{text}");
    thud_presets::design_file(&text).expect("the Python module's reader loads it too");

    let found = tables(&text);
    // Every table a design file can hold is in the file, so every one is tried.
    for t in [
        "[uncertainty]",
        "[design]",
        "[design.damper]",
        "[design.materials]",
        "[design.observer]",
        "[design.radiation]",
        "[design.solver.newmark]",
        "[design.thresholds]",
        "[design.atmosphere]",
    ] {
        assert!(found.contains(&t), "{t} not written:\n{text}");
    }
    let mut tried: Vec<Option<&str>> = vec![None];
    tried.extend(found.iter().copied().map(Some));
    for table in tried {
        // A key no table has (the uncertainties are named by flags, the rest in SI words).
        let typo = if table == Some("[uncertainty]") { "mian-mass = 0.05" } else { "gap_mm = 0.01" };
        let key = typo.split(' ').next().unwrap();
        let bad = home.path().join("typo.toml");
        let bad_text = with_line_in(&text, table, typo);
        fs::write(&bad, &bad_text).unwrap();
        for args in [
            vec!["simulate", "--design", "typo.toml"],
            vec!["response", "--design", "typo.toml", "--force-amplitude", "1N"],
            vec!["fit", "damper", "--design", "typo.toml", "--data", "none.csv"],
        ] {
            assert_refused(home.path(), &args, &["--design", key, "typo.toml"]);
        }
        let e = thud_presets::design_file(&bad_text).expect_err(typo).to_string();
        assert!(e.contains(key) && !e.contains('\n'), "{table:?}: the Python reader: {e}");
    }
}

#[test]
fn an_uncertainty_that_is_not_a_fraction_is_refused() {
    let home = tempfile::tempdir().unwrap();
    let text = every_table();
    for bad in ["-0.05", "nan", "inf"] {
        let bad_text = text.replace("main-mass = 0.05", &format!("main-mass = {bad}"));
        assert_ne!(bad_text, text);
        fs::write(home.path().join("u.toml"), &bad_text).unwrap();
        assert_refused(home.path(), &["simulate", "--design", "u.toml"], &["--design", "u.toml", "main-mass"]);
        assert!(thud_presets::design_file(&bad_text).is_err(), "{bad}");
    }
}

/// thud's first saved-design format (its first presets, as the explorer then wrote them):
/// `density`, `k_hz` and `"Event"`, since renamed.
const FIRST_FORMAT: &str = r#"description = "the paper's Fig 9: Table 2, v0 2 m/s, d 4 cm; the paper's quadrupole signs"

[design]
ball = { density = 1190.0 }
solver = "Event"
u0max_rule = "impacts"

[design.damper]
main_mass_kg = 0.5
stiffness_n_m = 500.0
damping_n_s_m = 0.05
impact_mass_kg = 0.0405
gap_m = 0.04
k_hz = 5.6e8
c1_n_s_m = 20.0
no_tension = false
v0_m_s = 2.0
duration_s = 2.0

[design.observer]
r_m = 0.7
theta_deg = 45.0

[design.radiation]
source = "quadrupole"
quad_signs = "paper"
air = { rho_c_pa_s_m = 400.0, c_m_s = 343.0 }

[design.thresholds]
spl_db = 103.0
inclination_cm_s = 0.9
zone_by = "paper"
"#;

#[test]
fn the_first_releases_design_files_and_every_writers_files_still_load() {
    let home = tempfile::tempdir().unwrap();
    fs::write(home.path().join("old.toml"), FIRST_FORMAT).unwrap();
    let (code, old, err) = thud(home.path(), &["simulate", "--design", "old.toml", "--json"]);
    assert_eq!(code, 0, "{err}");
    // It is the paper's Fig 9, which the preset of that name still is.
    let (code, fig9, err) = thud(home.path(), &["simulate", "--preset", "paper-fig9", "--json"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(old, fig9);
    assert_eq!(thud_presets::design_file(FIRST_FORMAT).unwrap(), thud_presets::preset("paper-fig9").unwrap());

    // The front `design --save DIR` writes: each of its files loads.
    let (code, _, err) = thud(
        home.path(),
        &["design", "--vary", "mass=20g:120g", "--minimize", "spl_max_db", "--evaluations", "4", "--save", "front"],
    );
    assert_eq!(code, 0, "{err}");
    let mut saved = 0;
    for e in fs::read_dir(home.path().join("front")).unwrap() {
        let path = e.unwrap().path();
        if path.extension().is_some_and(|x| x == "toml") {
            let p = path.to_str().unwrap();
            let (code, _, err) = thud(home.path(), &["simulate", "--design", p, "--duration", "0.01"]);
            assert_eq!(code, 0, "{p}: {err}");
            thud_presets::design_file(&fs::read_to_string(&path).unwrap()).unwrap();
            saved += 1;
        }
    }
    assert!(saved > 0, "design --save wrote no design file");
}

/// A continuation steps a little past its range's end before it lands on it. Where that end
/// was the parameter's own bound (f = 1e5 Hz, the largest forcing frequency), the step past it
/// was refused as out of range: `continue` and `bifurcation --branches` refused a range they
/// had accepted, naming `--freq` (not typed) and a value inside the range, or ended each branch
/// early at the bound.
#[test]
fn a_branch_continued_to_the_parameter_s_own_bound_lands_on_it() {
    let home = tempfile::tempdir().unwrap();
    for range in ["f=9e4Hz:1e5Hz:2", "f=1e5Hz:9e4Hz:2"] {
        let (code, out, err) = thud(home.path(), &["continue", "--vary", range, "--force-amplitude", "1"]);
        assert_eq!(code, 0, "{range}: {err}");
        assert!(!out.contains("out of range") && !out.contains("ended early"), "{range}:\n{out}");
        let (code, out, err) = thud(home.path(), &["continue", "--vary", range, "--force-amplitude", "1", "--json"]);
        assert_eq!(code, 0, "{range}: {err}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        let branches = v["branches"].as_array().unwrap();
        assert!(!branches.is_empty(), "{range}: no branch");
        for b in branches {
            let ended = b["ended"].as_str().unwrap_or_default();
            assert!(!ended.contains("out of range"), "{range}: {ended}");
            let values: Vec<f64> =
                b["points"].as_array().unwrap().iter().map(|p| p["value"].as_f64().unwrap()).collect();
            assert!(values.iter().all(|f| (9e4..=1e5).contains(f)), "{range}: {values:?}");
            // Each branch reaches both ends of the range.
            let (lo, hi) = values.iter().fold((f64::MAX, f64::MIN), |(a, b), &f| (a.min(f), b.max(f)));
            assert!(lo <= 9e4 * (1.0 + 1e-9) && hi >= 1e5 * (1.0 - 1e-9), "{range}: {lo} to {hi}");
        }
    }
    let svg = home.path().join("b.svg");
    let (code, _, err) = thud(
        home.path(),
        &[
            "bifurcation",
            "--force-amplitude",
            "1",
            "--vary",
            "f=9e4Hz:1e5Hz:3",
            "--svg",
            svg.to_str().unwrap(),
            "--branches",
            "2",
        ],
    );
    assert_eq!(code, 0, "{err}");
    let text = fs::read_to_string(&svg).unwrap();
    let non_finite = text.split(|c: char| !c.is_ascii_alphanumeric()).find(|w| *w == "NaN" || *w == "inf");
    assert!(non_finite.is_none(), "a non-finite number in the figure");
}
