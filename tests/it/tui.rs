#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test or benchmark fails
//! The explorer on ratatui's TestBackend: snapshots of the main screen, keys changing state
//! and the next frame, tiny terminals, the help overlay and refused input.

use crate::support::explorer::render;
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
    let mut app =
        App::with_grids(Design::default(), "default", Palette { color: true, ascii: false, light: false }, grids);
    let reqs = app.initial_requests();
    compute_sync(&mut app, reqs);
    app
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
        app.host.data_dir = Some(std::env::temp_dir().join("thud-tui-tiny-sizes-none"));
        for mode in [
            Mode::Normal,
            Mode::Help(0),
            Mode::Help(40),
            Mode::ConfirmQuit,
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
    assert_eq!(app.mode, Mode::Help(0));
    let screen = help_text(&mut app, 120, 40);
    for b in KEYS {
        assert!(screen.contains(b.label), "help lacks key {}", b.label);
        assert!(screen.contains(b.help), "help lacks '{}'", b.help);
    }
    press(&mut app, KeyCode::Esc);
    assert_eq!(app.mode, Mode::Normal);
    assert!(!app.quit, "Esc closes the help, it does not quit");
}

/// Every line the help shows at `w`×`h`, scrolled through from the top with ↓ (the app is
/// left at the top again).
fn help_text(app: &mut App, w: u16, h: u16) -> String {
    let mut seen: Vec<String> = Vec::new();
    for _ in 0..80 {
        for l in render(app, w, h).lines() {
            if !seen.iter().any(|s| s == l) {
                seen.push(l.to_string());
            }
        }
        press(app, KeyCode::Down);
    }
    press(app, KeyCode::Home);
    seen.join("\n")
}

#[test]
fn esc_never_quits_the_main_view_and_q_asks_once_with_unsaved_changes() {
    // Esc on the main view: nothing closes, nothing quits, the status line says how to quit.
    let mut app = computed_app();
    press(&mut app, KeyCode::Esc);
    assert!(!app.quit, "Esc must not quit the main view");
    assert_eq!(app.mode, Mode::Normal);
    assert!(status_of(&render(&mut app, 80, 24)).contains("q quits"));
    // Esc leaves the tour without quitting.
    press(&mut app, KeyCode::Char('T'));
    assert!(app.tour.is_some());
    press(&mut app, KeyCode::Esc);
    assert!(app.tour.is_none() && !app.quit);
    // An unknown key says so.
    let mut app = computed_app();
    press(&mut app, KeyCode::Char('Z'));
    assert!(status_of(&render(&mut app, 80, 24)).contains("unknown key — ? for help"));
    assert!(!app.quit);

    // Unchanged design: q quits at once.
    let mut app = computed_app();
    assert!(!render(&mut app, 80, 24).lines().next().unwrap().contains("default*"));
    press(&mut app, KeyCode::Char('q'));
    assert!(app.quit);

    // Changed: q asks once; n stays, y quits.
    let mut app = computed_app();
    press(&mut app, KeyCode::Right);
    assert!(render(&mut app, 80, 24).lines().next().unwrap().contains("preset default*"), "modified mark");
    press(&mut app, KeyCode::Char('q'));
    assert!(!app.quit);
    assert_eq!(app.mode, Mode::ConfirmQuit);
    assert!(status_of(&render(&mut app, 80, 24)).contains("quit without saving? y/n"));
    press(&mut app, KeyCode::Char('n'));
    assert!(!app.quit);
    assert_eq!(app.mode, Mode::Normal);
    press(&mut app, KeyCode::Char('q'));
    press(&mut app, KeyCode::Esc);
    assert!(!app.quit, "Esc answers no");
    press(&mut app, KeyCode::Char('q'));
    press(&mut app, KeyCode::Char('y'));
    assert!(app.quit);

    // q in a list popup asks the same; Ctrl-C always quits.
    let mut app = computed_app();
    press(&mut app, KeyCode::Right);
    press(&mut app, KeyCode::Char('P'));
    press(&mut app, KeyCode::Char('q'));
    assert_eq!(app.mode, Mode::ConfirmQuit);
    press_mod(&mut app, KeyCode::Char('c'), KeyModifiers::CONTROL);
    assert!(app.quit);

    // Saving makes it unmodified again: q quits.
    let data = tempfile::tempdir().unwrap();
    let mut app = computed_app();
    app.host.data_dir = Some(data.path().to_path_buf());
    press(&mut app, KeyCode::Right);
    app.save_as("kept");
    assert!(!render(&mut app, 80, 24).lines().next().unwrap().contains('*'));
    press(&mut app, KeyCode::Char('q'));
    assert!(app.quit);
}

#[test]
fn a_failed_load_keeps_the_list_open_with_the_whole_error() {
    let data = tempfile::tempdir().unwrap();
    let mut app = computed_app();
    app.host.data_dir = Some(data.path().to_path_buf());
    app.save_as("good-but-later-broken");
    press(&mut app, KeyCode::Char('L'));
    assert_eq!(app.mode, Mode::Saved(0));
    // The file goes bad after the list was read: loading it fails.
    let path = data.path().join("designs").join("good-but-later-broken.toml");
    std::fs::write(&path, "description = \"x\"\n[design]\nnot_a_field_of_any_design = 1\n").unwrap();
    press(&mut app, KeyCode::Enter);
    assert_eq!(app.mode, Mode::Saved(0), "the list stays open");
    let status = app.status().unwrap().text.clone();
    assert!(status.contains("cannot load good-but-later-broken"), "{status}");
    let why = status.trim_start_matches("error: ").to_string();
    for (w, h) in [(80, 24), (120, 40)] {
        let screen = render(&mut app, w, h);
        // The whole error is inside the popup (wrapped, never cut): its rows, read between
        // the popup's borders, hold every character of it in order.
        let lines: Vec<Vec<char>> = screen.lines().map(|l| l.trim_matches('"').chars().collect()).collect();
        let top = lines.iter().position(|l| l.iter().collect::<String>().contains("┌ saved designs")).unwrap();
        let x = lines[top].iter().collect::<String>().split("┌ saved designs").next().unwrap().chars().count();
        let w = lines[top][x..].iter().position(|&c| c == '┐').unwrap();
        let popup: String = lines[top + 1..]
            .iter()
            .take_while(|l| l[x] == '│')
            .map(|l| l[x + 1..x + w].iter().collect::<String>())
            .collect();
        let squeezed: String = why.split_whitespace().collect();
        let shown: String = popup.split_whitespace().collect();
        assert!(shown.contains(&squeezed), "{w}x{h}: error not whole:\n{why}\n{screen}");
    }
    press(&mut app, KeyCode::Esc);
    assert_eq!(app.mode, Mode::Normal);
    assert!(!app.quit);
}

#[test]
fn help_scrolls_wraps_and_closes_only_on_esc_question_mark_or_q() {
    let mut app = computed_app();
    press(&mut app, KeyCode::Char('?'));
    let top = render(&mut app, 80, 24);
    assert!(top.contains("more below"), "{top}");
    // ↓ scrolls instead of closing; PgDn a page; PgUp back.
    press(&mut app, KeyCode::Down);
    assert_eq!(app.mode, Mode::Help(1));
    assert_ne!(render(&mut app, 80, 24), top);
    press(&mut app, KeyCode::PageDown);
    assert_eq!(app.mode, Mode::Help(11));
    press(&mut app, KeyCode::PageUp);
    press(&mut app, KeyCode::Up);
    assert_eq!(app.mode, Mode::Help(0));
    // Stray keys leave it open.
    for c in ['x', 'v', 'p', 'u'] {
        press(&mut app, KeyCode::Char(c));
        assert_eq!(app.mode, Mode::Help(0), "{c} closed the help");
    }
    // Every binding's whole help text is reachable at 80×24 (wrapped, not cut).
    let all = help_text(&mut app, 80, 24);
    let words: String = all.split_whitespace().collect::<Vec<_>>().join(" ");
    for b in KEYS {
        for word in b.help.split_whitespace() {
            assert!(words.contains(word), "help at 80x24 lacks '{word}' of '{}'", b.help);
        }
    }
    let last = b_last_words(KEYS.last().unwrap().help);
    assert!(all.replace(['│', '\n'], " ").split_whitespace().collect::<Vec<_>>().join(" ").contains(&last), "{all}");
    for close in [KeyCode::Esc, KeyCode::Char('?'), KeyCode::Char('q')] {
        press(&mut app, KeyCode::Char('?'));
        press(&mut app, close);
        assert_eq!(app.mode, Mode::Normal);
        assert!(!app.quit, "{close:?} closes the help, it does not quit");
    }
    // The second page scrolls the same way.
    press(&mut app, KeyCode::Char('?'));
    press(&mut app, KeyCode::Right);
    press(&mut app, KeyCode::PageDown);
    assert_eq!(app.mode, Mode::Glossary(10));
}

/// The last three words of a help text (the part a cut would lose).
fn b_last_words(help: &str) -> String {
    let w: Vec<&str> = help.split_whitespace().collect();
    w[w.len().saturating_sub(3)..].join(" ")
}

#[test]
fn footer_shows_the_table_hints() {
    let mut app = computed_app();
    let screen = render(&mut app, 200, 60);
    let footer = screen.lines().last().unwrap();
    for (k, h) in thud::tui::keys::footer_hints() {
        assert!(footer.contains(&format!("{k} {h}")), "footer lacks {k} {h}: {footer}");
    }
}

/// The footer's text (the last line of the screen, without the quotes TestBackend adds).
fn footer_of(screen: &str) -> String {
    screen.lines().last().unwrap().trim_matches('"').to_string()
}

/// At 80, 120 and 200 columns the footer leaves out no hint that would fit in the
/// room left, a hint is left out only for more important ones (`v view` is shown at 120), and
/// with the mouse on it says `mouse on` where it fits.
#[test]
fn the_footer_shows_every_hint_that_fits_by_importance() {
    use thud::tui::keys::{mouse_hint, Keymap, FOOTER_PRIORITY};
    let rank = |name: &str| FOOTER_PRIORITY.iter().position(|n| *n == name).unwrap();
    // " key hint ": what a hint takes on the footer.
    let cost = |h: &thud::tui::keys::Hint| h.label.chars().count() + h.hint.chars().count() + 3;
    for mouse in [false, true] {
        let mut app = computed_app();
        app.mouse = mouse;
        let mut hints = Keymap::default().footer_items(false);
        if mouse {
            hints.push(mouse_hint());
        }
        for w in [80u16, 120, 200] {
            let footer = footer_of(&render(&mut app, w, 40));
            let room = usize::from(w) + 1; // the last hint's trailing space may fall off
            let (shown, left_out): (Vec<_>, Vec<_>) =
                hints.iter().partition(|h| format!("{footer} ").contains(&format!(" {} {} ", h.label, h.hint)));
            let used: usize = shown.iter().map(|h| cost(h)).sum();
            assert!(used <= room, "{w} cols: {used} columns of hints:\n{footer}");
            for h in &left_out {
                assert!(
                    used + cost(h) > room,
                    "{w} cols, mouse {mouse}: `{} {}` fits but is left out:\n{footer}",
                    h.label,
                    h.hint
                );
                let before: usize = shown.iter().filter(|s| rank(s.name) < rank(h.name)).map(|s| cost(s)).sum();
                assert!(
                    before + cost(h) > room,
                    "{w} cols, mouse {mouse}: `{} {}` is left out for less important hints:\n{footer}",
                    h.label,
                    h.hint
                );
            }
            if w >= 120 {
                assert!(footer.contains(" v view "), "{w} cols:\n{footer}");
            }
            assert_eq!(footer.contains(" mouse on"), mouse, "{w} cols:\n{footer}");
            if w == 200 {
                assert!(left_out.is_empty(), "every hint at 200 columns, {left_out:?} left out:\n{footer}");
            }
        }
    }
}

