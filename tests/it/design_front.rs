#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! The explorer's front view (`thud tui --front FILE`): the front of a `thud design --json`
//! report plotted, ↑↓ walking along it, Enter loading the selected design, and the readout of
//! the loaded design giving exactly the report's objectives (every bit: the explorer runs the
//! design the search ran). Bad front files are refused with exit 2 and one line naming them.

use std::sync::Arc;

use crossterm::event::KeyCode;
use serde_json::Value;
use thud::design::search::Column;
use thud::tui::app::App;
use thud::tui::compute::{Grid, Grids};
use thud::tui::front::Front;
use thud::tui::{compute_sync, Palette};
use thud::units::sig;

use crate::common;
use crate::support::design_problem::paper_problem_with;
use crate::support::explorer::{press, render};

/// A small search of the paper's problem (SPLmax against e over mass × gap), its report.
fn report(home: &std::path::Path) -> String {
    let args = paper_problem_with(&["--evaluations", "60", "--seed", "3", "--json"]);
    let (code, out, err) = common::thud_in(home, &args);
    assert_eq!(code, 0, "{err}");
    out
}

/// An explorer on the report's front, the front view open, everything computed.
fn explorer(text: &str) -> App {
    let front = Front::parse(text, "front.json").unwrap();
    let grids = Grids { coarse: None, fine: Grid::standard(4, 4) };
    let mut app = App::with_grids(front.base.clone(), "front-start", Palette::default(), grids);
    app.host.front = Some(Arc::new(front));
    let reqs = app.initial_requests();
    compute_sync(&mut app, reqs);
    press(&mut app, KeyCode::Char('D'));
    assert!(app.front_shown(), "D opens the front view");
    app
}

#[test]
fn enter_loads_a_front_design_and_its_readout_gives_the_reports_objectives_exactly() {
    let home = tempfile::tempdir().unwrap();
    let text = report(home.path());
    let json: Value = serde_json::from_str(&text).unwrap();
    let rows = json["front"].as_array().unwrap();
    assert!(rows.len() >= 3, "a front of several designs: {}", rows.len());
    let mut app = explorer(&text);
    // Walk to the last design, past the end (it stops there), and back one.
    for _ in 0..rows.len() + 2 {
        press(&mut app, KeyCode::Down);
    }
    assert_eq!(app.screen.front, Some(rows.len() - 1), "↓ stops at the last design");
    press(&mut app, KeyCode::Up);
    let k = rows.len() - 2;
    assert_eq!(app.screen.front, Some(k));
    let before = app.design.clone();
    press(&mut app, KeyCode::Enter);
    assert_ne!(app.design, before, "Enter made the selected design the live one");
    assert!(!app.design_busy(), "the loaded design's readout is computed");
    let want_mass = rows[k]["variables"]["mass_kg"].as_f64().unwrap();
    let want_gap = rows[k]["variables"]["gap_m"].as_f64().unwrap();
    assert_eq!(app.design.damper.impact_mass_kg.to_bits(), want_mass.to_bits(), "the live mass is the report's");
    assert_eq!(app.design.damper.gap_m.to_bits(), want_gap.to_bits(), "the live gap is the report's");
    let a = app.acoustic().unwrap();
    for (column, name) in [(Column::SplMax, "spl_max_db"), (Column::Inclination, "inclination_cm_s")] {
        let want = rows[k]["objectives"][name].as_f64().unwrap();
        let got = column.value(&a.metrics, a.steady.as_ref()).unwrap();
        assert_eq!(got.to_bits(), want.to_bits(), "{name}: the readout's {got} is the report's {want}");
    }
    // The readout's rows show those numbers (at their digits), the view marks them equal.
    let (readout, _) = thud::tui::ui::readout_rows(&app);
    let spl = rows[k]["objectives"]["spl_max_db"].as_f64().unwrap();
    let row = readout.iter().find(|r| r.label == "SPLmax").unwrap();
    assert_eq!(row.live, format!("{} dB", sig(spl, 4)));
    let screen = render(&mut app, 160, 50);
    assert_eq!(screen.matches("= the front's").count(), 2, "both objectives marked equal\n{screen}");
    assert!(!screen.contains("≠"), "{screen}");
    assert!(screen.contains(&format!("spl_max_db {spl}")), "every digit of the report's value\n{screen}");
    // D closes the view; u undoes the load.
    press(&mut app, KeyCode::Char('D'));
    assert!(!app.front_shown());
    press(&mut app, KeyCode::Char('u'));
    assert_eq!(app.design, before, "u undoes the load");
}

#[test]
fn snapshots_of_the_front_view() {
    let home = tempfile::tempdir().unwrap();
    let mut app = explorer(&report(home.path()));
    press(&mut app, KeyCode::Down);
    press(&mut app, KeyCode::Enter);
    insta::assert_snapshot!("front_120x40", render(&mut app, 120, 40));
    insta::assert_snapshot!("front_80x24", render(&mut app, 80, 24));
}

#[test]
fn d_without_a_front_says_how_to_give_one() {
    let grids = Grids { coarse: None, fine: Grid::standard(4, 4) };
    let mut app = App::with_grids(thud::design::Design::default(), "default", Palette::default(), grids);
    press(&mut app, KeyCode::Char('D'));
    assert!(!app.front_shown());
    let status = app.status().unwrap().text.clone();
    assert!(status.contains("thud tui --front FILE"), "{status}");
}

#[test]
fn bad_front_files_are_refused_naming_the_file() {
    let home = tempfile::tempdir().unwrap();
    let dir = home.path();
    let text = report(dir);
    std::fs::write(dir.join("not.json"), "{\"front\": 3}").unwrap();
    let mut banded: Value = serde_json::from_str(&text).unwrap();
    banded["band_hz"] = serde_json::json!([4.5, 5.0]);
    std::fs::write(dir.join("band.json"), banded.to_string()).unwrap();
    let mut odd: Value = serde_json::from_str(&text).unwrap();
    odd["front"][0]["variables"]["mass_kg"] = serde_json::json!("heavy");
    std::fs::write(dir.join("odd.json"), odd.to_string()).unwrap();
    for (file, says) in [
        ("missing.json", "missing.json"),
        ("not.json", "not a report of thud design --json"),
        ("band.json", "band of frequencies"),
        ("odd.json", "front design 1"),
    ] {
        let path = dir.join(file);
        let (code, out, err) = common::thud_in(dir, &["tui", "--front", path.to_str().unwrap()]);
        assert_eq!(code, 2, "{file}: {err}");
        assert!(out.is_empty(), "{file}: {out}");
        assert_eq!(err.trim().lines().count(), 1, "{file}: one line\n{err}");
        assert!(err.contains(file) && err.contains(says), "{file}: {err}");
    }
}
