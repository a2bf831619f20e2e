//! The explorer on ratatui's TestBackend: snapshots of the main screen, keys changing state
//! and the next frame, tiny terminals, the help overlay and refused input.

use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use ratatui::backend::TestBackend;
use ratatui::Terminal;
use thud::design::Design;
use thud::tui::app::{App, Mode, Msg};
use thud::tui::compute::{Grid, Grids};
use thud::tui::keys::KEYS;
use thud::tui::{compute_sync, draw, Palette};

/// The default design with every result computed on this thread (small chart grid).
fn computed_app() -> App {
    let grids = Grids { coarse: None, fine: Grid::standard(6, 5) };
    let mut app = App::with_grids(Design::default(), "default", Palette { color: true, ascii: false }, grids);
    let reqs = app.initial_requests();
    compute_sync(&mut app, reqs);
    app
}

fn render(app: &mut App, w: u16, h: u16) -> String {
    let mut term = Terminal::new(TestBackend::new(w, h)).unwrap();
    draw(&mut term, app).unwrap();
    term.backend().to_string()
}

/// Draws one frame without reading it back (TestBackend cannot print a 0-wide buffer).
fn draw_only(app: &mut App, w: u16, h: u16) {
    let mut term = Terminal::new(TestBackend::new(w, h)).unwrap();
    draw(&mut term, app).unwrap();
}

fn press(app: &mut App, code: KeyCode) {
    press_mod(app, code, KeyModifiers::NONE);
}

fn press_mod(app: &mut App, code: KeyCode, mods: KeyModifiers) {
    let reqs = app.update(Msg::Input(Event::Key(KeyEvent::new(code, mods))));
    compute_sync(app, reqs);
}

fn type_text(app: &mut App, text: &str) {
    for c in text.chars() {
        press(app, KeyCode::Char(c));
    }
}

/// The line of the screen that starts (after the border) with `label`.
fn row<'a>(screen: &'a str, label: &str) -> &'a str {
    screen.lines().find(|l| l.contains(&format!("│{label} "))).unwrap_or_else(|| panic!("no row {label} in\n{screen}"))
}

#[test]
fn main_screen_120x40() {
    let mut app = computed_app();
    assert!(!app.busy(), "everything computed");
    insta::assert_snapshot!("main_120x40", render(&mut app, 120, 40));
}

#[test]
fn main_screen_80x24() {
    let mut app = computed_app();
    insta::assert_snapshot!("main_80x24", render(&mut app, 80, 24));
}

#[test]
fn mass_up_changes_the_readout_on_the_next_frame() {
    let mut app = computed_app();
    let before = render(&mut app, 120, 40);
    assert!(before.contains("40.50 g"));
    press(&mut app, KeyCode::Right);
    let after = render(&mut app, 120, 40);
    assert!(after.contains("41.50 g"), "{after}");
    assert!((app.design.damper.impact_mass_kg - 0.0415).abs() < 1e-12);
    assert_ne!(row(&before, "U0max"), row(&after, "U0max"), "U0max follows the mass");
    assert!(!app.busy());
}

#[test]
fn shift_gives_a_fine_step_and_undo_goes_back() {
    let mut app = computed_app();
    press_mod(&mut app, KeyCode::Right, KeyModifiers::SHIFT);
    assert!((app.design.damper.impact_mass_kg - 0.0406).abs() < 1e-12);
    press(&mut app, KeyCode::Char('u'));
    assert!((app.design.damper.impact_mass_kg - 0.0405).abs() < 1e-12);
    assert!(render(&mut app, 120, 40).contains("40.50 g"));
}

#[test]
fn tiny_sizes_render_without_panic() {
    let mut fresh = App::new(Design::default(), "default", Palette::default());
    let mut done = computed_app();
    for app in [&mut fresh, &mut done] {
        app.data_dir = Some(std::env::temp_dir().join("thud-tui-tiny-sizes-none"));
        for mode in [
            Mode::Normal,
            Mode::Help,
            Mode::Presets(0),
            Mode::Editing("40".into()),
            Mode::SaveAs("design-1".into()),
            Mode::Saved(0),
            Mode::Export(3),
        ] {
            app.mode = mode;
            for w in 0..=20 {
                for h in 0..=5 {
                    draw_only(app, w, h);
                }
            }
            for (w, h) in [(30, 8), (59, 11), (60, 12), (79, 23), (109, 33), (200, 60)] {
                draw_only(app, w, h);
            }
        }
    }
}