/// The config's `mouse = false` turns the mouse off (and its footer word with it).
#[test]
fn config_mouse_false_turns_the_mouse_off() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir_all(dir.path()).unwrap();
    std::fs::write(dir.path().join("config.toml"), "mouse = false\n").unwrap();
    let load = thud::config::load_config(dir.path());
    let mut app = computed_app();
    app.mouse = true;
    app.configure(&load);
    assert!(!app.mouse, "mouse = false in config.toml");
    assert!(!footer_of(&render(&mut app, 200, 60)).contains("mouse"));
    let mut app = computed_app();
    app.mouse = true;
    app.configure(&thud::config::load_config(&dir.path().join("none")));
    assert!(app.mouse, "no config: the mouse stays on");
    assert!(footer_of(&render(&mut app, 200, 60)).contains(" mouse on"));
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
    for (code, mods) in [(KeyCode::Char('q'), KeyModifiers::NONE), (KeyCode::Char('c'), KeyModifiers::CONTROL)] {
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
fn work_for_step(field: thud::tui::fields::Knob) -> Vec<&'static str> {
    let mut app = computed_app();
    app.selected = thud::tui::fields::Knob::ALL.iter().position(|f| *f == field).unwrap();
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
    use thud::tui::fields::Knob;
    assert_eq!(work_for_step(Knob::THETA), ["acoustic", "relevel"], "θ: acoustics only");
    assert_eq!(work_for_step(Knob::R), ["acoustic", "relevel"], "r: acoustics only");
    assert_eq!(work_for_step(Knob::MASS), ["sim"], "m: this design only");
    assert_eq!(work_for_step(Knob::GAP), ["sim"], "d: this design only");
    assert_eq!(work_for_step(Knob::K), ["sim", "chart"], "K: design and sweep");
    assert!(work_for_step(Knob::L_STAR).is_empty(), "L*: zones are reclassified on draw");
}

#[test]
fn theta_change_relevels_the_chart_like_a_fresh_sweep() {
    let mut app = computed_app();
    app.selected = thud::tui::fields::Knob::ALL.iter().position(|f| *f == thud::tui::fields::Knob::THETA).unwrap();
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
    app.theme = Palette { color: false, ascii: false, light: false };
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
    app.theme = Palette { color: true, ascii: true, light: false };
    let screen = render(&mut app, 120, 40);
    assert!(!screen.chars().any(|c| ('\u{2800}'..='\u{28ff}').contains(&c)), "{screen}");
    assert!(screen.contains(">mass m"));
}

#[test]
fn presets_list_applies_a_preset() {
    let mut app = computed_app();
    press(&mut app, KeyCode::Char('P'));
    assert!(render(&mut app, 120, 40).contains("paper-table3"));
    let target = app.host.preset_list.iter().position(|p| p.name == "paper-table3").unwrap();
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
    let geo = app.drawn.geometry.clone().expect("chart drawn");
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

// ---- settings, saved designs and export ----

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
    app.host.data_dir = Some(data.path().to_path_buf());
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
    app.host.data_dir = Some(data.path().to_path_buf());
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
    app.host.data_dir = Some(file);
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
    app.host.data_dir = Some(data.path().to_path_buf());
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
    assert_eq!(app.theme, Palette { color: false, ascii: true, light: false });
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
    app.host.export_dir = out.path().to_path_buf();
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
    let chart = thud::tui::files::EXPORTS.iter().position(|(k, _)| *k == thud::export::Artifact::SvgChart).unwrap();
    for _ in 0..chart {
        press(&mut app, KeyCode::Down);
    }
    press(&mut app, KeyCode::Enter);
    assert!(std::fs::read_to_string(out.path().join("thud-chart.svg")).unwrap().contains("<svg"));
    assert!(app.host.exports.is_empty() && !app.busy());
}

/// With `--ascii` the explorer's figures are spelled as `thud export svg --ascii` spells them:
/// pure ASCII, where the default keeps the true minus sign.
#[test]
fn an_ascii_explorer_exports_ascii_figures() {
    let out = tempfile::tempdir().unwrap();
    let mut app = computed_app();
    app.host.export_dir = out.path().to_path_buf();
    let job = |app: &mut thud::tui::App| match app.export(thud::export::Artifact::SvgWaveform) {
        Some(thud::tui::Request::Export(job)) => job,
        other => panic!("no export job: {other:?}"),
    };
    let unicode = job(&mut app);
    assert!(matches!(unicode.run(), thud::tui::worker::Done::Export { result: Ok(()), .. }));
    let text = std::fs::read_to_string(&unicode.path).unwrap();
    assert!(!text.is_ascii() && text.contains('\u{2212}'), "the default figure keeps the true minus");
    app.theme = Palette { color: true, ascii: true, light: false };
    let ascii = job(&mut app);
    assert!(matches!(ascii.run(), thud::tui::worker::Done::Export { result: Ok(()), .. }));
    let text = std::fs::read_to_string(&ascii.path).unwrap();
    let body = text.split_once("?>").map_or(text.as_str(), |(_, b)| b);
    assert!(text.is_ascii() && body.contains("<svg") && !body.contains('?'), "{}", &text[..200.min(text.len())]);
}

#[test]
fn export_runs_on_the_worker_and_failures_reach_the_status_line() {
    use std::time::Duration;
    let out = tempfile::tempdir().unwrap();
    let mut app = computed_app();
    app.host.export_dir = out.path().to_path_buf();
    let (tx, rx) = std::sync::mpsc::channel();
    let worker = thud::tui::Worker::start(move |d| {
        let _ = tx.send(d);
    });
    worker.submit(app.export(thud::export::Artifact::Wav).unwrap());
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
    app.host.export_dir = file;
    worker.submit(app.export(thud::export::Artifact::CsvImpacts).unwrap());
    let done = rx.recv_timeout(Duration::from_secs(30)).expect("the export finished");
    app.update(Msg::Work(done));
    let screen = render(&mut app, 120, 40);
    assert!(status_of(&screen).contains("error: export of impacts CSV failed"), "{screen}");
}

// ---- saving over a name asks first; a crashed job is an error, not a hang ----

#[test]
fn saving_over_an_existing_name_asks_first_and_only_y_overwrites() {
    let data = tempfile::tempdir().unwrap();
    let mut app = computed_app();
    app.host.data_dir = Some(data.path().to_path_buf());
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
    key: thud::tui::cache_key::SimKey,
}

impl thud::tui::job::Job for Crash {
    const NAME: &'static str = "simulation";
    type Report = thud::tui::worker::Done;
    type State = ();
    type Key = thud::tui::cache_key::SimKey;

