#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! Without a force every output is the one thud 0.1 wrote (commit 60914cd, before forcing
//! existed; the files in tests/data/unforced were written by that build, with the Dormand–Prince
//! contact scheme, today's reference): the Fig 9 run as JSON, text and CSV, the Table 3 set-up,
//! a Newmark run and a sweep — but the design block's renamed keys and enums, and the numbers
//! the default contact scheme (Sundman–Adams, docs/model.md §11) moves within
//! its accuracy.
//!
//! What is compared:
//!
//! - **Byte for byte**: the Newmark run (no contact scheme) and the Table 3 run (`no_tension`,
//!   which falls back to the reference scheme); and in every other file everything but the
//!   numbers: the same text, keys, order and number of values ([`split`]), each number in the
//!   same format (in the text output the same width and decimals; in JSON and CSV, written in
//!   their shortest round-trip form, the same kind: integer, decimal or exponent).
//! - **Within the acceptance for a new contact scheme**, on the motion up to the end of the
//!   Fig 9 run's 8th impact (the horizon of that acceptance, [`HORIZON_IMPACTS`]): impact speeds
//!   within [`SPEED_M_S`]; every other number of that motion (times, restitutions, durations,
//!   penetrations, SPLs, cycle maxima, sampled positions) within [`REL`]; the largest impact
//!   (`U0max`, `|z'|max`, its SPL and contact time), one of the strike's first impacts, likewise in
//!   every run; the design echoes, the initial energy, the time grid and the structure's own motion
//!   `x_free` (closed form) and the Fig 9 run's impact count (also fixed by the number of values)
//!   exactly; each run's zone (the chart's verdicts) unchanged; the new run's energy ledger closed
//!   to [`LEDGER`] of its initial energy (0.1's own is open by 2.8e-9). Numbers rounded for print
//!   get one more unit in their last place (half a unit for each of the two roundings).
//! - **Not compared, past the horizon**: the later impacts and everything made of them (e,
//!   e_fit, the mean restitution, the impact count of a sweep's cell, the final energies, the
//!   later maxima and samples). The Fig 9 rattle amplifies any difference about tenfold every
//!   four or five impacts, and the reference errs by ~1e-9 a contact, so two schemes as accurate
//!   as each other part by ~1e-3 m/s by the end of the 2 s run (docs/model.md §11,
//!   tests/it/contact_scheme.rs): 0.1's own late numbers are uncertain at that level (measured
//!   here: the impact speeds agree to 1.5e-8 m/s up to the 8th impact, 2e-7 by the 16th, 1.5e-3
//!   by the 38th). Their format and count are still compared.

use std::path::Path;

use serde_json::Value;

use crate::common;

/// Impact speeds (m/s) within this of 0.1's: the acceptance for a new contact scheme.
const SPEED_M_S: f64 = 5e-8;

/// Impacts of the Fig 9 run that acceptance covers (its first 8: past them the rattle has
/// amplified the schemes' own errors beyond it; tests/it/contact_sundman.rs).
const HORIZON_IMPACTS: usize = 8;

/// Every other number of the motion within the horizon, relative (or relative to its column's
/// scale, for a sampled position). From [`SPEED_M_S`]: over the slowest impact in the horizon
/// (0.76 m/s) it is 6.6e-8 of the speed; a restitution is a ratio of two speeds, and a contact's
/// duration, penetration and pressure go as powers of the speed no larger than 6/5 (Hertz:
/// `τ ∝ u^(−1/5)`, `α_max ∝ u^(4/5)`, `p ∝ u^(6/5)`), so none of them moves by more than twice
/// that, 1.3e-7, rounded up to 2e-7. (Measured: 1.1e-8 at most.)
const REL: f64 = 2e-7;

/// A run's energy ledger, `initial − final − dissipated`, relative to its initial energy.
const LEDGER: f64 = 1e-9;

