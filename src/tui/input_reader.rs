//! The explorer's input thread: reads the terminal itself and parses it with
//! [`super::input_parse`], instead of crossterm's `event::read`, whose parser waits forever
//! (and buffers without bound) after a stray bracketed-paste start; see that module for why.
//!
//! One `poll(2)` waits for the terminal's input, for a window-size change (SIGWINCH, through
//! `signal-hook`'s self-pipe, as crossterm does it) and for the next deadline: the spinner's tick
//! while work is in flight, or the end of a paste's time. Each read is parsed as it comes; a
//! read that fills the buffer says more bytes are waiting, so a lone ESC at its end is not taken
//! for the Esc key yet (crossterm's rule). End of file or a read error other than "interrupted"
//! or "would block" (EIO on a dead pty) means the terminal is gone: the explorer is told and ends,
//! instead of retrying forever. Resizes carry the new size from `crossterm::terminal::size`, so
//! the events are crossterm's own in every case.

use std::io;
use std::os::fd::OwnedFd;
use std::os::unix::net::UnixStream;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::Sender;
use std::sync::Arc;
use std::time::{Duration, Instant};

use crossterm::event::Event;
use rustix::event::{poll, PollFd, PollFlags, Timespec};
use rustix::io::Errno;
use signal_hook::consts::SIGWINCH;
use signal_hook::SigId;

use super::app::Msg;
use super::input_parse::{Parsed, Parser};

/// Bytes read at once (crossterm's size: a full read means more are waiting).
const READ_SIZE: usize = 1024;

/// The terminal's input and the window-size signal's pipe.
pub struct Reader {
    tty: OwnedFd,
    winch: Option<(UnixStream, SigId)>,
    parser: Parser,
    buf: Box<[u8; READ_SIZE]>,
}

/// What one wait brought.
#[derive(Debug, Default)]
struct Woken {
    tty: bool,
    resized: bool,
}

impl Drop for Reader {
    fn drop(&mut self) {
        if let Some((_, id)) = self.winch.take() {
            signal_hook::low_level::unregister(id);
        }
    }
}

impl Reader {
    /// Opens the terminal's input (standard input if it is a terminal, else `/dev/tty`, as
    /// crossterm does) and starts listening for SIGWINCH. Without the signal (it cannot be
    /// registered) the explorer still runs and picks up a new size at its next frame.
    pub fn open() -> io::Result<Self> {
        let tty = super::hangup::terminal_input()?;
        let winch = UnixStream::pair().ok().and_then(|(read, write)| {
            read.set_nonblocking(true).ok()?;
            let id = signal_hook::low_level::pipe::register(SIGWINCH, write).ok()?;
            Some((read, id))
        });
        Ok(Self { tty, winch, parser: Parser::default(), buf: Box::new([0; READ_SIZE]) })
    }

    /// Waits up to `timeout` for input or a resize.
    fn wait(&self, timeout: Duration) -> Result<Woken, Errno> {
        let ts = Timespec::try_from(timeout).unwrap_or(Timespec { tv_sec: 1, tv_nsec: 0 });
        let mut fds = vec![PollFd::new(&self.tty, PollFlags::IN)];
        if let Some((pipe, _)) = &self.winch {
            fds.push(PollFd::new(pipe, PollFlags::IN));
        }
        poll(&mut fds, Some(&ts))?;
        Ok(Woken { tty: !fds[0].revents().is_empty(), resized: fds.get(1).is_some_and(|f| !f.revents().is_empty()) })
    }

    /// Empties the signal pipe (several signals make one resize).
    fn drain_winch(&self) {
        if let Some((pipe, _)) = &self.winch {
            let mut pipe = pipe;
            let mut sink = [0u8; 64];
            while matches!(io::Read::read(&mut pipe, &mut sink), Ok(n) if n > 0) {}
        }
    }

    /// Reads what the terminal has into the parser; `Err` when the terminal is gone.
    fn read(&mut self, now: Instant) -> Result<(), Errno> {
        match rustix::io::read(&self.tty, &mut self.buf[..]) {
            Ok(0) => Err(Errno::IO),
            Ok(n) => {
                self.parser.feed(&self.buf[..n], n == READ_SIZE, now);
                Ok(())
            }
            Err(Errno::INTR | Errno::AGAIN) => Ok(()),
            Err(e) => Err(e),
        }
    }

