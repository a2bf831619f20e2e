//! Colours and glyphs. Only the 16 named ANSI colours; with `NO_COLOR` set no colour at all
//! (everything must then read from glyphs and modifiers); `--ascii` draws pure ASCII: borders
//! of `+ - |`, plot glyphs like `* . + #`, and text folded to ASCII ([`fold`]: `θ` → `theta`,
//! `µs` → `us`), with a last pass over the frame ([`fold_buffer`]) so nothing else slips through.
//!
//! Every style comes from one table of roles ([`Role`], [`Palette::style`]), one column for a
//! dark terminal and one for a light one (`theme = "light"`, `--theme light`). Text, tick
//! labels, axis titles and ring labels are [`Role::Label`]: the terminal's own colour, never
//! dim, so they read on a projector. Dim (SGR 2) means one thing only, [`Palette::behind`]:
//! drawn behind for comparison, not the live design's own value (the pinned design, the
//! structure without the damper, a chart cell still guessed from the coarse pass).
//!
//! Contrast is checked against one reference palette, xterm's default 16 colours
//! ([`XTERM_RGB`]), with the WCAG 2.1 contrast ratio: text on a zone fill, and text on the
//! theme's background, at least 4.5:1; lines and plot marks at least 3:1 (WCAG's figure for
//! graphics). A terminal with its own palette may differ; the pairs are chosen so they hold
//! for the usual ones too (black on the yellow and green fills, white on the red and blue).
//!
//! The colour depth ([`Depth`]) is read from `TERM` and `COLORTERM`: a terminal that does not
//! advertise 256 colours gets the classic `30–37`/`90–97` codes only (see
//! [`super::terminal`]), never `38;5;N`.

use std::borrow::Cow;

/// The text fold every `--ascii` output shares ([`crate::ascii`]).
pub use crate::ascii::fold;

use ratatui::buffer::Buffer;
use ratatui::style::{Color, Modifier, Style};
use ratatui::symbols::border;
use ratatui::symbols::Marker;
use ratatui::text::{Line, Span};
use ratatui::widgets::Block;
use unicode_width::{UnicodeWidthChar, UnicodeWidthStr};

use crate::design::Zone;

/// How to draw: with or without colour, for a dark or a light background, with or without
/// Braille. (The `theme` setting of `config.toml`, [`crate::config::Theme`], and `--theme`
/// choose the first two.)
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Palette {
    pub color: bool,
    pub ascii: bool,
    /// The light column of the role table (a terminal with a light background).
    pub light: bool,
}

impl Default for Palette {
    fn default() -> Self {
        Self::dark()
    }
}

/// What a style is for: each role has one look per theme ([`Palette::style`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// Text, tick labels, axis titles, ring labels, legends: the terminal's own colour.
    Label,
    /// Lines that frame a plot: the polar's rings and walls, the zero line, threshold lines.
    Grid,
    /// The live design's main curve (the pulse, the polar, Leq).
    Live,
    /// The design with the damper: its maxima, its response.
    Damper,
    /// The structure alone, without the damper.
    Alone,
    /// The listener's ray on the polar.
    Listener,
    /// The e line through the first two maxima.
    Fit,
    /// The focused panel's border.
    Focus,
    /// The border of the panel the tour talks about.
    Highlight,
    /// Error text.
    Error,
}

impl Role {
    /// Every role (for the contrast test).
    pub const ALL: [Role; 10] = [
        Role::Label,
        Role::Grid,
        Role::Live,
        Role::Damper,
        Role::Alone,
        Role::Listener,
        Role::Fit,
        Role::Focus,
        Role::Highlight,
        Role::Error,
    ];

    /// The role's foreground on a dark and on a light background (None: the terminal's own),
    /// and whether it is bold. The one table of the explorer's colours.
    const fn look(self) -> (Option<Color>, Option<Color>, bool) {
        match self {
            Role::Label => (None, None, false),
            Role::Grid => (Some(Color::DarkGray), Some(Color::DarkGray), false),
            Role::Live | Role::Focus => (Some(Color::Cyan), Some(Color::Blue), true),
            Role::Damper | Role::Listener | Role::Highlight => (Some(Color::Yellow), Some(Color::Magenta), true),
            Role::Alone => (Some(Color::White), Some(Color::Black), true),
            Role::Fit => (Some(Color::LightRed), Some(Color::Red), false),
            Role::Error => (Some(Color::LightRed), Some(Color::Red), true),
        }
    }

