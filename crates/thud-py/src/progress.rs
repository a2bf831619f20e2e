//! Progress of a long sweep or response in Python, from the engine's own counter: the
//! engine's `on_cell` / `on_point` callbacks (called on its worker threads, without the GIL)
//! count into an atomic; the waiting Python thread ([`crate::detach::run_watched`]) hands the
//! count to the user's `progress(done, total)` at most once a poll (100 ms) and once at the
//! end. A callback that raises — `KeyboardInterrupt` included — cancels the run, and its
//! exception propagates. `progress=True` (a bar on stderr, or tqdm) is the Python wrapper's.

use std::cell::Cell;
use std::sync::atomic::{AtomicUsize, Ordering};

use pyo3::prelude::*;

use crate::args::{kind_of, parameter_error, Kwargs};

/// The progress of one call: the engine's count of finished items out of `total`, and the
/// user's callback.
pub struct Progress<'py> {
    /// Items finished so far (cells, or points of every run); the engine's threads add to it.
    pub done: AtomicUsize,
    total: usize,
    callback: Option<Bound<'py, PyAny>>,
    /// The count last handed to the callback (`usize::MAX`: none yet).
    shown: Cell<usize>,
}

impl<'py> Progress<'py> {
    /// The `progress` option of the call (None or False: no progress; else a callable), over
    /// `total` items.
    pub fn new(py: Python<'py>, kw: &Kwargs<'py>, total: usize) -> PyResult<Progress<'py>> {
        let callback = match kw.option("progress") {
            None => None,
            Some(v) if v.is_instance_of::<pyo3::types::PyBool>() && !v.is_truthy()? => None,
            Some(v) if v.is_callable() && !v.is_instance_of::<pyo3::types::PyBool>() => Some(v.clone()),
            Some(v) => {
                let msg =
                    format!("invalid progress: expected a callable progress(done, total) or True, not {}", kind_of(v));
                return Err(parameter_error(py, "progress", msg));
            }
        };
        Ok(Progress { done: AtomicUsize::new(0), total, callback, shown: Cell::new(usize::MAX) })
    }

    /// One more item finished (called by the engine's threads, given `&progress.done`).
    pub fn tick(done: &AtomicUsize) {
        done.fetch_add(1, Ordering::Relaxed);
    }

    /// Hands the count to the callback if it changed since the last call.
    pub fn report(&self) -> PyResult<()> {
        let Some(callback) = &self.callback else { return Ok(()) };
        let done = self.done.load(Ordering::Relaxed).min(self.total);
        if done != self.shown.get() {
            self.shown.set(done);
            callback.call1((done, self.total))?;
        }
        Ok(())
    }
}
