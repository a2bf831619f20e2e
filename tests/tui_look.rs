#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test or benchmark fails
//! How the explorer looks: legible on a projector and on light terminals (no dim labels, a
//! light theme, 16 colours when the terminal advertises no more), and text cut with an
//! ellipsis (pure ASCII with `--ascii`, spelled rather than `?`).

mod common;

use std::cell::RefCell;
use std::io::Write;
use std::rc::Rc;

use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::style::{Color, Modifier};
use ratatui::Terminal;
use thud::tui::app::{App, Msg, Panel};
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

fn press(app: &mut App, code: KeyCode) {
    let reqs = app.update(Msg::Input(Event::Key(KeyEvent::new(code, KeyModifiers::NONE))));
    compute_sync(app, reqs);
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

    use clap::Parser;
    let cli = thud::cli::Cli::try_parse_from(["thud", "tui", "--theme", "light"]).unwrap();
    let Some(thud::cli::Command::Tui(a)) = cli.command else { panic!("tui") };
    assert_eq!(a.theme, Some(thud::config::Theme::Light));
    let (code, _, err) = common::thud(&["tui", "--theme", "purple"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("purple"), "{err}");
}