/// How one number of the new output is held to 0.1's.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Check {
    /// Equal (as text, or as a value in JSON).
    Exact,
    /// Within this (absolute).
    Abs(f64),
    /// Within this times the value (or the scale given).
    Rel(f64),
    /// Past the horizon: format and count only.
    Late,
}

fn within(check: Check, want: f64, got: f64, scale: f64, unit: f64) -> bool {
    match check {
        Check::Exact => want == got,
        Check::Abs(t) => (want - got).abs() <= t + unit,
        Check::Rel(r) => (want - got).abs() <= r * scale.max(want.abs()) + unit,
        Check::Late => true,
    }
}

/// The text with every number replaced by `#`, and the numbers, in order. A number is an
/// optional `-`, digits, an optional fraction and an optional exponent, not preceded by a
/// letter, digit, `_` or `.` (so `u0_max`, `Eq 27`'s `Eq` and `K_HZ` stay text).
fn split(text: &str) -> (String, Vec<&str>) {
    let b = text.as_bytes();
    let digit = |i: usize| b.get(i).is_some_and(u8::is_ascii_digit);
    let (mut skeleton, mut nums, mut copied, mut i) = (String::new(), Vec::new(), 0, 0);
    while i < b.len() {
        let free = i == 0 || !(b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_' || b[i - 1] == b'.');
        if free && (digit(i) || (b[i] == b'-' && digit(i + 1))) {
            let mut j = i + 1;
            while digit(j) {
                j += 1;
            }
            if b.get(j) == Some(&b'.') && digit(j + 1) {
                j += 1;
                while digit(j) {
                    j += 1;
                }
            }
            if matches!(b.get(j), Some(b'e' | b'E')) {
                let k = if matches!(b.get(j + 1), Some(b'-' | b'+')) { j + 2 } else { j + 1 };
                if digit(k) {
                    j = k;
                    while digit(j) {
                        j += 1;
                    }
                }
            }
            skeleton.push_str(&text[copied..i]);
            skeleton.push('#');
            nums.push(&text[i..j]);
            (copied, i) = (j, j);
        } else {
            i += 1;
        }
    }
    skeleton.push_str(&text[copied..]);
    (skeleton, nums)
}

/// Decimals of a number as printed.
fn decimals(s: &str) -> usize {
    s.split(['e', 'E']).next().and_then(|m| m.split_once('.')).map_or(0, |(_, f)| f.len())
}

/// The same text but the numbers, each number in the same format: `fixed` (the text output)
/// the same width and decimals; otherwise the same kind (integer, decimal, exponent). Returns
/// the number pairs.
fn same_but_numbers<'a>(want: &'a str, got: &'a str, fixed: bool) -> Result<Vec<(&'a str, &'a str)>, String> {
    let ((ws, wn), (gs, gn)) = (split(want), split(got));
    if ws != gs {
        let line = ws.lines().zip(gs.lines()).position(|(a, b)| a != b);
        return Err(format!("the text differs (line {line:?}, numbers as #)"));
    }
    if wn.len() != gn.len() {
        return Err(format!("{} numbers against {}", gn.len(), wn.len()));
    }
    let kind = |s: &str| (s.contains('.'), s.contains(['e', 'E']), s.starts_with('-'));
    for (w, g) in wn.iter().zip(&gn) {
        let same = if fixed { w.len() == g.len() && decimals(w) == decimals(g) } else { kind(w) == kind(g) };
        if !same {
            return Err(format!("{g} is not written as {w}"));
        }
    }
    Ok(wn.into_iter().zip(gn).collect())
}