#[test]
fn help_overlay_lists_every_binding() {
    let mut app = computed_app();
    press(&mut app, KeyCode::Char('?'));
    assert_eq!(app.mode, Mode::Help);
    let screen = render(&mut app, 120, 40);
    for b in KEYS {
        assert!(screen.contains(b.label), "help lacks key {}", b.label);
        assert!(screen.contains(b.help), "help lacks '{}'", b.help);
    }
    press(&mut app, KeyCode::Esc);
    assert_eq!(app.mode, Mode::Normal);
    assert!(!app.quit, "Esc closes the help, it does not quit");
}

#[test]
fn footer_shows_the_table_hints() {
    let mut app = computed_app();
    let screen = render(&mut app, 120, 40);
    let footer = screen.lines().last().unwrap();
    for (k, h) in thud::tui::keys::footer_hints() {
        assert!(footer.contains(&format!("{k} {h}")), "footer lacks {k} {h}: {footer}");
    }
}

#[test]
fn bad_typed_value_is_refused_in_the_status_line() {
    let mut app = computed_app();
    press(&mut app, KeyCode::Enter);
    type_text(&mut app, "abc");
    assert!(render(&mut app, 120, 40).contains("mass m = abc"));
    press(&mut app, KeyCode::Enter);
    let screen = render(&mut app, 120, 40);
    assert!(screen.contains("error: invalid mass"), "{screen}");
    assert!((app.design.damper.impact_mass_kg - 0.0405).abs() < 1e-15, "design unchanged");
    press(&mut app, KeyCode::Enter);
    type_text(&mut app, "-3g");
    press(&mut app, KeyCode::Enter);
    assert!(render(&mut app, 120, 40).contains("error: invalid mass"));
}

#[test]
fn typed_value_with_units_is_applied() {
    let mut app = computed_app();
    press(&mut app, KeyCode::Down);
    press(&mut app, KeyCode::Enter);
    type_text(&mut app, "3cm");
    press(&mut app, KeyCode::Enter);
    assert!((app.design.damper.gap_m - 0.03).abs() < 1e-15);
    let screen = render(&mut app, 120, 40);
    assert!(screen.contains("m 40.50 g, d 3.00 cm"), "{screen}");
}

#[test]
fn quit_keys_quit() {
    for (code, mods) in [
        (KeyCode::Char('q'), KeyModifiers::NONE),
        (KeyCode::Esc, KeyModifiers::NONE),
        (KeyCode::Char('c'), KeyModifiers::CONTROL),
    ] {
        let mut app = App::new(Design::default(), "default", Palette::default());
        app.update(Msg::Input(Event::Key(KeyEvent::new(code, mods))));
        assert!(app.quit);
    }
}

#[test]
fn pin_shows_the_pinned_column_and_chart_view_toggles() {
    let mut app = computed_app();
    press(&mut app, KeyCode::Char('p'));
    press(&mut app, KeyCode::Right);
    let screen = render(&mut app, 120, 40);
    assert!(screen.contains("pinned"), "{screen}");
    press(&mut app, KeyCode::Char('v'));
    let screen = render(&mut app, 120, 40);
    assert!(screen.contains("e vs SPLmax"), "{screen}");
}

#[test]
fn stale_results_are_dropped() {
    let mut app = computed_app();
    let old = app.design.clone();
    // Change the mass but do not compute: then feed a result computed for another design.
    let _pending = app.update(Msg::Input(Event::Key(KeyEvent::new(KeyCode::Right, KeyModifiers::NONE))));
    let mut other =
        App::with_grids(old, "default", Palette::default(), Grids { coarse: None, fine: Grid::standard(2, 2) });
    let sim_req = thud::tui::Request::Sim(other.design.clone());
    let got = std::sync::Mutex::new(Vec::new());
    thud::tui::worker::run_sync(&sim_req, &|d| got.lock().unwrap().push(d));
    for d in got.into_inner().unwrap() {
        assert!(app.update(Msg::Work(d)).is_empty(), "a stale result asks for nothing");
    }
    assert!(app.busy(), "still waiting for the new design");
    other.quit = true;
}