    /// Whether the role is read as text (4.5:1 against the background) rather than as a line
    /// or mark (3:1).
    pub const fn is_text(self) -> bool {
        matches!(self, Role::Label | Role::Error)
    }
}

/// How many colours the terminal advertises: the classic 16 (SGR `30–37`, `90–97` and their
/// backgrounds) or the 256-colour codes (`38;5;N`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Depth {
    Sixteen,
    Indexed256,
}

impl Depth {
    /// From the values of `TERM` and `COLORTERM`: 256 colours when `COLORTERM` is set (it is
    /// set by terminals with true colour) or `TERM` names them (`*-256color`, `*-direct`);
    /// otherwise (plain `xterm`, `screen`, `linux`, no `TERM`) the 16.
    pub fn from_vars(term: Option<&str>, colorterm: Option<&str>) -> Self {
        let term = term.unwrap_or("");
        if colorterm.is_some_and(|c| !c.is_empty()) || term.contains("256col") || term.ends_with("-direct") {
            Depth::Indexed256
        } else {
            Depth::Sixteen
        }
    }

    /// From this process's environment.
    pub fn from_env() -> Self {
        let var = |k: &str| std::env::var(k).ok();
        Self::from_vars(var("TERM").as_deref(), var("COLORTERM").as_deref())
    }
}

/// The RGB values of the 16 named colours in xterm's default palette (the reference of the
/// contrast checks), in ANSI order: black, red, green, yellow, blue, magenta, cyan, grey,
/// then the bright ones.
pub const XTERM_RGB: [(u8, u8, u8); 16] = [
    (0x00, 0x00, 0x00),
    (0xcd, 0x00, 0x00),
    (0x00, 0xcd, 0x00),
    (0xcd, 0xcd, 0x00),
    (0x00, 0x00, 0xee),
    (0xcd, 0x00, 0xcd),
    (0x00, 0xcd, 0xcd),
    (0xe5, 0xe5, 0xe5),
    (0x7f, 0x7f, 0x7f),
    (0xff, 0x00, 0x00),
    (0x00, 0xff, 0x00),
    (0xff, 0xff, 0x00),
    (0x5c, 0x5c, 0xff),
    (0xff, 0x00, 0xff),
    (0x00, 0xff, 0xff),
    (0xff, 0xff, 0xff),
];

/// The ANSI index (0–15) of a named colour; None for the terminal's default, 256-colour
/// indices above 15 and RGB.
pub fn ansi_index(c: Color) -> Option<u8> {
    Some(match c {
        Color::Black => 0,
        Color::Red => 1,
        Color::Green => 2,
        Color::Yellow => 3,
        Color::Blue => 4,
        Color::Magenta => 5,
        Color::Cyan => 6,
        Color::Gray => 7,
        Color::DarkGray => 8,
        Color::LightRed => 9,
        Color::LightGreen => 10,
        Color::LightYellow => 11,
        Color::LightBlue => 12,
        Color::LightMagenta => 13,
        Color::LightCyan => 14,
        Color::White => 15,
        Color::Indexed(i) if i < 16 => i,
        _ => return None,
    })
}

/// A zone's fill (background) and the colour of the digit on it: red and blue fills carry
/// white digits, yellow and green ones black digits (at least 4.5:1 in [`XTERM_RGB`]).
pub const fn zone_colors(zone: Zone) -> (Color, Color) {
    match zone {
        Zone::NoisyWeak => (Color::Red, Color::White),
        Zone::NoisyStrong => (Color::Yellow, Color::Black),
        Zone::QuietStrong => (Color::Green, Color::Black),
        Zone::QuietWeak => (Color::Blue, Color::White),
    }
}

impl Palette {
    /// Colour unless `NO_COLOR` is set to anything non-empty (<https://no-color.org>).
    pub fn from_env(ascii: bool) -> Self {
        let no_color = std::env::var_os("NO_COLOR").is_some_and(|v| !v.is_empty());
        Self { color: !no_color, ascii, light: false }
    }

    /// The default palette: colour, Unicode, dark background.
    pub const fn dark() -> Self {
        Self { color: true, ascii: false, light: false }
    }

    /// This palette under `theme`: `mono` takes the colour away, `light` picks the light
    /// column of the role table.
    #[must_use]
    pub fn with_theme(self, theme: crate::config::Theme) -> Self {
        use crate::config::Theme;
        Self { color: self.color && theme != Theme::Mono, light: theme == Theme::Light, ..self }
    }