/// Every number of two JSON documents of the same shape, with its path (`impacts.3.u_in_m_s`).
fn leaves(path: &str, want: &Value, got: &Value, out: &mut Vec<(String, f64, f64)>) {
    match (want, got) {
        (Value::Object(w), Value::Object(g)) => {
            for (k, v) in w {
                let p = if path.is_empty() { k.clone() } else { format!("{path}.{k}") };
                leaves(&p, v, &g[k.as_str()], out);
            }
        }
        (Value::Array(w), Value::Array(g)) => {
            for (i, (a, b)) in w.iter().zip(g).enumerate() {
                leaves(&format!("{path}.{i}"), a, b, out);
            }
        }
        (Value::Number(a), Value::Number(b)) => out.push((path.to_string(), a.as_f64().unwrap(), b.as_f64().unwrap())),
        _ => assert_eq!(want, got, "{path}"),
    }
}

/// A JSON output against 0.1's: the text but the numbers, then each number by `rule(path)`.
fn compare_json(want: &str, got: &str, rule: impl Fn(&str, &Value) -> Check) -> Result<(), String> {
    same_but_numbers(want, got, false)?;
    let (w, g): (Value, Value) = (serde_json::from_str(want).unwrap(), serde_json::from_str(got).unwrap());
    let mut all = Vec::new();
    leaves("", &w, &g, &mut all);
    for (path, a, b) in all {
        let check = rule(&path, &w);
        if !within(check, a, b, 0.0, 0.0) {
            return Err(format!("{path}: {b} against 0.1's {a} ({check:?})"));
        }
    }
    Ok(())
}

/// A run's energy ledger (its JSON) closed to [`LEDGER`] of its initial energy.
fn ledger(run: &str) -> Result<(), String> {
    let v: Value = serde_json::from_str(run).unwrap();
    let f = |k: &str| v["energy"][k].as_f64().unwrap();
    let gap = f("initial_j") - f("final_mechanical_j") - f("dissipated_viscous_j") - f("dissipated_contact_j");
    if gap.abs() > LEDGER * f("initial_j") {
        return Err(format!("the ledger is open by {gap:e} J"));
    }
    Ok(())
}

/// The end (s) of the Fig 9 run's last impact within the horizon, in 0.1's JSON.
fn horizon_s(fig9: &Value) -> f64 {
    fig9["impacts"][HORIZON_IMPACTS - 1]["t_end_s"].as_f64().unwrap()
}

/// The checks of the Fig 9 run's JSON, by path.
fn fig9_rule(path: &str, want: &Value) -> Check {
    let parts: Vec<&str> = path.split('.').collect();
    match parts.as_slice() {
        ["design", ..] | ["ball_radius_m" | "final_time_s" | "n_impacts" | "zone"] | ["energy", "initial_j"] => {
            Check::Exact
        }
        ["u0_max_m_s" | "zdot_abs_max_m_s"] => Check::Abs(SPEED_M_S),
        ["spl_max_db" | "contact_duration_s"] => Check::Rel(REL),
        ["impacts", i, key] if i.parse::<usize>().unwrap() < HORIZON_IMPACTS => match *key {
            "u_in_m_s" | "u_out_m_s" => Check::Abs(SPEED_M_S),
            "wall" => Check::Exact,
            _ => Check::Rel(REL),
        },
        ["maxima", j, _] if want["maxima"][j.parse::<usize>().unwrap()]["t_s"].as_f64().unwrap() < horizon_s(want) => {
            Check::Rel(REL)
        }
        _ => Check::Late,
    }
}

/// The checks of the sweep's JSON, by path: each cell's largest impact and zone; the rest late.
fn sweep_rule(path: &str, _: &Value) -> Check {
    let parts: Vec<&str> = path.split('.').collect();
    match parts.as_slice() {
        ["design", ..] | ["chart", "masses_kg" | "gaps_m" | "thresholds", ..] => Check::Exact,
        ["chart", "cells", _, "mass_kg" | "gap_m"] => Check::Exact,
        ["chart", "cells", _, "metrics", key] => match *key {
            "u0_max_m_s" | "zdot_abs_max_m_s" => Check::Abs(SPEED_M_S),
            "spl_max_db" | "contact_duration_s" => Check::Rel(REL),
            "zone" => Check::Exact,
            _ => Check::Late,
        },
        _ => Check::Late,
    }
}

