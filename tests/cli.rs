//! The command line: output shapes and clear errors for bad input.

use std::process::Command;

fn thud(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_thud")).args(args).output().expect("run thud");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

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
    let k = v["k_hz"].as_f64().unwrap();
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
