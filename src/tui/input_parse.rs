//! Turns the bytes a terminal sends into crossterm [`Event`]s, the same events crossterm's own
//! reader makes for what the explorer turns on, so the rest of the explorer is unchanged — with
//! two limits crossterm lacks.
//!
//! **Why by hand.** crossterm 0.29's unix parser (`event/sys/unix/parse.rs`) keeps everything
//! after a bracketed-paste start (`ESC[200~`) until the end marker (`ESC[201~`), with no time
//! limit and no size limit, and its `bracketed-paste` feature cannot be turned off (ratatui's
//! crossterm dependency enables the default features). A stray or hostile `ESC[200~` (a pasted
//! fragment, a broken terminal, `printf '\e[200~'` into the pty) froze the explorer's input for
//! good: every key, `q` and Ctrl-C included, was swallowed and the buffer grew without bound.
//! A thin guard around crossterm's own reader cannot fix that: its parser is `pub(crate)`, its
//! reader reads the terminal itself (standard input or `/dev/tty`, not a source we could
//! filter), and it has no call to reset or bound a paste in progress (upstream the
//! report is still open and the fix that bounds it unreleased) — once `ESC[200~` reached it, only an
//! `ESC[201~` from the terminal would free it. The crates
//! that parse terminal input do not fit better: `termwiz`'s `InputParser` brings a large
//! dependency tree, and it and `anes`' parser make their own event types (a conversion layer
//! as large as this parser, and the rest of the explorer speaks crossterm's); `vte` is built
//! for the output direction (no key or mouse decoding, no Esc-versus-sequence rule). The
//! explorer needs a small, known subset, written here after crossterm's tables and tested
//! against crossterm's documented encodings.
//!
//! **What it reads.** Printable UTF-8 (uppercase with SHIFT, as crossterm), Enter, Tab, BackTab,
//! Backspace, Ctrl-letter and Ctrl-space/4–7, Esc (a lone ESC at the end of what the terminal
//! sent, as crossterm decides it), Alt-anything (ESC prefix), arrows, Home/End, PageUp/PageDown,
//! Insert/Delete, F1–F17 (CSI `~` numbered as crossterm numbers them, SS3 and the Linux
//! console's `ESC[[A`…`E`), modifiers in the CSI `1;m` and `n;m~` forms, and SGR, normal and
//! rxvt mouse reports. What only comes after a request the explorer never makes — kitty's
//! CSI `u` keys (key release, lock states), focus in/out, a paste's text — is not decoded: such
//! a sequence is dropped like any unknown one.
//! Cursor-position, keyboard-flag and device-attribute replies, which crossterm keeps to
//! itself, are read and dropped.
//!
//! **The limits.** The explorer never asks for bracketed paste, so a paste marker is a stray or
//! a leftover and its text is not commands: everything from `ESC[200~` to `ESC[201~` is skipped
//! (only counted; no text is kept). A paste with no end marker [`PASTE_TIMEOUT`] after it
//! started, or when the reader gives up at the end of the input, is reported dropped
//! ([`Parsed::PasteDropped`]) and parsing resumes with the next byte. Any other escape sequence
//! longer than [`SEQUENCE_MAX`] bytes is dropped, and a control character (ESC, Ctrl-C, …) that
//! breaks a sequence is read as the start of the next event. So the parser holds at most
//! `SEQUENCE_MAX` bytes whatever it is sent, and every byte is consumed. Times are passed in,
//! so the limits are tested without a clock.

use std::collections::VecDeque;
use std::time::{Duration, Instant};

use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers, MouseButton, MouseEvent, MouseEventKind};

/// How long a bracketed paste may take to reach its end marker before it is reported dropped.
pub const PASTE_TIMEOUT: Duration = Duration::from_secs(1);
/// The longest escape sequence (other than a paste) waited for, in bytes.
pub const SEQUENCE_MAX: usize = 64;

const PASTE_START: &[u8] = b"\x1b[200~";
const PASTE_END: &[u8] = b"\x1b[201~";

/// What the parser makes of the input.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Parsed {
    /// A key or a mouse report, as crossterm makes it.
    Event(Event),
    /// A bracketed paste that did not end within [`PASTE_TIMEOUT`] (or before the input ended)
    /// was dropped: `bytes` bytes after its start marker.
    PasteDropped { bytes: usize },
}

