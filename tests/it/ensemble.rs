#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test or benchmark fails
//! `--ensemble N`: N runs of a design from ball offsets spread over the clearance. Each run is
//! the single run with the ball at its offset; N = 1 is today's output exactly; the spread,
//! zone, zone-3 probability and agreement are what the runs say (recomputed here from the
//! per-run values with an independent nearest-rank percentile).

use crate::common;
use common::thud;

use serde_json::Value;
use thud::design::{self, Design, Thresholds, Zone};
use thud::ensemble;

fn ok(args: &[&str]) -> String {
    let (code, out, err) = thud(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    out
}

#[test]
fn an_ensemble_of_one_is_today_s_output_exactly() {
    for format in [&[][..], &["--json"], &["--csv"]] {
        let plain: Vec<&str> = ["simulate", "--preset", "paper-fig9"].iter().chain(format).copied().collect();
        let one: Vec<&str> = plain.iter().chain(&["--ensemble", "1"]).copied().collect();
        assert!(ok(&one) == ok(&plain), "simulate {format:?}");
    }
    let grid = ["sweep", "--masses", "30g:100g:4", "--gaps", "2cm:5cm:3", "--duration", "1"];
    for format in [&[][..], &["--json"], &["--csv"]] {
        let plain: Vec<&str> = grid.iter().chain(format).copied().collect();
        let one: Vec<&str> = plain.iter().chain(&["--ensemble", "1"]).copied().collect();
        assert!(ok(&one) == ok(&plain), "sweep {format:?}");
    }
}

/// The Fig 9 design over its whole 2 s, 16 runs: each run is `design::evaluate` of the design
/// with the ball at that run's offset.
#[test]
fn each_run_is_the_single_run_from_its_offset() {
    let d = Design::paper_fig9();
    let e = ensemble::evaluate(&d.clone().check().unwrap(), 16, None).unwrap().unwrap();
    let offsets = ensemble::ball_positions(d.damper.gap_m, 16);
    assert_eq!(offsets[0], -0.02 + 0.04 / 32.0);
    for (m, y0) in e.ensemble.iter().zip(&offsets) {
        let mut alone = d.clone();
        alone.damper.ball_position_m = *y0;
        let single = design::evaluate(&alone.check().unwrap(), 0, None).unwrap();
        assert_eq!(m.ball_position_m, *y0);
        assert_eq!(m.metrics, single.metrics, "y0 {y0}");
        assert_eq!(m.truncated, single.run.truncated);
    }
}

/// The p-th percentile by nearest rank, written out here apart from the engine: sort with the
/// runs lacking the value first, take rank ⌈p·N/100⌉.
fn nearest_rank(values: &[Option<f64>], p: usize) -> Option<f64> {
    let mut v = values.to_vec();
    v.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let rank = ((p * v.len()) as f64 / 100.0 - 1e-12).ceil().max(1.0) as usize;
    v[rank - 1]
}

fn num(v: &Value) -> Option<f64> {
    v.as_f64()
}

/// Checks one ensemble (`runs`: the per-run objects) against its summary: the spread of each
/// metric, the zone of the medians, the zone-3 probability and the agreement.
fn check_summary(runs: &[Value], spread: &Value, zone: Option<u8>, zone3: f64, agreement: f64, t: &Thresholds) {
    let col = |k: &str| runs.iter().map(|r| num(&r[k])).collect::<Vec<_>>();
    for key in ["inclination_cm_s", "inclination_fit_cm_s", "u0_max_m_s", "spl_max_db"] {
        let v = col(key);
        for (p, name) in [(10, "p10"), (50, "median"), (90, "p90")] {
            assert_eq!(num(&spread[key][name]), nearest_rank(&v, p), "{key} {name}");
        }
    }
    let e_key = match t.zone_by {
        design::ZoneBy::Paper => "inclination_cm_s",
        design::ZoneBy::Fit => "inclination_fit_cm_s",
    };
    let want = match (nearest_rank(&col("spl_max_db"), 50), nearest_rank(&col(e_key), 50)) {
        (Some(spl), Some(e)) => Some(Zone::classify(spl, e, t).number()),
        _ => None,
    };
    assert_eq!(zone, want, "the zone is that of the medians");
    let zones: Vec<Option<u64>> = runs.iter().map(|r| r["zone"].as_u64()).collect();
    let n = runs.len() as f64;
    assert_eq!(zone3, zones.iter().filter(|z| **z == Some(3)).count() as f64 / n);
    assert_eq!(agreement, zones.iter().filter(|z| z.map(|z| z as u8) == zone).count() as f64 / n);
}

#[test]
fn simulate_json_lists_every_run_and_the_spread_they_give() {
    let out = ok(&["simulate", "--preset", "paper-fig9", "--ensemble", "16", "--json"]);
    let v: Value = serde_json::from_str(&out).unwrap();
    let runs = v["ensemble"].as_array().unwrap();
    assert_eq!(runs.len(), 16);
    assert_eq!(v["runs"], 16);
    for r in runs {
        for key in ["ball_position_m", "u0_max_m_s", "spl_max_db", "inclination_cm_s", "inclination_fit_cm_s", "zone"] {
            assert!(!r[key].is_null(), "every run of Fig 9 has {key}: {r}");
        }
    }
    let d: Design = serde_json::from_value(v["design"].clone()).unwrap();
    for (r, y0) in runs.iter().zip(ensemble::ball_positions(d.damper.gap_m, 16)) {
        assert_eq!(num(&r["ball_position_m"]), Some(y0));
        let mut alone = d.clone();
        alone.damper.ball_position_m = y0;
        let m = design::evaluate(&alone.check().unwrap(), 0, None).unwrap().metrics;
        assert_eq!(num(&r["inclination_cm_s"]), m.inclination_cm_s, "y0 {y0}");
        assert_eq!(num(&r["spl_max_db"]), m.spl_max_db, "y0 {y0}");
        assert_eq!(r["zone"].as_u64(), m.zone.map(|z| u64::from(z.number())));
    }
    let zone = v["zone"].as_u64().map(|z| z as u8);
    let (z3, agree) = (v["zone3_probability"].as_f64().unwrap(), v["agreement"].as_f64().unwrap());
    check_summary(runs, &v["spread"], zone, z3, agree, &d.thresholds);
    let es: Vec<f64> = runs.iter().filter_map(|r| r["inclination_cm_s"].as_f64()).collect();
    assert!(es.iter().any(|&e| (e - es[0]).abs() > 0.1), "the offsets spread e (Eq 27): {es:?}");

    let text = ok(&["simulate", "--preset", "paper-fig9", "--ensemble", "16"]);
    let p = &v["spread"]["inclination_fit_cm_s"];
    let line = format!(
        "e_fit {:.4} cm/s [{:.4}–{:.4}]",
        p["median"].as_f64().unwrap(),
        p["p10"].as_f64().unwrap(),
        p["p90"].as_f64().unwrap()
    );
    assert!(text.contains(&line), "the summary shows the spread: {line}\n{text}");
}

#[test]
fn each_sweep_cell_is_the_zone_of_its_medians_with_its_zone3_probability() {
    let out = ok(&[
        "sweep",
        "--masses",
        "30g:100g:3",
        "--gaps",
        "1cm:3cm:3",
        "--duration",
        "1",
        "--ensemble",
        "5",
        "--l-star",
        "105",
        "--e-star",
        "0.5",
        "--json",
    ]);
    let v: Value = serde_json::from_str(&out).unwrap();
    let d: Design = serde_json::from_value(v["design"].clone()).unwrap();
    let cells = v["chart"]["cells"].as_array().unwrap();
    assert_eq!(cells.len(), 9);
    let mut zones = std::collections::BTreeSet::new();
    for c in cells {
        let runs = c["ensemble"].as_array().unwrap();
        assert_eq!(runs.len(), 5);
        let zone = c["metrics"]["zone"].as_u64().map(|z| z as u8);
        assert!(zone.is_some() || c["metrics"]["zone"].is_null(), "a zone is its number 1–4");
        zones.insert(zone);
        let (z3, agree) = (c["zone3_probability"].as_f64().unwrap(), c["agreement"].as_f64().unwrap());
        check_summary(runs, &c["spread"], zone, z3, agree, &d.thresholds);
        assert_eq!(num(&c["metrics"]["spl_max_db"]), num(&c["spread"]["spl_max_db"]["median"]));
    }
    assert!(zones.len() > 1, "the thresholds split this chart: {zones:?}");
    let csv = ok(&[
        "sweep",
        "--masses",
        "30g:100g:3",
        "--gaps",
        "1cm:3cm:3",
        "--duration",
        "1",
        "--ensemble",
        "5",
        "--l-star",
        "105",
        "--e-star",
        "0.5",
        "--csv",
    ]);
    let head = csv.lines().next().unwrap();
    assert!(
        head.starts_with("mass_kg,gap_m,runs,n_impacts,inclination_cm_s,")
            && head.ends_with(",zone3_probability,agreement")
    );
    assert_eq!(csv.lines().count(), 10);
}

#[test]
fn bad_or_too_large_ensembles_are_refused_in_one_line() {
    for bad in ["0", "1001", "2.5", "abc", "-3"] {
        for cmd in ["simulate", "sweep"] {
            let (code, out, err) = thud(&[cmd, "--ensemble", bad]);
            assert_eq!(code, 2, "{cmd} {bad}");
            assert!(out.is_empty());
            assert_eq!(err.lines().count(), 1, "{err}");
            assert!(err.starts_with("thud: invalid --ensemble: "), "{cmd} {bad}: {err}");
        }
    }
    let (code, _, err) = thud(&["sweep", "--ensemble", "1000"]);
    assert_eq!(code, 2);
    assert!(err.starts_with("thud: --ensemble 1000: 4e5 runs (cells × ensemble) exceed the limit of 1e5"), "{err}");
    let (code, _, err) = thud(&["simulate", "--ensemble", "1000", "--duration", "1000"]);
    assert_eq!(code, 2);
    assert!(err.starts_with("thud: --duration 1000: 1e6 simulated run-seconds exceed the limit of 2e5"), "{err}");
}

/// `simulate --ensemble N --json`: run k is exactly `simulate --ball-position y0_k --json`, the
/// offsets y0_k = −d/2 + (k + ½)·d/N written out here (d = 4 cm of the Fig 9 preset).
#[test]
fn each_run_equals_a_separate_simulate_from_its_offset() {
    let base = ["simulate", "--preset", "paper-fig9", "--duration", "0.6"];
    let json = |extra: &[&str]| -> Value {
        let args: Vec<&str> = base.iter().chain(extra).chain(&["--json"]).copied().collect();
        serde_json::from_str(&ok(&args)).unwrap()
    };
    let d = 0.04;
    for n in [3usize, 4] {
        let n_text = n.to_string();
        let v = json(&["--ensemble", &n_text]);
        let runs = v["ensemble"].as_array().unwrap();
        assert_eq!(runs.len(), n);
        for (k, r) in runs.iter().enumerate() {
            let y0 = -d / 2.0 + (k as f64 + 0.5) * d / n as f64;
            assert_eq!(r["ball_position_m"].as_f64(), Some(y0), "N {n}, k {k}");
            let alone = json(&["--ball-position", &format!("{y0:?}")]);
            for key in ["u0_max_m_s", "spl_max_db", "inclination_cm_s", "inclination_fit_cm_s", "zone", "n_impacts"] {
                assert_eq!(r[key], alone[key], "N {n}, k {k}: {key}");
            }
        }
    }
    // N = 1 is today's single run, whatever the output.
    for format in [&[][..], &["--json"], &["--csv"]] {
        let plain: Vec<&str> = base.iter().chain(format).copied().collect();
        let one: Vec<&str> = plain.iter().chain(&["--ensemble", "1"]).copied().collect();
        assert!(ok(&one) == ok(&plain), "simulate {format:?}");
    }
}

#[test]
fn an_ensemble_with_a_ball_position_is_refused_naming_both() {
    for args in [
        &["simulate", "--ensemble", "4", "--ball-position", "1cm"][..],
        &["sweep", "--masses", "30g:40g:2", "--gaps", "3cm:4cm:2", "--ensemble", "2", "--ball-position", "0"],
        &["response", "--force-amplitude", "1N", "--freqs", "4Hz:5Hz:2", "--ensemble", "3", "--ball-position", "-1cm"],
    ] {
        let (code, out, err) = thud(args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(out.is_empty());
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.starts_with("thud: invalid --ball-position: cannot be combined with --ensemble "), "{err}");
    }
    // One run is the single trajectory: the offset typed is kept.
    let v: Value = serde_json::from_str(&ok(&[
        "simulate",
        "--duration",
        "0.2",
        "--ensemble",
        "1",
        "--ball-position",
        "1cm",
        "--json",
    ]))
    .unwrap();
    assert_eq!(v["design"]["damper"]["ball_position_m"].as_f64(), Some(0.01));
}

/// `response --ensemble N`: every run at every frequency is `response --ball-position y0_k
/// --v0 0` (from rest),
/// and each frequency's p10/median/p90 are the nearest-rank percentiles of those runs.
#[test]
fn a_response_ensemble_is_its_runs_and_their_spread() {
    let base = ["response", "--force-amplitude", "1N", "--freqs", "4.6Hz:5.4Hz:3", "--periods", "4", "--duration", "1"];
    let json = |extra: &[&str]| -> Value {
        let args: Vec<&str> = base.iter().chain(extra).chain(&["--json"]).copied().collect();
        serde_json::from_str(&ok(&args)).unwrap()
    };
    let n = 3;
    let v = json(&["--ensemble", "3"]);
    assert_eq!(v["runs"], 3);
    let points = v["sweeps"][0]["points"].as_array().unwrap();
    assert_eq!(points.len(), 3);
    let d = v["design"]["damper"]["gap_m"].as_f64().unwrap();
    let steady = ["amplitude_m", "reduction_db", "impacts_per_period", "leq_db", "periodic", "settled", "final_time_s"];
    for k in 0..n {
        let y0 = -d / 2.0 + (k as f64 + 0.5) * d / n as f64;
        // From rest, as the ensemble's runs (a typed start otherwise keeps the preset's v0).
        let alone = json(&["--ball-position", &format!("{y0:?}"), "--v0", "0"]);
        for (p, q) in points.iter().zip(alone["sweeps"][0]["points"].as_array().unwrap()) {
            let run = &p["ensemble"][k];
            assert_eq!(run["ball_position_m"].as_f64(), Some(y0));
            assert_eq!(p["freq_hz"], q["freq_hz"]);
            for key in steady {
                assert_eq!(run[key], q[key], "k {k}, f {}: {key}", p["freq_hz"]);
            }
        }
    }
    for p in points {
        let runs = p["ensemble"].as_array().unwrap();
        for key in ["amplitude_m", "impacts_per_period", "leq_db"] {
            let col: Vec<Option<f64>> = runs.iter().map(|r| r[key].as_f64()).collect();
            for (pct, name) in [(10, "p10"), (50, "median"), (90, "p90")] {
                assert_eq!(p["spread"][key][name].as_f64(), nearest_rank(&col, pct), "{key} {name}");
            }
        }
        // The cut is the amplitude's runs' (the cut falls as the amplitude grows).
        for (cut, amp) in [("p10", "p90"), ("median", "median"), ("p90", "p10")] {
            let a = p["spread"]["amplitude_m"][amp].as_f64();
            let run = runs.iter().find(|r| r["amplitude_m"].as_f64() == a).unwrap();
            assert_eq!(p["spread"]["reduction_db"][cut], run["reduction_db"], "cut {cut}: the amplitude's {amp} run");
        }
    }
    let runs_seen: Vec<f64> = points.iter().map(|p| p["spread"]["amplitude_m"]["p90"].as_f64().unwrap()).collect();
    assert!(runs_seen.iter().all(|a| a.is_finite() && *a > 0.0));
    // N = 1 is the plain response; text and CSV show the spread.
    assert!(ok(&[&base[..], &["--ensemble", "1", "--json"]].concat()) == ok(&[&base[..], &["--json"]].concat()));
    let text = ok(&[&base[..], &["--ensemble", "3"]].concat());
    assert!(text.contains("ensemble  3 runs a frequency") && text.contains("median [p10–p90]"), "{text}");
    let csv = ok(&[&base[..], &["--ensemble", "3", "--csv"]].concat());
    assert!(csv.starts_with("direction,freq_hz,runs,amplitude_linear_m,amplitude_m_p10,amplitude_m_median,"), "{csv}");
    assert_eq!(csv.lines().count(), 4);
    // The work is capped over all the runs, before any starts.
    let (code, _, err) =
        thud(&["response", "--force-amplitude", "1", "--freqs", "3:8:1000", "--periods", "100", "--ensemble", "10"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("forcing periods"), "{err}");
}
