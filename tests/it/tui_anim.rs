#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! The animation view (`a`): the live run in slow motion from the engine's own record, its
//! keys, the impact flash at the wall the engine found, and a pause that stops the picture.

use crate::support::explorer::{press, render};
use crossterm::event::KeyCode;
use ratatui::Terminal;
use thud::design::Design;
use thud::tui::app::{App, Msg};
use thud::tui::compute::{Grid, Grids};
use thud::tui::{compute_sync, draw, Palette};

fn computed_app(d: Design, ascii: bool) -> App {
    let grids = Grids { coarse: None, fine: Grid::standard(6, 5) };
    let mut app = App::with_grids(d, "default", Palette { color: true, ascii, light: false }, grids);
    let reqs = app.initial_requests();
    compute_sync(&mut app, reqs);
    app
}

/// The picture's lines (the left part of the animation panel, above its status lines).
fn picture(screen: &str) -> String {
    screen.lines().skip(2).take(16).map(|l| l.chars().take(40).collect::<String>()).collect::<Vec<_>>().join("\n")
}

#[test]
fn a_plays_the_run_slowly_flashes_the_first_impact_at_its_wall_and_space_pauses() {
    let mut app = computed_app(Design::default(), false);
    press(&mut app, KeyCode::Char('a'));
    let start = render(&mut app, 80, 24);
    assert!(start.contains("speed 1/10×") && start.contains("playing"), "{start}");
    assert!(app.anim_playing());
    // 0.05 s of real time at 1/10×: 5 ms of the run, and the ball moved on screen.
    app.update(Msg::Frame(0.05));
    assert!((app.anim.as_ref().unwrap().t_s - 0.005).abs() < 1e-12);
    let later = render(&mut app, 80, 24);
    assert_ne!(picture(&start), picture(&later), "the drawn ball moves:\n{start}\n{later}");
    // The first impact, where the engine found it (`thud simulate --json`'s first impact).
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_thud")).args(["simulate", "--json"]).output().unwrap();
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let first = &json["impacts"][0];
    let (t1, wall) = (first["t_s"].as_f64().unwrap(), first["wall"].as_i64().unwrap());
    let now = app.anim.as_ref().unwrap().t_s;
    app.update(Msg::Frame((t1 - now) / 0.1 + 0.01));
    let flash = render(&mut app, 80, 24);
    let side = if wall > 0 { "upper wall (right)" } else { "lower wall (left)" };
    let spl = thud::units::sig(first["spl_db"].as_f64().unwrap(), 4);
    let speed = thud::units::sig(first["u_in_m_s"].as_f64().unwrap(), 4);
    assert!(flash.contains(&format!("impact 1 at the {side}: {speed} m/s, SPL {spl} dB")), "{flash}");
    // Space pauses: a frame changes nothing and the event loop stops drawing.
    press(&mut app, KeyCode::Char(' '));
    assert!(!app.anim_playing());
    let paused = render(&mut app, 80, 24);
    app.update(Msg::Frame(1.0));
    assert_eq!(render(&mut app, 80, 24), paused, "paused: the screen does not change");
    assert!(paused.contains("paused"));
    // ] faster, [ slower, . one frame on, Home back to the start, a closes.
    press(&mut app, KeyCode::Char(']'));
    assert!(render(&mut app, 80, 24).contains("speed 1/3×"));
    press(&mut app, KeyCode::Char('['));
    press(&mut app, KeyCode::Char('['));
    assert!(render(&mut app, 80, 24).contains("speed 1/30×"));
    let t = app.anim.as_ref().unwrap().t_s;
    press(&mut app, KeyCode::Char('.'));
    assert!((app.anim.as_ref().unwrap().t_s - t - 1.0 / 30.0 / 30.0).abs() < 1e-12);
    press(&mut app, KeyCode::Home);
    assert_eq!(app.anim.as_ref().unwrap().t_s, 0.0);
    press(&mut app, KeyCode::Char('a'));
    assert!(app.anim.is_none() && render(&mut app, 80, 24).contains("readout"));
}

