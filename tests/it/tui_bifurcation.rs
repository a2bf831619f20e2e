#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! The explorer's bifurcation view: with a force on, `v` cycles the chart
//! panel to x(kT) over f, coarse pass first, then the fine one, the current f marked and its
//! orbit named; its samples are `thud bifurcation`'s for the same f; then the periodic orbits'
//! branches over the band, `thud continue`'s, drawn over the samples.

use crate::support::explorer::render;
use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use thud::tui::app::{App, Msg};
use thud::tui::compute::{Grid, Grids};
use thud::tui::worker::{run_sync, ChartWork, Request};
use thud::tui::{compute_sync, Palette};

fn forced_app() -> App {
    let d = thud::presets::preset("forced-rattle").unwrap();
    let grids = Grids { coarse: None, fine: Grid::standard(4, 4) };
    let mut app = App::with_grids(d, "forced-rattle", Palette::default(), grids);
    let reqs = app.initial_requests();
    compute_sync(&mut app, reqs);
    app
}

fn key(code: KeyCode) -> Msg {
    Msg::Input(Event::Key(KeyEvent::new(code, KeyModifiers::NONE)))
}

/// `thud bifurcation` at the one value `f` (the explorer's run lengths given explicitly).
fn cli_point(f: f64) -> serde_json::Value {
    let vary = format!("f={f}:{f}:1");
    let args = [
        "bifurcation",
        "--preset",
        "forced-rattle",
        "--vary",
        &vary,
        "--transient",
        "200",
        "--periods",
        "100",
        "--json",
    ];
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_thud")).args(args).output().unwrap();
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    json["points"][0].clone()
}

/// The x(kT) samples of a CLI point (m).
fn xs(point: &serde_json::Value) -> Vec<f64> {
    point["samples"].as_array().unwrap().iter().map(|s| s["x_m"].as_f64().unwrap()).collect()
}

#[test]
fn v_cycles_to_the_bifurcation_diagram_coarse_first_then_fine_with_f_marked_and_its_orbit_named() {
    let mut app = forced_app();
    assert!(app.update(key(KeyCode::Char('v'))).is_empty(), "the scatter needs no work");
    let reqs = app.update(key(KeyCode::Char('v')));
    assert_eq!(reqs.len(), 1, "one bifurcation job");
    assert!(matches!(&reqs[0], Request::Chart(_, ChartWork::Bifurcation)));
    // The job reports the coarse pass, then the fine one.
    let done = std::sync::Mutex::new(Vec::new());
    run_sync(&reqs[0], &|d| done.lock().unwrap().push(d));
    let mut done = done.into_inner().unwrap();
    assert_eq!(done.len(), 3, "{done:?}");
    let branches = done.pop().unwrap();
    let fine = done.pop().unwrap();
    let coarse = done.pop().unwrap();
    let waiting = render(&mut app, 120, 40);
    assert!(waiting.contains("computing the coarse pass"), "{waiting}");
    app.update(Msg::Work(coarse));
    let (b, is_fine) = app.bifurcation().unwrap();
    assert!(!is_fine && b.points.len() == thud::tui::compute::BIFURCATION_VALUES[0]);
    let refining = render(&mut app, 120, 40);
    assert!(refining.contains("refining"), "{refining}");
    app.update(Msg::Work(fine));
    let (b, is_fine) = app.bifurcation().unwrap();
    assert!(is_fine && b.points.len() == thud::tui::compute::BIFURCATION_VALUES[1]);
    let screen = render(&mut app, 120, 40);
    insta::assert_snapshot!("bifurcation_forced_rattle_120x40", screen);
    assert!(!screen.contains("refining"), "{screen}");
    // The line under the diagram names the orbit at f (and so does the readout's title, at
    // every size: tests/it/tui_orbit.rs).
    let orbit = app.acoustic().unwrap().orbit.as_ref().unwrap().run.orbit.label();
    let f = thud::units::sig(app.design.damper.freq_hz, 4);
    assert!(screen.contains(&format!("f {f} Hz: orbit {orbit}")), "{screen}");
    let wide = render(&mut app, 200, 60);
    assert!(wide.contains(&format!(" readout: orbit {orbit} ")), "{wide}");
    // Then the branches, drawn over the samples: `thud continue`'s for the same band and seeds.
    app.update(Msg::Work(branches));
    let drawn = app.branches().unwrap().to_vec();
    assert!(!drawn.is_empty());
    let screen = render(&mut app, 120, 40);
    insta::assert_snapshot!("bifurcation_forced_rattle_branches_120x40", screen);
    // Its legend names the branches where the panel has room for them.
    let wide = render(&mut app, 200, 60);
    assert!(wide.contains("stable orbit"), "{wide}");
    let band = thud::tui::compute::bifurcation_band(&app.design, thud::tui::compute::BIFURCATION_VALUES[1]);
    let vary = format!("f={}:{}:{}", band.from_hz, band.to_hz, thud::tui::compute::BRANCH_SEEDS);
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_thud"))
        .args(["continue", "--preset", "forced-rattle", "--vary", &vary, "--json"])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let cli: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let cli = cli["branches"].as_array().unwrap();
    assert_eq!(cli.len(), drawn.len());
    for (c, b) in cli.iter().zip(&drawn) {
        let pts = c["points"].as_array().unwrap();
        assert_eq!(pts.len(), b.points.len());
        for (cp, bp) in pts.iter().zip(&b.points) {
            assert_eq!((cp["value"].as_f64().unwrap(), cp["x_m"].as_f64().unwrap()), (bp.value, bp.x_m));
            assert_eq!(bp.strobe_m.first(), Some(&bp.x_m));
        }
    }
    // A change of f moves the marker only: no new job; any other change asks again (the
    // worker's slot cancels the stale one), and the old passes are not shown for it.
    let gap = app.design.damper.gap_m;
    let reqs = app.select_design(0.05, gap);
    assert!(reqs.iter().any(|r| matches!(r, Request::Chart(_, ChartWork::Bifurcation))), "{reqs:?}");
    assert!(app.bifurcation().is_none(), "the old design's diagram is not the new one's");
    // v again: back to the zones.
    app.update(key(KeyCode::Char('v')));
    assert!(render(&mut app, 120, 40).contains("zones"));
}

