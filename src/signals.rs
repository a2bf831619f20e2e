//! What happens when thud is told to stop: every signal whose default action ends the process
//! and that a handler may catch — SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGUSR1, SIGUSR2, SIGALRM,
//! SIGXCPU, SIGVTALRM, SIGPROF, SIGPWR, SIGSTKFLT, SIGIO, SIGABRT, SIGTRAP, SIGSYS, SIGBUS and every real-time
//! signal SIGRTMIN..=SIGRTMAX — run every registered clean-up (remove a live temporary file or
//! folder, restore the terminal), then the process exits with status 128 + the signal number,
//! as a shell reports a process killed by that signal. SIGILL, SIGFPE and SIGSEGV are not
//! handled here: `signal-hook` refuses them (a real fault must not return into the faulting
//! code), and a clean-up on a thread cannot run before a fault's default action. While the
//! explorer runs, the `thud_fatal` crate (the workspace's one crate with `unsafe`, armed by
//! [`crate::tui::terminal`]) restores the terminal from their handler itself — async-signal-safe
//! `write` and `tcsetattr` only — and re-raises them, so the process still dies by the signal.
//! Elsewhere they keep their default action.
//!
//! One handler for the whole process, so the file writer ([`crate::fsio`]) and the terminal
//! ([`crate::tui::terminal`]) cannot race each other to `exit`. The signal itself is caught by
//! `signal-hook`, which only writes to a pipe in the signal handler; the clean-ups run on an
//! ordinary thread that reads that pipe, so they may lock, allocate and do I/O. The handler is
//! installed the first time something registers a clean-up, so commands that write no file and
//! draw no screen keep the default signal behaviour.
//!
//! Every step that creates, fills or publishes a resource runs inside [`guarded`]; the signal
//! thread takes the same lock before the clean-ups and keeps it until the process has exited.
//! So a clean-up never runs in the middle of such a step, and no step runs after one: a writer
//! cannot re-create a folder the clean-up removed, nor rename a partial one into place.

use std::cell::Cell;
use std::io;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, OnceLock, PoisonError};

use libc::{
    SIGABRT, SIGALRM, SIGBUS, SIGHUP, SIGINT, SIGIO, SIGPROF, SIGPWR, SIGQUIT, SIGSTKFLT, SIGSYS, SIGTERM, SIGTRAP,
    SIGUSR1, SIGUSR2, SIGVTALRM, SIGXCPU,
};
use signal_hook::iterator::Signals;

/// The signals with a fixed number that run the clean-ups and end the process (SIGPIPE is left
/// alone: a closed pipe is an error on the write, handled where it happens; likewise SIGXFSZ).
/// [`handled`] adds the real-time signals.
pub const HANDLED: [i32; 17] = [
    SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGUSR1, SIGUSR2, SIGALRM, SIGXCPU, SIGVTALRM, SIGPROF, SIGPWR, SIGSTKFLT, SIGIO,
    SIGABRT, SIGTRAP, SIGSYS, SIGBUS,
];

/// Every signal that runs the clean-ups: [`HANDLED`] and SIGRTMIN..=SIGRTMAX (their numbers are
/// the C library's, so they are asked for at run time).
#[must_use]
pub fn handled() -> Vec<i32> {
    HANDLED.iter().copied().chain(libc::SIGRTMIN()..=libc::SIGRTMAX()).collect()
}

type Cleanup = Box<dyn Fn() + Send + Sync>;

/// The live clean-ups, each with the id of its [`Registration`].
static CLEANUPS: Mutex<Vec<(u64, Cleanup)>> = Mutex::new(Vec::new());
static NEXT_ID: AtomicU64 = AtomicU64::new(0);
/// Held while a resource is created, filled or published ([`guarded`]), and by the signal
/// thread from before it runs the clean-ups until the process has exited.
static CRITICAL: Mutex<()> = Mutex::new(());

thread_local! {
    /// How deep this thread is in [`guarded`] (a guarded step may call another).
    static DEPTH: Cell<usize> = const { Cell::new(0) };
}

/// A registered clean-up; dropping it unregisters it (the clean-up is not run).
#[derive(Debug)]
#[must_use = "the clean-up is unregistered when this is dropped"]
pub struct Registration(u64);