/// A paste being skipped.
#[derive(Debug)]
struct Paste {
    started: Instant,
    /// Every byte after the start marker.
    bytes: usize,
    /// How many bytes of the end marker were just seen.
    matched: usize,
}

impl Paste {
    /// Skips one byte; true when it completes the end marker.
    fn push(&mut self, b: u8) -> bool {
        self.bytes += 1;
        // The marker's first byte (ESC) occurs only there, so a mismatch restarts at 0 or 1.
        self.matched = if PASTE_END[self.matched] == b { self.matched + 1 } else { usize::from(b == PASTE_END[0]) };
        self.matched == PASTE_END.len()
    }
}

/// The state between reads: an unfinished escape sequence or UTF-8 character, or a paste.
#[derive(Debug, Default)]
pub struct Parser {
    pending: Vec<u8>,
    paste: Option<Paste>,
    out: VecDeque<Parsed>,
}

/// What the bytes pending so far are.
#[derive(Debug, PartialEq)]
enum Step {
    /// Not complete yet.
    Wait,
    /// One event; the bytes are used.
    Event(Event),
    /// A sequence read and dropped (a reply crossterm keeps to itself), or nothing valid.
    Drop,
    /// The bracketed-paste start marker.
    PasteStart,
}

impl Parser {
    /// Feeds one read's `bytes`, received at `now`. `more` says the read filled its buffer, so
    /// more bytes are already waiting: a lone ESC at the end is then not yet the Esc key.
    pub fn feed(&mut self, bytes: &[u8], more: bool, now: Instant) {
        for (i, &b) in bytes.iter().enumerate() {
            self.push(b, more || i + 1 < bytes.len(), now);
        }
    }

    /// Ends a paste that ran out of time at `now`.
    pub fn expire(&mut self, now: Instant) {
        if self.paste.as_ref().is_some_and(|p| now.saturating_duration_since(p.started) >= PASTE_TIMEOUT) {
            self.drop_paste();
        }
    }

    /// The input ended: a paste in progress is dropped, an unfinished sequence forgotten.
    pub fn finish(&mut self) {
        self.drop_paste();
        self.pending.clear();
    }

    /// When [`Parser::expire`] next has something to do, if ever.
    pub fn deadline(&self) -> Option<Instant> {
        self.paste.as_ref().map(|p| p.started + PASTE_TIMEOUT)
    }

    /// The next parsed item, oldest first.
    pub fn next_parsed(&mut self) -> Option<Parsed> {
        self.out.pop_front()
    }

    /// Bytes held between reads (bounded by `SEQUENCE_MAX`; a paste's are not kept).
    pub fn held(&self) -> usize {
        self.pending.len()
    }

    fn drop_paste(&mut self) {
        if let Some(p) = self.paste.take() {
            self.out.push_back(Parsed::PasteDropped { bytes: p.bytes });
        }
    }

    fn push(&mut self, b: u8, more: bool, now: Instant) {
        if let Some(paste) = &mut self.paste {
            if paste.push(b) {
                self.paste = None;
            }
            return;
        }
        self.pending.push(b);
        match parse(&self.pending, more) {
            Step::Wait if self.pending.len() < SEQUENCE_MAX => {}
            Step::Wait | Step::Drop => {
                let broke = self.pending.len() > 1;
                self.pending.clear();
                // A control character (ESC, Ctrl-C, …) cannot be part of a sequence: one that
                // broke a sequence starts the next event (crossterm drops it with the sequence).
                if broke && b < 0x20 {
                    self.push(b, more, now);
                }
            }
            Step::Event(e) => {
                self.pending.clear();
                self.out.push_back(Parsed::Event(e));
            }
            Step::PasteStart => {
                self.pending.clear();
                self.paste = Some(Paste { started: now, bytes: 0, matched: 0 });
            }
        }
    }
}

fn key(code: KeyCode) -> Step {
    Step::Event(Event::Key(KeyEvent::new(code, KeyModifiers::NONE)))
}

fn key_with(code: KeyCode, modifiers: KeyModifiers) -> Step {
    Step::Event(Event::Key(KeyEvent::new(code, modifiers)))
}