    fn key(&self) -> &Self::Key {
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
    let key = thud::tui::cache_key::SimKey::of(&app.design);
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

// ---- an explorer you can teach with ----

fn render_with(app: &mut App, w: u16, h: u16) -> (String, ratatui::buffer::Buffer) {
    let mut term = Terminal::new(TestBackend::new(w, h)).unwrap();
    draw(&mut term, app).unwrap();
    (term.backend().to_string(), term.backend().buffer().clone())
}

/// The default design on the full 16 × 12 chart, everything computed.
fn full_app(preset: &str, theme: Palette) -> App {
    let d = thud::presets::preset(preset).unwrap();
    let grids = Grids { coarse: None, fine: Grid::standard(16, 12) };
    let mut app = App::with_grids(d, preset, theme, grids);
    let reqs = app.initial_requests();
    compute_sync(&mut app, reqs);
    app
}

const SIZES: [(u16, u16); 3] = [(80, 24), (120, 40), (200, 60)];

/// Brings the chart on screen in the teaching layout (Tab to the history/chart pair).
fn show_chart(app: &mut App) {
    while app.focus != thud::tui::app::Panel::History {
        press(app, KeyCode::Tab);
    }
}

#[test]
fn snapshots_of_the_main_screen_the_tour_help_page_2_no_color_and_ascii() {
    for (w, h) in SIZES {
        let mut app = full_app("default", Palette { color: true, ascii: false, light: false });
        if (w, h) == (200, 60) {
            insta::assert_snapshot!("main_200x60", render(&mut app, w, h));
        }
        press(&mut app, KeyCode::Char('T'));
        insta::assert_snapshot!(format!("tour_step1_{w}x{h}"), render(&mut app, w, h));

        let mut app = full_app("default", Palette { color: true, ascii: false, light: false });
        press(&mut app, KeyCode::Char('?'));
        press(&mut app, KeyCode::Right);
        assert_eq!(app.mode, Mode::Glossary(0));
        let screen = render(&mut app, w, h);
        assert!(screen.contains("What the numbers mean"), "{screen}");
        insta::assert_snapshot!(format!("help2_{w}x{h}"), screen);

        let mut app = full_app("default", Palette { color: false, ascii: false, light: false });
        let (screen, buf) = render_with(&mut app, w, h);
        assert!(buf
            .content
            .iter()
            .all(|c| c.fg == ratatui::style::Color::Reset && c.bg == ratatui::style::Color::Reset));
        insta::assert_snapshot!(format!("no_color_{w}x{h}"), screen);

        let mut app = full_app("default", Palette { color: true, ascii: true, light: false });
        let screen = render(&mut app, w, h);
        assert!(screen.is_ascii(), "--ascii draws only ASCII:\n{screen}");
        assert!(screen.contains("theta") && screen.contains("us"), "units spelled in ASCII:\n{screen}");
        insta::assert_snapshot!(format!("ascii_{w}x{h}"), screen);
    }
}

#[test]
fn ascii_frames_are_pure_ascii_in_every_mode_and_size() {
    let mut app = full_app("default", Palette { color: false, ascii: true, light: false });
    app.host.data_dir = Some(std::env::temp_dir().join("thud-tui-ascii-none"));
    for mode in [
        Mode::Normal,
        Mode::Help(0),
        Mode::Help(9),
        Mode::ConfirmQuit,
        Mode::Glossary(3),
        Mode::Presets(0),
        Mode::Editing("40".into()),
        Mode::SaveAs("x".into()),
        Mode::Saved(0),
        Mode::Export(2),
    ] {
        app.mode = mode.clone();
        for (w, h) in [(30, 8), (59, 14), (80, 24), (100, 30), (120, 40), (200, 60)] {
            let screen = render(&mut app, w, h);
            assert!(screen.is_ascii(), "{mode:?} at {w}x{h}:\n{screen}");
        }
    }
    app.mode = Mode::Normal;
    press(&mut app, KeyCode::Char('T'));
    for (w, h) in SIZES {
        assert!(render(&mut app, w, h).is_ascii());
    }
    press(&mut app, KeyCode::Esc);
    press(&mut app, KeyCode::Char('v'));
    show_chart(&mut app);
    assert!(render(&mut app, 80, 24).is_ascii());
}

/// The zone number the readout shows ("zone    1 noisy, weak").
fn readout_zone(screen: &str) -> Option<char> {
    let line = screen.lines().find(|l| l.contains("│zone "))?;
    let after = &line[line.find("│zone ")? + "│zone ".len()..];
    after.trim_start().chars().next()
}

/// Every zone the chart's marker shows: `[n]` on the grid and in the line under it.
fn marker_zones(screen: &str) -> Vec<char> {
    let chars: Vec<char> = screen.chars().collect();
    chars.windows(3).filter(|w| w[0] == '[' && w[2] == ']').map(|w| w[1]).collect()
}

#[test]
fn the_chart_marker_shows_the_readouts_zone_for_random_designs_and_sizes() {
    // A seeded loop (xorshift) over designs on and off the chart and terminal sizes.
    let mut seed = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let sizes = [(80, 24), (90, 28), (100, 30), (120, 40), (160, 50), (200, 60)];
    let grids = Grids { coarse: None, fine: Grid::standard(6, 5) };
    let mut base = App::with_grids(Design::default(), "default", Palette::default(), grids);
    let reqs = base.initial_requests();
    compute_sync(&mut base, reqs);
    let mut checked = 0;
    for case in 0..24 {
        let (m, d) = (0.005 + 0.145 * next(), 0.004 + 0.09 * next());
        let (w, h) = sizes[case % sizes.len()];
        let reqs = base.select_design(m, d);
        compute_sync(&mut base, reqs);
        show_chart(&mut base);
        let screen = render(&mut base, w, h);
        let want = readout_zone(&screen).unwrap_or_else(|| panic!("no readout zone:\n{screen}"));
        let want = if want == '—' { '-' } else { want };
        let live = base.metrics().and_then(|x| base.zone(x)).map_or('-', |z| char::from(b'0' + z.number()));
        assert_eq!(want, live, "the readout is the engine's zone");
        let marks = marker_zones(&screen);
        assert!(!marks.is_empty(), "case {case} {m} kg {d} m at {w}x{h}: no marker\n{screen}");
        for z in marks {
            assert_eq!(z, want, "case {case}: m {m} kg, d {d} m at {w}x{h}\n{screen}");
        }
        let grid = &base.chart.fine;
        let on = |v: &[f64], x: f64| {
            let half = 0.5 * (v[1] - v[0]);
            x >= v[0] - half && x <= v[v.len() - 1] + half
        };
        let inside = on(&grid.masses_kg, m) && on(&grid.gaps_m, d);
        assert_eq!(!inside, screen.contains("off the chart"), "case {case}: {m} {d}\n{screen}");
        checked += 1;
        press(&mut base, KeyCode::Tab);
        press(&mut base, KeyCode::Tab);
        press(&mut base, KeyCode::Tab);
    }
    assert_eq!(checked, 24);
}

#[test]
fn the_default_design_at_200x60_is_marked_with_its_own_zone_not_a_cells() {
    let mut app = full_app("default", Palette::default());
    let screen = render(&mut app, 200, 60);
    assert_eq!(readout_zone(&screen), Some('1'), "{screen}");
    assert!(marker_zones(&screen).iter().all(|z| *z == '1'), "{screen}");
    // Stepping the gap moves the marker (4.82 → 5.36 cm were one row at 80×24 before).
    app.selected = 1;
    let reqs = app.select_design(0.0405, 0.0482);
    compute_sync(&mut app, reqs);
    show_chart(&mut app);
    let (a, buf_a) = render_with(&mut app, 80, 24);
    let geo_a = app.drawn.geometry.clone().unwrap();
    let reqs = app.select_design(0.0405, 0.0536);
    compute_sync(&mut app, reqs);
    let (b, buf_b) = render_with(&mut app, 80, 24);
    let geo_b = app.drawn.geometry.clone().unwrap();
    // The marker is the grid's reversed cell (`[n]`, or the zone glyph alone in narrow cells).
    let find = |buf: &ratatui::buffer::Buffer, geo: &thud::tui::chart::Geometry| {
        let c = geo.cells;
        (c.y..c.bottom())
            .find(|&y| (c.x..c.right()).any(|x| buf[(x, y)].modifier.contains(ratatui::style::Modifier::REVERSED)))
    };
    assert!(find(&buf_a, &geo_a).is_some(), "{a}");
    assert_ne!(find(&buf_a, &geo_a), find(&buf_b, &geo_b), "the marker moves with d:\n{a}\n{b}");
}

#[test]
fn at_80x24_the_pulse_and_the_polar_are_side_by_side_and_tab_brings_history_and_chart() {
    let mut app = full_app("default", Palette::default());
    let screen = render(&mut app, 80, 24);
    let top = screen.lines().nth(1).unwrap();
    assert!(top.contains("p(t)") && top.contains("SPL(θ)"), "{screen}");
    assert!(screen.contains("ms after the direct arrival"), "{screen}");
    assert!(screen.contains("readout") && screen.contains("parameters"));
    show_chart(&mut app);
    let screen = render(&mut app, 80, 24);
    let top = screen.lines().nth(1).unwrap();
    assert!(top.contains("x(t)") && top.contains("zones"), "{screen}");
    assert!(screen.contains("m (g)") && screen.contains("d (cm)") && screen.contains("no impact"), "{screen}");
}

#[test]
fn the_chart_has_axis_titles_round_ticks_and_the_whole_legend_at_every_size() {
    for (w, h) in [(80, 24), (100, 30), (120, 40), (160, 45), (200, 60)] {
        let mut app = full_app("default", Palette::default());
        show_chart(&mut app);
        let screen = render(&mut app, w, h);
        for want in
            ["m (g) →", "d (cm) ↑", "1 noisy,weak", "2 noisy,strong", "3 quiet,strong", "4 quiet,weak", "- no impact"]
        {
            assert!(screen.contains(want), "{w}x{h} lacks {want}:\n{screen}");
        }
        // Round mass ticks: 20 … 100 g (some of them), never 36 or 52.
        assert!(screen.contains("100") && !screen.contains(" 36 "), "{w}x{h}:\n{screen}");
    }
}

#[test]
fn typed_plain_numbers_are_in_the_unit_shown_and_refusals_name_the_field() {
    let mut app = computed_app();
    press(&mut app, KeyCode::Enter);
    assert!(render(&mut app, 120, 40).contains("plain number: g"));
    type_text(&mut app, "45");
    press(&mut app, KeyCode::Enter);
    assert!((app.design.damper.impact_mass_kg - 0.045).abs() < 1e-15, "45 is 45 g");
    assert!(render(&mut app, 120, 40).contains("45.00 g"));
    press(&mut app, KeyCode::Enter);
    type_text(&mut app, "1e9g");
    press(&mut app, KeyCode::Enter);
    let screen = render(&mut app, 120, 40);
    assert!(status_of(&screen).contains("error: invalid mass: 1e9 g is out of range"), "{screen}");
    press(&mut app, KeyCode::Enter);
    type_text(&mut app, "450");
    press(&mut app, KeyCode::Enter);
    let screen = render(&mut app, 120, 40);
    assert!((app.design.damper.impact_mass_kg - 0.45).abs() < 1e-15);
    assert!(status_of(&screen).contains("off the chart"), "{screen}");
    press(&mut app, KeyCode::Down);
    press(&mut app, KeyCode::Enter);
    type_text(&mut app, "3");
    press(&mut app, KeyCode::Enter);
    assert!((app.design.damper.gap_m - 0.03).abs() < 1e-15, "3 is 3 cm for the gap");
}

#[test]
fn the_status_line_explains_the_selected_field() {
    let mut app = computed_app();
    // The design group in table order: m, d, M, K, C, c1.
    for _ in 0..5 {
        press(&mut app, KeyCode::Down);
    }
    assert_eq!(app.param(), thud::tui::fields::Knob::C1);
    let status = status_of(&render(&mut app, 120, 40)).to_string();
    assert!(status.contains("c1 — contact damping in the Hertz contact force (Eq 26), N·s/m, 0–"), "{status}");
}

#[test]
fn a_negative_e_is_marked_and_points_to_the_glossary() {
    let mut app = computed_app();
    let reqs = app.select_design(0.050, 0.060);
    compute_sync(&mut app, reqs);
    let e = app.metrics().unwrap().inclination_cm_s.unwrap();
    assert!(e < 0.0, "this design's e is negative: {e}");
    let screen = render(&mut app, 120, 40);
    assert!(row(&screen, "e").contains("(!)"), "{screen}");
    assert!(screen.contains("see ? page 2"), "{screen}");
    press(&mut app, KeyCode::Char('?'));
    press(&mut app, KeyCode::Right);
    let help = render(&mut app, 120, 40);
    assert!(help.contains("What the numbers mean") && help.contains("negative") && help.contains("decides"), "{help}");
}

#[test]
fn undo_names_what_changed() {
    let mut app = computed_app();
    press(&mut app, KeyCode::Right);
    press(&mut app, KeyCode::Char('u'));
    let screen = render(&mut app, 120, 40);
    assert!(status_of(&screen).contains("undo: mass 41.50 g → 40.50 g"), "{screen}");
    press(&mut app, KeyCode::Char('P'));
    let t3 = app.host.preset_list.iter().position(|p| p.name == "paper-table3").unwrap();
    for _ in 0..t3 {
        press(&mut app, KeyCode::Down);
    }
    press(&mut app, KeyCode::Enter);
    press(&mut app, KeyCode::Char('u'));
    let status = status_of(&render(&mut app, 120, 40)).to_string();
    assert!(status.contains("preset paper-table3 → default") && status.contains("v0 1.40 m/s → 2.00 m/s"), "{status}");
    assert_eq!(app.preset, "default");
}

#[test]
fn v_with_the_chart_hidden_says_how_to_show_it() {
    let mut app = computed_app();
    render(&mut app, 80, 24);
    press(&mut app, KeyCode::Char('v'));
    let screen = render(&mut app, 80, 24);
    assert!(status_of(&screen).contains("press Tab"), "{screen}");
    render(&mut app, 120, 40);
    press(&mut app, KeyCode::Char('v'));
    assert!(!status_of(&render(&mut app, 120, 40)).contains("press Tab"));
}

#[test]
fn the_export_menu_names_the_files() {
    let mut app = computed_app();
    press(&mut app, KeyCode::Char('e'));
    let screen = render(&mut app, 120, 40);
    assert!(screen.contains("restitution SVG — R against impact mass"), "{screen}");
    assert!(screen.contains("[thud-restitution.svg]") && screen.contains("[thud-fig17.svg]"), "{screen}");
}

#[test]
fn paper_fig2_opens_on_the_impact_thud_pulse_computes() {
    let app = full_app("paper-fig2", Palette::default());
    assert_eq!(app.screen.pulse, thud::tui::app::PulseView::Single);
    let single = app.acoustic().unwrap().single.clone().unwrap();
    // The same impact through the command line.
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_thud"))
        .args(["pulse", "--preset", "paper-fig2", "--json"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let arrival = json["arrival_s"].as_f64().unwrap();
    let peak = json["p_max_pa"].as_f64().unwrap().abs().max(json["p_min_pa"].as_f64().unwrap().abs());
    let cli: Vec<(f64, f64)> = json["extrema"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| ((e["t_s"].as_f64().unwrap() - arrival) * 1e3, e["p_pa"].as_f64().unwrap()))
        .filter(|e| e.1.abs() > 0.02 * peak)
        .collect();
    assert_eq!(single.peaks.len(), cli.len());
    for (a, b) in single.peaks.iter().zip(&cli) {
        assert!((a.0 - b.0).abs() < 1e-9 && (a.1 - b.1).abs() < 1e-9, "{a:?} vs {b:?}");
    }
    let mut app = app;
    let screen = render(&mut app, 80, 24);
    assert!(screen.contains("peaks +1.853 -2.426 +1.624"), "{screen}");
    assert!(screen.contains("one impact"), "{screen}");
    press(&mut app, KeyCode::Char('i'));
    assert!(!render(&mut app, 80, 24).contains("peaks +1.853"), "i shows the run's loudest impact");
}

/// The margin of a cell as `b` defines it, recomputed here from the cell's metrics.
fn margin(m: &thud::design::Metrics, t: &thud::design::Thresholds) -> f64 {
    let quiet = 1.0 - 10f64.powf((m.spl_max_db.unwrap() - t.spl_db) / 20.0);
    let strong = (m.inclination_by(t.zone_by).unwrap() - t.inclination_cm_s) / t.inclination_cm_s;
    quiet.min(strong)
}

#[test]
fn b_jumps_to_the_zone3_design_with_the_largest_margin() {
    let mut app = full_app("default", Palette::default());
    press(&mut app, KeyCode::Char('b'));
    assert!(status_of(&render(&mut app, 120, 40)).contains("none in zone 3"));

    let mut app = full_app("paper-table3", Palette::default());
    let t = app.design.thresholds;
    let zone3: Vec<_> = app
        .chart
        .fine
        .cells
        .iter()
        .flatten()
        .filter(|c| c.metrics.zone(&t) == Some(thud::design::Zone::QuietStrong))
        .collect();
    assert!(!zone3.is_empty(), "Table 3's set-up has zone-3 designs");
    let best = zone3.iter().max_by(|a, b| margin(&a.metrics, &t).total_cmp(&margin(&b.metrics, &t))).unwrap();
    let want = (best.mass_kg, best.gap_m);
    press(&mut app, KeyCode::Char('b'));
    assert_eq!((app.design.damper.impact_mass_kg, app.design.damper.gap_m), want);
    let screen = render(&mut app, 120, 40);
    assert!(status_of(&screen).contains("best zone 3") && status_of(&screen).contains("margin"), "{screen}");
    assert_eq!(readout_zone(&screen), Some('3'), "the readout, recomputed for that design, agrees:\n{screen}");
    assert!(marker_zones(&screen).iter().all(|z| *z == '3'));
}

#[test]
fn the_tour_runs_through_every_step_and_leaves_to_the_explorer() {
    let mut app = full_app("default", Palette::default());
    press(&mut app, KeyCode::Char('T'));
    let n = app.tour.as_ref().unwrap().tour.steps.len();
    assert!((6..=10).contains(&n));
    for i in 0..n {
        let state = app.tour.as_ref().expect("still touring");
        assert_eq!(state.step, i);
        let step = state.tour.steps[i].clone();
        for (w, h) in SIZES {
            let screen = render(&mut app, w, h);
            assert!(screen.contains(&format!("tour {}/{n}: {}", i + 1, step.title)), "{w}x{h}:\n{screen}");
            assert!(screen.contains("▶ "), "the step's panel is highlighted:\n{screen}");
            let first_words: String = step.caption.split_whitespace().take(3).collect::<Vec<_>>().join(" ");
            assert!(screen.contains(&first_words), "{w}x{h} caption:\n{screen}");
        }
        assert_eq!(app.screen.pulse, step.pulse);
        assert!(!app.busy(), "step {i} computed");
        press(&mut app, KeyCode::Right);
    }
    assert!(app.tour.is_none(), "→ on the last step leaves");
    let screen = render(&mut app, 80, 24);
    assert!(status_of(&screen).contains("tour finished"), "{screen}");
    // The last step found a zone-3 design and it stays to explore.
    assert_eq!(readout_zone(&screen), Some('3'), "{screen}");
    // ← goes back, Esc leaves with the state kept.
    press(&mut app, KeyCode::Char('T'));
    press(&mut app, KeyCode::Right);
    press(&mut app, KeyCode::Left);
    assert_eq!(app.tour.as_ref().unwrap().step, 0);
    press(&mut app, KeyCode::Right);
    let d = app.design.clone();
    press(&mut app, KeyCode::Esc);
    assert!(app.tour.is_none() && !app.quit && app.design == d);
    press(&mut app, KeyCode::Right);
    assert_eq!(app.param(), app.host.tour_def.as_ref().unwrap().steps[1].select, "the step's field stays selected");
    assert_ne!(app.design, d, "→ changes values again");
}

#[test]
fn a_bad_tour_file_is_refused_with_one_line_and_status_2() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("bad.toml");
    std::fs::write(&file, "title = \"x\"\n[[step]]\ntitle = \"a\"\npanel = \"nowhere\"\ncaption = \"c\"\n").unwrap();
    let out =
        std::process::Command::new(env!("CARGO_BIN_EXE_thud")).args(["tui", "--tour"]).arg(&file).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("bad.toml") && err.contains("step 1 (a): panel 'nowhere'"), "{err}");
}

#[test]
fn the_polar_curve_is_never_covered_and_its_parts_have_their_own_glyphs() {
    use ratatui::widgets::Widget;
    use thud::tui::polar::PolarView;
    let app = full_app("default", Palette::default());
    let polar: &'static [(f64, f64)] = Box::leak(app.acoustic().unwrap().polar.clone().into_boxed_slice());
    for theme in [
        Palette { color: false, ascii: false, light: false },
        Palette { color: false, ascii: true, light: false },
        Palette::default(),
    ] {
        for (w, h) in [(20, 10), (34, 14), (36, 16), (60, 25), (90, 30)] {
            let area = ratatui::layout::Rect::new(0, 0, w, h);
            let view = |live: &'static [(f64, f64)]| PolarView {
                block: theme.block("", false),
                live,
                pinned: None,
                theta_deg: 45.0,
                range_deg: (0.0, 90.0),
                theme,
            };
            let mut full = ratatui::buffer::Buffer::empty(area);
            view(polar).render(area, &mut full);
            let curve = view(polar).curve_layer(area);
            let mut curve_cells = 0;
            for (a, c) in full.content.iter().zip(&curve.content) {
                if c.symbol() != " " {
                    assert_eq!(a.symbol(), c.symbol(), "{w}x{h}: the curve is covered");
                    curve_cells += 1;
                }
            }
            assert!(curve_cells > 0, "{w}x{h}: no curve drawn");
            let symbols: std::collections::HashSet<&str> =
                full.content.iter().map(ratatui::buffer::Cell::symbol).collect();
            let (ring, ray) = if theme.ascii { (".", "+") } else { ("·", "•") };
            if h >= 14 {
                assert!(symbols.contains(ring) && symbols.contains(ray), "{w}x{h}: rings and ray have their glyphs");
            }
        }
    }
}

// ---- Forcing, the response view and ensembles ----

/// Selects field `knob` and types `text` into it, computing what it asks for.
fn set_field(app: &mut App, knob: thud::tui::fields::Knob, text: &str) {
    app.selected = thud::tui::fields::Knob::ALL.iter().position(|k| *k == knob).unwrap();
    press(app, KeyCode::Enter);
    type_text(app, text);
    press(app, KeyCode::Enter);
}

/// The default design under a 1 N force (f starts at the natural frequency), small chart grid.
fn forced_app(theme: Palette) -> App {
    let grids = Grids { coarse: None, fine: Grid::standard(6, 5) };
    let mut app = App::with_grids(Design::default(), "default", theme, grids);
    let reqs = app.initial_requests();
    compute_sync(&mut app, reqs);
    set_field(&mut app, thud::tui::fields::Knob::FORCE, "1");
    app
}

/// Whether a request is the response curve's job.
fn is_response_job(r: &thud::tui::Request) -> bool {
    matches!(r, thud::tui::Request::Chart(_, thud::tui::worker::ChartWork::Response(_)))
}

#[test]
fn a_force_switched_on_gets_the_natural_frequency_and_the_steady_readout() {
    let mut app = forced_app(Palette::default());
    assert_eq!(app.design.damper.force_n, 1.0);
    // Table 2's exact natural frequency √(K/M − (C/2M)²)/2π = 5.0329 Hz
    // (not rounded to 5.03), the value the response band is centred on.
    let p = &app.design.damper;
    let g = p.damping_n_s_m / (2.0 * p.main_mass_kg);
    let fn_hz = (p.stiffness_n_m / p.main_mass_kg - g * g).sqrt() / (2.0 * std::f64::consts::PI);
    assert!((fn_hz - 5.0329).abs() < 5e-5, "{fn_hz}");
    assert!((p.freq_hz - fn_hz).abs() < 1e-12, "f {} is the natural frequency {fn_hz}", p.freq_hz);
    let band = thud::tui::compute::default_band(&app.design);
    assert!((band.from_hz - 0.6 * p.freq_hz).abs() < 1e-12 && (band.to_hz - 1.6 * p.freq_hz).abs() < 1e-12);
    assert!(render(&mut app, 120, 40).contains("5.033 Hz"));
    let screen = render(&mut app, 120, 40);
    for label in ["amp", "alone", "cut", "Leq", "imp/T"] {
        row(&screen, label);
    }
    // The y0 field refuses what the command line refuses: outside the clearance.
    set_field(&mut app, thud::tui::fields::Knob::BALL_POSITION, "2.5");
    assert!(render(&mut app, 120, 40).contains("error: invalid ball-position"));
    assert_eq!(app.design.damper.ball_position_m, 0.0);
    set_field(&mut app, thud::tui::fields::Knob::BALL_POSITION, "5mm");
    assert_eq!(app.design.damper.ball_position_m, 0.005);
}

#[test]
fn response_view_snapshots_and_the_marker_moves_without_a_new_curve_job() {
    let mut app = forced_app(Palette::default());
    let reqs = app.update(Msg::Input(Event::Key(KeyEvent::new(KeyCode::Char('f'), KeyModifiers::NONE))));
    assert_eq!(reqs.iter().filter(|r| is_response_job(r)).count(), 1, "the curve is asked for once");
    compute_sync(&mut app, reqs);
    assert!(!app.busy());
    let curve = std::ptr::from_ref(app.response().expect("curve computed"));
    insta::assert_snapshot!("response_120x40", render(&mut app, 120, 40));
    let before = render(&mut app, 120, 40);
    // Changing f re-simulates the design but never asks for the curve again: it does not
    // depend on f; only the marker (and the line under the plots) moves.
    app.selected = thud::tui::fields::Knob::ALL.iter().position(|k| *k == thud::tui::fields::Knob::FREQ).unwrap();
    for _ in 0..3 {
        let reqs = app.update(Msg::Input(Event::Key(KeyEvent::new(KeyCode::Right, KeyModifiers::NONE))));
        assert!(!reqs.iter().any(is_response_job), "no new curve job for a new f");
        compute_sync(&mut app, reqs);
    }
    assert!(app.design.damper.freq_hz > 5.3, "{}", app.design.damper.freq_hz);
    assert!(std::ptr::eq(app.response().expect("curve kept"), curve), "the same curve");
    let after = render(&mut app, 120, 40);
    let marker_line = |s: &str| s.lines().find(|l| l.contains(" Hz from rest: ")).map(str::to_string);
    assert!(marker_line(&before).is_some(), "{before}");
    assert_ne!(marker_line(&before), marker_line(&after), "the marker moved:\n{after}");
    // The chart panel focused: ←→ move f too, still without a curve job.
    while app.focus != thud::tui::app::Panel::Chart {
        press(&mut app, KeyCode::Tab);
    }
    let f = app.design.damper.freq_hz;
    let reqs = app.update(Msg::Input(Event::Key(KeyEvent::new(KeyCode::Left, KeyModifiers::NONE))));
    assert!(!reqs.iter().any(is_response_job));
    compute_sync(&mut app, reqs);
    assert!(app.design.damper.freq_hz < f);
    // A change of the design itself (the mass) does ask for a new curve.
    app.focus = thud::tui::app::Panel::Params;
    app.selected = 0;
    let reqs = app.update(Msg::Input(Event::Key(KeyEvent::new(KeyCode::Right, KeyModifiers::NONE))));
    assert!(reqs.iter().any(is_response_job), "a new design needs a new curve");
}

#[test]
fn response_view_at_80x24_in_colour_no_color_and_ascii() {
    for (name, theme) in [
        ("response_80x24", Palette::default()),
        ("response_no_color_80x24", Palette { color: false, ascii: false, light: false }),
        ("response_ascii_80x24", Palette { color: true, ascii: true, light: false }),
    ] {
        let mut app = forced_app(theme);
        press(&mut app, KeyCode::Char('f'));
        show_chart(&mut app);
        let screen = render(&mut app, 80, 24);
        assert!(screen.contains("response"), "{screen}");
        if theme.ascii {
            assert!(screen.is_ascii(), "{screen}");
        }
        insta::assert_snapshot!(name, screen);
    }
    // Without a force the view says what to do instead of drawing a curve.
    let mut app = computed_app();
    let reqs = app.update(Msg::Input(Event::Key(KeyEvent::new(KeyCode::Char('f'), KeyModifiers::NONE))));
    assert!(!reqs.iter().any(is_response_job));
    assert!(render(&mut app, 120, 40).contains("No force"));
}

/// The default design with an ensemble of `n` runs on the small chart grid.
fn ensemble_app(n: usize, theme: Palette) -> App {
    let grids = Grids { coarse: None, fine: Grid::standard(6, 5) };
    let mut app = App::with_grids(Design::default(), "default", theme, grids);
    let reqs = app.initial_requests();
    compute_sync(&mut app, reqs);
    set_field(&mut app, thud::tui::fields::Knob::RUNS, &n.to_string());
    assert_eq!(app.runs, n);
    assert!(!app.busy());
    app
}

#[test]
fn an_ensemble_readout_shows_the_engines_median_and_p10_p90() {
    let mut app = ensemble_app(8, Palette::default());
    let screen = render(&mut app, 120, 40);
    let e = thud::ensemble::evaluate(&app.design.clone().check().unwrap(), 8, None).unwrap().unwrap();
    let sig = thud::units::sig;
    let p = e.spread.inclination_fit_cm_s;
    let want = format!("{} cm/s [{}–{}]", sig(p.median.unwrap(), 3), sig(p.p10.unwrap(), 3), sig(p.p90.unwrap(), 3));
    assert!(row(&screen, "e_fit").contains(&want), "{want} in\n{screen}");
    let s = e.spread.spl_max_db;
    let want = format!("{} dB [{}–{}]", sig(s.median.unwrap(), 4), sig(s.p10.unwrap(), 4), sig(s.p90.unwrap(), 4));
    assert!(row(&screen, "SPLmax").contains(&want), "{want} in\n{screen}");
    assert!(row(&screen, "zone").contains(&format!(", {:.0}%", 100.0 * e.agreement)), "{screen}");
    // The compact readout (80×24) keeps the spread.
    let screen = render(&mut app, 80, 24);
    assert!(screen.contains(&format!("[{}–", sig(p.p10.unwrap(), 3))), "{screen}");
    // N back to 1 is today's single trajectory.
    set_field(&mut app, thud::tui::fields::Knob::RUNS, "1");
    let screen = render(&mut app, 120, 40);
    assert!(!row(&screen, "e_fit").split("││").next().unwrap().contains('['), "{screen}");
}

#[test]
fn an_ensemble_chart_shades_the_cells_where_runs_disagree() {
    for (name, theme) in [
        ("ensemble", Palette::default()),
        ("ensemble_no_color", Palette { color: false, ascii: false, light: false }),
        ("ensemble_ascii", Palette { color: true, ascii: true, light: false }),
    ] {
        let mut app = ensemble_app(4, theme);
        // Every cell in the zone of its medians; shaded where fewer than 70 % of its runs agree.
        let unsure: Vec<bool> = app
            .chart
            .ensembles
            .iter()
            .map(|e| thud::tui::compute::ensemble_under(e.as_ref().unwrap(), &app.design.thresholds).agreement < 0.7)
            .collect();
        assert!(unsure.iter().any(|u| *u), "the default chart has a cell where the runs disagree");
        assert!(unsure.iter().any(|u| !*u));
        let screen = render(&mut app, 120, 40);
        let shade = if theme.ascii { ":" } else { "░" };
        assert!(screen.contains(&format!("{shade} <70% agree")), "legend:\n{screen}");
        insta::assert_snapshot!(format!("{name}_120x40"), screen);
        show_chart(&mut app);
        let screen = render(&mut app, 80, 24);
        assert!(screen.contains(shade), "{screen}");
        if theme.ascii {
            assert!(screen.is_ascii(), "{screen}");
        }
        insta::assert_snapshot!(format!("{name}_80x24"), screen);
    }
}

/// The readout of a design shows the same numbers as `thud simulate --json` for
/// it, at the readout's precision (the test fails if the readout showed another number).
#[test]
fn the_readout_shows_the_clis_json_numbers() {
    let sig = thud::units::sig;
    let json = |args: &[&str]| -> serde_json::Value {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_thud")).args(args).output().unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        serde_json::from_slice(&out.stdout).unwrap()
    };
    let num = |v: &serde_json::Value, k: &str| v[k].as_f64().unwrap_or_else(|| panic!("{k} in {v}"));
    // The paper's Fig 9 design.
    let cli = json(&["simulate", "--preset", "paper-fig9", "--json"]);
    let grids = Grids { coarse: None, fine: Grid::standard(2, 2) };
    let d = thud::presets::preset("paper-fig9").unwrap();
    let mut app = App::with_grids(d.clone(), "paper-fig9", Palette::default(), grids.clone());
    let reqs = app.initial_requests();
    compute_sync(&mut app, reqs);
    let screen = render(&mut app, 120, 40);
    for (label, want) in [
        ("U0max", format!("{} m/s", sig(num(&cli, "u0_max_m_s"), 5))),
        ("e", format!("{} cm/s", sig(num(&cli, "inclination_cm_s"), 3))),
        ("e_fit", format!("{} cm/s", sig(num(&cli, "inclination_fit_cm_s"), 3))),
        ("SPLmax", format!("{} dB", sig(num(&cli, "spl_max_db"), 4))),
        ("impacts", cli["n_impacts"].to_string()),
        ("τ@U0max", format!("{} µs", sig(num(&cli, "contact_duration_s") * 1e6, 4))),
        ("R mean", sig(num(&cli, "restitution_mean"), 3)),
    ] {
        assert!(row(&screen, label).contains(&format!("{label:<8}{want} ")), "{label}: {want} in\n{screen}");
    }
    let zone = cli["zone"].as_u64().unwrap();
    assert!(row(&screen, "zone").contains(&format!("zone    {zone} ")), "{screen}");
    // A forced design: the settled steady figures (the 2 s run's last
    // periods are still the start-up transient; the readout shows `simulate --settle`'s).
    let cli =
        json(&["simulate", "--preset", "paper-fig9", "--force-amplitude", "1N", "--freq", "5Hz", "--settle", "--json"]);
    let st = &cli["steady"];
    let mut forced = d;
    forced.damper.force_n = 1.0;
    forced.damper.freq_hz = 5.0;
    let mut app = App::with_grids(forced, "paper-fig9", Palette::default(), grids);
    let reqs = app.initial_requests();
    compute_sync(&mut app, reqs);
    let screen = render(&mut app, 120, 40);
    // The note leads with the design's verdict, as the command line's runs give it: the
    // settled run's (`simulate --settle`) and the orbit's at f (`bifurcation`), as one.
    let orbit = json(&[
        "bifurcation",
        "--preset",
        "paper-fig9",
        "--force-amplitude",
        "1N",
        "--freq",
        "5Hz",
        "--vary",
        "f=5Hz:5Hz:1",
        "--json",
    ]);
    let orbit: thud::verdict::Verdict = serde_json::from_value(orbit["points"][0]["orbit"].clone()).unwrap();
    let steady: thud::verdict::Verdict = serde_json::from_value(st["verdict"].clone()).unwrap();
    let v = thud::verdict::of_design(Some(steady), Some(orbit)).unwrap();
    let settled = format!("│{}, ", thud::tui::readout::verdict_words(&v));
    let end = sig(num(st, "window_end_s"), 3);
    assert!(screen.contains(&settled) && end.parse::<f64>().unwrap() > 2.0, "{settled} {end}\n{screen}");
    let plain = json(&["simulate", "--preset", "paper-fig9", "--force-amplitude", "1N", "--freq", "5Hz", "--json"]);
    for (label, want) in [
        ("U0max", format!("{} m/s", sig(num(&plain, "u0_max_m_s"), 5))),
        ("amp", format!("{} mm", sig(num(st, "amplitude_m") * 1e3, 4))),
        ("alone", format!("{} mm", sig(num(st, "amplitude_linear_m") * 1e3, 4))),
        ("cut", format!("{} dB", sig(num(st, "reduction_db"), 3))),
        ("Leq", format!("{} dB", sig(num(st, "leq_db"), 4))),
        ("imp/T", sig(num(st, "impacts_per_period"), 3)),
    ] {
        assert!(row(&screen, label).contains(&format!(" {want} ")), "{label}: {want} in\n{screen}");
    }
    // With N > 1 the forced figures are the N runs' settled states, median [p10–p90], as
    // `thud response --ensemble N` at this f (from the design's own v0).
    set_field(&mut app, thud::tui::fields::Knob::RUNS, "3");
    let cli = json(&[
        "response",
        "--preset",
        "paper-fig9",
        "--force-amplitude",
        "1N",
        "--v0",
        "2m/s",
        "--freqs",
        "5Hz:5Hz:1",
        "--ensemble",
        "3",
        "--json",
    ]);
    let p = &cli["sweeps"][0]["points"][0]["spread"];
    let spread = |k: &str, scale: f64, digits: usize, unit: &str| {
        let v = |q: &str| sig(num(&p[k], q) * scale, digits);
        format!("{}{unit} [{}–{}]", v("median"), v("p10"), v("p90"))
    };
    let screen = render(&mut app, 120, 40);
    for (label, want) in [
        ("amp", spread("amplitude_m", 1e3, 4, " mm")),
        ("cut", spread("reduction_db", 1.0, 3, " dB")),
        ("Leq", spread("leq_db", 1.0, 4, " dB")),
        ("imp/T", spread("impacts_per_period", 1.0, 3, " ")),
    ] {
        assert!(row(&screen, label).contains(&want), "{label}: {want} in\n{screen}");
    }
    let settled = cli["sweeps"][0]["points"][0]["settled_fraction"].as_f64().unwrap();
    assert!(screen.contains(&format!("3 runs: {:.0}% settled", 100.0 * settled)), "{screen}");
}

/// The polar's listener level is the level at the exact θ, as `thud simulate`
/// (the loudest impact, SPLmax) and `thud pulse` (one impact) report it, at angles off the
/// polar's 5° grid too (it used to show the nearest grid angle's level).
#[test]
fn the_polars_listener_level_is_the_clis_at_non_grid_angles() {
    let sig = thud::units::sig;
    let json = |args: &[&str]| -> serde_json::Value {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_thud")).args(args).output().unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        serde_json::from_slice(&out.stdout).unwrap()
    };
    let listener = |screen: &str| -> String {
        let line =
            screen.lines().find(|l| l.contains("θ ") && l.contains("° → ")).unwrap_or_else(|| panic!("{screen}"));
        let at = line.split("° → ").nth(1).unwrap();
        at.split(" dB").next().unwrap().to_string()
    };
    let mut app = computed_app();
    for theta in ["47", "51", "12.5", "83"] {
        set_field(&mut app, thud::tui::fields::Knob::THETA, theta);
        let loud = json(&["simulate", "--theta", theta, "--json"]);
        let pulse = json(&["pulse", "--preset", "default", "--theta", theta, "--json"]);
        let screen = render(&mut app, 120, 40);
        assert!(screen.contains(&format!("θ {}° → ", sig(theta.parse().unwrap(), 3))), "{screen}");
        assert_eq!(listener(&screen), sig(loud["spl_max_db"].as_f64().unwrap(), 4), "θ {theta}: SPLmax\n{screen}");
        // The readout's SPLmax is the same number.
        assert!(row(&screen, "SPLmax").contains(&format!("{} dB", listener(&screen))), "{screen}");
        press(&mut app, KeyCode::Char('i'));
        let screen = render(&mut app, 120, 40);
        assert_eq!(listener(&screen), sig(pulse["spl_db"].as_f64().unwrap(), 4), "θ {theta}: one impact\n{screen}");
        press(&mut app, KeyCode::Char('i'));
    }
}

/// The `░` legend entry never costs the chart a gap row: at every panel size
/// where the chart without it draws all 12 computed rows, the chart with it (and with the
/// pending entry) draws all 12 too (at 120×40 it used to draw 11).
#[test]
fn the_chart_draws_every_computed_row_with_the_unsure_legend_too() {
    let grid = Grid::standard(16, 12);
    let masses_g: Vec<f64> = grid.masses_kg.iter().map(|m| m * 1e3).collect();
    let gaps_cm: Vec<f64> = grid.gaps_m.iter().map(|g| g * 1e2).collect();
    let theme = Palette::default();
    let rows = |inner, pending, unsure| {
        thud::tui::chart::layout(inner, &masses_g, &gaps_cm, &theme, pending, unsure)
            .map_or(0, |l| l.geometry.rows.len())
    };
    let (mut checked, mut lost) = (0, vec![]);
    // From 28 columns: narrower, the 16 columns and their labels fill the panel and the
    // legend below needs a line more for the entry (24–27 columns).
    for w in 28..=200u16 {
        for h in 6..=60u16 {
            let inner = ratatui::layout::Rect::new(1, 1, w, h);
            if rows(inner, false, false) == 12 {
                checked += 1;
                if rows(inner, false, true) != 12 {
                    lost.push((w, h));
                }
            }
        }
    }
    assert!(lost.is_empty(), "a row lost to the ░ entry at {lost:?}");
    assert!(checked > 1000, "{checked}");
}

/// The export is what is on screen: with N > 1 the sweep CSV is the ensemble
/// chart (`thud sweep --ensemble N --csv` over the chart's grid), and while the frequency
/// response is shown the menu offers it as CSV and SVG, the curve the view draws.
#[test]
fn exports_are_the_ensemble_chart_and_the_response_on_screen() {
    let out = tempfile::tempdir().unwrap();
    let mut app = ensemble_app(2, Palette::default());
    app.host.export_dir = out.path().to_path_buf();
    let export = |app: &mut App, kind: thud::export::Artifact| {
        press(app, KeyCode::Char('e'));
        let at =
            app.export_menu().iter().position(|(k, _)| *k == kind).unwrap_or_else(|| panic!("{kind:?} in the menu"));
        for _ in 0..at {
            press(app, KeyCode::Down);
        }
        press(app, KeyCode::Enter);
    };
    export(&mut app, thud::export::Artifact::CsvSweep);
    let file = std::fs::read_to_string(out.path().join("thud-sweep.csv")).unwrap();
    let cli = std::process::Command::new(env!("CARGO_BIN_EXE_thud"))
        .args(["sweep", "--ensemble", "2", "--masses", "20g:100g:6", "--gaps", "1cm:7cm:5", "--csv"])
        .output()
        .unwrap();
    assert!(cli.status.success(), "{}", String::from_utf8_lossy(&cli.stderr));
    assert_eq!(file, String::from_utf8(cli.stdout).unwrap(), "the ensemble chart's CSV");
    assert!(file.lines().next().unwrap().contains("agreement"), "{file}");
    // The response: not in the menu until it is shown, then the curve on screen.
    let mut app = forced_app(Palette::default());
    app.host.export_dir = out.path().to_path_buf();
    assert!(!app.export_menu().iter().any(|(k, _)| k.is_response()));
    press(&mut app, KeyCode::Char('f'));
    export(&mut app, thud::export::Artifact::CsvResponse);
    let file = std::fs::read_to_string(out.path().join("thud-response.csv"))
        .unwrap_or_else(|e| panic!("{e}: {}", status_of(&render(&mut app, 120, 40))));
    assert_eq!(file, thud::export::csv::response(app.response().expect("curve")).unwrap());
    export(&mut app, thud::export::Artifact::SvgResponse);
    assert!(std::fs::read_to_string(out.path().join("thud-response.svg")).unwrap().contains("<svg"));
    assert!(render(&mut app, 120, 40).contains("exported response SVG"));
}

/// A forced design whose settled run has not settled says so on screen even
/// when its e is negative: the warning ranks above the `(!) e < 0` note (the e row keeps its
/// `(!)`), and the settled state is the command line's (`simulate --settle`).
#[test]
fn a_not_settled_note_is_never_hidden_behind_the_negative_e_note() {
    let mut app = computed_app();
    let reqs = app.select_design(0.050, 0.060);
    compute_sync(&mut app, reqs);
    set_field(&mut app, thud::tui::fields::Knob::FORCE, "1");
    let a = app.acoustic().expect("computed");
    let steady = a.steady.expect("forced");
    let e = app.metrics().unwrap().inclination_cm_s.unwrap();
    assert!(e < 0.0 && !steady.settled, "this design: e {e}, settled {}", steady.settled);
    // The same settled state as the command line's.
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_thud"))
        .args(["simulate", "--mass", "50g", "--gap", "6cm", "--force-amplitude", "1N", "--settle", "--json"])
        .arg(format!("--freq={}Hz", app.design.damper.freq_hz))
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let cli: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(cli["steady"]["amplitude_m"].as_f64().unwrap(), steady.amplitude_m);
    // The note leads with the design's one verdict, as the title names it.
    let v = thud::tui::ui::design_verdict(a).expect("forced");
    let words = format!("│{}, ", thud::tui::readout::verdict_words(&v));
    for (w, h) in [(120, 40), (200, 60)] {
        let screen = render(&mut app, w, h);
        assert!(screen.contains(&words) && row(&screen, "e").contains("(!)"), "{words}\n{screen}");
    }
}

/// Braille cells (plotted points) on a screen.
fn braille(screen: &str) -> usize {
    screen.chars().filter(|c| ('\u{2801}'..='\u{28ff}').contains(c)).count()
}

/// The title words of each panel, as drawn at 80 columns.
fn panel_title(p: thud::tui::app::Panel) -> &'static str {
    use thud::tui::app::Panel;
    match p {
        Panel::Waveform => "p(t)",
        Panel::Polar => "SPL(θ)",
        Panel::History => "x(t)",
        Panel::Chart => "m (g)",
        Panel::Params => "parameters",
        Panel::Readout => "readout",
    }
}

