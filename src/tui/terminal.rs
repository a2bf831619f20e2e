//! Terminal setup and restore. Every exit path — normal return, `?` error, panic, and SIGTERM,
//! SIGHUP (a dropped SSH connection) or SIGINT — leaves the terminal as it was: raw mode off,
//! alternate screen left, mouse capture off, cursor shown. On a signal the same [`restore`] as
//! the panic hook runs (through [`crate::signals`]), then thud exits with 128 + the signal.
//! SIGILL, SIGFPE and SIGSEGV, which no handler thread can catch, are covered by `thud_fatal`:
//! armed before raw mode is entered and disarmed once the terminal is restored, it writes the
//! same restore sequence (made once, before any fault) and puts the saved terminal settings
//! back from the signal handler itself, and the process then dies by that signal.

use std::io::{self, Stdout, Write};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{mpsc, Once, OnceLock};
use std::time::Duration;

use crossterm::cursor::{Hide, MoveTo, Show};
use crossterm::event::{DisableMouseCapture, EnableMouseCapture};
use crossterm::style::{Attribute, SetAttribute};
use crossterm::terminal::{self, Clear, ClearType, EnterAlternateScreen, LeaveAlternateScreen};
use crossterm::{execute, queue};
use ratatui::Terminal;

use super::clamp::Clamped;
use super::sgr16::Depth16;
use super::theme::Depth;
use crate::signals;

/// The terminal the app draws on, its size held to what the explorer draws ([`Clamped`]).
/// Its colours are written in the depth the terminal advertises ([`Depth16`]).
pub type Term = Terminal<Clamped<Depth16<Stdout>>>;

/// True between [`setup`] entering the alternate screen and the first [`restore`]: only then
/// is there an alternate screen of ours to clear (a restore without it, e.g. a panic after the
/// explorer ended, must not clear the shell's screen).
static ON_ALTERNATE_SCREEN: AtomicBool = AtomicBool::new(false);

/// Writes the escape sequences that undo [`setup`]: stop mouse capture, leave the alternate
/// screen, show the cursor. Separate from raw mode so it can be tested on a buffer.
///
/// With `clear_alternate` the alternate screen is first emptied (attributes reset, cleared,
/// cursor home). A terminal that was resized while the explorer ran may carry the alternate
/// screen's text over to the main screen when it is left: tmux 3.3 copies the rows below and
/// the columns beside the size the main screen had, after 80×24 → 120×40 twelve lines of the
/// explorer stayed on the shell's screen. An empty alternate screen leaves nothing behind.
pub fn write_restore_sequence(out: &mut impl Write, clear_alternate: bool) -> io::Result<()> {
    // CAN (0x18) first: a signal can stop a frame in the middle of an escape sequence, and
    // without it the terminal would take the restore (or the shell's next character) as that
    // sequence's end. In the ground state CAN does nothing.
    out.write_all(b"\x18")?;
    queue!(out, DisableMouseCapture)?;
    if clear_alternate {
        queue!(out, SetAttribute(Attribute::Reset), Clear(ClearType::All), MoveTo(0, 0))?;
    }
    queue!(out, LeaveAlternateScreen, Show)?;
    out.flush()
}

/// The restore sequence (emptying the alternate screen) as bytes, made once: the fault
/// handler (`thud_fatal`) may only write what is ready before the fault.
fn restore_bytes() -> &'static [u8] {
    static BYTES: OnceLock<Vec<u8>> = OnceLock::new();
    BYTES.get_or_init(|| {
        let mut buf = Vec::new();
        let _ = write_restore_sequence(&mut buf, true);
        buf
    })
}

/// Restores the terminal. Safe to call more than once and when setup never happened; errors
/// are ignored (there is nothing better to do on the way out).
pub fn restore() {
    let _ = terminal::disable_raw_mode();
    let on_alternate = ON_ALTERNATE_SCREEN.swap(false, Ordering::SeqCst);
    let _ = write_restore_sequence(&mut io::stdout().lock(), on_alternate);
    thud_fatal::disarm();
}

/// How long the way out of a signal waits for the terminal to take the restore: a terminal
/// that does not read (a stalled SSH session, a frozen emulator) must not keep thud alive.
pub const RESTORE_WAIT: Duration = Duration::from_millis(400);

