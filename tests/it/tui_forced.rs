#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! One truth between the explorer and the command line for forced designs and ensembles: the
//! readout's steady state (after the design's strike) is `thud simulate --force --settle`'s,
//! the response view's value at f (from rest) is `thud response --freqs f:f:1`'s, each says its
//! start; the chart's marker shows the readout's zone, which is `thud simulate --ensemble`'s.

use crate::support::explorer::{press, render, set};
use crossterm::event::KeyCode;
use thud::design::Design;
use thud::tui::app::App;
use thud::tui::chart::DesignZone;
use thud::tui::compute::{Grid, Grids};
use thud::tui::fields::Knob;
use thud::tui::{compute_sync, Palette};
use thud::units::sig;

fn computed_app() -> App {
    let grids = Grids { coarse: None, fine: Grid::standard(6, 5) };
    let mut app = App::with_grids(Design::default(), "default", Palette::default(), grids);
    let reqs = app.initial_requests();
    compute_sync(&mut app, reqs);
    app
}

fn cli(args: &[&str]) -> serde_json::Value {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_thud")).args(args).output().unwrap();
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn the_forced_readout_and_the_response_view_agree_with_the_cli_each_from_its_stated_start() {
    let mut app = computed_app();
    set(&mut app, Knob::MASS, "30.89");
    set(&mut app, Knob::GAP, "5.49");
    set(&mut app, Knob::FORCE, "2.17");
    set(&mut app, Knob::FREQ, "4.126");
    press(&mut app, KeyCode::Char('f'));
    // At 80×24 the chart panel (with the response view) shows beside the history.
    while app.focus != thud::tui::app::Panel::History {
        press(&mut app, KeyCode::Tab);
    }
    assert!(!app.busy());
    let design = ["--mass", "30.89g", "--gap", "5.49cm", "--force-amplitude", "2.17"];
    let strike = cli(&[&["simulate", "--freq", "4.126", "--settle", "--json"][..], &design[..]].concat());
    let rest = cli(&[&["response", "--freqs", "4.126:4.126:1", "--json"][..], &design[..]].concat());
    let strike_mm = sig(strike["steady"]["amplitude_m"].as_f64().unwrap() * 1e3, 4);
    let rest_mm = sig(rest["sweeps"][0]["points"][0]["amplitude_m"].as_f64().unwrap() * 1e3, 3);
    let cut = sig(strike["steady"]["reduction_db"].as_f64().unwrap(), 3);
    for (w, h) in [(80, 24), (120, 40)] {
        let screen = render(&mut app, w, h);
        // The readout: after the 2 m/s strike, as `thud simulate --force --settle`.
        assert!(screen.contains(&format!("{strike_mm} mm")), "{w}x{h}: amp {strike_mm} mm\n{screen}");
        assert!(screen.contains(&format!("{cut} dB")), "{w}x{h}: cut {cut} dB\n{screen}");
        assert!(screen.contains(", after the 2 m/s strike"), "{w}x{h}: the readout's start\n{screen}");
        // The response view: at f itself, from rest, as `thud response --freqs f:f:1`.
        let line = screen.lines().find(|l| l.contains("f 4.126 Hz from rest: ")).unwrap_or_else(|| panic!("{screen}"));
        assert!(line.contains(&format!("from rest: {rest_mm} mm")), "{w}x{h}: {rest_mm} mm at f\n{screen}");
    }
}

#[test]
fn the_ensemble_marker_shows_the_readouts_zone_which_is_the_clis() {
    let mut app = computed_app();
    set(&mut app, Knob::MASS, "31.2");
    set(&mut app, Knob::GAP, "5.6");
    set(&mut app, Knob::C1, "45");
    set(&mut app, Knob::V0, "2.6");
    set(&mut app, Knob::RUNS, "12");
    assert!(!app.busy());
    let json = cli(&[
        "simulate",
        "--mass",
        "31.2g",
        "--gap",
        "5.6cm",
        "--c1",
        "45",
        "--v0",
        "2.6",
        "--ensemble",
        "12",
        "--json",
    ]);
    let zone = json["zone"].as_u64().unwrap();
    let DesignZone::Known(Some(marker)) = app.design_zone() else { panic!("{:?}", app.design_zone()) };
    assert_eq!(u64::from(marker.number()), zone, "the marker's zone is the CLI's");
    let screen = render(&mut app, 120, 40);
    assert!(screen.contains(&format!("[{zone}] this design: zone {zone}")), "{screen}");
    let readout = screen.lines().find(|l| l.contains("│zone ")).unwrap();
    assert!(readout.contains(&format!("zone    {zone} ")), "{readout}");
}
