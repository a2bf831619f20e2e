//! Running the engine without the GIL: the work runs on its own thread while the calling
//! Python thread waits with the GIL released, so other Python threads (and
//! `concurrent.futures`) run designs at the same time. Every 100 ms the waiting thread takes
//! the GIL back for a moment to let Python handle signals: Ctrl-C cancels a simulation or a
//! sweep (the engine stops between impacts or cells) and raises `KeyboardInterrupt`. The same
//! moment reports progress ([`run_watched`]); a progress callback that raises cancels too.
//!
//! pyo3's `Python::detach` alone would release the GIL, but a long run could not then be
//! interrupted; hence the thread and the channel.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::Duration;

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;

/// How often the waiting thread looks at Python's signals.
const SIGNAL_POLL: Duration = Duration::from_millis(100);

/// Runs `work` (given the cancel flag it should watch) with the GIL released; returns its
/// result, or the error of a signal handler (KeyboardInterrupt) after cancelling the work and
/// waiting for it to stop.
pub fn run<T, F>(py: Python<'_>, work: F) -> PyResult<T>
where
    T: Send,
    F: FnOnce(&AtomicBool) -> T + Send,
{
    run_watched(py, work, || Ok(()))
}

/// [`run`], calling `watch` (with the GIL) at every poll and once when the work is done: the
/// progress callback's hook. An error from `watch` cancels the work as an interrupt does.
pub fn run_watched<T, F, W>(py: Python<'_>, work: F, mut watch: W) -> PyResult<T>
where
    T: Send,
    F: FnOnce(&AtomicBool) -> T + Send,
    W: FnMut() -> PyResult<()>,
{
    let cancel = AtomicBool::new(false);
    std::thread::scope(|s| {
        let (tx, mut rx) = mpsc::channel();
        let flag = &cancel;
        s.spawn(move || {
            // The receiver may be gone after an interrupt; the result is then not needed.
            let _ = tx.send(work(flag));
        });
        loop {
            let (back, got) = py.detach(move || {
                let got = rx.recv_timeout(SIGNAL_POLL);
                (rx, got)
            });
            rx = back;
            match got {
                Ok(result) => return watch().map(|()| result),
                Err(RecvTimeoutError::Timeout) => {
                    if let Err(interrupt) = py.check_signals().and_then(|()| watch()) {
                        cancel.store(true, Ordering::Relaxed);
                        let _ = py.detach(move || rx.recv());
                        return Err(interrupt);
                    }
                }
                Err(RecvTimeoutError::Disconnected) => {
                    return Err(PyRuntimeError::new_err("internal error: the engine stopped without a result"))
                }
            }
        }
    })
}