#[test]
fn every_tour_step_at_80x24_shows_its_named_panel_with_its_plot() {
    use thud::tui::app::Panel;
    let mut app = full_app("default", Palette::default());
    press(&mut app, KeyCode::Char('T'));
    let n = app.tour.as_ref().unwrap().tour.steps.len();
    for i in 0..n {
        let step = app.tour.as_ref().unwrap().tour.steps[i].clone();
        let screen = render(&mut app, 80, 24);
        insta::assert_snapshot!(format!("tour_zoomed_step{}_80x24", i + 1), screen);
        assert!(!screen.contains("too small"), "step {} at 80x24:\n{screen}", i + 1);
        let marked = screen.lines().find(|l| l.contains("▶ ")).expect("the step's panel is marked");
        let title = match (step.animate, step.table1) {
            (true, _) => "animation",
            (_, true) => "Table 1",
            _ => panel_title(step.panel),
        };
        assert!(marked.contains(title) || step.panel == Panel::Chart, "step {}:\n{screen}", i + 1);
        match step.panel {
            // The Table 1 view: the measurements beside both models, not a plot.
            _ if step.table1 => assert!(screen.contains("measured") && screen.contains("physical"), "{screen}"),
            Panel::Chart => {
                assert!(screen.contains(panel_title(Panel::Chart)) && screen.contains("d (cm)"), "{screen}");
            }
            // A plot: plotted cells, not a message.
            _ => assert!(braille(&screen) > 15, "step {} plot:\n{screen}", i + 1),
        }
        if i == 0 {
            // One impact on a plate: no damper run's zone or e beside it.
            assert!(!screen.contains("zone ") && !screen.contains("(!)"), "{screen}");
        }
        press(&mut app, KeyCode::Right);
    }
}

