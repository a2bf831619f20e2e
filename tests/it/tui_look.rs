#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test or benchmark fails
//! How the explorer looks: legible on a projector and on light terminals (no dim labels, a
//! light theme, 16 colours when the terminal advertises no more), and text cut with an
//! ellipsis (pure ASCII with `--ascii`, spelled rather than `?`).

use crate::common;
use crate::support::explorer::press;

use std::cell::RefCell;
use std::io::Write;
use std::rc::Rc;

use clap::Parser;
use crossterm::event::KeyCode;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::style::{Color, Modifier};
use ratatui::Terminal;
use thud::tui::app::{App, Panel};
use thud::tui::compute::{Grid, Grids};
use thud::tui::sgr16::Depth16;
use thud::tui::theme::Depth;
use thud::tui::{compute_sync, draw, Palette};

fn app_with(preset: &str, theme: Palette) -> App {
    let d = thud::presets::preset(preset).unwrap();
    let grids = Grids { coarse: None, fine: Grid::standard(8, 6) };
    let mut app = App::with_grids(d, preset, theme, grids);
    let reqs = app.initial_requests();
    compute_sync(&mut app, reqs);
    app
}

fn buffer(app: &mut App, w: u16, h: u16) -> Buffer {
    let mut term = Terminal::new(TestBackend::new(w, h)).unwrap();
    draw(&mut term, app).unwrap();
    term.backend().buffer().clone()
}

fn text(buf: &Buffer) -> String {
    let w = usize::from(buf.area.width);
    buf.content.chunks(w.max(1)).map(|row| row.iter().map(ratatui::buffer::Cell::symbol).collect::<String>()).fold(
        String::new(),
        |mut s, l| {
            s.push_str(&l);
            s.push('\n');
            s
        },
    )
}

/// Brings the history and chart pair on screen in the teaching layout.
fn show_chart(app: &mut App) {
    while app.focus != Panel::History {
        press(app, KeyCode::Tab);
    }
}

const DARK: Palette = Palette { color: true, ascii: false, light: false };
const LIGHT: Palette = Palette { color: true, ascii: false, light: true };

#[test]
fn tick_labels_axis_titles_and_ring_labels_are_not_dim() {
    for theme in [DARK, LIGHT] {
        let mut app = app_with("default", theme);
        assert!(!app.busy());
        for (w, h, chart) in [(120, 40, false), (80, 24, false), (80, 24, true)] {
            if chart {
                show_chart(&mut app);
            }
            let buf = buffer(&mut app, w, h);
            let screen = text(&buf);
            assert!(screen.contains("dB"), "a plot with labels is on screen:\n{screen}");
            for (i, c) in buf.content.iter().enumerate() {
                let s = c.symbol();
                if s.chars().any(char::is_alphanumeric) {
                    let (x, y) = (i % usize::from(w), i / usize::from(w));
                    assert!(
                        !c.modifier.contains(Modifier::DIM),
                        "{s:?} at ({x},{y}) is dim at {w}x{h} (light {}):\n{screen}",
                        theme.light
                    );
                }
            }
        }
    }
}

/// A writer the test can read after the terminal took it.
#[derive(Clone, Default)]
struct Shared(Rc<RefCell<Vec<u8>>>);

