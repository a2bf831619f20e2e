#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! The readout names the current orbit's type (issue 27, item 4): with a force on, the
//! readout's title says the live design's orbit at f, whole, at 80×24 (both teaching layouts)
//! and at 120×40; the label is the engine's for that design (`orbit_at_f`, the one value of
//! `thud bifurcation --vary f=f:f:1`), never a stale one while the design computes.

use crate::support::explorer::{press, render, set};
use crossterm::event::KeyCode;
use thud::design::Design;
use thud::tui::app::{App, Panel};
use thud::tui::compute::{orbit_at_f, Grid, Grids};
use thud::tui::fields::Knob;
use thud::tui::{compute_sync, Palette};

fn app_of(d: Design, preset: &str) -> App {
    let grids = Grids { coarse: None, fine: Grid::standard(4, 4) };
    let mut app = App::with_grids(d, preset, Palette::default(), grids);
    let reqs = app.initial_requests();
    compute_sync(&mut app, reqs);
    app
}

/// The orbit's label of the live design, straight from the engine (not the app's copy), and
/// the app's copy agreeing with it.
fn engine_label(app: &App) -> String {
    let engine = orbit_at_f(&app.design, None).unwrap().unwrap().run.orbit.label();
    let shown = app.acoustic().unwrap().orbit.as_ref().unwrap().run.orbit.label();
    assert_eq!(shown, engine, "the worker's orbit is the engine's");
    engine
}

/// The screen's line holding the readout's top border.
fn readout_title_line(screen: &str) -> &str {
    screen.lines().find(|l| l.contains(" readout")).unwrap_or_else(|| panic!("no readout title\n{screen}"))
}

/// Every size and layout: 80×24 with the pulse and polar (the readout beside the parameters,
/// 50 columns), 80×24 with the history and the chart (40 columns), 120×40 (40 columns, tall).
fn screens(app: &mut App) -> Vec<(String, String)> {
    let mut out = vec![
        ("80x24 sound".to_string(), render(app, 80, 24)),
        ("120x40".to_string(), render(app, 120, 40)),
        ("160x50".to_string(), render(app, 160, 50)),
    ];
    while app.focus != Panel::History {
        press(app, KeyCode::Tab);
    }
    out.push(("80x24 design".to_string(), render(app, 80, 24)));
    out
}

#[test]
fn the_readout_title_names_the_forced_presets_orbit_whole_at_80x24_and_120x40() {
    let mut app = app_of(thud::presets::preset("forced-rattle").unwrap(), "forced-rattle");
    let label = engine_label(&app);
    for (size, screen) in screens(&mut app) {
        let title = readout_title_line(&screen);
        assert!(title.contains(&format!(" readout: orbit {label} ")), "{size}: orbit {label}\n{screen}");
    }
}

#[test]
fn the_default_design_forced_names_its_orbit_and_keeps_its_note_start() {
    let mut app = app_of(Design::default(), "default");
    set(&mut app, Knob::FORCE, "1");
    let label = engine_label(&app);
    for (size, screen) in screens(&mut app) {
        let title = readout_title_line(&screen);
        assert!(title.contains(&format!(" readout: orbit {label} ")), "{size}: orbit {label}\n{screen}");
        // The note still says which start the figures are from.
        assert!(screen.contains("settled, after the 2 m/s strike"), "{size}\n{screen}");
    }
}

#[test]
fn with_n_runs_the_title_names_the_designs_own_starts_orbit_and_says_so() {
    let mut app = app_of(thud::presets::preset("forced-rattle").unwrap(), "forced-rattle");
    set(&mut app, Knob::RUNS, "4");
    assert!(app.acoustic().unwrap().forced_ensemble.is_some(), "the readout is the 4 runs'");
    // The orbit is the design's own start's (the ball's y0 as set), not one of the 4 offsets'.
    let label = engine_label(&app);
    for (size, screen) in screens(&mut app) {
        let title = readout_title_line(&screen);
        assert!(title.contains(&format!(" readout: orbit {label} from y0 ")), "{size}: orbit {label}\n{screen}");
    }
}

#[test]
fn no_stale_orbit_while_the_design_computes_and_none_without_a_force() {
    let mut app = app_of(thud::presets::preset("forced-rattle").unwrap(), "forced-rattle");
    let label = engine_label(&app);
    assert!(readout_title_line(&render(&mut app, 120, 40)).contains(&format!("orbit {label}")));
    // A new f, its readout not yet computed: the old f's orbit is not shown for it.
    app.selected = Knob::ALL.iter().position(|k| *k == Knob::FREQ).unwrap();
    let reqs = app.submit_text("6");
    assert!(app.design_busy());
    for (w, h) in [(80, 24), (120, 40)] {
        let screen = render(&mut app, w, h);
        assert!(!readout_title_line(&screen).contains("orbit"), "{w}x{h}\n{screen}");
    }
    compute_sync(&mut app, reqs);
    let label = engine_label(&app);
    assert!(readout_title_line(&render(&mut app, 80, 24)).contains(&format!("orbit {label} ")));
    // The paper's free decay has no orbit to name.
    set(&mut app, Knob::FORCE, "0");
    assert!(app.acoustic().unwrap().orbit.is_none());
    for (w, h) in [(80, 24), (120, 40)] {
        let screen = render(&mut app, w, h);
        assert!(!screen.contains("orbit"), "{w}x{h}\n{screen}");
    }
}
