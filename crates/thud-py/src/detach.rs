//! Running the engine without the GIL: the work runs on its own thread while the calling
//! Python thread waits with the GIL released, so other Python threads (and
//! `concurrent.futures`) run designs at the same time. Every 100 ms the waiting thread takes
//! the GIL back for a moment to let Python handle signals: Ctrl-C cancels a simulation or a
//! sweep (the engine stops between impacts or cells) and raises `KeyboardInterrupt`. The same
//! moment reports progress ([`run_watched`]); a progress callback that raises cancels too.
//!
//! pyo3's `Python::detach` alone would release the GIL, but a long run could not then be
//! interrupted; hence the thread and the channel.
//!
//! Python runs its signal handlers in the main thread only, so a run waited for in another
//! thread (`threading`, `concurrent.futures`) never sees Ctrl-C there. The module therefore
//! counts SIGINTs itself (a `signal-hook` handler, installed with the first run, which chains
//! to Python's own, so Python still raises `KeyboardInterrupt` in the main thread): a run that
//! sees the count change while it waits is cancelled and raises `KeyboardInterrupt` in its own
//! thread, within a poll.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::sync::OnceLock;
use std::time::Duration;

use pyo3::exceptions::{PyKeyboardInterrupt, PyRuntimeError};
use pyo3::prelude::*;

/// How often the waiting thread looks at Python's signals.
const SIGNAL_POLL: Duration = Duration::from_millis(100);

/// SIGINTs this process has received since the first run (see the module doc).
static INTERRUPTS: AtomicUsize = AtomicUsize::new(0);

/// Starts counting SIGINTs into [`INTERRUPTS`] (once). Without it (the handler refused), runs
/// in other threads than the main one are not interrupted, as before.
fn count_interrupts() {
    static STARTED: OnceLock<()> = OnceLock::new();
    STARTED.get_or_init(|| {
        let Ok(mut signals) = signal_hook::iterator::Signals::new([signal_hook::consts::SIGINT]) else { return };
        let _ = std::thread::Builder::new().name("thud-sigint".into()).spawn(move || {
            for _ in signals.forever() {
                INTERRUPTS.fetch_add(1, Ordering::SeqCst);
            }
        });
    });
}

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
    count_interrupts();
    let interrupts = INTERRUPTS.load(Ordering::SeqCst);
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
                    let interrupted = || {
                        if INTERRUPTS.load(Ordering::SeqCst) == interrupts {
                            Ok(())
                        } else {
                            Err(PyKeyboardInterrupt::new_err("the run was stopped by Ctrl-C (SIGINT)"))
                        }
                    };
                    if let Err(interrupt) = py.check_signals().and_then(|()| interrupted()).and_then(|()| watch()) {
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
