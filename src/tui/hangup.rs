//! Notices when the explorer's terminal is gone without a SIGHUP (the pty's master side closed
//! while thud is not its session's controlling process, e.g. after `setsid`).
//!
//! crossterm's reader retries every read error other than "would block", so on a dead terminal
//! (each read fails with EIO, or returns 0 at end of file) its `poll`/`read` never returned and
//! the input thread spun at 100 % CPU. The explorer's own reader ([`super::input_reader`]) now
//! ends on EOF or EIO itself; this watch stays as the second path. It watches the same terminal
//! from a thread of its own with `poll(2)` asking for no event at all: the call sleeps, costing nothing, until
//! the kernel reports a hang-up or an error on the descriptor (POLLHUP, POLLERR, POLLNVAL are
//! always reported). Then the explorer is told and ends, restoring what can be restored.
//! Written by hand on `rustix`'s `poll` because crossterm has no hook for it.

use std::fs::File;
use std::io::{self, IsTerminal};
use std::os::fd::{AsFd, OwnedFd};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use rustix::event::{poll, PollFd, PollFlags};

/// The terminal input crossterm reads (standard input if it is a terminal, else `/dev/tty`),
/// as a descriptor of our own on the same open file.
pub(crate) fn terminal_input() -> io::Result<OwnedFd> {
    if io::stdin().is_terminal() {
        io::stdin().as_fd().try_clone_to_owned()
    } else {
        Ok(File::open("/dev/tty")?.into())
    }
}

/// True when `flags` say the terminal is gone.
pub fn is_gone(flags: PollFlags) -> bool {
    flags.intersects(PollFlags::HUP | PollFlags::ERR | PollFlags::NVAL)
}

/// Blocks until `fd` reports a hang-up or an error; `Err` if polling itself fails.
fn wait_for_hangup(fd: &OwnedFd) -> io::Result<()> {
    loop {
        let mut fds = [PollFd::new(fd, PollFlags::empty())];
        match poll(&mut fds, None) {
            Ok(_) if is_gone(fds[0].revents()) => return Ok(()),
            Ok(_) | Err(rustix::io::Errno::INTR) => {}
            Err(e) => return Err(e.into()),
        }
    }
}

/// Starts the watcher: when the terminal's input hangs up, the returned flag is set and
/// `on_gone` runs (once). If the terminal cannot be opened or no thread can be started the
/// explorer runs unwatched (`Err` says why), as it did before.
pub fn watch(on_gone: impl FnOnce() + Send + 'static) -> io::Result<Arc<AtomicBool>> {
    let fd = terminal_input()?;
    let gone = Arc::new(AtomicBool::new(false));
    let flag = gone.clone();
    std::thread::Builder::new().name("thud-hangup".into()).spawn(move || {
        if wait_for_hangup(&fd).is_ok() {
            flag.store(true, Ordering::SeqCst);
            on_gone();
        }
    })?;
    Ok(gone)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_hang_up_or_an_error_is_gone_readable_is_not() {
        assert!(is_gone(PollFlags::HUP) && is_gone(PollFlags::ERR | PollFlags::IN) && is_gone(PollFlags::NVAL));
        assert!(!is_gone(PollFlags::IN) && !is_gone(PollFlags::empty()));
    }

    #[test]
    fn a_closed_pipe_wakes_the_watcher() {
        // A pipe's read end reports POLLHUP when its write end closes, as a pty slave does
        // when its master closes.
        let (r, w) = std::io::pipe().unwrap();
        let r: OwnedFd = r.into();
        let t = std::thread::spawn(move || wait_for_hangup(&r));
        drop(w);
        assert!(t.join().unwrap().is_ok());
    }
}