/// What `buf` (one event's bytes so far) is; `more`: more bytes are waiting.
fn parse(buf: &[u8], more: bool) -> Step {
    let Some(&first) = buf.first() else { return Step::Wait };
    match first {
        0x1b => parse_escape(buf, more),
        b'\r' => key(KeyCode::Enter),
        b'\t' => key(KeyCode::Tab),
        0x7f => key(KeyCode::Backspace),
        // In raw mode \n is Ctrl-J, as every other control character is Ctrl-letter.
        c @ 0x01..=0x1a => key_with(KeyCode::Char(char::from(c - 0x01 + b'a')), KeyModifiers::CONTROL),
        c @ 0x1c..=0x1f => key_with(KeyCode::Char(char::from(c - 0x1c + b'4')), KeyModifiers::CONTROL),
        0 => key_with(KeyCode::Char(' '), KeyModifiers::CONTROL),
        _ => parse_utf8(buf),
    }
}

/// One UTF-8 character; uppercase letters carry SHIFT.
fn parse_utf8(buf: &[u8]) -> Step {
    match std::str::from_utf8(buf) {
        Ok(s) => match s.chars().next() {
            Some(c) if c.is_uppercase() => key_with(KeyCode::Char(c), KeyModifiers::SHIFT),
            Some(c) => key(KeyCode::Char(c)),
            None => Step::Wait,
        },
        Err(e) if e.error_len().is_none() => Step::Wait,
        Err(_) => Step::Drop,
    }
}

/// `ESC`, `ESC ESC`, SS3 (`ESC O x`), CSI (`ESC [ …`) or Alt + the key after the ESC.
fn parse_escape(buf: &[u8], more: bool) -> Step {
    match buf.get(1) {
        None if more => Step::Wait,
        None | Some(0x1b) => key(KeyCode::Esc),
        Some(b'O') => match buf.get(2) {
            None => Step::Wait,
            Some(b'D') => key(KeyCode::Left),
            Some(b'C') => key(KeyCode::Right),
            Some(b'A') => key(KeyCode::Up),
            Some(b'B') => key(KeyCode::Down),
            Some(b'H') => key(KeyCode::Home),
            Some(b'F') => key(KeyCode::End),
            Some(&c @ b'P'..=b'S') => key(KeyCode::F(1 + c - b'P')),
            Some(_) => Step::Drop,
        },
        Some(b'[') => parse_csi(buf),
        Some(_) => match parse(&buf[1..], more) {
            Step::Event(Event::Key(mut k)) => {
                k.modifiers |= KeyModifiers::ALT;
                Step::Event(Event::Key(k))
            }
            other => other,
        },
    }
}

/// A CSI sequence, `ESC [` then parameters and a final byte.
fn parse_csi(buf: &[u8]) -> Step {
    let Some(&third) = buf.get(2) else { return Step::Wait };
    match third {
        b'[' => match buf.get(3) {
            None => Step::Wait,
            Some(&c @ b'A'..=b'E') => key(KeyCode::F(1 + c - b'A')),
            Some(_) => Step::Drop,
        },
        b'D' => key(KeyCode::Left),
        b'C' => key(KeyCode::Right),
        b'A' => key(KeyCode::Up),
        b'B' => key(KeyCode::Down),
        b'H' => key(KeyCode::Home),
        b'F' => key(KeyCode::End),
        b'Z' => key_with(KeyCode::BackTab, KeyModifiers::SHIFT),
        b'M' => parse_normal_mouse(buf),
        b'<' => parse_sgr_mouse(buf),
        b'P' => key(KeyCode::F(1)),
        b'Q' => key(KeyCode::F(2)),
        b'S' => key(KeyCode::F(4)),
        b';' | b'?' | b'0'..=b'9' => parse_numbered(buf),
        _ => Step::Drop,
    }
}

/// `ESC [` parameters (digits, `;`, `:`, `?`) and a final byte (0x40–0x7E).
fn parse_numbered(buf: &[u8]) -> Step {
    let body = &buf[2..];
    let Some((&last, params)) = body.split_last() else { return Step::Wait };
    if !(0x40..=0x7e).contains(&last) {
        // Parameter and intermediate bytes (0x20–0x3F) wait for the final byte; anything else
        // (an ESC, a control character) breaks the sequence.
        return if (0x20..=0x3f).contains(&last) { Step::Wait } else { Step::Drop };
    }
    if buf == PASTE_START {
        return Step::PasteStart;
    }
    let Ok(params) = std::str::from_utf8(params) else { return Step::Drop };
    if params.starts_with('?') {
        // Keyboard-flag and device-attribute replies: crossterm keeps them to itself.
        return Step::Drop;
    }
    let parsed = match last {
        b'M' => parse_rxvt_mouse(params),
        b'~' => parse_special_key(params),
        // A cursor-position reply (crossterm reads every `R` so, modified F3 included); CSI `u`
        // keys come only after kitty's keyboard request, which the explorer never sends.
        b'R' | b'u' => None,
        _ => parse_modified_key(params, last),
    };
    parsed.map_or(Step::Drop, Step::Event)
}