#[test]
fn the_tour_caption_keys_do_what_the_caption_says() {
    use thud::tui::fields::Knob;
    let mut app = full_app("default", Palette::default());
    press(&mut app, KeyCode::Char('T'));
    press(&mut app, KeyCode::Right);
    let step = app.tour.as_ref().unwrap().step;
    let caption = app.tour.as_ref().unwrap().tour.steps[step].caption.clone();
    assert!(caption.contains("θ is selected") && caption.contains('+'), "{caption}");
    assert!(!caption.contains("←→"), "← and → move the tour, not θ: {caption}");
    // As written: the step selects θ, then + walks it.
    assert_eq!(app.param(), Knob::THETA);
    let s = render(&mut app, 80, 24);
    let field = s.lines().rev().nth(1).unwrap();
    assert!(field.contains("θ = 45.0 deg"), "the caption box shows the selected θ (no footer in the tour):\n{s}");
    let theta = app.design.observer.theta_rad;
    press(&mut app, KeyCode::Char('+'));
    assert!(app.design.observer.theta_rad > theta, "+ walks the listener");
    assert_eq!(app.tour.as_ref().unwrap().step, step, "still on the same step");
    press(&mut app, KeyCode::Char('-'));
    assert!((app.design.observer.theta_rad - theta).abs() < 1e-12);
}