/// Restores the terminal on the way out of a signal, and keeps standard output locked until
/// the process exits, so the UI thread cannot draw one more frame (hiding the cursor again)
/// over the restored screen. The restore runs on a thread of its own and is waited for at most
/// [`RESTORE_WAIT`]: when the terminal stops reading, the UI thread sits in a write holding
/// standard output, and the restore would wait for it for ever; then thud exits without it
/// (raw mode is switched off first, which needs no output).
fn restore_for_exit() {
    let (done, finished) = mpsc::sync_channel::<()>(1);
    let spawned = std::thread::Builder::new().name("thud-restore".into()).stack_size(256 << 10).spawn(move || {
        let _ = terminal::disable_raw_mode();
        let mut out = io::stdout().lock();
        let on_alternate = ON_ALTERNATE_SCREEN.swap(false, Ordering::SeqCst);
        let _ = write_restore_sequence(&mut out, on_alternate);
        thud_fatal::disarm();
        // Held until `exit`: the signal thread exits right after the clean-ups.
        std::mem::forget(out);
        let _ = done.send(());
    });
    if spawned.is_ok() {
        let _ = finished.recv_timeout(RESTORE_WAIT);
    }
}

/// Installs (once) a panic hook that restores the terminal before the default hook prints.
pub fn install_panic_hook() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            restore();
            previous(info);
        }));
    });
}

/// Restores the terminal when dropped: hold one for the life of the UI. While it lives, SIGTERM,
/// SIGHUP and SIGINT restore the terminal before thud exits.
pub struct Guard {
    _on_signal: signals::Registration,
}

impl Drop for Guard {
    fn drop(&mut self) {
        restore();
    }
}

/// Raw mode, alternate screen, hidden cursor and (if asked) mouse capture. On error the
/// terminal is restored before returning.
pub fn setup(mouse: bool) -> io::Result<(Term, Guard)> {
    use std::io::IsTerminal;
    use std::os::fd::AsRawFd;
    if !io::stdout().is_terminal() {
        // Nothing was changed, so nothing is restored (no stray escape sequences in a pipe).
        return Err(io::Error::other("standard output is not a terminal"));
    }
    install_panic_hook();
    // Registered before the terminal changes, so a signal at any point after is covered. If the
    // handler cannot be installed the explorer still runs (quit, errors and panics restore).
    let (on_signal, _installed) = signals::on_signal(restore_for_exit);
    // Before raw mode, so the settings it saves are the shell's. Without it the explorer still
    // runs (SIGILL, SIGFPE and SIGSEGV then keep the bare default action).
    let _armed = thud_fatal::arm(io::stdout().as_raw_fd(), restore_bytes());
    if let Err(e) = terminal::enable_raw_mode() {
        thud_fatal::disarm();
        return Err(e);
    }
    let guard = Guard { _on_signal: on_signal };
    let mut out = io::stdout();
    ON_ALTERNATE_SCREEN.store(true, Ordering::SeqCst);
    execute!(out, EnterAlternateScreen, Hide)?;
    if mouse {
        execute!(out, EnableMouseCapture)?;
    }
    let term = Terminal::new(Clamped(Depth16::new(out, Depth::from_env())))?;
    Ok((term, guard))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn restore_sequence_leaves_alt_screen_shows_cursor_and_stops_mouse() {
        for clear in [false, true] {
            let mut buf = Vec::new();
            write_restore_sequence(&mut buf, clear).unwrap();
            let s = String::from_utf8(buf).unwrap();
            assert!(s.starts_with('\x18'), "cancels a half-written escape sequence first: {s:?}");
            assert!(s.contains("\x1b[?1049l"), "leave alternate screen: {s:?}");
            assert!(s.contains("\x1b[?25h"), "show cursor: {s:?}");
            assert!(s.contains("\x1b[?1000l"), "mouse capture off: {s:?}");
            assert_eq!(s.contains("\x1b[2J"), clear, "clears only the alternate screen of ours: {s:?}");
        }
    }

    #[test]
    fn the_alternate_screen_is_emptied_before_it_is_left() {
        let mut buf = Vec::new();
        write_restore_sequence(&mut buf, true).unwrap();
        let s = String::from_utf8(buf).unwrap();
        let (reset, clear, home, leave) =
            (s.find("\x1b[0m"), s.find("\x1b[2J"), s.find("\x1b[1;1H"), s.find("\x1b[?1049l"));
        assert!(reset < clear && clear < home && home < leave && reset.is_some(), "{s:?}");
    }
}
