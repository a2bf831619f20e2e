#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test or benchmark fails
//! `thud fit structure|damper` on the command line: a closed-form decay
//! (written here, not by thud) recovered through the CSV path with units in the column names,
//! the JSON keys, `--save` and `--design` reading it back, `thud simulate --csv`'s
//! output fitted by `fit damper`, and every kind of bad data refused with exit 2 and one line.

use std::fmt::Write as _;
use std::path::Path;

use crate::common;

fn run(home: &Path, args: &[&str]) -> (i32, String, String) {
    common::thud_in(home, args)
}

/// A closed-form decay of M 2 kg, K 8e4 N/m, C 6 N·s/m struck at 0.3 m/s, in mm, with a
/// deterministic ±1 % ripple of noise, an offset and a drift, unevenly sampled at about 2 kHz.
fn decay_csv() -> String {
    let (m, k, c) = (2.0f64, 8.0e4f64, 6.0f64);
    let s = c / (2.0 * m);
    let wd = (k / m - s * s).sqrt();
    let mut out = String::from("t_ms,x_mm\n");
    let mut t = 0.0f64;
    let mut i = 0u32;
    while t < 1.5 {
        let x = 0.3 / wd * (-s * t).exp() * (wd * t).sin() * 1e3;
        let noise = 0.015 * ((f64::from(i) * 12.9898).sin() * 43758.5453).fract();
        writeln!(out, "{},{}", t * 1e3, x + noise + 0.08 + 0.02 * t).unwrap();
        t += (0.6 + 0.8 * ((f64::from(i) * 78.233).sin() * 12345.678).fract().abs()) / 2000.0;
        i += 1;
    }
    out
}