#[test]
fn z_zooms_the_focused_panel_to_the_whole_screen_and_back() {
    let mut app = full_app("default", Palette::default());
    press(&mut app, KeyCode::Tab);
    press(&mut app, KeyCode::Tab);
    press(&mut app, KeyCode::Tab);
    let before = render(&mut app, 80, 24);
    assert!(before.contains("x(t)") && before.contains("m (g)"), "history and chart side by side:\n{before}");
    press(&mut app, KeyCode::Char('z'));
    let zoomed = render(&mut app, 80, 24);
    assert!(zoomed.contains("x(t) of the main mass near its peaks"), "the long title fits:\n{zoomed}");
    assert!(!zoomed.contains("m (g)") && !zoomed.contains("parameters"), "only the history:\n{zoomed}");
    assert!(braille(&zoomed) > braille(&before) / 2, "{zoomed}");
    assert!(zoomed.lines().next().unwrap().contains("zoom: history"));
    // Tab moves the zoom to the next panel; z goes back to all panels.
    press(&mut app, KeyCode::Tab);
    let chart = render(&mut app, 80, 24);
    assert!(chart.contains("m (g)") && !chart.contains("x(t)"), "{chart}");
    press(&mut app, KeyCode::Char('z'));
    assert_eq!(render(&mut app, 80, 24).lines().filter(|l| l.contains("x(t)")).count(), 1);
    // The key table has it, so help and footer show it.
    assert!(render(&mut app, 80, 24).lines().last().unwrap().contains("z zoom"));
    assert!(KEYS.iter().any(|b| b.label == "z" && b.help.contains("fills the screen")));
}

