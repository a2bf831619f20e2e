//! Driving the explorer in tests: a key, a field typed in, a frame drawn on a `TestBackend`;
//! each request the app makes is computed synchronously (`compute_sync`), as the worker would.

use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use ratatui::backend::TestBackend;
use ratatui::Terminal;
use thud::tui::app::{App, Msg};
use thud::tui::fields::Knob;
use thud::tui::{compute_sync, draw};

/// Presses `code` (no modifier) and computes what it asks for.
pub fn press(app: &mut App, code: KeyCode) {
    let reqs = app.update(Msg::Input(Event::Key(KeyEvent::new(code, KeyModifiers::NONE))));
    compute_sync(app, reqs);
}

/// Types `text` into `field` as a user does (select, submit), computes what it asks for, and
/// fails the test if the app refused it.
pub fn set(app: &mut App, field: Knob, text: &str) {
    app.selected = Knob::ALL.iter().position(|k| *k == field).unwrap();
    let reqs = app.submit_text(text);
    compute_sync(app, reqs);
    assert!(!app.status().unwrap().error, "{text}: {:?}", app.status());
}

/// One frame of `app` at `w`×`h`, as the backend's text.
pub fn render(app: &mut App, w: u16, h: u16) -> String {
    let mut term = Terminal::new(TestBackend::new(w, h)).unwrap();
    draw(&mut term, app).unwrap();
    term.backend().to_string()
}
