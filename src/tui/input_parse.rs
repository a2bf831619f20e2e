//! Turns the bytes a terminal sends into crossterm [`Event`]s, the same events crossterm's own
//! reader makes, so the rest of the explorer is unchanged — with two limits crossterm lacks.
//!
//! **Why by hand.** crossterm 0.29's unix parser (`event/sys/unix/parse.rs`) keeps everything
//! after a bracketed-paste start (`ESC[200~`) until the end marker (`ESC[201~`), with no time
//! limit and no size limit, and its `bracketed-paste` feature cannot be turned off (ratatui's
//! crossterm dependency enables the default features). A stray or hostile `ESC[200~` (a pasted
//! fragment, a broken terminal, `printf '\e[200~'` into the pty) froze the explorer's input for
//! good: every key, `q` and Ctrl-C included, was swallowed and the buffer grew without bound.
//! crossterm's parser is private, so it cannot be fed bytes with a limit around it. The crates
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
//! Insert/Delete, F1–F12 (CSI `~`, SS3 and the Linux console's `ESC[[A`…`E`), modifiers in the
//! CSI `1;m` and `n;m~` forms, CSI `u` keys (the plain code points), SGR, normal and rxvt mouse
//! reports, focus in/out, and bracketed paste. Cursor-position, keyboard-flag and
//! device-attribute replies, which crossterm keeps to itself, are read and dropped.
//!
//! **The limits.** A paste ends at its end marker, or [`PASTE_TIMEOUT`] after it started, or
//! when the reader gives up at the end of the input; it never keeps more than [`PASTE_MAX`]
//! bytes (the rest is counted and skipped). A paste that ran out of time is dropped (its text is
//! never replayed as keys: the explorer never asks for bracketed paste, so a paste marker is a
//! stray or a leftover and its text is not commands) and parsing resumes with the next byte.
//! Any other escape sequence longer than [`SEQUENCE_MAX`] bytes is dropped, and a control
//! character (ESC, Ctrl-C, …) that breaks a sequence is read as the start of the next event. So the parser holds
//! at most `PASTE_MAX + SEQUENCE_MAX` bytes whatever it is sent, and every byte is consumed.
//! Times are passed in, so the limits are tested without a clock.

use std::collections::VecDeque;
use std::time::{Duration, Instant};

use crossterm::event::{
    Event, KeyCode, KeyEvent, KeyEventKind, KeyEventState, KeyModifiers, MouseButton, MouseEvent, MouseEventKind,
};

/// How long a bracketed paste may take to reach its end marker before it is dropped.
pub const PASTE_TIMEOUT: Duration = Duration::from_secs(1);
/// The most bytes of one paste kept (1 MiB); the rest is skipped up to the end marker.
pub const PASTE_MAX: usize = 1 << 20;
/// The longest escape sequence (other than a paste) waited for, in bytes.
pub const SEQUENCE_MAX: usize = 64;

const PASTE_START: &[u8] = b"\x1b[200~";
const PASTE_END: &[u8] = b"\x1b[201~";

/// What the parser makes of the input.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Parsed {
    /// A key, a mouse report, a focus change or a complete paste, as crossterm makes it.
    Event(Event),
    /// A bracketed paste that did not end within [`PASTE_TIMEOUT`] (or before the input ended)
    /// was dropped: `bytes` bytes after its start marker.
    PasteDropped { bytes: usize },
}

/// A paste in progress.
#[derive(Debug)]
struct Paste {
    started: Instant,
    /// The text so far, at most [`PASTE_MAX`] bytes.
    text: Vec<u8>,
    /// Every byte after the start marker, kept or not.
    bytes: usize,
    /// The last bytes seen (up to the end marker's length), to find the marker past the cap.
    tail: Vec<u8>,
}

impl Paste {
    fn new(started: Instant) -> Self {
        Self { started, text: Vec::new(), bytes: 0, tail: Vec::with_capacity(PASTE_END.len()) }
    }

    /// Adds one byte; true when it completes the end marker.
    fn push(&mut self, b: u8) -> bool {
        self.bytes += 1;
        if self.text.len() < PASTE_MAX {
            self.text.push(b);
        }
        if self.tail.len() == PASTE_END.len() {
            self.tail.remove(0);
        }
        self.tail.push(b);
        self.tail == PASTE_END
    }

