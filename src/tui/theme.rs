//! Colours and glyphs. Only the 16 named ANSI colours; with `NO_COLOR` set no colour at all
//! (everything must then read from glyphs and modifiers); `--ascii` draws pure ASCII: borders
//! of `+ - |`, plot glyphs like `* . + #`, and text folded to ASCII ([`fold`]: `θ` → `theta`,
//! `µs` → `us`), with a last pass over the frame ([`fold_buffer`]) so nothing else slips through.

use std::borrow::Cow;

use ratatui::buffer::Buffer;
use ratatui::style::{Color, Modifier, Style};
use ratatui::symbols::border;
use ratatui::symbols::Marker;
use ratatui::text::Line;
use ratatui::widgets::Block;

use crate::design::Zone;

/// How to draw: with or without colour, with or without Braille. (The `theme` setting of
/// `config.toml`, [`crate::config::Theme`], is one of the things that chooses it.)
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Palette {
    pub color: bool,
    pub ascii: bool,
}

impl Default for Palette {
    fn default() -> Self {
        Self { color: true, ascii: false }
    }
}

impl Palette {
    /// Colour unless `NO_COLOR` is set to anything non-empty (<https://no-color.org>).
    pub fn from_env(ascii: bool) -> Self {
        let no_color = std::env::var_os("NO_COLOR").is_some_and(|v| !v.is_empty());
        Self { color: !no_color, ascii }
    }

    /// A foreground colour, or nothing without colour.
    pub fn fg(&self, c: Color) -> Style {
        if self.color {
            Style::default().fg(c)
        } else {
            Style::default()
        }
    }

    /// The style of the pinned design's curves: dim grey, or dim without colour.
    pub fn pinned(&self) -> Style {
        self.fg(Color::DarkGray).add_modifier(Modifier::DIM)
    }

    /// The focused panel's border.
    pub fn focus(&self, focused: bool) -> Style {
        if focused {
            self.fg(Color::Cyan).add_modifier(Modifier::BOLD)
        } else {
            Style::default()
        }
    }

    /// A chart cell of a zone: the zone colour as background (black digit), or plain.
    pub fn zone(&self, zone: Zone) -> Style {
        if !self.color {
            return Style::default();
        }
        let bg = match zone {
            Zone::NoisyWeak => Color::Red,
            Zone::NoisyStrong => Color::Yellow,
            Zone::QuietStrong => Color::Green,
            Zone::QuietWeak => Color::Blue,
        };
        Style::default().bg(bg).fg(Color::Black)
    }

    /// Line marker for plots: Braille, or plain dots with `--ascii`.
    pub fn marker(&self) -> Marker {
        if self.ascii {
            Marker::Dot
        } else {
            Marker::Braille
        }
    }

    /// Marker of the pinned design's curves: Braille like the live one when colour tells them
    /// apart, plain dots otherwise.
    pub fn pinned_marker(&self) -> Marker {
        if self.color && !self.ascii {
            Marker::Braille
        } else {
            Marker::Dot
        }
    }

    /// The marker put before the selected row.
    pub fn pointer(&self) -> &'static str {
        if self.ascii {
            ">"
        } else {
            "▶"
        }
    }

    /// Spinner frames.
    pub fn spinner(&self) -> &'static [&'static str] {
        if self.ascii {
            &["|", "/", "-", "\\"]
        } else {
            &["⠋", "⠙", "⠹", "⠸", "⠼", "⠴", "⠦", "⠧", "⠇", "⠏"]
        }
    }

    /// Error text.
    pub fn error(&self) -> Style {
        self.fg(Color::Red).add_modifier(Modifier::BOLD)
    }

    /// A panel's bordered block: ASCII borders with `--ascii`; the focused panel's border
    /// coloured and bold.
    pub fn block<'a>(&self, title: impl Into<Line<'a>>, focused: bool) -> Block<'a> {
        let b = Block::bordered().title(title).border_style(self.focus(focused));
        if self.ascii {
            b.border_set(ASCII_BORDER)
        } else {
            b
        }
    }

    /// The block of the panel a tour step talks about: a heavy border (`#`/`=` in ASCII) so
    /// it stands out without colour too.
    pub fn highlight_block<'a>(&self, title: impl Into<Line<'a>>) -> Block<'a> {
        let set = if self.ascii { HIGHLIGHT_ASCII } else { border::THICK };
        Block::bordered().title(title).border_set(set).border_style(self.fg(Color::Yellow).add_modifier(Modifier::BOLD))
    }

    /// Text as drawn: unchanged, or folded to ASCII with `--ascii`.
    pub fn text<'a>(&self, s: &'a str) -> Cow<'a, str> {
        if self.ascii {
            Cow::Owned(fold(s))
        } else {
            Cow::Borrowed(s)
        }
    }

    /// The marker of a main curve: Braille, or `*` with `--ascii`.
    pub fn line_marker(&self) -> Marker {
        if self.ascii {
            Marker::Custom('*')
        } else {
            Marker::Braille
        }
    }

    /// The marker of a faint curve under others: Braille, or `.` with `--ascii`.
    pub fn line_marker_faint(&self) -> Marker {
        if self.ascii {
            Marker::Custom('.')
        } else {
            Marker::Braille
        }
    }

    /// A one-character marker: `unicode`, or `ascii` with `--ascii`.
    pub fn mark(&self, unicode: char, ascii: char) -> Marker {
        Marker::Custom(if self.ascii { ascii } else { unicode })
    }

    /// A glyph as text: `unicode`, or `ascii` with `--ascii`.
    pub fn sym(&self, unicode: &'static str, ascii: &'static str) -> &'static str {
        if self.ascii {
            ascii
        } else {
            unicode
        }
    }
}

