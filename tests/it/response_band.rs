#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test or benchmark fails
//! The default frequencies of a response are the engine's one definition
//! (`thud_core::response::default_freqs_hz`: 0.6–1.6 × the damped natural frequency, 101
//! points): `thud response` and `thud export … response` without `--freqs`, and the explorer's
//! curve and export, all span it. Python's `thud.response()` without
//! frequencies is checked against the command line in crates/thud-py/tests/test_forced.py.

use std::path::Path;

use thud::design::Design;
use thud::export::Artifact;
use thud::response::{default_freqs_hz, DEFAULT_POINTS};
use thud::tui::compute::{default_band, Grid, Grids};
use thud::tui::App;
use thud::tui::{Palette, Request};

use crate::common;

/// Runs the built binary with HOME and the XDG folders in `home`; it must succeed.
fn thud(home: &Path, args: &[&str]) -> String {
    let (code, stdout, stderr) = common::thud_in(home, args);
    assert_eq!(code, 0, "{args:?}: {stderr}");
    stdout
}

/// The damped natural frequency (Hz) of Table 2's main mass from K, M and C (Eq 25):
/// √(K/M − (C/2M)²)/2π, with K 500 N/m, M 0.5 kg, C 0.05 N·s/m.
fn table_2_natural_frequency_hz() -> f64 {
    let (k, m, c) = (500.0_f64, 0.5_f64, 0.05_f64);
    (k / m - (c / (2.0 * m)).powi(2)).sqrt() / (2.0 * std::f64::consts::PI)
}

/// The frequencies of the points of a `thud response --json`.
fn json_freqs(text: &str) -> Vec<f64> {
    let v: serde_json::Value = serde_json::from_str(text).unwrap();
    v["sweeps"][0]["points"].as_array().unwrap().iter().map(|p| p["freq_hz"].as_f64().unwrap()).collect()
}

#[test]
fn thud_response_without_freqs_spans_0_6_to_1_6_times_the_natural_frequency() {
    let home = tempfile::tempdir().unwrap();
    let json =
        thud(home.path(), &["response", "--force-amplitude", "1N", "--periods", "1", "--duration", "0.2", "--json"]);
    let freqs = json_freqs(&json);
    let f_n = table_2_natural_frequency_hz();
    assert_eq!(freqs.len(), 101);
    assert!((freqs[0] - 0.6 * f_n).abs() < 1e-9 * f_n, "{} vs 0.6 × {f_n}", freqs[0]);
    assert!((freqs[100] - 1.6 * f_n).abs() < 1e-9 * f_n, "{} vs 1.6 × {f_n}", freqs[100]);
    for w in freqs.windows(2) {
        assert!((w[1] - w[0] - f_n / 100.0).abs() < 1e-9, "evenly spaced: {w:?}");
    }
    // The band follows the design: K four times as stiff doubles f_n.
    let stiff = thud(
        home.path(),
        &["response", "--force-amplitude", "1N", "--k", "2000", "--periods", "1", "--duration", "0.2", "--json"],
    );
    let f_stiff = (2000.0_f64 / 0.5 - (0.05_f64 / 1.0).powi(2)).sqrt() / (2.0 * std::f64::consts::PI);
    let stiff = json_freqs(&stiff);
    assert!((stiff[0] - 0.6 * f_stiff).abs() < 1e-9 * f_stiff && (stiff[100] - 1.6 * f_stiff).abs() < 1e-9 * f_stiff);
    // The CSV export without --freqs runs the same frequencies as `thud response --csv`.
    let args = ["--periods", "1", "--duration", "0.2"];
    let export = thud(
        home.path(),
        &[&["export", "csv", "response", "--force-amplitude", "1N", "--out", "-"][..], &args[..]].concat(),
    );
    let cli = thud(home.path(), &[&["response", "--force-amplitude", "1N", "--csv"][..], &args[..]].concat());
    assert_eq!(export, cli);
}

#[test]
fn help_states_the_default_band_in_words() {
    let home = tempfile::tempdir().unwrap();
    let words = format!("0.6–1.6 × the natural frequency, {DEFAULT_POINTS} points");
    for cmd in [&["response", "--help"][..], &["export", "csv", "--help"][..]] {
        let help = thud(home.path(), cmd);
        let line = help.lines().skip_while(|l| !l.contains("--freqs")).take(3).collect::<String>();
        assert!(line.contains(&words), "{cmd:?}: {line}");
        assert!(!help.contains("[default: 3Hz:8Hz:101]"), "{cmd:?}");
    }
}

#[test]
fn the_explorer_s_curve_and_export_use_the_engine_s_band() {
    let mut d = Design::default();
    d.damper.force_n = 1.0;
    d.damper.freq_hz = table_2_natural_frequency_hz();
    let grids = Grids { coarse: None, fine: Grid::standard(6, 5) };
    let mut app = App::with_grids(d, "default", Palette::default(), grids);
    let engine = default_freqs_hz(&app.design);
    let f_n = table_2_natural_frequency_hz();
    assert!((engine[0] - 0.6 * f_n).abs() < 1e-12 && (engine[DEFAULT_POINTS - 1] - 1.6 * f_n).abs() < 1e-12);
    let band = default_band(&app.design);
    assert_eq!((band.from_hz, band.to_hz), (engine[0], engine[DEFAULT_POINTS - 1]), "the curve spans the band");
    let Some(Request::Export(job)) = app.export(Artifact::CsvResponse) else { panic!("no export job") };
    assert_eq!(job.options.freqs_hz.as_deref(), Some(&engine[..]), "the explorer's export runs the CLI's frequencies");
}