    /// A foreground colour, or nothing without colour.
    pub fn fg(&self, c: Color) -> Style {
        if self.color {
            Style::default().fg(c)
        } else {
            Style::default()
        }
    }

    /// The colour of `role` in this theme (None: the terminal's own foreground).
    pub fn role_color(&self, role: Role) -> Option<Color> {
        let (dark, light, _) = role.look();
        if self.light {
            light
        } else {
            dark
        }
    }

    /// The style of `role`: its colour (none without colour) and its weight. Never dim.
    pub fn style(&self, role: Role) -> Style {
        let (_, _, bold) = role.look();
        let s = self.role_color(role).map_or(Style::default(), |c| self.fg(c));
        if bold {
            s.add_modifier(Modifier::BOLD)
        } else {
            s
        }
    }

    /// The colour of `role` alone, without its weight (for a curve drawn [`Self::behind`]).
    pub fn ink(&self, role: Role) -> Style {
        self.role_color(role).map_or(Style::default(), |c| self.fg(c))
    }

    /// Text, tick labels, axis titles and ring labels: [`Role::Label`].
    pub fn label(&self) -> Style {
        self.style(Role::Label)
    }

    /// The one meaning of dim: `style` drawn behind for comparison, not the live design's own
    /// value (the pinned design, the structure without the damper, a guessed chart cell).
    pub fn behind(&self, style: Style) -> Style {
        style.add_modifier(Modifier::DIM)
    }

    /// The style of the pinned design's curves: grey, behind.
    pub fn pinned(&self) -> Style {
        self.behind(self.style(Role::Grid))
    }

    /// The focused panel's border.
    pub fn focus(&self, focused: bool) -> Style {
        if focused {
            self.style(Role::Focus)
        } else {
            Style::default()
        }
    }

    /// A chart cell of a zone: the zone colour as background with a digit that reads on it
    /// ([`zone_colors`]), or plain.
    pub fn zone(&self, zone: Zone) -> Style {
        if !self.color {
            return Style::default();
        }
        let (bg, fg) = zone_colors(zone);
        Style::default().bg(bg).fg(fg)
    }

    /// A zone's digit on the plain background (the scatter plot): the zone's colour on a dark
    /// terminal; the terminal's own colour, bold, on a light one (where the yellow and green
    /// would not read).
    pub fn zone_ink(&self, zone: Zone) -> Style {
        let bold = Style::default().add_modifier(Modifier::BOLD);
        if self.light {
            return bold;
        }
        let c = match zone {
            Zone::NoisyWeak => Color::LightRed,
            Zone::NoisyStrong => Color::Yellow,
            Zone::QuietStrong => Color::Green,
            Zone::QuietWeak => Color::LightBlue,
        };
        self.fg(c).patch(bold)
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
        self.style(Role::Error)
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
        Block::bordered().title(title).border_set(set).border_style(self.style(Role::Highlight))
    }