/// The kinds of work a key asks for, after moving the selection to `field`.
fn work_for_step(field: thud::tui::fields::Param) -> Vec<&'static str> {
    let mut app = computed_app();
    app.selected = thud::tui::fields::Param::ALL.iter().position(|f| *f == field).unwrap();
    let reqs = app.update(Msg::Input(Event::Key(KeyEvent::new(KeyCode::Right, KeyModifiers::NONE))));
    let kinds = reqs
        .iter()
        .map(|r| match r {
            thud::tui::Request::Sim(_) => "sim",
            thud::tui::Request::Acoustic(..) => "acoustic",
            thud::tui::Request::Chart(..) => "chart",
            thud::tui::Request::Relevel(..) => "relevel",
            thud::tui::Request::Export(_) => "export",
        })
        .collect();
    compute_sync(&mut app, reqs);
    assert!(!app.busy(), "{field:?}: all results in");
    kinds
}

#[test]
fn each_change_recomputes_only_what_it_must() {
    use thud::tui::fields::Param;
    assert_eq!(work_for_step(Param::Theta), ["acoustic", "relevel"], "θ: acoustics only");
    assert_eq!(work_for_step(Param::R), ["acoustic", "relevel"], "r: acoustics only");
    assert_eq!(work_for_step(Param::Mass), ["sim"], "m: this design only");
    assert_eq!(work_for_step(Param::Gap), ["sim"], "d: this design only");
    assert_eq!(work_for_step(Param::K), ["sim", "chart"], "K: design and sweep");
    assert!(work_for_step(Param::LStar).is_empty(), "L*: zones are reclassified on draw");
}

#[test]
fn theta_change_relevels_the_chart_like_a_fresh_sweep() {
    let mut app = computed_app();
    app.selected = thud::tui::fields::Param::ALL.iter().position(|f| *f == thud::tui::fields::Param::Theta).unwrap();
    press(&mut app, KeyCode::Left);
    let fresh = computed_with(app.design.clone());
    for (a, b) in app.chart.fine.cells.iter().zip(&fresh.chart.fine.cells) {
        let (a, b) = (a.unwrap().metrics.spl_max_db, b.unwrap().metrics.spl_max_db);
        assert_eq!(a.is_some(), b.is_some());
        if let (Some(a), Some(b)) = (a, b) {
            assert!((a - b).abs() < 1e-9);
        }
    }
}

fn computed_with(d: Design) -> App {
    let grids = Grids { coarse: None, fine: Grid::standard(6, 5) };
    let mut app = App::with_grids(d, "default", Palette::default(), grids);
    let reqs = app.initial_requests();
    compute_sync(&mut app, reqs);
    app
}

fn render_buffer(app: &mut App, w: u16, h: u16) -> ratatui::buffer::Buffer {
    let mut term = Terminal::new(TestBackend::new(w, h)).unwrap();
    draw(&mut term, app).unwrap();
    term.backend().buffer().clone()
}

#[test]
fn default_palette_is_the_16_named_colours_and_no_color_has_none() {
    use ratatui::style::Color;
    let mut app = computed_app();
    app.pinned = None;
    let named = |c: Color| !matches!(c, Color::Rgb(..) | Color::Indexed(_));
    let buf = render_buffer(&mut app, 120, 40);
    assert!(buf.content.iter().all(|c| named(c.fg) && named(c.bg)));
    assert!(buf.content.iter().any(|c| c.bg != Color::Reset), "zones are coloured by default");
    app.theme = Palette { color: false, ascii: false };
    let buf = render_buffer(&mut app, 120, 40);
    for c in &buf.content {
        assert_eq!((c.fg, c.bg), (Color::Reset, Color::Reset), "NO_COLOR: no colour at {:?}", c.symbol());
    }
    let screen = render(&mut app, 120, 40);
    assert!(screen.contains("[1]") || screen.contains('*'), "current design marked by a glyph");
    assert!(screen.contains("▶mass m"), "selection marked by a glyph");
}

#[test]
fn ascii_mode_draws_no_braille() {
    let mut app = computed_app();
    app.theme = Palette { color: true, ascii: true };
    let screen = render(&mut app, 120, 40);
    assert!(!screen.chars().any(|c| ('\u{2800}'..='\u{28ff}').contains(&c)), "{screen}");
    assert!(screen.contains(">mass m"));
}

