//! The explorer on ratatui's TestBackend: snapshots of the main screen, keys changing state
//! and the next frame, tiny terminals, the help overlay and refused input.

use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use ratatui::backend::TestBackend;
use ratatui::Terminal;
use thud::design::Design;
use thud::tui::app::{App, Mode, Msg};
use thud::tui::keys::KEYS;
use thud::tui::worker::{Grid, Grids};
use thud::tui::{compute_sync, draw, Theme};

/// The default design with every result computed on this thread (small chart grid).
fn computed_app() -> App {
    let grids = Grids { coarse: None, fine: Grid::standard(6, 5) };
    let mut app = App::with_grids(Design::default(), "default", Theme { color: true, ascii: false }, grids);
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
    let mut fresh = App::new(Design::default(), "default", Theme::default());
    let mut done = computed_app();
    for app in [&mut fresh, &mut done] {
        for mode in [Mode::Normal, Mode::Help, Mode::Presets(0), Mode::Editing("40".into())] {
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
        let mut app = App::new(Design::default(), "default", Theme::default());
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
        App::with_grids(old, "default", Theme::default(), Grids { coarse: None, fine: Grid::standard(2, 2) });
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
fn work_for_step(field: thud::tui::fields::Field) -> Vec<&'static str> {
    let mut app = computed_app();
    app.selected = thud::tui::fields::Field::ALL.iter().position(|f| *f == field).unwrap();
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
    use thud::tui::fields::Field;
    assert_eq!(work_for_step(Field::Theta), ["acoustic", "relevel"], "θ: acoustics only");
    assert_eq!(work_for_step(Field::R), ["acoustic", "relevel"], "r: acoustics only");
    assert_eq!(work_for_step(Field::Mass), ["sim"], "m: this design only");
    assert_eq!(work_for_step(Field::Gap), ["sim"], "d: this design only");
    assert_eq!(work_for_step(Field::K), ["sim", "chart"], "K: design and sweep");
    assert!(work_for_step(Field::LStar).is_empty(), "L*: zones are reclassified on draw");
}

#[test]
fn theta_change_relevels_the_chart_like_a_fresh_sweep() {
    let mut app = computed_app();
    app.selected = thud::tui::fields::Field::ALL.iter().position(|f| *f == thud::tui::fields::Field::Theta).unwrap();
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
    let mut app = App::with_grids(d, "default", Theme::default(), grids);
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
    app.theme = Theme { color: false, ascii: false };
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
    app.theme = Theme { color: true, ascii: true };
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