impl Write for Shared {
    fn write(&mut self, b: &[u8]) -> std::io::Result<usize> {
        self.0.borrow_mut().extend_from_slice(b);
        Ok(b.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// The bytes one frame of `app` sends to a terminal of `depth`.
fn wire(app: &mut App, depth: Depth) -> String {
    let out = Shared::default();
    let backend = Depth16::new(out.clone(), depth);
    let mut term = Terminal::with_options(
        backend,
        ratatui::TerminalOptions { viewport: ratatui::Viewport::Fixed(ratatui::layout::Rect::new(0, 0, 120, 40)) },
    )
    .unwrap();
    draw(&mut term, app).unwrap();
    let bytes = out.0.borrow().clone();
    String::from_utf8(bytes).unwrap()
}

#[test]
fn under_term_xterm_no_256_colour_code_is_sent() {
    let depth = Depth::from_vars(Some("xterm"), None);
    assert_eq!(depth, Depth::Sixteen);
    for theme in [DARK, LIGHT] {
        let mut app = app_with("default", theme);
        let sent = wire(&mut app, depth);
        assert!(sent.contains("40.50 g"), "the frame was sent");
        assert!(!sent.contains("38;5;") && !sent.contains("48;5;"), "a 256-colour code under TERM=xterm");
        // The zones' fills and the live curve's colour are there, as the classic codes.
        assert!(sent.contains(";41m") || sent.contains(";41;"), "red fill as SGR 41");
        let live = if theme.light { ";34m" } else { ";36m" };
        assert!(sent.contains(live), "the live curve's colour as {live}");
        // The same frame through crossterm's own colours: what the check above guards against.
        let mut app = app_with("default", theme);
        assert!(wire(&mut app, Depth::Indexed256).contains("38;5;"));
    }
}

#[test]
fn the_light_theme_has_no_ink_that_vanishes_on_white() {
    let mut app = app_with("paper-table3", LIGHT);
    app.pinned = None;
    for chart in [false, true] {
        if chart {
            show_chart(&mut app);
        }
        let buf = buffer(&mut app, 80, 24);
        for c in &buf.content {
            if c.bg == Color::Reset {
                assert!(
                    !matches!(c.fg, Color::Yellow | Color::White | Color::Cyan | Color::LightYellow | Color::Gray),
                    "{:?} in {:?} on the light background",
                    c.symbol(),
                    c.fg
                );
            }
        }
    }
}

/// Each cell's foreground as a letter (k r g y b m c w; capital for the bright ones, `.`
/// for the terminal's own), one row per line: the colours the snapshot records.
fn colour_map(buf: &Buffer) -> String {
    let letter = |c: Color| match thud::tui::theme::ansi_index(c) {
        None => '.',
        Some(i) => {
            let l = b"krgybmcw"[usize::from(i % 8)] as char;
            if i >= 8 {
                l.to_ascii_uppercase()
            } else {
                l
            }
        }
    };
    let w = usize::from(buf.area.width);
    buf.content.chunks(w).map(|row| row.iter().map(|c| letter(c.fg)).collect::<String>() + "\n").collect()
}

#[test]
fn light_theme_80x24() {
    let mut app = app_with("default", LIGHT);
    let buf = buffer(&mut app, 80, 24);
    insta::assert_snapshot!("light_80x24", format!("{}\n{}", text(&buf), colour_map(&buf)));
    show_chart(&mut app);
    let buf = buffer(&mut app, 80, 24);
    insta::assert_snapshot!("light_chart_80x24", format!("{}\n{}", text(&buf), colour_map(&buf)));
}

#[test]
fn theme_light_in_config_and_on_the_command_line() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("config.toml"), "theme = \"light\"\n").unwrap();
    let load = thud::config::load_config(dir.path());
    assert!(load.warning().is_none(), "{:?}", load.warning());
    let mut app = app_with("default", DARK);
    app.configure(&load);
    assert_eq!(app.theme, LIGHT);
    assert!(thud::config::check_text(std::path::Path::new("c.toml"), "theme = \"light\"\n").is_empty());

    let cli = thud::cli::Cli::try_parse_from(["thud", "tui", "--theme", "light"]).unwrap();
    let Some(thud::cli::Command::Tui(a)) = cli.command else { panic!("tui") };
    assert_eq!(a.theme, Some(thud::config::Theme::Light));
    let (code, _, err) = common::thud(&["tui", "--theme", "purple"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("purple"), "{err}");
}

// ---- Item 11: text cut with an ellipsis; --ascii spells rather than `?` ----

const ASCII: Palette = Palette { color: true, ascii: true, light: false };

fn screen(app: &mut App, w: u16, h: u16) -> String {
    text(&buffer(app, w, h))
}

/// The status line's row: above the footer when there is one.
fn status_row(app: &App, h: u16) -> usize {
    let footer = h >= 12 && app.tour.is_none();
    usize::from(h) - 1 - usize::from(footer)
}

/// `narrow` is `full` whole, or its start ended with the ellipsis `ell`.
fn assert_whole_or_cut(narrow: &str, full: &str, ell: &str, what: &str) {
    let (n, f) = (narrow.trim_end(), full.trim_end());
    if n == f {
        return;
    }
    assert!(n.ends_with(ell), "{what} cut without {ell:?}:\n  narrow {n:?}\n  full   {f:?}");
    let head = n.strip_suffix(ell).unwrap().trim_end();
    assert!(f.starts_with(head), "{what}: {n:?} is not the start of {f:?}");
}

/// The header and the status line at 60×20 and 80×24 against the same lines at 400 columns.
fn check_header_and_status(app: &mut App, ell: &str, what: &str) -> usize {
    let full = screen(app, 400, 60);
    let full_rows: Vec<&str> = full.lines().collect();
    let mut cut = 0;
    for (w, h) in [(60, 20), (80, 24)] {
        let s = screen(app, w, h);
        let rows: Vec<&str> = s.lines().collect();
        assert_whole_or_cut(rows[0], full_rows[0], ell, &format!("{what}: header at {w}x{h}"));
        let (r, fr) = (status_row(app, h), status_row(app, 60));
        assert_whole_or_cut(rows[r], full_rows[fr], ell, &format!("{what}: status at {w}x{h}"));
        cut += usize::from(rows[0].trim_end() != full_rows[0].trim_end());
        cut += usize::from(rows[r].trim_end() != full_rows[fr].trim_end());
    }
    cut
}

#[test]
fn the_header_and_the_status_line_end_with_an_ellipsis_where_cut() {
    for (theme, ell) in [(DARK, "…"), (ASCII, "...")] {
        let d = thud::presets::preset("paper-table3").unwrap();
        let grids = Grids { coarse: None, fine: Grid::standard(4, 3) };
        let mut app = App::with_grids(d, "a-long-preset-name-read-from-the-back-row", theme, grids);
        let reqs = app.initial_requests();
        compute_sync(&mut app, reqs);
        let mut cut = check_header_and_status(&mut app, ell, "main");
        // A refused value: the error names the whole of what was typed.
        press(&mut app, KeyCode::Enter);
        for c in "forty-and-a-half-grams-please-and-then-some-more".chars() {
            press(&mut app, KeyCode::Char(c));
        }
        cut += check_header_and_status(&mut app, ell, "typing");
        press(&mut app, KeyCode::Enter);
        let s = screen(&mut app, 400, 60);
        assert!(s.contains("error: invalid mass: 'forty-and-a-half"), "{s}");
        cut += check_header_and_status(&mut app, ell, "error");
        assert!(cut >= 4, "the header and the error were cut at 60 columns ({cut} cut)");
    }
}

#[test]
fn the_too_small_message_ends_with_an_ellipsis() {
    for (theme, ell) in [(DARK, "…"), (ASCII, "...")] {
        let mut app = app_with("default", theme);
        for (w, h) in [(20, 5), (29, 7), (12, 3)] {
            let s = screen(&mut app, w, h);
            let first = s.lines().next().unwrap().trim_end();
            assert!(first.starts_with("thud: ter"), "{s}");
            assert!(first.ends_with(ell), "{w}x{h}: {first:?}");
        }
        // Wide enough for the whole message: no ellipsis.
        let first = screen(&mut app, 60, 6).lines().next().unwrap().trim_end().to_string();
        assert!(first.ends_with("need 30x8") || first.ends_with("need 30×8"), "{first:?}");
    }
}

#[test]
fn tour_captions_and_titles_are_whole_or_end_with_an_ellipsis() {
    for (theme, ell) in [(DARK, "…"), (ASCII, "...")] {
        let mut app = app_with("default", theme);
        press(&mut app, KeyCode::Char('T'));
        let n = app.tour.as_ref().unwrap().tour.steps.len();
        let mut cut = 0;
        for _ in 0..n {
            let step = app.tour.as_ref().unwrap().tour.steps[app.tour.as_ref().unwrap().step].clone();
            for (w, h) in [(60, 20), (80, 24)] {
                let s = screen(&mut app, w, h);
                let rows: Vec<&str> = s.lines().collect();
                // The caption box: the five rows above the status line.
                let status = status_row(&app, h);
                let inner: Vec<String> = rows[status - 4..status - 1]
                    .iter()
                    .map(|r| {
                        let r = r.trim_end();
                        let body = if theme.ascii { r.trim_start_matches('|') } else { r.trim_start_matches('│') };
                        let body = if theme.ascii { body.trim_end_matches('|') } else { body.trim_end_matches('│') };
                        body.trim_end().to_string()
                    })
                    .collect();
                let last_word = step.caption.split_whitespace().last().unwrap();
                let last_word = if theme.ascii { thud::tui::theme::fold(last_word) } else { last_word.to_string() };
                let whole = inner.iter().any(|l| l.ends_with(&last_word));
                let last = inner.iter().rev().find(|l| !l.is_empty()).unwrap();
                assert!(whole || last.ends_with(ell), "step caption at {w}x{h} cut without {ell:?}:\n{s}");
                cut += usize::from(!whole);
                // The box's title.
                let top = rows[status - 5];
                let title = if theme.ascii { fold_title(&step.title) } else { step.title.clone() };
                assert!(top.contains(&title) || top.contains(ell), "title at {w}x{h}: {top:?}");
            }
            press(&mut app, KeyCode::Right);
        }
        assert!(cut > 0, "some caption is cut at 60x20");
    }
}

fn fold_title(t: &str) -> String {
    thud::tui::theme::fold(t)
}

/// Every character of many screens (every field selected, both help pages, every tour step).
fn chars_of_many_screens(theme: Palette) -> Vec<String> {
    let mut app = app_with("paper-table3", theme);
    let mut screens = vec![screen(&mut app, 120, 40), screen(&mut app, 80, 24)];
    for _ in 0..thud::tui::fields::Knob::ALL.len() {
        screens.push(screen(&mut app, 200, 60));
        press(&mut app, KeyCode::Down);
    }
    press(&mut app, KeyCode::Char('?'));
    screens.push(screen(&mut app, 120, 60));
    press(&mut app, KeyCode::Right);
    screens.push(screen(&mut app, 120, 60));
    press(&mut app, KeyCode::Esc);
    press(&mut app, KeyCode::Char('T'));
    while app.tour.is_some() {
        screens.push(screen(&mut app, 120, 40));
        screens.push(screen(&mut app, 80, 24));
        press(&mut app, KeyCode::Right);
    }
    screens
}

#[test]
fn ascii_spells_every_character_the_screens_use_and_never_prints_a_question_mark_for_one() {
    let unicode = chars_of_many_screens(DARK);
    let mut unknown: Vec<char> =
        unicode.iter().flat_map(|s| s.chars()).filter(|c| !thud::tui::theme::spellable(*c)).collect();
    unknown.sort_unstable();
    unknown.dedup();
    assert!(unknown.is_empty(), "--ascii would print ? for {unknown:?}");
    let ascii = chars_of_many_screens(ASCII);
    let all = ascii.join("\n");
    assert!(all.is_ascii());
    assert!(all.contains("+/-90deg"), "± spelled +/- (the polar's tour step)");
    assert!(all.contains("Newmark-beta"), "β spelled beta (the solver's explanation)");
    assert!(!all.contains("Newmark-?"));
    // What `?` remains is the help key, never a stand-in: each is followed or preceded by a blank
    // or a bracket as in "? help", "(?)" or "help?".
    for s in &ascii {
        for (i, _) in s.match_indices('?') {
            let around = &s[i.saturating_sub(12)..(i + 12).min(s.len())];
            let prev = s[..i].chars().last().unwrap_or(' ');
            assert!(
                !prev.is_alphanumeric() || around.contains("help") || around.contains("y/n"),
                "a ? standing in for a character: {around:?}"
            );
        }
    }
}