    /// One round: wait, read, parse. The messages for the app, and false once the terminal is
    /// gone (the last message is then [`Msg::Hangup`]).
    fn round(&mut self, tick: Duration, busy: bool) -> (Vec<Msg>, bool) {
        let now = Instant::now();
        let timeout = self.parser.deadline().map_or(tick, |d| d.saturating_duration_since(now).min(tick));
        let woken = match self.wait(timeout) {
            Ok(w) => w,
            Err(Errno::INTR) => Woken::default(),
            Err(_) => return (vec![Msg::Hangup], false),
        };
        let now = Instant::now();
        let mut alive = true;
        if woken.tty && self.read(now).is_err() {
            self.parser.finish();
            alive = false;
        }
        self.parser.expire(now);
        let mut msgs: Vec<Msg> = std::iter::from_fn(|| self.parser.next_parsed()).map(message).collect();
        if woken.resized {
            self.drain_winch();
            if let Ok((w, h)) = crossterm::terminal::size() {
                msgs.push(Msg::Input(Event::Resize(w, h)));
            }
        }
        if !alive {
            msgs.push(Msg::Hangup);
        } else if msgs.is_empty() && !woken.tty && !woken.resized && busy {
            msgs.push(Msg::Tick);
        }
        (msgs, alive)
    }
}

/// The app's message for a parsed item.
fn message(p: Parsed) -> Msg {
    match p {
        Parsed::Event(e) => Msg::Input(e),
        Parsed::PasteDropped { bytes } => Msg::PasteDropped { bytes },
    }
}

/// Runs `reader` on its own thread, sending its messages to `tx` and a tick every `tick` while
/// `busy`; sets `gone` (and sends [`Msg::Hangup`]) when the terminal is gone.
pub fn spawn(
    mut reader: Reader,
    tx: Sender<Msg>,
    busy: Arc<AtomicBool>,
    gone: Arc<AtomicBool>,
    tick: Duration,
) -> io::Result<()> {
    let thread = std::thread::Builder::new().name("thud-input".into()).spawn(move || loop {
        let (msgs, alive) = reader.round(tick, busy.load(Ordering::Relaxed));
        if !alive {
            gone.store(true, Ordering::SeqCst);
        }
        for m in msgs {
            if tx.send(m).is_err() {
                return;
            }
        }
        if !alive {
            return;
        }
    });
    thread.map(drop)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crossterm::event::{KeyCode, KeyEvent};
    use std::io::Write;

    /// A reader on one end of a socket pair standing in for the terminal.
    fn reader() -> (Reader, UnixStream) {
        let (ours, theirs) = UnixStream::pair().unwrap();
        let r = Reader { tty: ours.into(), winch: None, parser: Parser::default(), buf: Box::new([0; READ_SIZE]) };
        (r, theirs)
    }

    fn keys(msgs: &[Msg]) -> Vec<KeyCode> {
        msgs.iter()
            .filter_map(|m| match m {
                Msg::Input(Event::Key(KeyEvent { code, .. })) => Some(*code),
                _ => None,
            })
            .collect()
    }

    #[test]
    fn keys_arrive_as_crossterm_events() {
        let (mut r, mut term) = reader();
        term.write_all(b"q\x1b[A").unwrap();
        let (msgs, alive) = r.round(Duration::from_secs(5), false);
        assert!(alive);
        assert_eq!(keys(&msgs), [KeyCode::Char('q'), KeyCode::Up]);
    }

    #[test]
    fn an_unterminated_paste_is_dropped_within_its_timeout_and_q_reads_after() {
        let (mut r, mut term) = reader();
        term.write_all(b"\x1b[200~abc").unwrap();
        let start = Instant::now();
        let mut dropped = None;
        while dropped.is_none() && start.elapsed() < Duration::from_secs(5) {
            let (msgs, _) = r.round(Duration::from_millis(50), false);
            dropped = msgs.iter().find_map(|m| match m {
                Msg::PasteDropped { bytes } => Some(*bytes),
                _ => None,
            });
        }
        assert_eq!(dropped, Some(3));
        assert!(start.elapsed() < super::super::input_parse::PASTE_TIMEOUT + Duration::from_millis(500));
        term.write_all(b"q").unwrap();
        assert_eq!(keys(&r.round(Duration::from_secs(5), false).0), [KeyCode::Char('q')]);
    }

    #[test]
    fn end_of_input_is_a_hang_up() {
        let (mut r, term) = reader();
        drop(term);
        let (msgs, alive) = r.round(Duration::from_secs(5), false);
        assert!(!alive);
        assert!(matches!(msgs.last(), Some(Msg::Hangup)), "{msgs:?}");
    }

    #[test]
    fn idle_and_busy_ticks_idle_and_not_busy_waits() {
        let (mut r, _term) = reader();
        assert!(matches!(r.round(Duration::from_millis(10), true).0.as_slice(), [Msg::Tick]));
        assert!(r.round(Duration::from_millis(10), false).0.is_empty());
    }
}