#[test]
fn the_views_samples_at_f_and_at_a_band_value_are_thud_bifurcations() {
    let mut app = forced_app();
    app.update(key(KeyCode::Char('v')));
    let reqs = app.update(key(KeyCode::Char('v')));
    compute_sync(&mut app, reqs);
    // At the current f: the orbit the view marks (and the readout names).
    let f = app.design.damper.freq_hz;
    let at_f = app.acoustic().unwrap().orbit.as_ref().unwrap();
    let cli = cli_point(f);
    let view: Vec<f64> = at_f.run.samples.iter().map(|s| s.x_m).collect();
    assert_eq!(view, xs(&cli), "x(kT) at f {f} Hz");
    assert_eq!(at_f.run.orbit.label(), cli_point_label(&cli));
    // At a value of the fine pass.
    let (b, _) = app.bifurcation().unwrap();
    let p = &b.points[37];
    let view: Vec<f64> = p.run.samples.iter().map(|s| s.x_m).collect();
    assert_eq!(view, xs(&cli_point(p.value)), "x(kT) at f {} Hz", p.value);
}

/// The orbit's label as `thud bifurcation --json` states it (its kind and numbers).
fn cli_point_label(p: &serde_json::Value) -> String {
    let o = &p["orbit"];
    match o["kind"].as_str().unwrap() {
        "periodic" => {
            let sym = if o["symmetric"].as_bool().unwrap() { " sym" } else { "" };
            format!("{}/{}{sym}", o["impacts"], o["periods"])
        }
        "chaotic" => "chaotic".into(),
        _ => "not settled".into(),
    }
}

#[test]
fn without_a_force_v_cycles_zones_and_scatter_only() {
    let grids = Grids { coarse: None, fine: Grid::standard(4, 4) };
    let mut app = App::with_grids(thud::design::Design::default(), "default", Palette::default(), grids);
    let reqs = app.initial_requests();
    compute_sync(&mut app, reqs);
    app.update(key(KeyCode::Char('v')));
    assert!(app.update(key(KeyCode::Char('v'))).is_empty());
    assert!(render(&mut app, 120, 40).contains("zones"));
}