#[test]
fn input_lines_start_with_the_current_value_selected_and_typing_replaces_it() {
    let mut app = computed_app();
    press(&mut app, KeyCode::Enter);
    assert_eq!(app.mode, Mode::Editing("40.50 g".into()), "the line opens on the value shown");
    let (screen, buf) = render_with(&mut app, 80, 24);
    let y = screen.lines().count() - 2;
    let line: String = (0..80).map(|x| buf[(x, y as u16)].symbol().to_string()).collect();
    let x = line.find("40.50 g").unwrap();
    let x = u16::try_from(line[..x].chars().count()).unwrap();
    assert!(buf[(x, y as u16)].modifier.contains(ratatui::style::Modifier::REVERSED), "shown selected");
    // Enter on it: nothing changes (the shown value is rounded).
    press(&mut app, KeyCode::Enter);
    assert!((app.design.damper.impact_mass_kg - 0.0405).abs() < 1e-15);
    assert!(!app.modified(), "no change was made");
    // Typing replaces the selection.
    press(&mut app, KeyCode::Enter);
    type_text(&mut app, "45");
    assert_eq!(app.mode, Mode::Editing("45".into()));
    press(&mut app, KeyCode::Enter);
    assert!((app.design.damper.impact_mass_kg - 0.045).abs() < 1e-12);
    // An arrow keeps the text to edit; Ctrl-U clears it.
    press(&mut app, KeyCode::Enter);
    press(&mut app, KeyCode::End);
    type_text(&mut app, "0");
    assert_eq!(app.mode, Mode::Editing("45.00 g0".into()));
    press_mod(&mut app, KeyCode::Char('u'), KeyModifiers::CONTROL);
    assert_eq!(app.mode, Mode::Editing(String::new()));
    press(&mut app, KeyCode::Esc);
    // The save line too: the offered name is selected, typing replaces it.
    press(&mut app, KeyCode::Char('s'));
    assert_eq!(app.mode, Mode::SaveAs("design-1".into()));
    assert!(app.screen.line_selected);
    type_text(&mut app, "mine");
    assert_eq!(app.mode, Mode::SaveAs("mine".into()));
}

#[test]
fn a_saved_design_keeps_every_field_the_ensemble_n_and_the_force_included() {
    use thud::tui::fields::Knob;
    let data = tempfile::tempdir().unwrap();
    let mut app = ensemble_app(4, Palette::default());
    app.host.data_dir = Some(data.path().to_path_buf());
    set_field(&mut app, Knob::FORCE, "1");
    set_field(&mut app, Knob::FREQ, "5.45");
    set_field(&mut app, Knob::THETA, "51");
    let (design, runs) = (app.design.clone(), app.runs);
    assert!(design.damper.forced() && runs == 4);
    app.save_as("forced-ensemble");
    // Change everything back, then load it.
    set_field(&mut app, Knob::RUNS, "1");
    set_field(&mut app, Knob::FORCE, "0");
    set_field(&mut app, Knob::THETA, "30");
    press(&mut app, KeyCode::Char('L'));
    press(&mut app, KeyCode::Enter);
    assert_eq!(app.design, design, "every field of the design");
    assert_eq!(app.runs, 4, "the ensemble N");
    assert!(!app.modified(), "just loaded: not modified");
    // A file with an N the field refuses is a load error, nothing applied.
    let path = data.path().join("designs").join("forced-ensemble.toml");
    let text = std::fs::read_to_string(&path).unwrap().replace("ensemble = 4", "ensemble = 0");
    assert!(text.contains("ensemble = 0"), "{text}");
    std::fs::write(&path, text).unwrap();
    set_field(&mut app, Knob::RUNS, "1");
    press(&mut app, KeyCode::Char('L'));
    press(&mut app, KeyCode::Enter);
    assert_eq!(app.mode, Mode::Saved(0));
    assert!(app.status().unwrap().text.contains("ensemble N 0"), "{:?}", app.status());
    assert_eq!(app.runs, 1);
}

/// A file of the repository (README.md, a page of the guide).
fn repo_path(name: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(name)
}

/// The guide's explorer chapter, where the keys table and most screens live.
const EXPLORER_PAGE: &str = "docs/guide/the-explorer.md";

/// Every key of the key table (the explorer's and the tour's) is in the guide's keys table
/// (its first column, each key in backticks), so the guide cannot fall behind the table.
#[test]
fn readme_keys_table_has_every_key_of_the_table() {
    let readme = std::fs::read_to_string(repo_path(EXPLORER_PAGE)).unwrap();
    let start = readme.find("## Keys\n").expect("the explorer chapter's keys section");
    let table: Vec<&str> = readme[start..]
        .lines()
        .skip(1)
        .skip_while(|l| !l.starts_with('|'))
        .take_while(|l| l.starts_with('|'))
        .collect();
    let documented: Vec<&str> = table
        .iter()
        .skip(2)
        .flat_map(|row| row.trim_start_matches('|').split(" | ").next().unwrap().split('`').skip(1).step_by(2))
        .collect();
    for b in KEYS.iter().chain(thud::tui::keys::TOUR_KEYS) {
        assert!(documented.contains(&b.label), "key `{}` ({}) is not in the guide's keys table", b.label, b.name);
    }
}

/// The explorer screens the README shows, by the name of their marker: the default design
/// computed with the real chart grid (16 × 12), the mouse on as in the real explorer.
fn readme_screen(name: &str) -> String {
    let mut app = full_app("default", Palette::default());
    app.mouse = true;
    let screen = match name {
        "main_80x24" => render(&mut app, 80, 24),
        "history_chart_80x24" => {
            show_chart(&mut app);
            render(&mut app, 80, 24)
        }
        "main_120x40" => render(&mut app, 120, 40),
        "tour_step4_80x24" => {
            press(&mut app, KeyCode::Char('T'));
            for _ in 1..4 {
                press(&mut app, KeyCode::Right);
            }
            render(&mut app, 80, 24)
        }
        other => panic!("no README screen named {other}"),
    };
    // TestBackend quotes each line; the README shows the text, trailing blanks cut.
    let lines: Vec<&str> =
        screen.lines().map(|l| l.strip_prefix('"').and_then(|l| l.strip_suffix('"')).unwrap()).collect();
    lines.iter().map(|l| format!("{}\n", l.trim_end())).collect()
}

/// The text captures of the explorer in the README and the guide's explorer chapter (between
/// `<!-- screen NAME ... -->` and `<!-- /screen -->`, a ```text block) are what the explorer draws
/// today. `THUD_BLESS=1 cargo test --release --test it tui::readme_screens` re-captures them in place
/// (after a change of the screens, or a merge of other explorer work).
#[test]
fn readme_screens_are_what_the_explorer_draws() {
    let pages: [(&str, &[&str]); 2] = [
        // The README opens with the explorer as a picture (tests/it/pictures.rs), not a capture.
        ("README.md", &[]),
        (EXPLORER_PAGE, &["main_80x24", "history_chart_80x24", "main_120x40", "tour_step4_80x24"]),
    ];
    for (page, want_names) in pages {
        let path = repo_path(page);
        let readme = std::fs::read_to_string(&path).unwrap();
        let bless = std::env::var_os("THUD_BLESS").is_some();
        let (mut out, mut rest, mut names) = (String::new(), readme.as_str(), Vec::new());
        while let Some(at) = rest.find("<!-- screen ") {
            let open_end = at + rest[at..].find("-->\n").expect("the marker's end") + "-->\n".len();
            let name = rest[at + "<!-- screen ".len()..].split([' ', ':']).next().unwrap().to_string();
            let close = open_end + rest[open_end..].find("<!-- /screen -->").expect("the closing marker");
            let want = format!("```text\n{}```\n", readme_screen(&name));
            if !bless {
                assert_eq!(
                    rest[open_end..close],
                    want,
                    "{page}'s screen {name} is not what the explorer draws; re-capture with \
                     THUD_BLESS=1 cargo test --release --test it tui::readme_screens"
                );
            }
            out.push_str(&rest[..open_end]);
            out.push_str(&want);
            rest = &rest[close..];
            names.push(name);
        }
        out.push_str(rest);
        assert_eq!(names, want_names, "{page}'s screens");
        if bless && out != readme {
            let dir = path.parent().unwrap();
            let mut tmp = tempfile::NamedTempFile::new_in(dir).unwrap();
            std::io::Write::write_all(&mut tmp, out.as_bytes()).unwrap();
            tmp.persist(&path).unwrap();
        }
    }
}

/// The field list is grouped as the engine's table groups its rows (design,
/// forcing, listener, solver, study), each group under its heading and in table order; the
/// panel scrolls to the selected field with its group's heading above it.
#[test]
fn the_field_list_is_grouped_by_the_table_s_groups() {
    use thud::params::{Group, DESIGN};
    use thud::tui::fields::Knob;
    let position = |k: &Knob| k.rows().first().and_then(|n| DESIGN.iter().position(|p| p.name == *n));
    let key = |k: &Knob| (Group::ALL.iter().position(|g| *g == k.group()), position(k).unwrap_or(usize::MAX));
    let keys: Vec<_> = Knob::ALL.iter().map(key).collect();
    assert!(keys.windows(2).all(|w| w[0] < w[1]), "grouped, then in table order: {:?}", Knob::ALL);
    for k in Knob::ALL {
        if let Some(row) = k.row() {
            assert_eq!(k.group(), row.group, "{k:?}");
        }
    }
    let mut app = computed_app();
    app.selected = Knob::ALL.iter().position(|q| *q == Knob::FORCE).unwrap();
    let screen = render(&mut app, 120, 40);
    insta::assert_snapshot!("fields_grouped_120x40", screen);
    let panel: Vec<&str> =
        screen.lines().map(|l| l.get(..l.char_indices().nth(42).map_or(l.len(), |(i, _)| i)).unwrap_or(l)).collect();
    let heading = |title: &str| panel.iter().position(|l| l.contains(&format!("─ {title} ─")));
    let (forcing, listener) = (heading("forcing").expect("forcing heading"), heading("listener").expect("listener"));
    let force = panel.iter().position(|l| l.contains("▶")).unwrap();
    assert!(forcing < force && force < listener, "{screen}");
    app.selected = Knob::ALL.len() - 1;
    assert!(render(&mut app, 120, 40).contains("─ study ─"), "the last field, N, is with the study");
}

// ---- The chart's marker and labels, the readout's columns ----

/// The chart's cells in the last frame: (geometry, the cells' views, masses in g, gaps in cm).
fn chart_of(app: &App) -> (thud::tui::chart::Geometry, Vec<thud::tui::chart::CellView>, Vec<f64>, Vec<f64>) {
    let geo = app.drawn.geometry.clone().expect("chart drawn");
    let masses: Vec<f64> = app.chart.fine.masses_kg.iter().map(|m| m * 1e3).collect();
    let gaps: Vec<f64> = app.chart.fine.gaps_m.iter().map(|g| g * 1e2).collect();
    (geo, thud::tui::ui::chart_cells(app), masses, gaps)
}

/// The text of columns `xs` on line `y` of `buf`.
fn text_at(buf: &ratatui::buffer::Buffer, xs: std::ops::Range<u16>, y: u16) -> String {
    xs.map(|x| buf[(x, y)].symbol().to_string()).collect()
}

/// Numbers written on line `y` from column `from` to `to` (exclusive): (first, end, value).
fn numbers_on(buf: &ratatui::buffer::Buffer, from: u16, to: u16, y: u16) -> Vec<(u16, u16, f64)> {
    let mut out = vec![];
    let mut x = from;
    while x < to {
        if buf[(x, y)].symbol() == " " {
            x += 1;
            continue;
        }
        let start = x;
        while x < buf.area.right() && buf[(x, y)].symbol() != " " {
            x += 1;
        }
        if let Ok(v) = text_at(buf, start..x, y).parse::<f64>() {
            out.push((start, x, v));
        }
    }
    out
}

/// The chart at 80×24 (Tab to it), 120×40 and 200×60 of the default design on the full grid
/// and of an ensemble of 4 on the small one.
fn chart_frames() -> Vec<(String, App, u16, u16)> {
    let mut out = vec![];
    for (w, h) in SIZES {
        let mut app = full_app("default", Palette::default());
        show_chart(&mut app);
        out.push((format!("default {w}x{h}"), app, w, h));
        let mut app = ensemble_app(4, Palette::default());
        show_chart(&mut app);
        out.push((format!("ensemble {w}x{h}"), app, w, h));
    }
    out
}