/// Plain ASCII borders (ratatui has no ASCII border set).
pub const ASCII_BORDER: border::Set = border::Set {
    top_left: "+",
    top_right: "+",
    bottom_left: "+",
    bottom_right: "+",
    vertical_left: "|",
    vertical_right: "|",
    horizontal_top: "-",
    horizontal_bottom: "-",
};

/// The highlighted panel's border in ASCII.
const HIGHLIGHT_ASCII: border::Set = border::Set {
    top_left: "#",
    top_right: "#",
    bottom_left: "#",
    bottom_right: "#",
    vertical_left: "#",
    vertical_right: "#",
    horizontal_top: "=",
    horizontal_bottom: "=",
};

/// The ASCII spelling of a non-ASCII character in text, if it has one.
fn ascii_word(c: char) -> Option<&'static str> {
    Some(match c {
        'θ' => "theta",
        'µ' | 'μ' => "u",
        'τ' => "tau",
        'λ' => "lambda",
        'ρ' => "rho",
        'α' => "alpha",
        'δ' => "delta",
        'Δ' => "delta ",
        'ν' => "nu",
        'π' => "pi",
        'ω' => "omega",
        '·' => "*",
        '—' | '–' | '−' => "-",
        '×' => "x",
        '≥' => ">=",
        '≤' => "<=",
        '≈' | '≃' | '∼' => "~",
        '±' => "+/-",
        '≠' => "!=",
        '∞' => "inf",
        '√' => "sqrt",
        '○' | '◇' => "o",
        '●' | '◆' => "o",
        '…' | '⋯' => "...",
        '→' => "->",
        '←' => "<-",
        '↑' => "^",
        '↓' => "v",
        '°' => "deg",
        '▶' => ">",
        '✗' => "x",
        '²' => "^2",
        '³' => "^3",
        '½' => "1/2",
        '•' => "o",
        '’' | '‘' => "'",
        '“' | '”' => "\"",
        '│' => "|",
        '─' => "-",
        '░' => ":",
        '┌' | '┐' | '└' | '┘' | '┼' | '┬' | '┴' | '├' | '┤' => "+",
        _ => return None,
    })
}

/// `s` in ASCII: known symbols spelled out (`θ` → `theta`, `µs` → `us`), anything else `?`.
pub fn fold(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        if c.is_ascii() {
            out.push(c);
        } else {
            out.push_str(ascii_word(c).unwrap_or("?"));
        }
    }
    out
}

/// The one-cell ASCII stand-in for a non-ASCII cell symbol (the frame's last pass).
fn ascii_cell(sym: &str) -> &'static str {
    let Some(c) = sym.chars().next() else { return " " };
    match c {
        '│' | '┃' | '║' | '┊' | '╎' => "|",
        '─' | '━' | '═' | '┈' | '╌' => "-",
        '┌' | '┐' | '└' | '┘' | '├' | '┤' | '┬' | '┴' | '┼' | '┏' | '┓' | '┗' | '┛' | '╭' | '╮' | '╰' | '╯' => {
            "+"
        }
        '\u{2800}'..='\u{28ff}' => "*",
        '·' => ".",
        '░' => ":",
        '•' | '●' | '◆' => "o",
        '▶' | '→' => ">",
        '←' => "<",
        '↑' => "^",
        '↓' => "v",
        '—' | '–' | '−' => "-",
        '±' | '○' | '◇' => "+",
        '≈' | '≃' | '∼' => "~",
        '…' | '⋯' => ".",
        _ => "?",
    }
}

/// Replaces every non-ASCII cell of `buf` by an ASCII one (the `--ascii` frame's last pass:
/// the widgets already draw ASCII, this keeps a stray symbol off the screen). Returns how many
/// cells it changed.
pub fn fold_buffer(buf: &mut Buffer) -> usize {
    let mut changed = 0;
    for cell in &mut buf.content {
        if !cell.symbol().is_ascii() {
            let s = ascii_cell(cell.symbol());
            cell.set_symbol(s);
            changed += 1;
        }
    }
    changed
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ascii_spells_what_it_can_instead_of_a_question_mark() {
        let folded = fold("±0.02 dB, e ≈ 0.5, N ≠ 1, ∞, ○○ none ●● damper, cut…");
        assert_eq!(folded, "+/-0.02 dB, e ~ 0.5, N != 1, inf, oo none oo damper, cut...");
        assert!(!folded.contains('?'));
    }

    #[test]
    fn fold_spells_units_and_symbols_in_ascii() {
        assert_eq!(fold("θ 45.0° τ@U0max 229 µs N·s/m"), "theta 45.0deg tau@U0max 229 us N*s/m");
        assert_eq!(fold("a — b → c ≥ d"), "a - b -> c >= d");
        assert!(fold("日本").is_ascii());
    }
}