#[test]
fn presets_list_applies_a_preset() {
    let mut app = computed_app();
    press(&mut app, KeyCode::Char('P'));
    assert!(render(&mut app, 120, 40).contains("paper-table3"));
    let target = app.preset_list.iter().position(|p| p.name == "paper-table3").unwrap();
    for _ in 0..target {
        press(&mut app, KeyCode::Down);
    }
    press(&mut app, KeyCode::Enter);
    assert_eq!(app.preset, "paper-table3");
    assert_eq!(app.design.damper.v0_m_s, 1.4);
    assert!(render(&mut app, 120, 40).contains("preset paper-table3"));
    press(&mut app, KeyCode::Char('u'));
    assert_eq!(app.design.damper.v0_m_s, 2.0, "undo restores the design");
}

#[test]
fn mouse_click_on_the_chart_selects_that_design() {
    let mut app = computed_app();
    app.mouse = true;
    render(&mut app, 120, 40);
    let geo = app.chart_geometry.clone().expect("chart drawn");
    let r = geo.rect(0, 0);
    let click = crossterm::event::MouseEvent {
        kind: crossterm::event::MouseEventKind::Down(crossterm::event::MouseButton::Left),
        column: r.x,
        row: r.y,
        modifiers: KeyModifiers::NONE,
    };
    let reqs = app.update(Msg::Input(Event::Mouse(click)));
    compute_sync(&mut app, reqs);
    assert_eq!(app.design.damper.impact_mass_kg, app.chart.fine.masses_kg[geo.cols[0]]);
    assert_eq!(app.design.damper.gap_m, app.chart.fine.gaps_m[geo.rows[0]]);
    assert!(!app.busy());
}

#[test]
fn chart_focus_moves_the_design_across_the_grid() {
    let mut app = computed_app();
    while app.focus != thud::tui::app::Panel::Chart {
        press(&mut app, KeyCode::Tab);
    }
    let m0 = app.design.damper.impact_mass_kg;
    press(&mut app, KeyCode::Right);
    assert!(app.design.damper.impact_mass_kg > m0);
    assert!(app.chart.fine.masses_kg.contains(&app.design.damper.impact_mass_kg));
}

// ---- settings, saved designs and export (issue 5) ----

fn status_of(screen: &str) -> &str {
    let lines: Vec<&str> = screen.lines().collect();
    lines[lines.len() - 2]
}

fn clear_line(app: &mut App) {
    for _ in 0..70 {
        press(app, KeyCode::Backspace);
    }
}

#[test]
fn save_then_load_round_trips_through_the_keys() {
    let data = tempfile::tempdir().unwrap();
    let mut app = computed_app();
    app.data_dir = Some(data.path().to_path_buf());
    press(&mut app, KeyCode::Right);
    let saved_mass = app.design.damper.impact_mass_kg;
    press(&mut app, KeyCode::Char('s'));
    assert_eq!(app.mode, Mode::SaveAs("design-1".into()), "a sensible name is offered");
    assert!(render(&mut app, 120, 40).contains("save as: design-1"));
    clear_line(&mut app);
    type_text(&mut app, "my-test");
    press(&mut app, KeyCode::Enter);
    let path = data.path().join("designs").join("my-test.toml");
    assert!(path.exists());
    let screen = render(&mut app, 120, 40);
    assert!(status_of(&screen).contains("saved my-test to"), "{screen}");

    // Move away, then load it back from the list.
    press(&mut app, KeyCode::Right);
    press(&mut app, KeyCode::Right);
    assert_ne!(app.design.damper.impact_mass_kg, saved_mass);
    press(&mut app, KeyCode::Char('L'));
    assert_eq!(app.mode, Mode::Saved(0));
    let screen = render(&mut app, 120, 40);
    assert!(screen.contains("saved designs") && screen.contains("my-test"), "{screen}");
    press(&mut app, KeyCode::Enter);
    assert_eq!(app.design.damper.impact_mass_kg, saved_mass);
    assert!(!app.busy(), "loading recomputes like any change");
    assert!(render(&mut app, 120, 40).contains("loaded my-test"));
    press(&mut app, KeyCode::Char('u'));
    assert_ne!(app.design.damper.impact_mass_kg, saved_mass, "loading is undoable");

    // `o` opens the same list; Esc closes it.
    press(&mut app, KeyCode::Char('o'));
    assert_eq!(app.mode, Mode::Saved(0));
    press(&mut app, KeyCode::Esc);
    assert_eq!(app.mode, Mode::Normal);
    assert!(!app.quit);
}

