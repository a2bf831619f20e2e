//! The explorer's app: its state, and the changes a message makes to it. No physics and no
//! drawing here, so every behaviour can be tested without a terminal; the view (`ui.rs`) draws
//! from the state and never changes it.
//!
//! One concern a module, one `impl App` block each, each calling only the ones above it:
//! - `state`: the state, grouped by concern (the live setup and its edits, its results, the
//!   chart, the curves over f, the screen, what the last frame drew, the host's set-up: at
//!   most 20 fields, each group a type), and the queries the view reads;
//! - `change`: a new live design (undoable) and the work it needs; undo, stepping and typing
//!   a field, moving on the chart;
//! - `screen`: the pin, the chart panel's and the pulse panel's views, the field's hint;
//! - `guide`: the guided tour and the jump to the best zone-3 design;
//! - `files`: save, load and export;
//! - `input`: what a key (in each mode) or a click does;
//! - `update`: [`App::update`], the one entry: a message (key, click, worker result, tick)
//!   in, the state changed, the [`Request`](super::worker::Request)s for the worker out.

mod change;
mod files;
mod guide;
mod input;
mod screen;
mod state;
mod update;

pub use super::view::{Panel, PulseView};
pub use change::changes;
pub use state::{best_zone3, App, Best, ChartState, ChartView, Host, Mode, Options, Pinned, Screen, Status, TourState};
pub use update::Msg;
