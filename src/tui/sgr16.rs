//! The colour depth on the wire: [`Depth16`] wraps ratatui's crossterm backend and, on a
//! terminal that does not advertise 256 colours ([`Depth::Sixteen`], e.g. `TERM=xterm`),
//! writes the classic SGR codes `30–37`/`90–97` (backgrounds `40–47`/`100–107`) itself.
//!
//! Written by hand because crossterm writes even the 16 named colours as `38;5;N`, which a
//! terminal without 256-colour support may show wrong or not at all; ratatui has no switch for
//! it. Everything but the cells' colours (cursor moves, clearing, size) is crossterm's.

use std::io::{self, Write};

use crossterm::cursor::MoveTo;
use crossterm::queue;
use ratatui::backend::{Backend, ClearType, CrosstermBackend, WindowSize};
use ratatui::buffer::Cell;
use ratatui::layout::{Position, Size};
use ratatui::style::{Color, Modifier};

use super::theme::{ansi_index, Depth};

/// A crossterm backend that keeps to 16 colours when [`Depth::Sixteen`].
#[derive(Debug)]
pub struct Depth16<W: Write> {
    inner: CrosstermBackend<W>,
    depth: Depth,
}

impl<W: Write> Depth16<W> {
    pub fn new(writer: W, depth: Depth) -> Self {
        Self { inner: CrosstermBackend::new(writer), depth }
    }
}

/// SGR parameters of a modifier set, in SGR order (1 bold … 9 crossed out).
const MODIFIER_CODES: [(Modifier, u8); 9] = [
    (Modifier::BOLD, 1),
    (Modifier::DIM, 2),
    (Modifier::ITALIC, 3),
    (Modifier::UNDERLINED, 4),
    (Modifier::SLOW_BLINK, 5),
    (Modifier::RAPID_BLINK, 6),
    (Modifier::REVERSED, 7),
    (Modifier::HIDDEN, 8),
    (Modifier::CROSSED_OUT, 9),
];

/// The SGR parameter of colour `c` as a foreground (`base` 30) or background (`base` 40):
/// `base + i` for the eight normal colours, `base + 60 + i` for the bright ones. None (the
/// terminal's default) for `Reset` and for anything beyond the 16, which the explorer never
/// uses.
fn color_code(c: Color, base: u8) -> Option<u8> {
    let i = ansi_index(c)?;
    Some(if i < 8 { base + i } else { base + 60 + i - 8 })
}

/// The whole SGR sequence of a cell's look: reset, then its modifiers and colours.
pub fn sgr(fg: Color, bg: Color, modifier: Modifier) -> String {
    let mut s = String::from("\x1b[0");
    for (m, code) in MODIFIER_CODES {
        if modifier.contains(m) {
            s.push_str(&format!(";{code}"));
        }
    }
    for code in [color_code(fg, 30), color_code(bg, 40)].into_iter().flatten() {
        s.push_str(&format!(";{code}"));
    }
    s.push('m');
    s
}

impl<W: Write> Depth16<W> {
    /// ratatui's drawing loop with the cell looks written by [`sgr`].
    fn draw16<'a, I>(&mut self, content: I) -> io::Result<()>
    where
        I: Iterator<Item = (u16, u16, &'a Cell)>,
    {
        // crossterm's backend is itself the writer (its own accessor is unstable).
        let out = &mut self.inner;
        let mut look: Option<(Color, Color, Modifier)> = None;
        let mut last: Option<Position> = None;
        for (x, y, cell) in content {
            if !matches!(last, Some(p) if x == p.x + 1 && y == p.y) {
                queue!(out, MoveTo(x, y))?;
            }
            last = Some(Position { x, y });
            let now = (cell.fg, cell.bg, cell.modifier);
            if look != Some(now) {
                out.write_all(sgr(now.0, now.1, now.2).as_bytes())?;
                look = Some(now);
            }
            out.write_all(cell.symbol().as_bytes())?;
        }
        out.write_all(b"\x1b[0m")
    }
}

impl<W: Write> Backend for Depth16<W> {
    type Error = io::Error;

    fn draw<'a, I>(&mut self, content: I) -> io::Result<()>
    where
        I: Iterator<Item = (u16, u16, &'a Cell)>,
    {
        match self.depth {
            Depth::Sixteen => self.draw16(content),
            Depth::Indexed256 => self.inner.draw(content),
        }
    }

    fn append_lines(&mut self, n: u16) -> io::Result<()> {
        self.inner.append_lines(n)
    }

    fn hide_cursor(&mut self) -> io::Result<()> {
        self.inner.hide_cursor()
    }

    fn show_cursor(&mut self) -> io::Result<()> {
        self.inner.show_cursor()
    }

    fn get_cursor_position(&mut self) -> io::Result<Position> {
        self.inner.get_cursor_position()
    }

    fn set_cursor_position<P: Into<Position>>(&mut self, position: P) -> io::Result<()> {
        self.inner.set_cursor_position(position)
    }

    fn clear(&mut self) -> io::Result<()> {
        self.inner.clear()
    }

    fn clear_region(&mut self, clear_type: ClearType) -> io::Result<()> {
        self.inner.clear_region(clear_type)
    }

    fn size(&self) -> io::Result<Size> {
        self.inner.size()
    }

    fn window_size(&mut self) -> io::Result<WindowSize> {
        self.inner.window_size()
    }

    fn flush(&mut self) -> io::Result<()> {
        Backend::flush(&mut self.inner)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sixteen_colours_are_the_classic_codes() {
        assert_eq!(sgr(Color::Red, Color::Reset, Modifier::empty()), "\x1b[0;31m");
        assert_eq!(sgr(Color::White, Color::Blue, Modifier::BOLD), "\x1b[0;1;97;44m");
        assert_eq!(sgr(Color::DarkGray, Color::LightYellow, Modifier::DIM | Modifier::REVERSED), "\x1b[0;2;7;90;103m");
        assert_eq!(sgr(Color::Reset, Color::Reset, Modifier::empty()), "\x1b[0m");
    }
}