#[test]
fn saving_with_a_bad_name_or_an_unwritable_dir_is_an_error_line() {
    let data = tempfile::tempdir().unwrap();
    let mut app = computed_app();
    app.data_dir = Some(data.path().to_path_buf());
    press(&mut app, KeyCode::Char('s'));
    clear_line(&mut app);
    type_text(&mut app, "../evil");
    press(&mut app, KeyCode::Enter);
    let screen = render(&mut app, 120, 40);
    assert!(status_of(&screen).contains("error: cannot save"), "{screen}");
    assert!(!data.path().join("designs").exists());

    // A data dir that is a file: the directory cannot be created.
    let file = data.path().join("not-a-dir");
    std::fs::write(&file, "x").unwrap();
    app.data_dir = Some(file);
    press(&mut app, KeyCode::Char('s'));
    press(&mut app, KeyCode::Enter);
    let screen = render(&mut app, 120, 40);
    assert!(status_of(&screen).contains("error: cannot save design-1"), "{screen}");
    assert!(!app.quit);
}

#[test]
fn the_load_list_shows_a_corrupt_saved_file_as_a_problem() {
    let data = tempfile::tempdir().unwrap();
    let designs = data.path().join("designs");
    std::fs::create_dir_all(&designs).unwrap();
    std::fs::write(designs.join("broken.toml"), "description = \"x\"\n[design\n").unwrap();
    let mut app = computed_app();
    app.data_dir = Some(data.path().to_path_buf());
    app.save_as("good");
    let before = app.design.clone();
    press(&mut app, KeyCode::Char('L'));
    let screen = render(&mut app, 120, 40);
    assert!(screen.contains("good") && screen.contains("broken.toml (cannot be loaded)"), "{screen}");
    press(&mut app, KeyCode::Down);
    let screen = render(&mut app, 120, 40);
    assert!(screen.contains("broken.toml:2:"), "the problem names the file and line:\n{screen}");
    press(&mut app, KeyCode::Enter);
    let screen = render(&mut app, 120, 40);
    assert!(status_of(&screen).contains("error: cannot load"), "{screen}");
    assert_eq!(app.design, before, "nothing loaded");
    assert_eq!(std::fs::read_to_string(designs.join("broken.toml")).unwrap(), "description = \"x\"\n[design\n");
}

#[test]
fn a_corrupt_config_warns_in_the_status_line_and_the_app_runs_on_defaults() {
    let dir = tempfile::tempdir().unwrap();
    let text = "theme = \"mono\"\nmarkers = 3\n";
    std::fs::write(dir.path().join("config.toml"), text).unwrap();
    let load = thud::config::load_config(dir.path());
    let mut app = computed_app();
    app.configure(&load);
    let screen = render(&mut app, 120, 40);
    let status = status_of(&screen);
    assert!(status.contains("warning:") && status.contains("config.toml:2:"), "{screen}");
    assert!(screen.contains("parameters") && screen.contains("U0max"), "still renders:\n{screen}");
    assert!(app.theme.color, "defaults, not the half-read file");
    assert_eq!(std::fs::read_to_string(dir.path().join("config.toml")).unwrap(), text, "file untouched");
    press(&mut app, KeyCode::Right);
    assert!(render(&mut app, 120, 40).contains("41.50 g"), "keys still work");
}

#[test]
fn config_sets_theme_markers_and_thresholds() {
    let dir = tempfile::tempdir().unwrap();
    let text = "theme = \"mono\"\nmarkers = \"ascii\"\n[thresholds]\nl_star_db = 99.5\ne_star_cm_s = 3.25\n";
    std::fs::write(dir.path().join("config.toml"), text).unwrap();
    let mut app = computed_app();
    app.configure(&thud::config::load_config(dir.path()));
    assert_eq!(app.theme, Palette { color: false, ascii: true });
    assert_eq!((app.design.thresholds.spl_db, app.design.thresholds.inclination_cm_s), (99.5, 3.25));
    let screen = render(&mut app, 120, 40);
    assert!(screen.contains("L* 99.5 dB") && screen.contains("e* 3.25 cm/s"), "{screen}");
    assert!(!screen.chars().any(|c| ('\u{2800}'..='\u{28ff}').contains(&c)), "ascii markers");
}

