//! The terminal put back on SIGILL, SIGFPE and SIGSEGV, the three signals whose default action
//! ends the process and that thud's signal module (through `signal-hook`) cannot catch.
//!
//! **Why a crate of its own, by hand.** `signal-hook` refuses these signals outright (its
//! `FORBIDDEN` list: a handler that returns into a real fault runs the faulting instruction
//! again), and no well-kept crate offers "restore the terminal, then die by the same signal";
//! catching them takes `libc::sigaction`, which is `unsafe`. The workspace forbids unsafe code
//! everywhere else, so this crate is the one place it lives: about 80 lines of code, every block
//! with its `SAFETY` comment (`clippy::undocumented_unsafe_blocks` is denied).
//!
//! **What the handler does.** Only async-signal-safe work, on the alternate signal stack that
//! Rust's standard library gives every thread it starts (`SA_ONSTACK`; std sets one up for its
//! stack-overflow report, so it costs nothing here):
//! 1. if [`arm`]ed (an atomic flag, cleared by [`disarm`] and by the first handler to run),
//!    `write(2)` the precomputed restore bytes to the terminal and `tcsetattr(3)` the terminal
//!    settings saved by [`arm`] before raw mode was entered;
//! 2. call the handler that was there before (std's SIGSEGV handler, which prints "thread …
//!    has overflowed its stack" and aborts when the fault is in a guard page);
//! 3. raise the signal again. `SA_RESETHAND` has put the default action back and `SA_NODEFER`
//!    leaves the signal unblocked, so the process ends at once by that very signal: the shell
//!    reports it (`128 + n`, "Segmentation fault") and core dumps are as they were. A real
//!    fault ends the same way, never returning into the faulting code.

use std::io;
use std::os::fd::RawFd;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::OnceLock;

/// The signals handled here.
pub const SIGNALS: [i32; 3] = [libc::SIGILL, libc::SIGFPE, libc::SIGSEGV];

/// What the handler restores, saved by the first [`arm`].
struct Saved {
    /// The terminal whose settings are put back (standard input if it is a terminal, as
    /// crossterm's raw mode picks it, else the output).
    termios_fd: RawFd,
    termios: libc::termios,
    out_fd: RawFd,
    restore: &'static [u8],
}

static SAVED: OnceLock<Saved> = OnceLock::new();
/// The actions in place before ours, one per [`SIGNALS`] entry (set before ours are installed).
static PREVIOUS: OnceLock<[libc::sigaction; 3]> = OnceLock::new();
static INSTALLED: OnceLock<Result<(), i32>> = OnceLock::new();
/// True between [`arm`] and [`disarm`]: the handler restores the terminal.
static ACTIVE: AtomicBool = AtomicBool::new(false);

/// Saves the terminal's settings (the first time only: call it before raw mode is entered),
/// installs the handlers (once) and arms them: until [`disarm`], SIGILL, SIGFPE or SIGSEGV
/// writes `restore` to `out_fd` and puts the saved settings back before the process dies.
///
/// # Errors
/// The terminal's settings cannot be read (`tcgetattr`) or a handler cannot be installed
/// (`sigaction`); nothing is armed then.
pub fn arm(out_fd: RawFd, restore: &'static [u8]) -> io::Result<()> {
    if SAVED.get().is_none() {
        // SAFETY: isatty only inspects the descriptor number.
        let termios_fd = if unsafe { libc::isatty(0) } == 1 { 0 } else { out_fd };
        // SAFETY: termios is plain old data; all-zero is a valid value that tcgetattr overwrites.
        let mut termios: libc::termios = unsafe { std::mem::zeroed() };
        // SAFETY: `termios` is a valid, writable termios for the call's duration.
        if unsafe { libc::tcgetattr(termios_fd, &raw mut termios) } != 0 {
            return Err(io::Error::last_os_error());
        }
        // Another thread's arm may have won the race; its settings are the same terminal's.
        let _ = SAVED.set(Saved { termios_fd, termios, out_fd, restore });
    }
    INSTALLED.get_or_init(install).map_err(io::Error::from_raw_os_error)?;
    ACTIVE.store(true, Ordering::SeqCst);
    Ok(())
}

