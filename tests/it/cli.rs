#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test or benchmark fails
//! The command line: output shapes and clear errors for bad input.

use crate::common;
use common::thud;

#[test]
fn pulse_json_has_the_documented_keys() {
    let (code, out, err) =
        thud(&["pulse", "--radius", "19.05mm", "--mass", "40.5g", "--u0", "1.4", "--k-hz", "5.6e8", "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    for key in ["alpha_max_m", "accel_max_m_s2", "tau_s", "spl_db", "spl_peak_db", "p_max_pa", "p_min_pa", "arrival_s"]
    {
        assert!(v[key].is_number(), "missing {key}");
    }
    let t = v["waveform"]["t_s"].as_array().unwrap();
    let p = v["waveform"]["p_pa"].as_array().unwrap();
    assert_eq!(t.len(), p.len());
    assert!(t.len() >= 1000);
    assert!((v["alpha_max_m"].as_f64().unwrap() - 1.257110e-4).abs() < 1e-9);
}

#[test]
fn pulse_csv_is_the_waveform() {
    let (code, out, _) = thud(&["pulse", "--csv", "--points", "50"]);
    assert_eq!(code, 0);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines[0], "t_s,p_pa");
    assert_eq!(lines.len(), 51);
}

#[test]
fn pulse_materials_replace_k_hz() {
    let (code, out, err) = thud(&["pulse", "--sphere", "acrylic", "--plate", "steel", "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let k = v["k_hz_n_m1_5"].as_f64().unwrap();
    assert!((k / 5.6e8 - 1.0).abs() < 0.01, "{k}");
}

#[test]
fn paper_table1_prints_eight_rows_with_errors() {
    let (code, out, _) = thud(&["paper", "table1", "--json"]);
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 8);
    for r in rows {
        assert!(r["model_minus_paper_db"].as_f64().unwrap().abs() < 0.03);
        assert!(r["spl_experiment_db"].is_number());
    }
    let (code, text, _) = thud(&["paper", "table1"]);
    assert_eq!(code, 0);
    assert!(text.contains("model − paper (dB)"));
}

#[test]
fn paper_list_names_items() {
    let (code, out, _) = thud(&["paper", "--list"]);
    assert_eq!(code, 0);
    for id in ["table1", "fig2", "fig3", "fig6", "fig7"] {
        assert!(out.contains(id), "{id}");
    }
}

#[test]
fn invalid_inputs_exit_nonzero_with_one_clear_line() {
    let cases: &[(&[&str], &str)] = &[
        (&["pulse", "--mass", "-1"], "mass"),
        (&["pulse", "--mass", "0"], "mass"),
        (&["pulse", "--radius", "0"], "radius"),
        (&["pulse", "--u0", "-0.5"], "u0"),
        (&["pulse", "--u0", "NaN"], "u0"),
        (&["pulse", "--r", "1cm"], "r"),
        (&["pulse", "--r", "19.05mm"], "r"),
        (&["pulse", "--sphere", "unobtainium"], "material"),
        (&["pulse", "--mass", "3furlongs"], "unknown unit"),
        (&["pulse", "--theta", "135"], "theta"),
        (&["pulse", "--rho-c", "0"], "rho-c"),
        (&["paper", "table99"], "table99"),
    ];
    for (args, needle) in cases {
        let (code, out, err) = thud(args);
        assert_ne!(code, 0, "{args:?} succeeded: {out}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
    }
}

#[test]
fn simulate_json_has_the_documented_keys() {
    let (code, out, err) = thud(&["simulate", "--preset", "paper-fig9", "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    for key in ["n_impacts", "inclination_cm_s", "inclination_fit_cm_s", "u0_max_m_s", "zdot_abs_max_m_s", "spl_max_db"]
    {
        assert!(!v[key].is_null(), "missing {key}");
    }
    let first = &v["impacts"][0];
    for key in ["t_s", "wall", "u_in_m_s", "u_out_m_s", "t_end_s", "penetration_max_m", "spl_db"] {
        assert!(first[key].is_number(), "impact missing {key}");
    }
    assert!((first["u_in_m_s"].as_f64().unwrap() - 1.89529).abs() < 5e-5);
    assert!(v["maxima"][0]["x_m"].is_number() && v["maxima"][0]["t_s"].is_number());
}

#[test]
fn simulate_flags_override_the_preset() {
    let (_, out, _) = thud(&["simulate", "--preset", "paper-table3", "--gap", "3cm", "--mass", "50g", "--json"]);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["design"]["damper"]["gap_m"].as_f64().unwrap(), 0.03);
    assert_eq!(v["design"]["damper"]["impact_mass_kg"].as_f64().unwrap(), 0.05);
    assert_eq!(v["design"]["damper"]["v0_m_s"].as_f64().unwrap(), 1.4);
}

#[test]
fn simulate_csv_is_the_time_history() {
    let (code, out, _) = thud(&["simulate", "--csv", "--samples", "101"]);
    assert_eq!(code, 0);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines[0], "t_s,x_m,y_m,x_free_m");
    assert_eq!(lines.len(), 102);
}

#[test]
fn sweep_outputs_a_chart() {
    let (code, out, err) = thud(&["sweep", "--masses", "30g:60g:3", "--gaps", "2cm:3cm:2", "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["chart"]["cells"].as_array().unwrap().len(), 6);
    let (code, out, _) = thud(&["sweep", "--masses", "30g:60g:3", "--gaps", "2cm:3cm:2", "--csv"]);
    assert_eq!(code, 0);
    assert_eq!(out.lines().count(), 7);
}

#[test]
fn paper_damper_items_run() {
    for id in ["table3", "table4", "table5", "fig9", "fig10", "fig13", "fig17"] {
        let (code, out, err) = thud(&["paper", id, "--json"]);
        assert_eq!(code, 0, "{id}: {err}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        assert!(!v["rows"].as_array().unwrap().is_empty(), "{id}");
    }
}

#[test]
fn invalid_design_inputs_exit_nonzero_with_one_clear_line() {
    let cases: &[(&[&str], &str)] = &[
        (&["simulate", "--mass", "0"], "mass"),
        (&["simulate", "--mass", "-5g"], "mass"),
        (&["simulate", "--gap", "0"], "gap"),
        (&["simulate", "--v0", "NaN"], "v0"),
        (&["simulate", "--duration", "0"], "duration"),
        (&["simulate", "--duration", "-1"], "duration"),
        (&["simulate", "--solver", "newmark", "--dt", "0"], "dt"),
        (&["simulate", "--dt", "1e-6"], "dt"),
        (&["simulate", "--preset", "nonesuch"], "preset"),
        (&["simulate", "--r", "1mm"], "r"),
        (&["sweep", "--masses", "30g:100g"], "masses"),
        (&["sweep", "--gaps", "0:5cm:3"], "gap"),
    ];
    for (args, needle) in cases {
        let (code, out, err) = thud(args);
        assert_ne!(code, 0, "{args:?} succeeded: {out}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
    }
}

#[test]
fn restitution_curve_and_its_inverse() {
    let (code, out, err) = thud(&["restitution", "--masses", "10g:100g:4", "--target", "0.9", "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 4);
    // R rises with the mass (docs/model.md §9: ≈ 0.84 at 10 g, 0.95 at 100 g).
    assert!((rows[0]["restitution"].as_f64().unwrap() - 0.84).abs() < 0.01);
    assert!((rows[3]["restitution"].as_f64().unwrap() - 0.95).abs() < 0.01);
    // A heavier ball needs more c1 for the same R.
    let c1: Vec<f64> = rows.iter().map(|r| r["c1_for_target_n_s_m"].as_f64().unwrap()).collect();
    assert!(c1.windows(2).all(|w| w[1] > w[0]), "{c1:?}");
    let (code, _, err) = thud(&["restitution", "--target", "1.5"]);
    assert_ne!(code, 0);
    assert!(err.contains("restitution"), "{err}");
}

#[test]
fn sphere_poisson_changes_k_hz_and_is_refused_out_of_range_or_without_a_sphere() {
    let k_hz = |args: &[&str]| {
        let (code, out, err) =
            thud(&[&["simulate", "--duration", "0.05", "--sphere", "steel", "--json"][..], args].concat());
        assert_eq!(code, 0, "{err}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        (v["design"]["damper"]["k_hz_n_m1_5"].as_f64().unwrap(), out)
    };
    let (own, plain) = k_hz(&[]);
    let (given, out) = k_hz(&["--sphere-poisson", "0.28"]);
    assert_ne!(out, plain, "the ball's ν is a real parameter");
    assert!(given < own, "ν 0.28 below steel's 0.30 is a softer contact: {given} vs {own}");
    assert!(out.contains(r#""sphere_nu": 0.28"#) || out.contains(r#""sphere_nu":0.28"#), "{out}");
    assert!(!plain.contains("sphere_nu"), "without the flag the output is as before");
    let (same, out) = k_hz(&["--sphere-poisson", "0.3"]);
    assert_eq!(same.to_bits(), own.to_bits(), "steel's own ν: {out}");
    for (args, names) in [
        (&["simulate", "--sphere", "steel", "--sphere-poisson", "0.7"][..], &["--sphere-poisson"][..]),
        (&["simulate", "--sphere-poisson", "0.28"][..], &["--sphere-poisson", "--sphere"][..]),
    ] {
        let (code, out, err) = thud(args);
        assert_eq!(code, 2, "{args:?}: {out}{err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: one line: {err}");
        for name in names {
            assert!(err.contains(name), "{args:?}: {err}");
        }
    }
}

/// Words that say only what is so: the observer's bound at its angle, a source's wall signs only
/// where it has a second wall, and counts as whole numbers.
#[test]
fn small_untruths_are_gone() {
    // Along the normal the sphere reaches 2a = 38.1 mm: 37 mm is inside it, and the error says so.
    let (code, out, err) = thud(&["pulse", "--r", "0.037", "--theta", "0"]);
    assert_eq!((code, out.as_str(), err.lines().count()), (2, "", 1), "{err}");
    assert!(err.contains("0.037") && err.contains("must be > 2a·cos θ = 0.0381 m"), "{err}");
    assert_eq!(thud(&["pulse", "--r", "0.0382", "--theta", "0"]).0, 0, "just outside");
    // Only the corner's second wall has signs.
    for (source, signs) in [("single", false), ("dipole", false), ("quadrupole", true)] {
        let (code, out, err) = thud(&["simulate", "--source", source, "--duration", "0.2"]);
        assert_eq!(code, 0, "{err}");
        let listener = out.lines().find(|l| l.starts_with("listener")).unwrap();
        assert_eq!(listener.contains("signs"), signs, "{listener}");
    }
    // Table 5 counts designs: whole numbers.
    let (code, out, err) = thud(&["paper", "table5"]);
    assert_eq!(code, 0, "{err}");
    let header = out.lines().nth(1).unwrap();
    let col = header.split("  ").filter(|c| !c.trim().is_empty()).position(|c| c.trim() == "designs").unwrap();
    for row in out.lines().skip(2).take_while(|l| !l.starts_with("note")) {
        let cell = row.split_whitespace().nth(col).unwrap();
        assert!(cell.parse::<u32>().is_ok(), "a count: {cell} in {row}");
    }
}