/// `m` (1 + a bit mask) as crossterm reads it: shift, alt, control, super, hyper, meta.
fn modifiers(m: u8) -> KeyModifiers {
    let bits = m.saturating_sub(1);
    let table = [
        KeyModifiers::SHIFT,
        KeyModifiers::ALT,
        KeyModifiers::CONTROL,
        KeyModifiers::SUPER,
        KeyModifiers::HYPER,
        KeyModifiers::META,
    ];
    table.iter().enumerate().filter(|(i, _)| bits & (1 << i) != 0).fold(KeyModifiers::NONE, |acc, (_, &m)| acc | m)
}

/// The modifier mask field `m` (a `:kind` after it comes only with kitty's protocol).
fn modifier_field(field: Option<&str>) -> Option<KeyModifiers> {
    field?.split(':').next()?.parse().ok().map(modifiers)
}

/// `ESC [ 1 ; m X` (and crossterm's single-digit `ESC [ m X`): an arrow, Home/End or F1–F4.
fn parse_modified_key(params: &str, last: u8) -> Option<Event> {
    let code = match last {
        b'A' => KeyCode::Up,
        b'B' => KeyCode::Down,
        b'C' => KeyCode::Right,
        b'D' => KeyCode::Left,
        b'F' => KeyCode::End,
        b'H' => KeyCode::Home,
        b'P' => KeyCode::F(1),
        b'Q' => KeyCode::F(2),
        b'R' => KeyCode::F(3),
        b'S' => KeyCode::F(4),
        _ => return None,
    };
    let modifiers = if let Some(m) = modifier_field(params.split(';').nth(1)) {
        m
    } else {
        // crossterm's fallback: the digit before the final byte is the mask.
        let digit = params.bytes().last().map_or(Some(1), |d| char::from(d).to_digit(10).map(|d| d as u8))?;
        modifiers(digit)
    };
    Some(Event::Key(KeyEvent::new(code, modifiers)))
}

/// `ESC [ n [; m] ~`: Home, Insert, Delete, End, PageUp, PageDown, F1–F20.
fn parse_special_key(params: &str) -> Option<Event> {
    let mut fields = params.split(';');
    let n: u8 = fields.next()?.parse().ok()?;
    let code = match n {
        1 | 7 => KeyCode::Home,
        2 => KeyCode::Insert,
        3 => KeyCode::Delete,
        4 | 8 => KeyCode::End,
        5 => KeyCode::PageUp,
        6 => KeyCode::PageDown,
        11..=15 => KeyCode::F(n - 10),
        17..=21 => KeyCode::F(n - 11),
        23..=26 => KeyCode::F(n - 12),
        28..=29 => KeyCode::F(n - 15),
        31..=34 => KeyCode::F(n - 17),
        _ => return None,
    };
    Some(Event::Key(KeyEvent::new(code, modifier_field(fields.next()).unwrap_or(KeyModifiers::NONE))))
}

/// The button byte of a mouse report (xterm's layout): button, shift, alt, control, drag.
fn mouse_button(cb: u8) -> Option<(MouseEventKind, KeyModifiers)> {
    let button = (cb & 0b11) | ((cb & 0b1100_0000) >> 4);
    let dragging = cb & 0b10_0000 != 0;
    let kind = match (button, dragging) {
        (0, false) => MouseEventKind::Down(MouseButton::Left),
        (1, false) => MouseEventKind::Down(MouseButton::Middle),
        (2, false) => MouseEventKind::Down(MouseButton::Right),
        (0, true) => MouseEventKind::Drag(MouseButton::Left),
        (1, true) => MouseEventKind::Drag(MouseButton::Middle),
        (2, true) => MouseEventKind::Drag(MouseButton::Right),
        (3, false) => MouseEventKind::Up(MouseButton::Left),
        (3..=5, true) => MouseEventKind::Moved,
        (4, false) => MouseEventKind::ScrollUp,
        (5, false) => MouseEventKind::ScrollDown,
        (6, false) => MouseEventKind::ScrollLeft,
        (7, false) => MouseEventKind::ScrollRight,
        _ => return None,
    };
    let mut modifiers = KeyModifiers::NONE;
    for (bit, m) in [(0b100, KeyModifiers::SHIFT), (0b1000, KeyModifiers::ALT), (0b1_0000, KeyModifiers::CONTROL)] {
        if cb & bit != 0 {
            modifiers |= m;
        }
    }
    Some((kind, modifiers))
}