/// The Fig 9 run's text output against 0.1's, line by line (`horizon_s` from 0.1's JSON).
fn compare_text(want: &str, got: &str, horizon_s: f64) -> Result<(), String> {
    // The design's and the listener's lines print each value as typed now (0.1 printed
    // `0.5000`): their text the same but the numbers, which are compared as values below; every
    // other line's numbers also in 0.1's format.
    let typed = |l: &str| l.starts_with("design") || l.starts_with("listener");
    let lines = |t: &str, keep: bool| t.lines().filter(|l| typed(l) == keep).collect::<Vec<_>>().join("\n");
    same_but_numbers(&lines(want, false), &lines(got, false), true)?;
    if split(&lines(want, true)).0 != split(&lines(got, true)).0 {
        return Err("the design's or the listener's line differs (numbers as #)".into());
    }
    for (wl, gl) in want.lines().zip(got.lines()) {
        let ((_, wn), (_, gn)) = (split(wl), split(gl));
        let head = wl.split_whitespace().next().unwrap_or("");
        let checks: Vec<Check> = match head {
            "design" | "listener" => vec![Check::Exact; wn.len()],
            "noise" => vec![Check::Abs(SPEED_M_S), Check::Rel(REL), Check::Rel(REL), Check::Exact],
            "energy" => [Check::Exact].into_iter().chain(std::iter::repeat(Check::Late)).take(wn.len()).collect(),
            "impacts" => vec![Check::Exact; wn.len()],
            "maxima" => wn
                .chunks(2)
                .flat_map(|xt| {
                    let early = xt[1].parse::<f64>().unwrap() < horizon_s;
                    [if early { Check::Rel(REL) } else { Check::Late }; 2]
                })
                .collect(),
            n if n.parse::<usize>().is_ok_and(|k| k <= HORIZON_IMPACTS) => {
                let (r, s) = (Check::Rel(REL), Check::Abs(SPEED_M_S));
                vec![Check::Exact, r, Check::Exact, s, s, r, r, r, r]
            }
            _ => vec![Check::Late; wn.len()],
        };
        if checks.len() != wn.len() {
            return Err(format!("{} numbers in {wl}", wn.len()));
        }
        for ((w, g), check) in wn.iter().zip(&gn).zip(checks) {
            // Each side is rounded to half a unit of its last place.
            let unit = if check == Check::Exact { 0.0 } else { 10f64.powi(-i32::try_from(decimals(w)).unwrap()) };
            let (a, b) = (w.parse::<f64>().unwrap(), g.parse::<f64>().unwrap());
            // The design's values are printed as typed now (`0.5`, 0.1 printed `0.5000`): equal
            // as values there, as text everywhere else.
            let as_text = !matches!(head, "design" | "listener");
            if !within(check, a, b, 0.0, unit) || (check == Check::Exact && as_text && w != g) {
                return Err(format!("{g} against 0.1's {w} ({check:?}) in {gl}"));
            }
        }
    }
    Ok(())
}

/// The Fig 9 run's samples (CSV `t_s,x_m,y_m,x_free_m`) against 0.1's: the time grid and the
/// structure alone (closed form) exactly; `x`, `y` within [`REL`] of their column's scale up to
/// `horizon_s`.
fn compare_csv(want: &str, got: &str, horizon_s: f64) -> Result<(), String> {
    same_but_numbers(want, got, false)?;
    let rows = |s: &str| -> Vec<Vec<f64>> {
        s.lines().skip(1).map(|l| l.split(',').map(|v| v.parse().unwrap()).collect()).collect()
    };
    let (w, g) = (rows(want), rows(got));
    let scale = |c: usize| w.iter().map(|r| r[c].abs()).fold(0.0, f64::max);
    for (a, b) in w.iter().zip(&g) {
        let early = a[0] <= horizon_s;
        for c in 0..4 {
            let check = match c {
                0 | 3 => Check::Exact,
                _ if early => Check::Rel(REL),
                _ => Check::Late,
            };
            if !within(check, a[c], b[c], scale(c), 0.0) {
                return Err(format!("t {} s, column {c}: {} against 0.1's {} ({check:?})", a[0], b[c], a[c]));
            }
        }
    }
    Ok(())
}