/// The terminal is restored: a fault from now on leaves it alone (and still ends the process).
pub fn disarm() {
    ACTIVE.store(false, Ordering::SeqCst);
}

/// Records the previous actions, then installs [`on_fault`] for every signal of [`SIGNALS`].
fn install() -> Result<(), i32> {
    // SAFETY: sigaction is plain old data; all-zero is a valid (default) action.
    let mut previous: [libc::sigaction; 3] = unsafe { std::mem::zeroed() };
    for (sig, old) in SIGNALS.iter().zip(previous.iter_mut()) {
        // SAFETY: a null new action only reads the current one into `old`, a valid sigaction.
        if unsafe { libc::sigaction(*sig, std::ptr::null(), old) } != 0 {
            return Err(io::Error::last_os_error().raw_os_error().unwrap_or(libc::EINVAL));
        }
    }
    let previous = PREVIOUS.get_or_init(|| previous);
    // SAFETY: as above, all-zero is a valid sigaction, filled in below.
    let mut action: libc::sigaction = unsafe { std::mem::zeroed() };
    action.sa_sigaction = on_fault as *const () as libc::sighandler_t;
    action.sa_flags = libc::SA_SIGINFO | libc::SA_RESETHAND | libc::SA_NODEFER | libc::SA_ONSTACK;
    for (sig, old) in SIGNALS.iter().zip(previous) {
        if old.sa_sigaction == libc::SIG_IGN {
            continue; // ignored by whoever started us: leave it so.
        }
        // SAFETY: `action` is a valid sigaction naming a handler with the SA_SIGINFO signature
        // that does only async-signal-safe work; a null old action is allowed.
        if unsafe { libc::sigaction(*sig, &raw const action, std::ptr::null_mut()) } != 0 {
            return Err(io::Error::last_os_error().raw_os_error().unwrap_or(libc::EINVAL));
        }
    }
    Ok(())
}

/// The handler (see the crate documentation): restore if armed, chain, die by `sig`.
extern "C" fn on_fault(sig: libc::c_int, info: *mut libc::siginfo_t, context: *mut libc::c_void) {
    // `OnceLock::get` and the swap are single atomic operations: async-signal-safe.
    if ACTIVE.swap(false, Ordering::SeqCst) {
        if let Some(saved) = SAVED.get() {
            let mut rest = saved.restore;
            for _ in 0..64 {
                if rest.is_empty() {
                    break;
                }
                // SAFETY: write(2) is async-signal-safe; `rest` is valid for `rest.len()` bytes.
                let n = unsafe { libc::write(saved.out_fd, rest.as_ptr().cast(), rest.len()) };
                rest = usize::try_from(n).ok().and_then(|n| rest.get(n..)).unwrap_or(rest);
            }
            // SAFETY: tcsetattr is async-signal-safe; `saved.termios` came from tcgetattr.
            unsafe { libc::tcsetattr(saved.termios_fd, libc::TCSANOW, &raw const saved.termios) };
        }
    }
    let index = SIGNALS.iter().position(|s| *s == sig);
    if let Some(old) = index.and_then(|i| PREVIOUS.get().map(|p| p[i])) {
        let handler = old.sa_sigaction;
        if handler != libc::SIG_DFL && handler != libc::SIG_IGN {
            if old.sa_flags & libc::SA_SIGINFO != 0 {
                // SAFETY: with SA_SIGINFO the kernel calls the handler with this signature; it
                // gets the signal, info and context we were given.
                let f: extern "C" fn(libc::c_int, *mut libc::siginfo_t, *mut libc::c_void) =
                    unsafe { std::mem::transmute(handler) };
                f(sig, info, context);
            } else {
                // SAFETY: without SA_SIGINFO the handler takes the signal number only.
                let f: extern "C" fn(libc::c_int) = unsafe { std::mem::transmute(handler) };
                f(sig);
            }
        }
    }
    // SAFETY: raise is async-signal-safe. SA_RESETHAND made the action the default one and
    // SA_NODEFER left the signal unblocked, so this ends the process by `sig` here.
    unsafe { libc::raise(sig) };
    // SAFETY: _exit is async-signal-safe; only reached if the signal somehow did not end us.
    unsafe { libc::_exit(128 + sig) };
}
