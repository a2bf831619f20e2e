//! Colours and glyphs. Only the 16 named ANSI colours; with `NO_COLOR` set no colour at all
//! (everything must then read from glyphs and modifiers); `--ascii` avoids Braille.

use ratatui::style::{Color, Modifier, Style};
use ratatui::symbols::Marker;

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
}