    /// Text as drawn: unchanged, or folded to ASCII with `--ascii`.
    pub fn text<'a>(&self, s: &'a str) -> Cow<'a, str> {
        if self.ascii {
            Cow::Owned(fold(s))
        } else {
            Cow::Borrowed(s)
        }
    }

    /// The ellipsis that ends cut text: `…`, or `...` with `--ascii`.
    pub fn ellipsis(&self) -> &'static str {
        if self.ascii {
            "..."
        } else {
            "…"
        }
    }

    /// `text` in at most `width` columns (display width): whole when it fits, else cut and
    /// ended with [`Self::ellipsis`] ([`cut_to`]). Every place that cuts text cuts it here.
    pub fn fit<'a>(&self, text: &'a str, width: usize) -> Cow<'a, str> {
        cut_to(text, width, self.ellipsis())
    }

    /// A line of styled spans in at most `width` columns, cut like [`Self::fit`]: the
    /// ellipsis takes the style of the span it cuts.
    pub fn fit_line(&self, line: Line<'static>, width: usize) -> Line<'static> {
        // Trailing blanks (a padded column) may fall off the edge: nothing is lost.
        let mut blanks = 0;
        for span in line.spans.iter().rev() {
            let c = &span.content;
            blanks += c.width() - c.trim_end().width();
            if !c.trim_end().is_empty() {
                break;
            }
        }
        if line.width() - blanks <= width {
            return line;
        }
        let room = width.saturating_sub(self.ellipsis().width());
        let mut spans: Vec<Span<'static>> = Vec::new();
        let mut used = 0;
        for span in line.spans {
            let w = span.width();
            if used + w <= room {
                used += w;
                spans.push(span);
                continue;
            }
            // The span that does not fit: as much of it as does, then the ellipsis.
            let mut cut = take_width(&span.content, room - used).trim_end().to_string();
            cut.push_str(self.ellipsis());
            spans.push(Span::styled(cut, span.style));
            return Line::from(spans).style(line.style);
        }
        Line::from(spans).style(line.style)
    }

    /// Wrapped `lines` in a box `height` rows high and `width` wide: when they do not all fit,
    /// the last one shown ends with the ellipsis.
    pub fn fit_lines(&self, mut lines: Vec<String>, height: usize, width: usize) -> Vec<String> {
        if lines.len() > height {
            lines.truncate(height);
            if let Some(last) = lines.last_mut() {
                let room = width.saturating_sub(self.ellipsis().width());
                *last = format!("{}{}", take_width(last, room).trim_end(), self.ellipsis());
            }
        }
        lines
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

/// The longest start of `text` at most `width` columns wide.
/// `text` in at most `width` columns (display width): whole when it fits, else its start and
/// `ell`. [`Palette::fit`] with the palette's ellipsis; the readout's columns cut with it too.
pub fn cut_to<'a>(text: &'a str, width: usize, ell: &str) -> Cow<'a, str> {
    if text.width() <= width {
        return Cow::Borrowed(text);
    }
    let Some(room) = width.checked_sub(ell.width()) else {
        return Cow::Owned(ell.chars().take(width).collect());
    };
    let mut out = take_width(text, room).trim_end().to_string();
    out.push_str(ell);
    Cow::Owned(out)
}

fn take_width(text: &str, width: usize) -> &str {
    let mut used = 0;
    for (i, c) in text.char_indices() {
        used += c.width().unwrap_or(0);
        if used > width {
            return &text[..i];
        }
    }
    text
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
        // Anything else the text fold can spell: its first letter (one cell has room for one).
        _ => crate::ascii::word(c).map_or("?", |w| &w[..1]),
    }
}