#[test]
fn the_animation_draws_forced_runs_the_pinned_design_and_ascii() {
    let mut d = Design::default();
    d.damper.force_n = 2.0;
    d.damper.freq_hz = 5.0;
    let mut app = computed_app(d, true);
    press(&mut app, KeyCode::Char('p'));
    press(&mut app, KeyCode::Char('a'));
    app.update(Msg::Frame(0.3));
    for (w, h) in [(80, 24), (120, 40), (200, 60)] {
        let s = render(&mut app, w, h);
        assert!(s.is_ascii() || s.chars().all(|c| c.is_ascii() || c == '"'), "ascii:\n{s}");
        assert!(s.contains("speed 1/10x") && s.contains("t 0.03"), "{w}x{h}:\n{s}");
    }
}

/// A writer that counts the bytes sent through it.
struct Count(std::sync::Arc<std::sync::atomic::AtomicUsize>);

impl std::io::Write for Count {
    fn write(&mut self, b: &[u8]) -> std::io::Result<usize> {
        self.0.fetch_add(b.len(), std::sync::atomic::Ordering::Relaxed);
        Ok(b.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// Bytes the real backend sends for one second of playback (30 frames) at `w × h`, after the
/// first full frame; ratatui sends only the cells that changed.
pub fn bytes_per_second(w: u16, h: u16, speed: usize) -> usize {
    use ratatui::backend::CrosstermBackend;
    use ratatui::layout::Rect;
    use ratatui::{TerminalOptions, Viewport};
    use std::sync::atomic::Ordering;
    let mut app = computed_app(Design::default(), false);
    press(&mut app, KeyCode::Char('a'));
    app.anim.as_mut().unwrap().speed = speed;
    let sent = std::sync::Arc::new(std::sync::atomic::AtomicUsize::new(0));
    let opts = TerminalOptions { viewport: Viewport::Fixed(Rect::new(0, 0, w, h)) };
    let mut term = Terminal::with_options(CrosstermBackend::new(Count(sent.clone())), opts).unwrap();
    draw(&mut term, &mut app).unwrap();
    let first = sent.load(Ordering::Relaxed);
    for _ in 0..30 {
        app.update(Msg::Frame(thud::tui::anim::FRAME_S));
        draw(&mut term, &mut app).unwrap();
    }
    sent.load(Ordering::Relaxed) - first
}

#[test]
fn one_second_of_playback_at_80x24_sends_under_30_kb_at_every_speed() {
    // The slowest and 1× (the most motion, an impact every few frames): under 30 KB.
    for speed in [0, thud::tui::anim::SPEEDS.len() - 1] {
        let bytes = bytes_per_second(80, 24, speed);
        eprintln!("animation at 80x24, speed {}: {bytes} bytes per second", thud::tui::anim::SPEEDS[speed]);
        assert!(bytes > 0 && bytes < 30_000, "speed {speed}: {bytes} B/s");
    }
}

/// The lines of the lower half of the animation's picture at 80×24 (the pinned run's).
fn lower_picture(screen: &str) -> String {
    screen.lines().skip(10).take(8).map(|l| l.chars().take(44).collect::<String>()).collect::<Vec<_>>().join("\n")
}

#[test]
fn a_pinned_design_plays_below_the_live_one_on_the_same_clock() {
    let mut app = computed_app(Design::default(), false);
    press(&mut app, KeyCode::Char('p'));
    // The live design now differs from the pinned one (a heavier ball, a wider gap).
    let reqs = app.select_design(0.06, 0.05);
    compute_sync(&mut app, reqs);
    press(&mut app, KeyCode::Char('a'));
    let start = render(&mut app, 80, 24);
    assert!(lower_picture(&start).contains("pinned"), "{start}");
    assert!(!picture(&start).lines().take(8).any(|l| l.contains("pinned")), "the live run on top:\n{start}");
    // 20 ms of both runs (0.2 s at 1/10×): the pinned ball and mass move too.
    app.update(Msg::Frame(0.2));
    let later = render(&mut app, 80, 24);
    assert_ne!(lower_picture(&start), lower_picture(&later), "the pinned run plays:\n{start}\n{later}");
    // Unpinned: one run again.
    press(&mut app, KeyCode::Char('a'));
    press(&mut app, KeyCode::Char('p'));
    press(&mut app, KeyCode::Char('a'));
    assert!(!render(&mut app, 80, 24).contains("pinned"));
}