#[test]
fn a_key_override_shows_in_help_and_footer_and_works() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("config.toml"), "[keys]\nsave = \"ctrl-s\"\npin = \"q\"\n").unwrap();
    let mut app = computed_app();
    app.configure(&thud::config::load_config(dir.path()));
    let screen = render(&mut app, 120, 40);
    assert!(status_of(&screen).contains("pin = \"q\": that key is already quit"), "bad override reported:\n{screen}");
    assert!(screen.lines().last().unwrap().contains("Ctrl-S save"), "footer:\n{screen}");
    press(&mut app, KeyCode::Char('?'));
    let help = render(&mut app, 120, 40);
    let save_row = help.lines().find(|l| l.contains("save this design")).unwrap();
    assert!(save_row.contains("Ctrl-S") && save_row.contains("save"), "{save_row}");
    press(&mut app, KeyCode::Esc);
    press(&mut app, KeyCode::Char('s'));
    assert_eq!(app.mode, Mode::Normal, "s is no longer save");
    press_mod(&mut app, KeyCode::Char('s'), KeyModifiers::CONTROL);
    assert!(matches!(app.mode, Mode::SaveAs(_)), "Ctrl-S saves");
    press(&mut app, KeyCode::Esc);
    press(&mut app, KeyCode::Char('p'));
    assert!(app.pinned.is_some(), "the refused override left p as pin");
}

#[test]
fn export_through_the_key_writes_the_file_and_names_it() {
    let out = tempfile::tempdir().unwrap();
    let mut app = computed_app();
    app.export_dir = out.path().to_path_buf();
    press(&mut app, KeyCode::Char('e'));
    assert_eq!(app.mode, Mode::Export(0));
    let screen = render(&mut app, 120, 40);
    assert!(screen.contains("waveform CSV") && screen.contains("sound WAV"), "{screen}");
    press(&mut app, KeyCode::Enter); // waveform CSV, computed synchronously by compute_sync
    let file = out.path().join("thud-waveform.csv");
    assert!(std::fs::read_to_string(&file).unwrap().starts_with("t_s,p_pa"));
    let screen = render(&mut app, 120, 40);
    assert!(status_of(&screen).contains("exported waveform CSV") && screen.contains("thud-waveform.csv"), "{screen}");
    // Again: a new name, the first file is kept.
    press(&mut app, KeyCode::Char('e'));
    press(&mut app, KeyCode::Enter);
    assert!(out.path().join("thud-waveform-1.csv").exists());
    assert!(render(&mut app, 120, 40).contains("thud-waveform-1.csv"));
    // The chart SVG uses the chart's grid.
    press(&mut app, KeyCode::Char('e'));
    let chart = thud::tui::files::EXPORTS.iter().position(|(k, _)| *k == thud::export::Kind::SvgChart).unwrap();
    for _ in 0..chart {
        press(&mut app, KeyCode::Down);
    }
    press(&mut app, KeyCode::Enter);
    assert!(std::fs::read_to_string(out.path().join("thud-chart.svg")).unwrap().contains("<svg"));
    assert!(app.exports.is_empty() && !app.busy());
}

#[test]
fn export_runs_on_the_worker_and_failures_reach_the_status_line() {
    use std::time::Duration;
    let out = tempfile::tempdir().unwrap();
    let mut app = computed_app();
    app.export_dir = out.path().to_path_buf();
    let (tx, rx) = std::sync::mpsc::channel();
    let worker = thud::tui::Worker::start(move |d| {
        let _ = tx.send(d);
    });
    worker.submit(app.export(thud::export::Kind::Wav));
    assert!(app.busy(), "the spinner turns while the file is written");
    assert!(render(&mut app, 120, 40).contains("exporting"));
    let done = rx.recv_timeout(Duration::from_secs(30)).expect("the export finished");
    app.update(Msg::Work(done));
    assert!(!app.busy());
    let wav = out.path().join("thud-sound.wav");
    assert!(std::fs::metadata(&wav).unwrap().len() > 44);
    assert!(status_of(&render(&mut app, 120, 40)).contains("exported sound WAV"));

    // An export dir that is a file: an error line, no crash.
    let file = out.path().join("plain-file");
    std::fs::write(&file, "x").unwrap();
    app.export_dir = file;
    worker.submit(app.export(thud::export::Kind::CsvImpacts));
    let done = rx.recv_timeout(Duration::from_secs(30)).expect("the export finished");
    app.update(Msg::Work(done));
    let screen = render(&mut app, 120, 40);
    assert!(status_of(&screen).contains("error: export of impacts CSV failed"), "{screen}");
}