    /// The pasted text without the end marker (lossy UTF-8, as crossterm).
    fn finish(mut self) -> Parsed {
        let keep = (self.bytes - PASTE_END.len()).min(self.text.len());
        self.text.truncate(keep);
        Parsed::Event(Event::Paste(String::from_utf8_lossy(&self.text).into_owned()))
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

    /// Bytes held between reads (bounded by `PASTE_MAX + SEQUENCE_MAX`).
    pub fn held(&self) -> usize {
        self.pending.len() + self.paste.as_ref().map_or(0, |p| p.text.len() + p.tail.len())
    }

    fn drop_paste(&mut self) {
        if let Some(p) = self.paste.take() {
            self.out.push_back(Parsed::PasteDropped { bytes: p.bytes });
        }
    }

    fn push(&mut self, b: u8, more: bool, now: Instant) {
        if let Some(paste) = &mut self.paste {
            if paste.push(b) {
                if let Some(p) = self.paste.take() {
                    self.out.push_back(p.finish());
                }
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
                self.paste = Some(Paste::new(now));
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
        b'I' => Step::Event(Event::FocusGained),
        b'O' => Step::Event(Event::FocusLost),
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
        b'u' => parse_csi_u(params),
        // A cursor-position reply (crossterm reads every `R` so, modified F3 included).
        b'R' => None,
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

/// Caps lock and num lock from the same mask.
fn lock_state(m: u8) -> KeyEventState {
    let bits = m.saturating_sub(1);
    let mut state = KeyEventState::NONE;
    if bits & 64 != 0 {
        state |= KeyEventState::CAPS_LOCK;
    }
    if bits & 128 != 0 {
        state |= KeyEventState::NUM_LOCK;
    }
    state
}

/// `mask[:kind]`: the modifiers, the press/repeat/release kind and the lock state.
fn modifier_field(field: Option<&str>) -> Option<(KeyModifiers, KeyEventKind, KeyEventState)> {
    let mut parts = field?.split(':');
    let mask: u8 = parts.next()?.parse().ok()?;
    let kind = match parts.next().and_then(|k| k.parse::<u8>().ok()) {
        Some(2) => KeyEventKind::Repeat,
        Some(3) => KeyEventKind::Release,
        _ => KeyEventKind::Press,
    };
    Some((modifiers(mask), kind, lock_state(mask)))
}

fn key_event(code: KeyCode, (modifiers, kind, state): (KeyModifiers, KeyEventKind, KeyEventState)) -> Event {
    Event::Key(KeyEvent::new_with_kind_and_state(code, modifiers, kind, state))
}

const PLAIN: (KeyModifiers, KeyEventKind, KeyEventState) =
    (KeyModifiers::NONE, KeyEventKind::Press, KeyEventState::NONE);

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
    let (modifiers, kind, _) = if let Some(m) = modifier_field(params.split(';').nth(1)) {
        m
    } else {
        // crossterm's fallback: the digit before the final byte is the mask.
        let digit = params.bytes().last().map_or(Some(1), |d| char::from(d).to_digit(10).map(|d| d as u8))?;
        (modifiers(digit), KeyEventKind::Press, KeyEventState::NONE)
    };
    Some(Event::Key(KeyEvent::new_with_kind(code, modifiers, kind)))
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
    Some(key_event(code, modifier_field(fields.next()).unwrap_or(PLAIN)))
}

/// `ESC [ code[:shifted] [; m[:kind]] u` (fixterms / kitty): keys by code point. Kitty's
/// private-use codes (keypad, media, lone modifiers) are not used by the explorer and dropped.
fn parse_csi_u(params: &str) -> Option<Event> {
    let mut fields = params.split(';');
    let mut codes = fields.next()?.split(':');
    let c = char::from_u32(codes.next()?.parse().ok()?)?;
    let (mut modifiers, kind, state) = modifier_field(fields.next()).unwrap_or(PLAIN);
    let mut code = match c {
        '\x1b' => KeyCode::Esc,
        '\r' => KeyCode::Enter,
        '\t' if modifiers.contains(KeyModifiers::SHIFT) => KeyCode::BackTab,
        '\t' => KeyCode::Tab,
        '\x7f' => KeyCode::Backspace,
        '\u{e000}'..='\u{f8ff}' => return None,
        c => KeyCode::Char(c),
    };
    if modifiers.contains(KeyModifiers::SHIFT) {
        if let Some(shifted) = codes.next().and_then(|s| s.parse().ok()).and_then(char::from_u32) {
            code = KeyCode::Char(shifted);
            modifiers.remove(KeyModifiers::SHIFT);
        }
    }
    Some(key_event(code, (modifiers, kind, state)))
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
            (b"\x1b[97u", k(KeyCode::Char('a'), N)),
            (b"\x1b[97;5u", k(KeyCode::Char('a'), C)),
            (b"\x1b[97:65;2u", k(KeyCode::Char('A'), N)),
            (b"\x1b[27u", k(KeyCode::Esc, N)),
            (b"\x1b[9;2u", k(KeyCode::BackTab, S)),
            (b"\x1b[I", Event::FocusGained),
            (b"\x1b[O", Event::FocusLost),
            (b"\x1b[200~on and on\x1b[201~", Event::Paste("on and on".into())),
            (b"\x1b[200~o\x1b[2D\x1b[201~", Event::Paste("o\x1b[2D".into())),
        ];
        for (bytes, want) in table {
            assert_eq!(&one(bytes), want, "{bytes:?}");
        }
        let release = one(b"\x1b[97;1:3u");
        assert!(matches!(release, Event::Key(k) if k.kind == KeyEventKind::Release), "{release:?}");
        let caps = one(b"\x1b[97;65u");
        assert!(matches!(caps, Event::Key(k) if k.state == KeyEventState::CAPS_LOCK), "{caps:?}");
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
    fn a_paste_keeps_at_most_its_cap_and_still_finds_its_end() {
        let mut p = Parser::default();
        let now = Instant::now();
        p.feed(PASTE_START, false, now);
        let chunk = vec![b'x'; 64 * 1024];
        for _ in 0..20 {
            p.feed(&chunk, true, now);
            assert!(p.held() <= PASTE_MAX + PASTE_END.len(), "held {}", p.held());
        }
        p.feed(PASTE_END, false, now);
        match p.next_parsed() {
            Some(Parsed::Event(Event::Paste(s))) => assert_eq!(s.len(), PASTE_MAX),
            other => panic!("{other:?}"),
        }
        assert_eq!(p.held(), 0);
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
                prop_assert!(p.held() <= PASTE_MAX + PASTE_END.len() + SEQUENCE_MAX);
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