/// A mouse event at 1-based terminal coordinates (0 is not a cell: dropped).
fn mouse(cb: u8, x: u16, y: u16) -> Option<Event> {
    let (kind, modifiers) = mouse_button(cb)?;
    Some(Event::Mouse(MouseEvent { kind, column: x.checked_sub(1)?, row: y.checked_sub(1)?, modifiers }))
}

/// `b;x;y` as numbers (crossterm ignores anything after the third).
fn three_numbers(params: &str) -> Option<(u8, u16, u16)> {
    let mut it = params.split(';');
    Some((it.next()?.parse().ok()?, it.next()?.parse().ok()?, it.next()?.parse().ok()?))
}

/// SGR mouse: `ESC [ < b ; x ; y M` (press, drag, scroll) or `… m` (release).
fn parse_sgr_mouse(buf: &[u8]) -> Step {
    let body = &buf[3..];
    let Some((&last, params)) = body.split_last() else { return Step::Wait };
    match last {
        b'M' | b'm' => {}
        b'0'..=b'9' | b';' => return Step::Wait,
        _ => return Step::Drop,
    }
    let Some(Event::Mouse(mut m)) =
        std::str::from_utf8(params).ok().and_then(three_numbers).and_then(|(b, x, y)| mouse(b, x, y))
    else {
        return Step::Drop;
    };
    if last == b'm' {
        if let MouseEventKind::Down(button) = m.kind {
            m.kind = MouseEventKind::Up(button);
        }
    }
    Step::Event(Event::Mouse(m))
}

/// Normal (X10) mouse: `ESC [ M` and three bytes, each the value + 32.
fn parse_normal_mouse(buf: &[u8]) -> Step {
    let [_, _, _, cb, x, y] = buf else { return Step::Wait };
    let event =
        cb.checked_sub(32).and_then(|cb| mouse(cb, u16::from(x.saturating_sub(32)), u16::from(y.saturating_sub(32))));
    event.map_or(Step::Drop, Step::Event)
}