// ---- saving over a name asks first (issue 9); a crashed job is an error, not a hang ----

#[test]
fn saving_over_an_existing_name_asks_first_and_only_y_overwrites() {
    let data = tempfile::tempdir().unwrap();
    let mut app = computed_app();
    app.data_dir = Some(data.path().to_path_buf());
    press(&mut app, KeyCode::Char('s'));
    clear_line(&mut app);
    type_text(&mut app, "mine");
    press(&mut app, KeyCode::Enter);
    assert_eq!(app.mode, Mode::Normal, "a new name is saved without a question");
    let path = data.path().join("designs").join("mine.toml");
    let first = std::fs::read_to_string(&path).unwrap();

    press(&mut app, KeyCode::Right);
    for refusal in [KeyCode::Char('n'), KeyCode::Esc, KeyCode::Enter] {
        press(&mut app, KeyCode::Char('s'));
        assert_eq!(app.mode, Mode::SaveAs("mine".into()), "the saved name is offered");
        press(&mut app, KeyCode::Enter);
        assert_eq!(app.mode, Mode::ConfirmOverwrite("mine".into()));
        let screen = render(&mut app, 120, 40);
        assert!(status_of(&screen).contains("overwrite mine? y/n"), "{screen}");
        for (w, h) in [(0, 0), (10, 3), (30, 8), (80, 24)] {
            draw_only(&mut app, w, h);
        }
        press(&mut app, refusal);
        assert_eq!(app.mode, Mode::Normal);
        assert!(!app.quit);
        assert_eq!(std::fs::read_to_string(&path).unwrap(), first, "{refusal:?} keeps the saved design");
        assert!(status_of(&render(&mut app, 120, 40)).contains("save cancelled"));
    }

    press(&mut app, KeyCode::Char('s'));
    press(&mut app, KeyCode::Enter);
    press(&mut app, KeyCode::Char('y'));
    assert_eq!(app.mode, Mode::Normal);
    assert!(status_of(&render(&mut app, 120, 40)).contains("saved mine to"));
    let saved = thud::store::load_design(data.path(), "mine").unwrap();
    assert_eq!(saved.design, app.design, "y overwrote the file with the live design");
    assert_ne!(std::fs::read_to_string(&path).unwrap(), first);
}

/// A job that panics, standing in for the simulation of the design with `key`.
struct Crash {
    key: String,
}

impl thud::tui::job::Job for Crash {
    const NAME: &'static str = "simulation";
    type Report = thud::tui::worker::Done;
    type State = ();

    fn key(&self) -> &str {
        &self.key
    }

    fn run(&self, (): &mut (), _: &thud::tui::job::Context<'_, Self::Report>) {
        panic!("injected failure");
    }

    fn failed(&self, error: thud::tui::job::JobError) -> Self::Report {
        thud::tui::worker::Done::Sim { key: self.key.clone(), result: Err(error.into()) }
    }
}

#[test]
fn a_panicking_job_is_an_error_in_the_status_line_and_frees_its_slot() {
    use std::time::Duration;
    let mut app = computed_app();
    // Change the mass but do not compute: the app now waits for that design's simulation.
    let _pending = app.update(Msg::Input(Event::Key(KeyEvent::new(KeyCode::Right, KeyModifiers::NONE))));
    assert!(app.busy());
    let (tx, rx) = std::sync::mpsc::channel();
    let runner = thud::tui::job::SingleJob::start(std::sync::Arc::new(move |d| {
        let _ = tx.send(d);
    }));
    let key = thud::tui::compute::sim_key(&app.design);
    runner.spawn(Crash { key: key.clone() });
    let done = rx.recv_timeout(Duration::from_secs(30)).expect("the runner answered the crashed job");
    assert!(!runner.is_pending(), "the slot is free, not stuck running");
    app.update(Msg::Work(done));
    let screen = render(&mut app, 120, 40);
    let status = status_of(&screen);
    assert!(status.contains("error: internal error in the simulation job: injected failure"), "{screen}");
    assert!(!app.busy(), "the app stops waiting for the crashed job");

    runner.spawn(Crash { key });
    rx.recv_timeout(Duration::from_secs(30)).expect("the same runner takes the next job");
    // The next change computes again and clears the error.
    press(&mut app, KeyCode::Right);
    let screen = render(&mut app, 120, 40);
    assert!(!status_of(&screen).contains("error"), "{screen}");
    assert!(!app.busy());
}
