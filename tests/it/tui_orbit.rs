#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! The readout names the current orbit's type: with a force on, the
//! readout's title says the live design's orbit at f, whole, at 80×24 (both teaching layouts)
//! and at 120×40; the label is the engine's for that design (`orbit_at_f`, the one value of
//! `thud bifurcation --vary f=f:f:1`), never a stale one while the design computes.

use crate::support::explorer::{press, render, set};
use crossterm::event::KeyCode;
use thud::design::Design;
use thud::tui::app::{App, Panel};
use thud::tui::compute::{orbit_at_f, settled_steady, Grid, Grids};
use thud::tui::fields::Knob;
use thud::tui::readout::verdict_words;
use thud::tui::{compute_sync, Palette};

fn app_of(d: Design, preset: &str) -> App {
    let grids = Grids { coarse: None, fine: Grid::standard(4, 4) };
    let mut app = App::with_grids(d, preset, Palette::default(), grids);
    let reqs = app.initial_requests();
    compute_sync(&mut app, reqs);
    app
}

/// The verdict on the live design as the readout words it, straight from the engine (its
/// orbit at f and its settled run, not the app's copies), and the app's copy agreeing with it.
fn engine_label(app: &App) -> String {
    let orbit = orbit_at_f(&app.design, None).unwrap().unwrap().run.orbit;
    let shown = app.acoustic().unwrap().orbit.as_ref().unwrap().run.orbit;
    assert_eq!(shown, orbit, "the worker's orbit is the engine's");
    let steady = settled_steady(&app.design, None).unwrap().unwrap().verdict;
    let v = thud::verdict::of_design(Some(steady), Some(orbit)).unwrap();
    verdict_words(&v).trim_start_matches("orbit ").to_string()
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
        // The note still says which start the figures are from, after the same verdict.
        assert!(screen.contains(&format!("orbit {label}, after the 2 m/s strike")), "{size}\n{screen}");
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

/// Every verdict the screen names (`orbit 3/1`, `orbit settled`, `orbit NOT SETTLED`, …), in
/// the order it names them, whole words only (a note cut at the readout's edge names none).
fn verdicts_on(screen: &str) -> Vec<String> {
    let words = ["not settled", "settled", "chaotic", "truncated"];
    let mut out = Vec::new();
    for line in screen.lines() {
        let mut rest = line;
        while let Some(i) = rest.find("orbit ") {
            let after = &rest[i + "orbit ".len()..];
            let lower = after.to_lowercase();
            let ratio: String = after.chars().take_while(|c| c.is_ascii_digit() || *c == '/').collect();
            let found = if ratio.contains('/') && !ratio.ends_with('/') && !ratio.starts_with('/') {
                let sym = after[ratio.len()..].starts_with(" sym");
                Some(format!("{ratio}{}", if sym { " sym" } else { "" }))
            } else {
                words.iter().find(|w| lower.starts_with(*w)).map(|w| (*w).to_string())
            };
            out.extend(found);
            rest = after;
        }
        // The old wordings of a second verdict may not come back.
        assert!(!line.contains("NOT settled") && !line.contains("NOT periodic"), "{line}");
    }
    out
}

#[test]
fn the_explorer_never_shows_two_verdicts_for_one_design() {
    // Random forced designs (a fixed seed: the same ones every run) about the default design:
    // ball mass, gap, force and frequency drawn over the explorer's usual ranges, the force's
    // frequency about the structure's resonance (0.6–1.6 × its natural frequency), the 2 m/s
    // strike kept. Each must show one verdict: the readout's title and its note the same.
    let mut seed: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut uniform = |lo: f64, hi: f64| {
        seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        lo + (hi - lo) * ((seed >> 11) as f64 / (1u64 << 53) as f64)
    };
    let mut designs: Vec<Design> = (0..10)
        .map(|_| {
            let mut d = Design::default();
            let fn_hz = d.damper.natural_frequency_hz();
            d.damper.impact_mass_kg = uniform(0.02, 0.06);
            d.damper.gap_m = uniform(0.005, 0.04);
            d.damper.force_n = uniform(0.5, 3.0);
            d.damper.freq_hz = fn_hz * uniform(0.6, 1.6);
            d
        })
        .collect();
    // The design the explorer showed two verdicts for: the default with a 1 N force.
    let mut one_newton = Design::default();
    one_newton.damper.force_n = 1.0;
    one_newton.damper.freq_hz = one_newton.damper.natural_frequency_hz();
    designs.push(one_newton);
    for d in designs {
        let what = format!(
            "m {:.4} kg, d {:.4} m, F0 {:.3} N, f {:.4} Hz",
            d.damper.impact_mass_kg, d.damper.gap_m, d.damper.force_n, d.damper.freq_hz
        );
        let mut app = app_of(d, "default");
        let label = engine_label(&app);
        for (size, screen) in screens(&mut app) {
            let title = readout_title_line(&screen);
            assert!(title.contains(&format!(" readout: orbit {label} ")), "{what}, {size}: orbit {label}\n{screen}");
            let seen = verdicts_on(&screen);
            assert!(!seen.is_empty(), "{what}, {size}\n{screen}");
            assert!(
                seen.iter().all(|v| v.to_lowercase() == label.to_lowercase()),
                "{what}, {size}: {seen:?} for one design\n{screen}"
            );
        }
    }
}