fn renamed_since_0_1(text: &str) -> String {
    text.replace("\"k_hz\": ", "\"k_hz_n_m1_5\": ")
        .replace("\"density\": ", "\"density_kg_m3\": ")
        .replace("\"pulse\": \"half_sine\"", "\"pulse\": \"half-sine\"")
        .replace("\"solver\": \"Event\"", "\"solver\": \"event\"")
        .replace("\"Newmark\": {", "\"newmark\": {")
}

fn ok(args: &[&str]) -> String {
    let home = tempfile::tempdir().unwrap();
    let (code, stdout, stderr) = common::thud_in(home.path(), args);
    assert_eq!(code, 0, "{args:?}: {stderr}");
    stdout
}

fn recorded(file: &str) -> String {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/unforced");
    renamed_since_0_1(&std::fs::read_to_string(data.join(file)).unwrap())
}

#[test]
fn unforced_outputs_are_those_of_0_1_within_the_contact_schemes_accuracy() {
    // No contact scheme, or the reference's: byte for byte.
    for (args, file) in [
        (vec!["simulate", "--preset", "paper-table3", "--no-tension", "--json"], "simulate_table3.json"),
        (vec!["simulate", "--solver", "newmark", "--duration", "0.05", "--json"], "simulate_newmark.json"),
    ] {
        assert!(ok(&args) == recorded(file), "{args:?} differs from {file}");
    }
    let want = recorded("simulate_fig9.json");
    let horizon = horizon_s(&serde_json::from_str(&want).unwrap());
    let got = ok(&["simulate", "--json"]);
    compare_json(&want, &got, fig9_rule).unwrap();
    ledger(&got).unwrap();
    compare_text(&recorded("simulate_fig9.txt"), &ok(&["simulate"]), horizon).unwrap();
    compare_csv(&recorded("simulate_fig9.csv"), &ok(&["simulate", "--csv", "--samples", "501"]), horizon).unwrap();
    let sweep = ok(&["sweep", "--masses", "30g:100g:5", "--gaps", "2cm:5cm:4", "--json"]);
    compare_json(&recorded("sweep.json"), &sweep, sweep_rule).unwrap();
    // A centred ball at rest and the default window, typed, change nothing; a frequency alone
    // (no force) changes no result (the design echoed in the output shows it).
    let same = ok(&["simulate", "--json", "--ball-position", "0", "--ball-velocity", "0", "--periods", "10"]);
    assert!(same == got);
    let mut with_freq: Value = serde_json::from_str(&ok(&["simulate", "--json", "--freq", "5Hz"])).unwrap();
    let mut plain: Value = serde_json::from_str(&got).unwrap();
    assert_eq!(with_freq["design"]["damper"]["freq_hz"], 5.0);
    with_freq.as_object_mut().unwrap().remove("design");
    plain.as_object_mut().unwrap().remove("design");
    assert_eq!(with_freq, plain);
}