/// rxvt mouse: `ESC [ b ; x ; y M`, the button + 32.
fn parse_rxvt_mouse(params: &str) -> Option<Event> {
    let (b, x, y) = three_numbers(params)?;
    mouse(b.checked_sub(32)?, x, y)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn events(bytes: &[u8]) -> Vec<Parsed> {
        let mut p = Parser::default();
        p.feed(bytes, false, Instant::now());
        std::iter::from_fn(|| p.next_parsed()).collect()
    }

    fn one(bytes: &[u8]) -> Event {
        match events(bytes).as_slice() {
            [Parsed::Event(e)] => e.clone(),
            other => panic!("{bytes:?} gave {other:?}, not one event"),
        }
    }

    fn k(code: KeyCode, m: KeyModifiers) -> Event {
        Event::Key(KeyEvent::new(code, m))
    }

    const N: KeyModifiers = KeyModifiers::NONE;
    const S: KeyModifiers = KeyModifiers::SHIFT;
    const A: KeyModifiers = KeyModifiers::ALT;
    const C: KeyModifiers = KeyModifiers::CONTROL;

    /// The encodings crossterm's parser documents (its `parse.rs` tests and xterm's ctlseqs),
    /// and the event crossterm makes of each.
    #[test]
    fn keys_read_as_crossterm_reads_them() {
        let table: &[(&[u8], Event)] = &[
            (b"q", k(KeyCode::Char('q'), N)),
            (b"Q", k(KeyCode::Char('Q'), S)),
            ("Ž".as_bytes(), k(KeyCode::Char('Ž'), S)),
            ("é".as_bytes(), k(KeyCode::Char('é'), N)),
            ("€".as_bytes(), k(KeyCode::Char('€'), N)),
            (b"\r", k(KeyCode::Enter, N)),
            (b"\t", k(KeyCode::Tab, N)),
            (b"\x7f", k(KeyCode::Backspace, N)),
            (b"\x03", k(KeyCode::Char('c'), C)),
            (b"\x15", k(KeyCode::Char('u'), C)),
            (b"\n", k(KeyCode::Char('j'), C)),
            (b"\x1c", k(KeyCode::Char('4'), C)),
            (b"\0", k(KeyCode::Char(' '), C)),
            (b"\x1b", k(KeyCode::Esc, N)),
            (b"\x1b\x1b", k(KeyCode::Esc, N)),
            (b"\x1bc", k(KeyCode::Char('c'), A)),
            (b"\x1bH", k(KeyCode::Char('H'), A | S)),
            (b"\x1b\x03", k(KeyCode::Char('c'), A | C)),
            (b"\x1b[A", k(KeyCode::Up, N)),
            (b"\x1b[B", k(KeyCode::Down, N)),
            (b"\x1b[C", k(KeyCode::Right, N)),
            (b"\x1b[D", k(KeyCode::Left, N)),
            (b"\x1b[H", k(KeyCode::Home, N)),
            (b"\x1b[F", k(KeyCode::End, N)),
            (b"\x1bOA", k(KeyCode::Up, N)),
            (b"\x1bOD", k(KeyCode::Left, N)),
            (b"\x1bOH", k(KeyCode::Home, N)),
            (b"\x1bOF", k(KeyCode::End, N)),
            (b"\x1bOP", k(KeyCode::F(1), N)),
            (b"\x1bOS", k(KeyCode::F(4), N)),
            (b"\x1b[[A", k(KeyCode::F(1), N)),
            (b"\x1b[[E", k(KeyCode::F(5), N)),
            (b"\x1b[Z", k(KeyCode::BackTab, S)),
            (b"\x1b[1~", k(KeyCode::Home, N)),
            (b"\x1b[2~", k(KeyCode::Insert, N)),
            (b"\x1b[3~", k(KeyCode::Delete, N)),
            (b"\x1b[4~", k(KeyCode::End, N)),
            (b"\x1b[5~", k(KeyCode::PageUp, N)),
            (b"\x1b[6~", k(KeyCode::PageDown, N)),
            (b"\x1b[15~", k(KeyCode::F(5), N)),
            (b"\x1b[17~", k(KeyCode::F(6), N)),
            (b"\x1b[21~", k(KeyCode::F(10), N)),
            (b"\x1b[23~", k(KeyCode::F(11), N)),
            (b"\x1b[24~", k(KeyCode::F(12), N)),
            (b"\x1b[3;2~", k(KeyCode::Delete, S)),
            (b"\x1b[5;5~", k(KeyCode::PageUp, C)),
            (b"\x1b[1;2D", k(KeyCode::Left, S)),
            (b"\x1b[1;3C", k(KeyCode::Right, A)),
            (b"\x1b[1;5A", k(KeyCode::Up, C)),
            (b"\x1b[1;6B", k(KeyCode::Down, C | S)),
            (b"\x1b[1;2P", k(KeyCode::F(1), S)),
            (b"\x1b[1;9A", k(KeyCode::Up, KeyModifiers::SUPER)),
            (b"\x1b[34~", k(KeyCode::F(17), N)),
        ];
        for (bytes, want) in table {
            assert_eq!(&one(bytes), want, "{bytes:?}");
        }
    }

    /// What comes only after a request the explorer never makes is dropped, and the key after
    /// it reads: kitty's CSI `u` keys, focus reports, and a paste with its text (never keys).
    #[test]
    fn what_the_explorer_never_asks_for_is_dropped() {
        for bytes in [
            &b"\x1b[97u"[..],
            b"\x1b[97;1:3u",
            b"\x1b[I",
            b"\x1b[O",
            b"\x1b[200~on and on\x1b[201~",
            b"\x1b[200~o\x1b[2D\x1b\x1b[201~",
        ] {
            let mut input = bytes.to_vec();
            input.push(b'q');
            assert_eq!(events(&input), [Parsed::Event(k(KeyCode::Char('q'), N))], "{bytes:?}");
        }
    }

    fn m(kind: MouseEventKind, column: u16, row: u16, modifiers: KeyModifiers) -> Event {
        Event::Mouse(MouseEvent { kind, column, row, modifiers })
    }

    #[test]
    fn mouse_reports_read_as_crossterm_reads_them() {
        use MouseButton::{Left, Middle, Right};
        let table: &[(&[u8], Event)] = &[
            (b"\x1b[<0;20;10M", m(MouseEventKind::Down(Left), 19, 9, N)),
            (b"\x1b[<0;20;10m", m(MouseEventKind::Up(Left), 19, 9, N)),
            (b"\x1b[<1;1;1M", m(MouseEventKind::Down(Middle), 0, 0, N)),
            (b"\x1b[<2;300;200M", m(MouseEventKind::Down(Right), 299, 199, N)),
            (b"\x1b[<32;5;6M", m(MouseEventKind::Drag(Left), 4, 5, N)),
            (b"\x1b[<35;5;6M", m(MouseEventKind::Moved, 4, 5, N)),
            (b"\x1b[<64;5;6M", m(MouseEventKind::ScrollUp, 4, 5, N)),
            (b"\x1b[<65;5;6M", m(MouseEventKind::ScrollDown, 4, 5, N)),
            (b"\x1b[<66;5;6M", m(MouseEventKind::ScrollLeft, 4, 5, N)),
            (b"\x1b[<20;5;6M", m(MouseEventKind::Down(Left), 4, 5, S | C)),
            (b"\x1b[<8;5;6;M", m(MouseEventKind::Down(Left), 4, 5, A)),
            (b"\x1b[M !!", m(MouseEventKind::Down(Left), 0, 0, N)),
            (b"\x1b[M#44", m(MouseEventKind::Up(Left), 19, 19, N)),
            (b"\x1b[32;30;40;M", m(MouseEventKind::Down(Left), 29, 39, N)),
            (b"\x1b[35;30;40M", m(MouseEventKind::Up(Left), 29, 39, N)),
        ];
        for (bytes, want) in table {
            assert_eq!(&one(bytes), want, "{bytes:?}");
        }
    }

    #[test]
    fn replies_and_broken_sequences_are_dropped_and_the_next_key_reads() {
        for bytes in [
            &b"\x1b[12;34R"[..],
            b"\x1b[?1u",
            b"\x1b[?64;1;2c",
            b"\x1b[99~",
            b"\x1b[<0;0;5M",
            b"\x1b[<128;5;6M",
            b"\x1b[M  !",
            b"\x1bOx",
            b"\x1b[x",
            b"\xff",
        ] {
            let mut input = bytes.to_vec();
            input.push(b'q');
            assert_eq!(events(&input), [Parsed::Event(k(KeyCode::Char('q'), N))], "{bytes:?}");
        }
        // A control character that breaks a sequence is the next key: an ESC starts the next
        // sequence, Ctrl-C after a broken sequence or a broken character still quits.
        assert_eq!(events(b"\x1b[1\x1b[A"), [Parsed::Event(k(KeyCode::Up, N))]);
        assert_eq!(events(b"\x1b[<0;1\x03"), [Parsed::Event(k(KeyCode::Char('c'), C))]);
        assert_eq!(events(b"\xe2\x82\x03"), [Parsed::Event(k(KeyCode::Char('c'), C))]);
        assert_eq!(events(b"\x1b[1\x1b"), [Parsed::Event(k(KeyCode::Esc, N))]);
    }

    #[test]
    fn a_lone_esc_waits_only_while_more_bytes_are_in_the_read() {
        let mut p = Parser::default();
        let now = Instant::now();
        p.feed(b"\x1b", true, now);
        assert_eq!(p.next_parsed(), None, "more bytes are waiting: maybe a sequence");
        p.feed(b"[A", false, now);
        assert_eq!(p.next_parsed(), Some(Parsed::Event(k(KeyCode::Up, N))));
        p.feed(b"\x1b", false, now);
        assert_eq!(p.next_parsed(), Some(Parsed::Event(k(KeyCode::Esc, N))));
    }

    #[test]
    fn a_sequence_split_across_reads_is_one_event() {
        let mut p = Parser::default();
        let now = Instant::now();
        for part in [&b"\x1b["[..], b"<0;1", b"2;3", b"M"] {
            p.feed(part, true, now);
        }
        assert_eq!(p.next_parsed(), Some(Parsed::Event(m(MouseEventKind::Down(MouseButton::Left), 11, 2, N))));
        p.feed(&"€".as_bytes()[..1], false, now);
        p.feed(&"€".as_bytes()[1..], false, now);
        assert_eq!(p.next_parsed(), Some(Parsed::Event(k(KeyCode::Char('€'), N))));
    }

    #[test]
    fn an_unterminated_paste_is_dropped_after_the_timeout_and_keys_read_again() {
        let mut p = Parser::default();
        let t0 = Instant::now();
        p.feed(b"\x1b[200~abc", false, t0);
        p.feed(b"q", false, t0 + Duration::from_millis(500));
        assert_eq!(p.next_parsed(), None, "inside the paste");
        assert_eq!(p.deadline(), Some(t0 + PASTE_TIMEOUT));
        p.expire(t0 + Duration::from_millis(999));
        assert_eq!(p.next_parsed(), None, "not yet timed out");
        p.expire(t0 + PASTE_TIMEOUT);
        assert_eq!(p.next_parsed(), Some(Parsed::PasteDropped { bytes: 4 }));
        assert_eq!((p.deadline(), p.held()), (None, 0));
        p.feed(b"q", false, t0 + PASTE_TIMEOUT);
        assert_eq!(p.next_parsed(), Some(Parsed::Event(k(KeyCode::Char('q'), N))));
    }

    #[test]
    fn a_long_paste_holds_nothing_and_still_finds_its_end() {
        let mut p = Parser::default();
        let now = Instant::now();
        p.feed(PASTE_START, false, now);
        let chunk = vec![b'x'; 64 * 1024];
        for _ in 0..20 {
            p.feed(&chunk, true, now);
            assert_eq!(p.held(), 0);
        }
        p.feed(b"\x1b[201", true, now);
        assert_eq!(p.deadline(), Some(now + PASTE_TIMEOUT), "not ended by a part of the marker");
        p.feed(b"~q", false, now);
        assert_eq!(p.deadline(), None);
        assert_eq!(p.next_parsed(), Some(Parsed::Event(k(KeyCode::Char('q'), N))));
    }

    #[test]
    fn a_paste_still_open_when_the_input_ends_is_dropped() {
        let mut p = Parser::default();
        p.feed(b"\x1b[200~ab", false, Instant::now());
        p.finish();
        assert_eq!(p.next_parsed(), Some(Parsed::PasteDropped { bytes: 2 }));
    }

    #[test]
    fn an_endless_sequence_is_cut_at_its_cap() {
        let mut p = Parser::default();
        let mut endless = b"\x1b[1".to_vec();
        endless.extend(std::iter::repeat_n(b';', 10 * SEQUENCE_MAX));
        let mut most = 0;
        for &b in &endless {
            p.feed(&[b], true, Instant::now());
            most = most.max(p.held());
        }
        assert_eq!(most, SEQUENCE_MAX - 1, "held at most the cap");
        while p.next_parsed().is_some() {}
        p.feed(b"q", false, Instant::now());
        assert_eq!(p.next_parsed(), Some(Parsed::Event(k(KeyCode::Char('q'), N))));
    }

    proptest! {
        /// Any bytes, in any split, at any times: no panic, bounded memory, and once the input
        /// stops and the paste time passes, nothing is held and a typed key reads.
        #[test]
        fn any_input_is_consumed_with_bounded_memory(
            chunks in proptest::collection::vec(proptest::collection::vec(any::<u8>(), 0..200), 0..20),
            gaps_ms in proptest::collection::vec(0u64..700, 20),
            marker in any::<bool>(),
        ) {
            let mut p = Parser::default();
            let mut now = Instant::now();
            if marker {
                p.feed(PASTE_START, true, now);
            }
            for (chunk, gap) in chunks.iter().zip(&gaps_ms) {
                now += Duration::from_millis(*gap);
                p.expire(now);
                p.feed(chunk, false, now);
                prop_assert!(p.held() < SEQUENCE_MAX);
                while p.next_parsed().is_some() {}
            }
            now += PASTE_TIMEOUT;
            p.expire(now);
            // An unfinished sequence or character waits for its end: a control character
            // cannot continue one (three: a normal mouse report takes any three bytes).
            p.feed(b"\x18\x18\x18", false, now);
            while p.next_parsed().is_some() {}
            prop_assert_eq!(p.held(), 0);
            p.feed(b"q", false, now);
            prop_assert_eq!(p.next_parsed(), Some(Parsed::Event(k(KeyCode::Char('q'), N))));
        }
    }
}