/// Whether `--ascii` can show `c` without a `?`: it is ASCII, or the text fold or the
/// frame's last pass has a spelling for it.
pub fn spellable(c: char) -> bool {
    let mut b = [0; 4];
    c.is_ascii() || crate::ascii::word(c).is_some() || ascii_cell(c.encode_utf8(&mut b)) != "?"
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

    /// WCAG 2.1 relative luminance of a colour of the reference palette.
    fn luminance(c: Color) -> f64 {
        let (r, g, b) = XTERM_RGB[usize::from(ansi_index(c).expect("a named colour"))];
        let lin = |v: u8| {
            let s = f64::from(v) / 255.0;
            if s <= 0.04045 {
                s / 12.92
            } else {
                ((s + 0.055) / 1.055).powf(2.4)
            }
        };
        0.2126 * lin(r) + 0.7152 * lin(g) + 0.0722 * lin(b)
    }

    /// WCAG 2.1 contrast ratio of two colours.
    fn contrast(a: Color, b: Color) -> f64 {
        let (la, lb) = (luminance(a), luminance(b));
        (la.max(lb) + 0.05) / (la.min(lb) + 0.05)
    }

    #[test]
    fn the_reference_luminances_are_wcags() {
        assert!((contrast(Color::Black, Color::White) - 21.0).abs() < 1e-9);
        assert!((luminance(Color::Red) - 0.2126 * ((205.0 / 255.0 + 0.055) / 1.055_f64).powf(2.4)).abs() < 1e-12);
    }

    #[test]
    fn zone_digits_read_on_their_fill_at_4_5_to_1_in_both_themes() {
        for light in [false, true] {
            let p = Palette { light, ..Palette::dark() };
            for zone in [Zone::NoisyWeak, Zone::NoisyStrong, Zone::QuietStrong, Zone::QuietWeak] {
                let s = p.zone(zone);
                let (fg, bg) = (s.fg.expect("a digit colour"), s.bg.expect("a fill"));
                let c = contrast(fg, bg);
                assert!(c >= 4.5, "zone {zone:?} (light {light}): {fg:?} on {bg:?} is {c:.2}:1");
            }
        }
    }

    #[test]
    fn every_role_reads_on_its_themes_background() {
        for (light, background) in [(false, Color::Black), (true, Color::White)] {
            let p = Palette { light, ..Palette::dark() };
            for role in Role::ALL {
                let Some(c) = p.role_color(role) else { continue };
                let need = if role.is_text() { 4.5 } else { 3.0 };
                let got = contrast(c, background);
                assert!(got >= need, "{role:?} {c:?} on {background:?} (light {light}): {got:.2}:1 < {need}");
            }
            for zone in [Zone::NoisyWeak, Zone::NoisyStrong, Zone::QuietStrong, Zone::QuietWeak] {
                if let Some(c) = p.zone_ink(zone).fg {
                    assert!(contrast(c, background) >= 3.0, "zone ink {zone:?} {c:?} on {background:?}");
                }
            }
        }
    }

    #[test]
    fn no_role_is_dim_and_behind_is_the_only_dim() {
        for light in [false, true] {
            let p = Palette { light, ..Palette::dark() };
            for role in Role::ALL {
                assert!(!p.style(role).add_modifier.contains(Modifier::DIM), "{role:?}");
                assert!(p.style(role).fg.is_none_or(|c| ansi_index(c).is_some()), "{role:?}: a named colour");
            }
        }
        let p = Palette::dark();
        assert!(p.behind(p.label()).add_modifier.contains(Modifier::DIM));
        assert!(p.pinned().add_modifier.contains(Modifier::DIM));
    }

    #[test]
    fn sixteen_colours_unless_the_terminal_advertises_256() {
        assert_eq!(Depth::from_vars(Some("xterm"), None), Depth::Sixteen);
        assert_eq!(Depth::from_vars(Some("screen"), Some("")), Depth::Sixteen);
        assert_eq!(Depth::from_vars(None, None), Depth::Sixteen);
        assert_eq!(Depth::from_vars(Some("xterm-256color"), None), Depth::Indexed256);
        assert_eq!(Depth::from_vars(Some("tmux-256color"), None), Depth::Indexed256);
        assert_eq!(Depth::from_vars(Some("xterm-direct"), None), Depth::Indexed256);
        assert_eq!(Depth::from_vars(Some("xterm"), Some("truecolor")), Depth::Indexed256);
    }

    #[test]
    fn themes_map_to_palettes() {
        use crate::config::Theme;
        let p = Palette::dark();
        assert_eq!(p.with_theme(Theme::Light), Palette { light: true, ..p });
        assert_eq!(p.with_theme(Theme::Mono), Palette { color: false, ..p });
        assert_eq!(Palette { light: true, ..p }.with_theme(Theme::Default), p);
        assert_eq!(p.with_theme(Theme::Light).style(Role::Damper).fg, Some(Color::Magenta));
        assert_eq!(p.style(Role::Damper).fg, Some(Color::Yellow));
    }

    #[test]
    fn fit_cuts_by_display_width_and_ends_with_the_ellipsis() {
        let (u, a) = (Palette::dark(), Palette { ascii: true, ..Palette::dark() });
        assert_eq!(u.fit("θ 45.0°", 7), "θ 45.0°", "fits: whole");
        assert_eq!(u.fit("SPL: rms over tau", 10), "SPL: rms…");
        assert_eq!(a.fit("SPL: rms over tau", 10), "SPL: rm...");
        // Wide characters count two columns; the cut never splits one.
        assert_eq!(u.fit("日本語テキスト", 6), "日本…");
        assert!(UnicodeWidthStr::width(&*u.fit("日本語テキスト", 6)) <= 6);
        assert_eq!(a.fit("abcdef", 2), "..");
        assert_eq!(u.fit("abcdef", 0), "");
        let line = Line::from(vec![Span::raw(" thud "), Span::styled("preset long-name", Style::new().bold())]);
        let cut = u.fit_line(line, 12);
        assert_eq!(cut.to_string(), " thud prese…");
        assert_eq!(cut.width(), 12);
        assert!(cut.spans[1].style.add_modifier.contains(Modifier::BOLD), "the ellipsis keeps the cut span's style");
        let padded = Line::from(vec![Span::raw("zone 1"), Span::raw("          ")]);
        assert_eq!(u.fit_line(padded, 8).to_string(), "zone 1          ", "trailing blanks are not text");
        let lines = vec!["one two".to_string(), "three four".into(), "five".into()];
        assert_eq!(u.fit_lines(lines.clone(), 2, 10), ["one two", "three fou…"]);
        assert_eq!(u.fit_lines(lines.clone(), 3, 10), lines);
    }
}