/// Each gap label sits on the glyph line of the row whose gap is nearest its
/// value (within half a row step; never on a spacer line of a tall cell), and each mass label
/// over the glyph column of the column whose mass is nearest it.
#[test]
fn the_charts_axis_labels_sit_on_the_rows_and_columns_of_their_values() {
    for (name, mut app, w, h) in chart_frames() {
        let (screen, buf) = render_with(&mut app, w, h);
        let (geo, _, masses, gaps) = chart_of(&app);
        let shown_gaps: Vec<f64> = geo.rows.iter().map(|&i| gaps[i]).collect();
        let step = shown_gaps.windows(2).map(|p| p[1] - p[0]).fold(0.0, f64::max);
        let label_x = geo.cells.x - thud::tui::chart::LABEL_W;
        let labels: Vec<(u16, f64)> = (geo.cells.y..geo.cells.bottom())
            .filter_map(|y| text_at(&buf, label_x..geo.cells.x, y).trim().parse().ok().map(|v| (y, v)))
            .collect();
        assert!(labels.len() >= 2, "{name}: gap labels {labels:?}\n{screen}");
        for (y, v) in labels {
            let r = (0..geo.rows.len()).find(|&r| geo.glyph_at(0, r).1 == y);
            let r = r.unwrap_or_else(|| panic!("{name}: label {v} on a spacer line {y}\n{screen}"));
            let off = (shown_gaps[r] - v).abs();
            let best = shown_gaps.iter().map(|g| (g - v).abs()).fold(f64::INFINITY, f64::min);
            assert!(off <= best + 1e-9, "{name}: {v} labels the {} cm row\n{screen}", shown_gaps[r]);
            assert!(off <= 0.5 * step + 1e-9, "{name}: {v} is {off} cm from its row\n{screen}");
        }
        let shown_masses: Vec<f64> = geo.cols.iter().map(|&i| masses[i]).collect();
        let mstep = shown_masses.windows(2).map(|p| p[1] - p[0]).fold(0.0, f64::max);
        let ticks = numbers_on(&buf, label_x, geo.cells.right(), geo.cells.bottom());
        assert!(ticks.len() >= 2, "{name}: mass labels\n{screen}");
        for (x0, x1, v) in ticks {
            let best = shown_masses.iter().map(|m| (m - v).abs()).fold(f64::INFINITY, f64::min);
            // The nearest column (either of two halfway) has its glyph under the label.
            let under = (0..shown_masses.len())
                .filter(|&c| (shown_masses[c] - v).abs() <= best + 1e-9)
                .any(|c| (x0..x1).contains(&geo.glyph_at(c, 0).0));
            assert!(under, "{name}: mass label {v} at {x0}..{x1} is not over its column\n{screen}");
            assert!(best <= 0.5 * mstep + 1e-9, "{name}: {v}\n{screen}");
        }
    }
}

/// What a cell shows on screen at (x, y) of its rectangle `r` without a marker: its zone
/// digit (or `-`, `·` pending) in the middle, its fill (`░` unsure, else blank) elsewhere.
fn cell_glyph(cell: thud::tui::chart::CellView, r: ratatui::layout::Rect, x: u16, y: u16) -> String {
    use thud::tui::chart::CellView;
    let digit = |z: Option<thud::design::Zone>| z.map_or("-".to_string(), |z| z.number().to_string());
    if (x, y) == thud::tui::chart::centre(r) {
        return match cell {
            CellView::Empty => "·".into(),
            CellView::Approx(z) | CellView::Exact(z) | CellView::Unsure(z) => digit(z),
        };
    }
    if matches!(cell, CellView::Unsure(_)) { "░" } else { " " }.to_string()
}

/// The design's marker stays inside its own cell; the cells beside it (left
/// and right) show the digits and fill they show without it, for designs on a cell, between
/// cells and between rows, at 80×24, 120×40 and 200×60, on the plain and the ensemble chart.
#[test]
fn the_chart_marker_never_covers_the_cells_beside_it() {
    for (name, mut app, w, h) in chart_frames() {
        let (masses, gaps) = (app.chart.fine.masses_kg.clone(), app.chart.fine.gaps_m.clone());
        let designs = [
            (app.design.damper.impact_mass_kg, app.design.damper.gap_m),
            (masses[2], gaps[2]),
            (0.5 * (masses[1] + masses[2]), 0.5 * (gaps[2] + gaps[3])),
            (0.3 * masses[3] + 0.7 * masses[4], 0.7 * gaps[1] + 0.3 * gaps[2]),
        ];
        for (m, d) in designs {
            let reqs = app.select_design(m, d);
            compute_sync(&mut app, reqs);
            let (screen, buf) = render_with(&mut app, w, h);
            let (geo, cells, _, _) = chart_of(&app);
            let c = geo.cells;
            let marked: Vec<(u16, u16)> = (c.y..c.bottom())
                .flat_map(|y| (c.x..c.right()).map(move |x| (x, y)))
                .filter(|&(x, y)| buf[(x, y)].modifier.contains(ratatui::style::Modifier::REVERSED))
                .collect();
            assert!(!marked.is_empty(), "{name} {m} {d}: no marker\n{screen}");
            let own = geo.hit(marked[0].0, marked[0].1).unwrap();
            assert!(marked.iter().all(|&(x, y)| geo.hit(x, y) == Some(own)), "{name}: marker {marked:?}\n{screen}");
            let col = geo.cols.iter().position(|&i| i == own.0).unwrap();
            let row = geo.rows.iter().position(|&i| i == own.1).unwrap();
            for nc in [col.wrapping_sub(1), col + 1].into_iter().filter(|&k| k < geo.cols.len()) {
                let r = geo.rect(nc, row);
                let cell = cells[geo.rows[row] * app.chart.fine.masses_kg.len() + geo.cols[nc]];
                for y in r.y..r.bottom() {
                    for x in r.x..r.right() {
                        let want = cell_glyph(cell, r, x, y);
                        assert_eq!(buf[(x, y)].symbol(), want, "{name} {m} {d}: ({x}, {y}) beside\n{screen}");
                    }
                }
            }
        }
    }
}

/// Whether `line` is `texts` (each whole, or with a middle or end cut to `…`) one after the
/// other, each column one blank or more from the one before.
fn columns_apart(line: &[char], texts: &[Vec<char>], first: bool) -> bool {
    let mut p = 0;
    while p < line.len() && line[p] == ' ' {
        p += 1;
    }
    if p == line.len() {
        return true;
    }
    if p == 0 && !first {
        return false;
    }
    let rest = &line[p..];
    let ends = |t: &Vec<char>| -> Vec<usize> {
        let mut out = vec![];
        if rest.starts_with(t) {
            out.push(t.len());
        }
        let Some(q) = rest.iter().position(|&c| c == '…') else { return out };
        if q <= t.len() && rest[..q] == t[..q] {
            // After the `…`: the text's own ending, or nothing.
            for k in 0..t.len() - q {
                if rest[q + 1..].starts_with(&t[t.len() - k..]) {
                    out.push(q + 1 + k);
                }
            }
        }
        out
    };
    texts.iter().any(|t| ends(t).into_iter().any(|e| columns_apart(&rest[e..], texts, false)))
}

/// The inside lines of the panel titled `title` on `screen`.
fn panel_lines(screen: &str, title: &str) -> Vec<Vec<char>> {
    let lines: Vec<Vec<char>> = screen.lines().map(|l| l.trim_matches('"').chars().collect()).collect();
    let head: Vec<char> = format!("┌{title}").chars().collect();
    let Some((top, x)) =
        lines.iter().enumerate().find_map(|(y, l)| l.windows(head.len()).position(|w| w == head).map(|x| (y, x)))
    else {
        return vec![];
    };
    let right = (x + 1..lines[top].len()).find(|&i| lines[top][i] == '┐').unwrap();
    lines[top + 1..].iter().take_while(|l| l[x] != '└').map(|l| l[x + 1..right].to_vec()).collect()
}

/// Every readout line in `app`'s frames from 60×20 to 200×60 (both teaching layouts): its
/// columns (labels, live and pinned values, each whole or cut with `…`) a blank or more apart;
/// where the history is drawn, its legend keeps `●● damper`. (lines checked, legends seen)
fn readout_columns_at_every_size(app: &mut App) -> (usize, usize) {
    let (rows, note) = thud::tui::ui::readout_rows(app);
    let mut texts: Vec<Vec<char>> = ["live", "pinned"].iter().map(|t| t.chars().collect()).collect();
    for r in &rows {
        for t in [r.label, &r.live, r.pinned.as_deref().unwrap_or("")] {
            texts.push(t.chars().collect());
        }
    }
    let note: Vec<char> = note.unwrap().chars().collect();
    let (mut checked, mut legends) = (0, 0);
    for w in (60..=200u16).step_by(7).chain([200]) {
        for h in [20u16, 24, 33, 40, 60] {
            for focus in [thud::tui::app::Panel::Params, thud::tui::app::Panel::History] {
                app.focus = focus;
                let screen = render(app, w, h);
                // " readout " or " readout: orbit 8/4 " (tests/it/tui_orbit.rs).
                let lines = panel_lines(&screen, " readout");
                assert!(lines.len() >= 3, "{w}x{h}: no readout\n{screen}");
                for line in &lines {
                    let text: String = line.iter().collect::<String>().trim_end().to_string();
                    // The note, whole or cut with an ellipsis.
                    let shown = text.strip_suffix('…').unwrap_or(&text);
                    if !text.is_empty() && note.starts_with(&shown.chars().collect::<Vec<_>>()) {
                        continue;
                    }
                    // A later line of the note, wrapped in the tall readout.
                    let whole: String = note.iter().collect();
                    if !shown.trim().is_empty() && whole.contains(shown.trim()) {
                        continue;
                    }
                    assert!(columns_apart(line, &texts, true), "{w}x{h}: columns run together in\n{text}\n{screen}");
                    checked += 1;
                }
                if let Some(l) = screen.lines().find(|l| l.contains("│x (cm) ")) {
                    assert!(l.contains("●● damper"), "{w}x{h}: the legend lost the damper:\n{screen}");
                    legends += 1;
                }
            }
        }
    }
    (checked, legends)
}

/// With a pinned design, an ensemble of 4 and a force on, at every size from
/// 60×20 to 200×60, every readout line is its columns (labels, live and pinned values, each
/// whole or cut with `…`) a blank or more apart; the history legend keeps `●● damper`. Without
/// the pin too (the compact readout's pairs of spreads).
#[test]
fn readout_columns_never_run_into_each_other_with_pin_ensemble_and_force() {
    let mut app = forced_app(Palette::default());
    set_field(&mut app, thud::tui::fields::Knob::RUNS, "4");
    press(&mut app, KeyCode::Char('p'));
    assert!(app.pinned.is_some());
    set_field(&mut app, thud::tui::fields::Knob::GAP, "2.5");
    assert!(!app.busy());
    let (rows, _) = thud::tui::ui::readout_rows(&app);
    assert!(rows.iter().all(|r| r.pinned.is_some()) && rows.iter().any(|r| r.live.contains(" [")), "{rows:?}");
    let (checked, legends) = readout_columns_at_every_size(&mut app);
    assert!(checked > 500 && legends > 50, "{checked} lines, {legends} legends");
    press(&mut app, KeyCode::Char('p'));
    assert!(app.pinned.is_none());
    let (checked, _) = readout_columns_at_every_size(&mut app);
    assert!(checked > 500, "{checked} lines");
}