/// The comparison fails where it should: on 0.1's own files, nudged.
#[test]
fn the_0_1_comparison_catches_a_moved_number_or_format() {
    let (json, text, csv) =
        (recorded("simulate_fig9.json"), recorded("simulate_fig9.txt"), recorded("simulate_fig9.csv"));
    let horizon = horizon_s(&serde_json::from_str(&json).unwrap());
    // Each file against itself passes.
    compare_json(&json, &json, fig9_rule).unwrap();
    compare_text(&text, &text, horizon).unwrap();
    compare_csv(&csv, &csv, horizon).unwrap();
    let swap = |s: &str, from: &str, to: &str| {
        assert!(s.contains(from), "{from}");
        s.replacen(from, to, 1)
    };
    // Impact 3's speed off by 1e-7 m/s (twice the tolerance), and by 2e-8 (within it).
    assert!(compare_json(&json, &swap(&json, "0.8316131522800423", "0.8316132522800423"), fig9_rule).is_err());
    compare_json(&json, &swap(&json, "0.8316131522800423", "0.8316131722800423"), fig9_rule).unwrap();
    // Impact 8's restitution off by 1e-6 relative; a late one (impact 9) anywhere.
    let r8 = serde_json::from_str::<Value>(&json).unwrap()["impacts"][7]["restitution"].to_string();
    let r8_moved = format!("{}", r8.parse::<f64>().unwrap() * (1.0 + 1e-6));
    assert!(compare_json(&json, &swap(&json, &r8, &r8_moved), fig9_rule).is_err());
    // The ledger: 0.1's own run (the reference scheme) leaves it open by 2.8e-9 of its initial
    // energy, more than the new scheme may (docs/model.md §11).
    assert!(ledger(&json).is_err());
    // A key renamed, a number dropped, an integer written as a decimal.
    assert!(compare_json(&json, &swap(&json, "\"spl_db\"", "\"spl_dB\""), fig9_rule).is_err());
    assert!(compare_json(&json, &swap(&json, "\"n_impacts\": 38", "\"n_impacts\": 38.0"), fig9_rule).is_err());
    // Text: a speed of the first impacts off by two units of its last place; a width changed.
    assert!(compare_text(&text, &swap(&text, "1.89529      1.76371", "1.89531      1.76371"), horizon).is_err());
    compare_text(&text, &swap(&text, "1.89529      1.76371", "1.89530      1.76371"), horizon).unwrap();
    assert!(compare_text(&text, &swap(&text, "e_fit 0.5968 cm/s", "e_fit 0.597 cm/s"), horizon).is_err());
    // A design value as typed (`0.5`) is 0.1's `0.5000`; another value is not.
    compare_text(&text, &swap(&text, "M 0.5000 kg", "M 0.5 kg"), horizon).unwrap();
    assert!(compare_text(&text, &swap(&text, "M 0.5000 kg", "M 0.6 kg"), horizon).is_err());
    assert!(compare_text(&text, &swap(&text, "M 0.5000 kg", "M 0.5 kg,"), horizon).is_err());
    assert!(compare_text(&text, &swap(&text, "38 impacts", "39 impacts"), horizon).is_ok(), "e's line is late");
    assert!(compare_text(&text, &swap(&text, "(first 12 of 38)", "(first 12 of 39)"), horizon).is_err());
    // CSV: the structure alone moved; a sample in the horizon moved; a row dropped.
    assert!(compare_csv(&csv, &swap(&csv, "0.007977088202888262\n", "0.007977088202888263\n"), horizon).is_err());
    assert!(
        compare_csv(&csv, &swap(&csv, "0.004,0.007977088202888262", "0.004,0.007977188202888262"), horizon).is_err()
    );
    let mut short: Vec<&str> = csv.lines().collect();
    short.pop();
    assert!(compare_csv(&csv, &(short.join("\n") + "\n"), horizon).is_err());
}

#[test]
fn numbers_are_split_from_the_text() {
    let (s, n) = split("u0_max 2.5e-3 m/s, Eq 27, K_HZ 5.6000e8 N/m^1.5 at -0.25 s; t_s,x_m\n1,-2");
    assert_eq!(s, "u0_max # m/s, Eq #, K_HZ # N/m^# at # s; t_s,x_m\n#,#");
    assert_eq!(n, ["2.5e-3", "27", "5.6000e8", "1.5", "-0.25", "1", "-2"]);
    assert_eq!((decimals("0.9306"), decimals("38"), decimals("5.6000e8")), (4, 0, 4));
}