impl Drop for Registration {
    fn drop(&mut self) {
        let mut list = CLEANUPS.lock().unwrap_or_else(PoisonError::into_inner);
        list.retain(|(id, _)| *id != self.0);
    }
}

/// Registers `cleanup` to run if one of [`HANDLED`] arrives while the returned
/// [`Registration`] is alive; installs the handler on first use. If the handler cannot be
/// installed the clean-up is still registered (and never runs) and the error is returned, so a
/// caller may go on without the safety net.
pub fn on_signal(cleanup: impl Fn() + Send + Sync + 'static) -> (Registration, io::Result<()>) {
    let installed = install();
    let id = NEXT_ID.fetch_add(1, Ordering::Relaxed);
    CLEANUPS.lock().unwrap_or_else(PoisonError::into_inner).push((id, Box::new(cleanup)));
    (Registration(id), installed)
}

/// Runs `f` — create a resource and register its clean-up, fill it, or publish it — with the
/// clean-ups held off: the handler is installed first, and a signal that arrives meanwhile runs
/// the clean-ups only after `f` returns. Once the clean-ups have started, `f` never runs: the
/// call waits for the process to exit. A guarded step may itself call `guarded`.
pub fn guarded<T>(f: impl FnOnce() -> T) -> T {
    // Without a handler the default action ends the process at once; `f`'s resource is then
    // left as it would be without this module, and `on_signal` reports the failure.
    let _ = install();
    if DEPTH.get() > 0 {
        return f();
    }
    let _critical = CRITICAL.lock().unwrap_or_else(PoisonError::into_inner);
    DEPTH.set(1);
    let out = f();
    DEPTH.set(0);
    out
}

/// Ends the process with `code` unless a signal's clean-ups are under way, in which case it
/// waits for them (the process then exits with the signal's status). The front end's last call,
/// so a run that fails because a clean-up removed its folder does not exit first with its own
/// error while the clean-up is half done.
pub fn exit(code: i32) -> ! {
    if DEPTH.get() == 0 {
        let critical = CRITICAL.lock().unwrap_or_else(PoisonError::into_inner);
        std::mem::forget(critical);
    }
    std::process::exit(code)
}

/// Installs the handler and its thread (once).
fn install() -> io::Result<()> {
    static INSTALLED: OnceLock<Result<(), Arc<io::Error>>> = OnceLock::new();
    INSTALLED
        .get_or_init(|| {
            let mut signals = Signals::new(handled()).map_err(Arc::new)?;
            std::thread::Builder::new()
                .name("thud-signals".into())
                // Its own size, whatever RUST_MIN_STACK says: the clean-ups must not overflow.
                .stack_size(256 << 10)
                .spawn(move || {
                    if let Some(signal) = signals.forever().next() {
                        // Held until the process has exited: no guarded step runs after this.
                        let critical = CRITICAL.lock().unwrap_or_else(PoisonError::into_inner);
                        run_cleanups();
                        std::mem::forget(critical);
                        std::process::exit(128 + signal);
                    }
                })
                .map(drop)
                .map_err(Arc::new)
        })
        .clone()
        .map_err(|e| io::Error::new(e.kind(), e.to_string()))
}

/// Runs every registered clean-up, newest first (the caller holds [`CRITICAL`]).
fn run_cleanups() {
    let list = CLEANUPS.lock().unwrap_or_else(PoisonError::into_inner);
    for (_, cleanup) in list.iter().rev() {
        cleanup();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicUsize;
    use std::sync::Arc;

    #[test]
    fn a_dropped_registration_is_forgotten() {
        let runs = Arc::new(AtomicUsize::new(0));
        let r = runs.clone();
        let (reg, installed) = on_signal(move || {
            r.fetch_add(1, Ordering::SeqCst);
        });
        assert!(installed.is_ok());
        let id = reg.0;
        assert!(CLEANUPS.lock().unwrap().iter().any(|(i, _)| *i == id));
        drop(reg);
        assert!(!CLEANUPS.lock().unwrap().iter().any(|(i, _)| *i == id));
        assert_eq!(runs.load(Ordering::SeqCst), 0, "dropping does not run the clean-up");
    }
}