#[test]
fn structure_fit_recovers_a_closed_form_decay_and_saves_it() {
    let home = tempfile::tempdir().unwrap();
    let file = home.path().join("decay.csv");
    std::fs::write(&file, decay_csv()).unwrap();
    let f = file.to_str().unwrap();
    let (code, out, err) = run(home.path(), &["fit", "structure", "--data", f, "--main-mass", "2kg", "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    for key in ["f_n_hz", "zeta", "k_n_m", "c_n_s_m"] {
        assert!(v[key].is_f64() && v[format!("{key}_stderr")].is_f64(), "{key}: {out}");
    }
    assert!(v["residual_rms"].is_f64());
    let f_n = (4.0e4f64).sqrt() / (2.0 * std::f64::consts::PI);
    assert!((v["f_n_hz"].as_f64().unwrap() / f_n - 1.0).abs() < 0.005);
    assert!((v["zeta"].as_f64().unwrap() / 0.0075 - 1.0).abs() < 0.1);
    let (code, out, err) =
        run(home.path(), &["fit", "structure", "--data", f, "--main-mass", "2", "--save", "measured"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("Saved as"), "{out}");
    // Saving again under the same name is refused (no-clobber).
    let (code, _, err) = run(home.path(), &["fit", "structure", "--data", f, "--main-mass", "2", "--save", "measured"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--save"), "{err}");
    let saved = std::fs::read_to_string(home.path().join("data/thud/designs/measured.toml"))
        .or_else(|_| {
            let mut found = String::new();
            for e in walk(home.path()) {
                if e.ends_with("measured.toml") {
                    found = std::fs::read_to_string(e).unwrap();
                }
            }
            Ok::<String, std::io::Error>(found)
        })
        .unwrap();
    assert!(saved.contains("stiffness_n_m"), "{saved}");
}

fn walk(dir: &Path) -> Vec<std::path::PathBuf> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).unwrap().flatten() {
        let p = e.path();
        if p.is_dir() {
            out.extend(walk(&p));
        } else {
            out.push(p);
        }
    }
    out
}

#[test]
fn damper_fit_reads_simulate_csv_and_brackets_its_c1() {
    let home = tempfile::tempdir().unwrap();
    let (code, csv, err) = run(home.path(), &["simulate", "--c1", "60", "--csv", "--samples", "6001"]);
    assert_eq!(code, 0, "{err}");
    let file = home.path().join("sim.csv");
    std::fs::write(&file, csv).unwrap();
    let (code, out, err) = run(home.path(), &["fit", "damper", "--data", file.to_str().unwrap(), "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let ci = v["c1_n_s_m_ci"].as_array().unwrap();
    let (lo, hi) = (ci[0].as_f64().unwrap(), ci[1].as_f64().unwrap());
    assert!(lo <= 60.0 && 60.0 <= hi && hi / lo <= 3.0, "[{lo}, {hi}]");
    for key in ["c1_n_s_m", "c1_n_s_m_stderr", "restitution", "restitution_stderr", "residual_rms"] {
        assert!(v[key].is_f64(), "{key}: {out}");
    }
}

#[test]
fn bad_data_is_refused_in_one_line() {
    let home = tempfile::tempdir().unwrap();
    let decay = decay_csv();
    let mut rows: Vec<&str> = decay.lines().collect();
    let cases: Vec<(&str, String, &str)> = vec![
        ("nounit", "t,x\n0,1\n1,2\n".to_string(), "no unit"),
        ("short", "t_s,x_m\n0,0\n0.001,1\n0.002,0\n".to_string(), "too short"),
        (
            "nan2",
            {
                let mut s = String::from("t_s,x_m\n");
                for i in 0..100 {
                    writeln!(
                        s,
                        "{},{}",
                        f64::from(i) * 1e-3,
                        if i == 50 { "nan".to_string() } else { "0.1".to_string() }
                    )
                    .unwrap();
                }
                s
            },
            "sample 51",
        ),
        (
            "unsorted",
            {
                rows.swap(20, 21);
                rows.join("\n")
            },
            "unsorted",
        ),
        (
            "repeated",
            {
                let mut s = String::from("t_s,x_m\n");
                for i in 0..100 {
                    writeln!(s, "{},{}", if i == 10 { 9e-3 } else { f64::from(i) * 1e-3 }, (f64::from(i) * 0.3).sin())
                        .unwrap();
                }
                s
            },
            "repeated",
        ),
        (
            "clipped",
            {
                let mut s = String::from("t_s,x_m\n");
                for i in 0..2000 {
                    let t = f64::from(i) * 1e-3;
                    writeln!(s, "{t},{}", (2.0 * (-0.5 * t).exp() * (31.4 * t).sin()).clamp(-1.0, 1.0)).unwrap();
                }
                s
            },
            "clipped",
        ),
        (
            "steady",
            {
                let mut s = String::from("t_s,x_m\n");
                for i in 0..2000 {
                    let t = f64::from(i) * 1e-3;
                    writeln!(s, "{t},{}", (31.4 * t).sin() + 1e-4 * f64::from(i % 7)).unwrap();
                }
                s
            },
            "no decay",
        ),
    ];
    for (name, text, needle) in cases {
        let file = home.path().join(format!("{name}.csv"));
        std::fs::write(&file, text).unwrap();
        let (code, out, err) =
            run(home.path(), &["fit", "structure", "--data", file.to_str().unwrap(), "--main-mass", "1"]);
        assert_eq!(code, 2, "{name}: {err}");
        assert!(out.is_empty(), "{name}");
        assert_eq!(err.lines().count(), 1, "{name}: {err}");
        assert!(err.contains("--data") && err.contains(needle), "{name}: {err}");
    }
    let (code, _, err) = run(home.path(), &["fit", "structure", "--data", "missing.csv", "--main-mass", "1"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--data"), "{err}");
    let (code, _, err) = run(home.path(), &["fit", "structure", "--data", "x.csv", "--main-mass", "-1"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--main-mass"), "{err}");
}

#[test]
fn export_fit_draws_the_measurement_over_the_model() {
    let home = tempfile::tempdir().unwrap();
    let file = home.path().join("decay.csv");
    std::fs::write(&file, decay_csv()).unwrap();
    let svg = home.path().join("fit.svg");
    let args =
        ["export", "svg", "fit", "--data", file.to_str().unwrap(), "--main-mass", "2", "--out", svg.to_str().unwrap()];
    let (code, _, err) = run(home.path(), &args);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.contains("measurement") && text.contains("fitted free decay"), "{}", &text[..200]);
    // No clobber: the same export again is refused, the file kept.
    let (code, _, err) = run(home.path(), &args);
    assert_eq!(code, 2, "{err}");
    // --data belongs to `fit` only.
    let (code, _, err) = run(home.path(), &["export", "svg", "history", "--data", "x.csv", "--out", "h.svg"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--data"), "{err}");
}

/// The decay of [`decay_csv`] (M 2 kg, K 8e4 N/m, C 6 N·s/m, struck at 0.3 m/s) without noise
/// but for a ±1 % ripple, as (t in s, x in m, x'' in m/s²) about every 0.5 ms.
fn decay_rows() -> Vec<(f64, f64, f64)> {
    let (m, k, c) = (2.0f64, 8.0e4f64, 6.0f64);
    let s = c / (2.0 * m);
    let wd = (k / m - s * s).sqrt();
    (0..3000)
        .map(|i| {
            let t = f64::from(i) * 5e-4;
            let e = (-s * t).exp();
            let (sn, cs) = (wd * t).sin_cos();
            let x = 0.3 / wd * e * sn;
            let v = 0.3 * e * (cs - s / wd * sn);
            let ripple = 1.0 + 0.01 * ((f64::from(i) * 12.9898).sin() * 43758.5453).fract();
            (t, x * ripple, -(k * x + c * v) / m * ripple)
        })
        .collect()
}

/// A signal column made from a row of [`decay_rows`].
type Signal = Box<dyn Fn(&(f64, f64, f64)) -> f64>;

/// A column's unit is a unit name of thud's one table, nothing else: `t_s`, `t_ms`, `t_us`,
/// `x_mm`, `a_g`, `a_m_s2` give the same f_n; `t_0ms` and `t_10us` (a number in the unit) are
/// refused in one line naming the column, never read as a factor.
#[test]
fn header_units_are_unit_names_and_a_number_in_one_is_refused() {
    let home = tempfile::tempdir().unwrap();
    let rows = decay_rows();
    let f_n = (4.0e4f64).sqrt() / (2.0 * std::f64::consts::PI);
    let g = 9.80665;
    let cases: Vec<(&str, f64, Signal)> = vec![
        ("t_s,x_m", 1.0, Box::new(|r| r.1)),
        ("t_ms,x_mm", 1e3, Box::new(|r| r.1 * 1e3)),
        ("t_us,x_um", 1e6, Box::new(|r| r.1 * 1e6)),
        ("t_ms,a_g", 1e3, Box::new(move |r| r.2 / g)),
        ("T_S,A_M_S2", 1.0, Box::new(|r| r.2)),
        ("t_0ms,x_m", 1e3, Box::new(|r| r.1)),
        ("t_10us,x_m", 1e5, Box::new(|r| r.1)),
        ("t_s,x_1mm", 1.0, Box::new(|r| r.1 * 1e3)),
        ("t_s,a_s2", 1.0, Box::new(|r| r.2)),
    ];
    for (header, tf, y) in cases {
        let mut text = format!("{header}\n");
        for r in &rows {
            writeln!(text, "{},{}", r.0 * tf, y(r)).unwrap();
        }
        let file = home.path().join("units.csv");
        std::fs::write(&file, text).unwrap();
        let (code, out, err) =
            run(home.path(), &["fit", "structure", "--data", file.to_str().unwrap(), "--main-mass", "2", "--json"]);
        let bad =
            header.split(',').find(|c| c.contains("0ms") || c.contains("10us") || c.contains("1mm") || *c == "a_s2");
        if let Some(col) = bad {
            assert_eq!(code, 2, "{header}: {err}");
            assert_eq!(err.lines().count(), 1, "{header}: {err}");
            assert!(err.contains("--data") && err.contains(&format!("column '{col}'")), "{header}: {err}");
            assert!(err.contains("is not a"), "{header}: {err}");
        } else {
            assert_eq!(code, 0, "{header}: {err}");
            let v: serde_json::Value = serde_json::from_str(&out).unwrap();
            let got = v["f_n_hz"].as_f64().unwrap();
            assert!((got / f_n - 1.0).abs() < 1e-3, "{header}: f_n {got}, truth {f_n}");
            assert!((v["k_n_m"].as_f64().unwrap() / 8.0e4 - 1.0).abs() < 2e-3, "{header}: {out}");
        }
    }
}

/// Files not separated by commas, a decimal comma and an empty column name are told what
/// they are, in one line naming `--data` (not "the header needs t_s" when it has it).
#[test]
fn csv_errors_say_what_they_see() {
    let home = tempfile::tempdir().unwrap();
    let rows = decay_rows();
    let body = |sep: &str, decimal: &str, trail: &str| {
        let mut s = String::new();
        for r in &rows {
            let line = format!("{:.6}{sep}{:.9}{trail}", r.0, r.1);
            writeln!(s, "{}", if decimal == "," { line.replace('.', ",") } else { line }).unwrap();
        }
        s
    };
    let cases = [
        ("semicolon", format!("t_s;x_m\n{}", body(";", ".", "")), "';' separated: use ','"),
        ("semicolon-comma", format!("t_s;x_m\n{}", body(";", ",", "")), "';' separated: use ','"),
        ("tab", format!("t_s\tx_m\n{}", body("\t", ".", "")), "tab separated: use ','"),
        ("decimal-comma", format!("t_s,x_m\n{}", body(",", ",", "")), "decimal comma"),
        ("trailing", format!("t_s,x_m,\n{}", body(",", ".", ",")), "column 3 of the header has no name"),
    ];
    for (name, text, needle) in cases {
        let file = home.path().join(format!("{name}.csv"));
        std::fs::write(&file, text).unwrap();
        let (code, out, err) =
            run(home.path(), &["fit", "structure", "--data", file.to_str().unwrap(), "--main-mass", "2"]);
        assert_eq!(code, 2, "{name}: {err}");
        assert!(out.is_empty(), "{name}: {out}");
        assert_eq!(err.lines().count(), 1, "{name}: {err}");
        assert!(err.contains("--data") && err.contains(needle), "{name}: {err}");
        assert!(!err.contains("needs t_s"), "{name}: {err}");
    }
}

/// Degenerate records are refused, never fitted with "± 0": a stray row at t = 1e305 s, a
/// signal in subnormal numbers.
#[test]
fn degenerate_records_are_refused_not_given_zero_errors() {
    let home = tempfile::tempdir().unwrap();
    let rows = decay_rows();
    let mut far = String::from("t_s,x_m\n");
    let mut tiny = String::from("t_s,x_m\n");
    for r in &rows {
        writeln!(far, "{},{}", r.0, r.1).unwrap();
        writeln!(tiny, "{},{:e}", r.0, r.1 * 1e-305).unwrap();
    }
    writeln!(far, "1e305,0.0001").unwrap();
    for (name, text, needle) in [("far", far, "1e305"), ("tiny", tiny, "spans only")] {
        let file = home.path().join(format!("{name}.csv"));
        std::fs::write(&file, text).unwrap();
        let (code, out, err) =
            run(home.path(), &["fit", "structure", "--data", file.to_str().unwrap(), "--main-mass", "2"]);
        assert_eq!(code, 2, "{name}: {out} {err}");
        assert!(!out.contains("± 0\n") && !out.contains("± 0 "), "{name}: {out}");
        assert!(err.contains("--data") && err.contains(needle), "{name}: {err}");
    }
}

/// `fit damper` takes only the flags a fit uses: c1 (fitted), the run's length (the
/// record's), the force, the ball's start (spread by the fit), the listener and the zones are
/// refused by the parser (exit 2, naming the flag), not silently ignored.
#[test]
fn fit_damper_refuses_the_flags_a_fit_does_not_use() {
    let home = tempfile::tempdir().unwrap();
    for (flag, value) in [
        ("--c1", Some("5")),
        ("--ball-position", Some("0")),
        ("--ball-velocity", Some("0")),
        ("--duration", Some("1")),
        ("--force", Some("1")),
        ("--freq", Some("5")),
        ("--r", Some("1")),
        ("--l-star", Some("80")),
        ("--settle", None),
    ] {
        let mut args = vec!["fit", "damper", "--data", "x.csv", flag];
        args.extend(value);
        let (code, out, err) = run(home.path(), &args);
        assert_eq!(code, 2, "{flag}: {err}");
        assert!(out.is_empty(), "{flag}");
        assert!(err.contains(&format!("'{flag}'")), "{flag}: {err}");
    }
}

/// A fitted structure is a design every command loads: `fit structure --save s.toml`, then
/// `simulate --design s.toml` replays the record (an independent closed form) to its noise
/// level, and `fit damper --design s.toml` needs no structure flags (only the damper's);
/// every command that takes a design takes `--design`, refusing a missing file naming it.
#[test]
fn a_fitted_structure_loads_with_design_everywhere() {
    let home = tempfile::tempdir().unwrap();
    let rows = decay_rows();
    let mut text = String::from("t_s,x_m\n");
    for r in &rows {
        writeln!(text, "{},{}", r.0, r.1).unwrap();
    }
    let rec = home.path().join("rec.csv");
    std::fs::write(&rec, text).unwrap();
    let saved = home.path().join("s.toml");
    let s = saved.to_str().unwrap();
    let (code, out, err) = run(
        home.path(),
        &["fit", "structure", "--data", rec.to_str().unwrap(), "--main-mass", "2", "--save", s, "--json"],
    );
    assert_eq!(code, 0, "{err}");
    let fitted: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert!(std::fs::read_to_string(&saved).unwrap().contains("stiffness_n_m"));
    // Never replaced without being asked.
    let (code, _, err) =
        run(home.path(), &["fit", "structure", "--data", rec.to_str().unwrap(), "--main-mass", "2", "--save", s]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--save"), "{err}");
    // The replay at the record's own times.
    let samples = rows.len().to_string();
    let (code, csv, err) = run(home.path(), &["simulate", "--design", s, "--csv", "--samples", &samples]);
    assert_eq!(code, 0, "{err}");
    let replay: Vec<(f64, f64)> = csv
        .lines()
        .skip(1)
        .map(|l| {
            let c: Vec<f64> = l.split(',').map(|v| v.parse().unwrap()).collect();
            (c[0], c[1])
        })
        .collect();
    assert_eq!(replay.len(), rows.len());
    let mut sq = 0.0;
    for (r, p) in rows.iter().zip(&replay) {
        assert!((r.0 - p.0).abs() < 1e-9, "t {} vs {}", r.0, p.0);
        sq += (r.1 - p.1).powi(2);
    }
    let rms = (sq / rows.len() as f64).sqrt();
    let residual = fitted["residual_rms"].as_f64().unwrap();
    assert!(rms <= 1.5 * residual, "replay rms {rms} vs the fit's residual {residual}");
    // A damper on the fitted structure, fitted with the file and the damper's flags only.
    let damper = ["--gap", "2mm", "--mass", "50g"];
    let mut sim =
        vec!["simulate", "--design", s, "--c1", "40", "--ball-position", "0.0003", "--csv", "--samples", "6001"];
    sim.extend(damper);
    let (code, csv, err) = run(home.path(), &sim);
    assert_eq!(code, 0, "{err}");
    let strike = home.path().join("strike.csv");
    std::fs::write(&strike, csv).unwrap();
    let mut fit = vec!["fit", "damper", "--design", s, "--data", strike.to_str().unwrap(), "--json"];
    fit.extend(damper);
    let (code, from_file, err) = run(home.path(), &fit);
    assert_eq!(code, 0, "{err}");
    // The same fit with the structure typed as flags (the fitted K and C, the file's v0).
    let toml = std::fs::read_to_string(&saved).unwrap();
    let v0 = toml.lines().find_map(|l| l.strip_prefix("v0_m_s = ")).unwrap().trim().to_string();
    // The file carries the fit's standard errors of K and C; typed, they are `±`.
    assert!(toml.contains("[uncertainty]"), "{toml}");
    let pm = |key: &str| format!("{}±{}", fitted[key], fitted[format!("{key}_stderr")]);
    let (k, c) = (pm("k_n_m"), pm("c_n_s_m"));
    let mut typed = vec!["fit", "damper", "--main-mass", "2", "--k", &k, "--c", &c, "--v0", &v0];
    typed.extend(["--data", strike.to_str().unwrap(), "--json"]);
    typed.extend(damper);
    let (code, from_flags, err) = run(home.path(), &typed);
    assert_eq!(code, 0, "{err}");
    let (a, b): (serde_json::Value, serde_json::Value) =
        (serde_json::from_str(&from_file).unwrap(), serde_json::from_str(&from_flags).unwrap());
    assert!(a["c1_n_s_m_ci"].is_array() && a["c1_n_s_m"].as_f64().unwrap() > 0.0, "{from_file}");
    assert_eq!(a, b, "--design s.toml and the same structure as flags differ");
    // Every command that takes a design takes --design.
    for cmd in [
        &["simulate"][..],
        &["response"],
        &["sweep"],
        &["impact-map"],
        &["basins"],
        &["pulse"],
        &["restitution"],
        &["fit", "damper", "--data", "x.csv"],
    ] {
        let mut args = cmd.to_vec();
        args.extend(["--design", "missing.toml"]);
        let (code, _, err) = run(home.path(), &args);
        assert_eq!(code, 2, "{cmd:?}: {err}");
        assert!(err.contains("--design") && err.contains("missing.toml"), "{cmd:?}: {err}");
    }
    // --design and --preset are two starting designs: one at a time.
    let (code, _, err) = run(home.path(), &["simulate", "--design", s, "--preset", "default"]);
    assert_eq!(code, 2, "{err}");
}

/// The inputs' uncertainty in the interval: a record of M 0.525 kg (c1 60 N·s/m, struck at
/// 1.4 m/s) fitted with `--main-mass 0.5kg±5%`, and one fitted with `--v0 1.54m/s+-10%` (10 %
/// off), and one with `--v0 1.54` (10 % off, no uncertainty stated: the record's own strike
/// disagrees, a one-line warning says so and the difference is carried): each interval holds
/// the truth, the JSON names the input it carried and v0 read from the record is within 2 %
/// of 1.4 m/s. A `±` that is not a number is refused in one line naming the flag.
#[test]
fn the_inputs_uncertainty_widens_the_interval() {
    let home = tempfile::tempdir().unwrap();
    let record = |name: &str, extra: &[&str]| {
        let mut args = vec!["simulate", "--c1", "60", "--v0", "1.4", "--csv", "--samples", "6001"];
        args.extend(extra);
        let (code, csv, err) = run(home.path(), &args);
        assert_eq!(code, 0, "{err}");
        let file = home.path().join(name);
        std::fs::write(&file, csv).unwrap();
        file
    };
    let heavy = record("heavy.csv", &["--main-mass", "0.525", "--ball-position", "0.004"]);
    let plain = record("plain.csv", &["--ball-position", "0.004"]);
    for (file, flags, input) in [
        (&heavy, ["--main-mass", "0.5kg±5%", "--v0", "1.4"], "main-mass"),
        (&plain, ["--v0", "1.54m/s+-10%", "--main-mass", "0.5"], "v0"),
        // 10 % off with no uncertainty stated: the record's strike disagrees, says so in one
        // line and carries the difference.
        (&plain, ["--v0", "1.54", "--main-mass", "0.5"], "v0"),
    ] {
        let mut args = vec!["fit", "damper", "--data", file.to_str().unwrap(), "--json"];
        args.extend(flags);
        let (code, out, err) = run(home.path(), &args);
        assert_eq!(code, 0, "{err}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        let ci = v["c1_n_s_m_ci"].as_array().unwrap();
        let (lo, hi) = (ci[0].as_f64().unwrap(), ci[1].as_f64().unwrap());
        assert!(lo <= 60.0 && 60.0 <= hi, "{flags:?}: [{lo}, {hi}]");
        let carried: Vec<&str> = v["inputs"].as_array().unwrap().iter().map(|i| i["input"].as_str().unwrap()).collect();
        assert_eq!(carried, [input], "{out}");
        // v0 read from the record's strike: 1.4 m/s within 2 % where the design's M is the
        // record's (the reading uses M: 5 % off in M reads it 7 % high, and M's uncertainty
        // is carried into the reading's, so it is not a disagreement).
        let read = v["v0_m_s_record"].as_f64().unwrap();
        if file == &plain {
            assert!((read / 1.4 - 1.0).abs() <= 0.02, "{flags:?}: {read}");
        }
        assert!(v["v0_m_s_record_stderr"].as_f64().unwrap() > 0.0, "{out}");
        let warned = flags[1] == "1.54";
        assert_eq!(err.contains("strike was"), warned, "{flags:?}: {err}");
        if warned {
            assert_eq!(err.lines().count(), 1, "{err}");
            assert!(err.contains("1.54"), "{err}");
        }
    }
    // The text names it too.
    let (code, text, err) = run(home.path(), &["fit", "damper", "--data", plain.to_str().unwrap(), "--v0", "1.4"]);
    assert_eq!(code, 0, "{err}");
    assert!(text.contains("v0 of the record's strike"), "{text}");
    let (code, _, err) =
        run(home.path(), &["fit", "damper", "--data", plain.to_str().unwrap(), "--main-mass", "0.5kg±two%"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("main-mass") && err.contains("0.5kg±two%") && err.trim().lines().count() == 1, "{err}");
}
