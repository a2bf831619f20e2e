//! The readout: what the design is worth, live beside pinned. Tall (one row per number) where
//! there is room, compact (two numbers a row, the zone first) in the teaching layout at 80×24.
//! A forced design's compact readout pairs its steady figures instead (amplitude with and
//! without the damper, cut, Leq, impacts a period); an ensemble's gives e, e_fit and SPLmax
//! a row each, with their [p10–p90].
//!
//! Columns never run together: each value is cut to its column with one blank or more after
//! it, losing first the insides of its bracketed parts (`1.4000 m/s […]`), then them (`1.4000
//! m/s…`), then its end, each cut marked with `…` (`...` in ASCII); beside a pinned design the
//! live column is as wide as the longest forms that leave the pinned one room for its own.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph, Widget};

use super::theme::{self, Palette};
use crate::verdict::Verdict;
use unicode_width::UnicodeWidthStr;

/// One readout row: label, live value, pinned value (if a design is pinned).
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    pub label: &'static str,
    pub live: String,
    pub pinned: Option<String>,
}

/// The readout's data.
pub struct ReadoutView<'a> {
    pub block: Block<'a>,
    pub rows: &'a [Row],
    /// A line under the rows (e.g. "no impacts" or an error), if any.
    pub note: Option<&'a str>,
    pub theme: Palette,
    /// Two numbers a row (the zone on its own row first).
    pub compact: bool,
}

/// The pinned column's least width where the live one wants more room than there is: its own
/// width or this, whichever is less (a third of the room where that is more).
pub const PINNED_MIN: usize = 8;

/// `text` cut to at most `room` columns: the first of its [`forms`] that fits, else its start
/// and `ell` (`…`, or `...` in ASCII) as every cut text ends ([`theme::cut_to`]). The forms
/// are the readout's own: its columns are the only cut text with bracketed parts to drop first.
pub fn cut(text: &str, room: usize, ell: &str) -> String {
    forms(text, ell)
        .into_iter()
        .find(|f| f.width() <= room)
        .unwrap_or_else(|| theme::cut_to(text, room, ell).into_owned())
}

/// A value's forms, longest first: itself; with the insides of its bracketed parts elided
/// (`1.4000 m/s […]`, `1 noisy, weak (…), 75%`); its head before them and `ell`
/// (`1.4000 m/s…`).
pub fn forms(text: &str, ell: &str) -> [String; 3] {
    let elided = elide_brackets(text, ell);
    let head = match [text.find(" ("), text.find(" [")].into_iter().flatten().min() {
        Some(i) => format!("{}{ell}", &text[..i]),
        None => elided.clone(),
    };
    [text.to_string(), elided, head]
}

/// `text` with the inside of each ` (…)` and ` […]` part replaced by `ell` where that is
/// shorter (a `(!)` stays).
fn elide_brackets(text: &str, ell: &str) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(i) = [rest.find(" ("), rest.find(" [")].into_iter().flatten().min() {
        let close = if rest[i + 1..].starts_with('(') { ')' } else { ']' };
        let Some(j) = rest[i + 2..].find(close) else { break };
        let inside = &rest[i + 2..i + 2 + j];
        out.push_str(&rest[..i + 2]);
        out.push_str(if inside.chars().count() > ell.chars().count() { ell } else { inside });
        out.push(close);
        rest = &rest[i + 3 + j..];
    }
    out.push_str(rest);
    out
}

/// `text` cut to `width − gap` columns (see [`cut`]) and padded to `width`: the next column
/// starts `gap` or more blanks after it.
fn fit(text: &str, width: usize, gap: usize, ell: &str) -> String {
    let t = cut(text, width.saturating_sub(gap), ell);
    format!("{t:<width$}")
}

/// The widths of the live and the pinned columns in `room` columns, given the widest of each
/// column's values in each of their [`forms`]: the live one as wide as its longest form that
/// leaves the pinned one room for its own (full values first, then elided, then heads), and two
/// blanks; the pinned one the rest. Where not even the heads fit, the pinned one gets its
/// width, or a third of the room (at least [`PINNED_MIN`]) where that is less.
pub fn split(room: usize, live: [usize; 3], pinned: [usize; 3]) -> (usize, usize) {
    for (a, b) in [(0, 0), (0, 1), (1, 1), (1, 2), (2, 2)] {
        if live[a] + 2 + pinned[b] <= room {
            return (live[a] + 2, room - live[a] - 2);
        }
    }
    let pin_min = pinned[2].min((room / 3).max(PINNED_MIN)).min(room);
    let live_w = (live[2] + 2).min(room - pin_min);
    (live_w, room - live_w)
}

/// The widest of `texts` in each of their [`forms`] (at least `min`).
fn widest<'a>(texts: impl Iterator<Item = &'a str>, ell: &str, min: usize) -> [usize; 3] {
    let mut w = [min; 3];
    for t in texts {
        for (k, f) in forms(t, ell).iter().enumerate() {
            w[k] = w[k].max(f.chars().count());
        }
    }
    w
}

impl ReadoutView<'_> {
    fn ell(&self) -> &'static str {
        self.theme.sym("…", "...")
    }

    fn tall(&self, w: usize) -> Vec<Line<'static>> {
        let th = &self.theme;
        let ell = self.ell();
        let any_pinned = self.rows.iter().any(|r| r.pinned.is_some());
        // The labels' column: 8 wide, or wider for a label spelled out in ASCII (tau@U0max).
        let lw = self.rows.iter().map(|r| th.text(r.label).chars().count() + 1).max().unwrap_or(0).max(8);
        let room = w.saturating_sub(lw);
        let (live_w, pin_w) = if any_pinned && w >= 30 {
            let live: Vec<String> = self.rows.iter().map(|r| th.text(&r.live).into_owned()).collect();
            let pinned: Vec<String> =
                self.rows.iter().map(|r| th.text(r.pinned.as_deref().unwrap_or_default()).into_owned()).collect();
            let (live, pinned) =
                (widest(live.iter().map(String::as_str), ell, 4), widest(pinned.iter().map(String::as_str), ell, 6));
            split(room, live, pinned)
        } else {
            (room, 0)
        };
        let mut lines: Vec<Line> = Vec::new();
        if pin_w > 0 {
            let head = format!("{:<lw$}{}{}", "", fit("live", live_w, 1, ell), fit("pinned", pin_w, 0, ell));
            lines.push(Line::from(Span::styled(head, Style::default().add_modifier(Modifier::UNDERLINED))));
        }
        for r in self.rows {
            let gap = usize::from(pin_w > 0);
            let mut spans = vec![
                Span::styled(format!("{:<lw$}", th.text(r.label)), Style::default().add_modifier(Modifier::BOLD)),
                Span::raw(fit(&th.text(&r.live), live_w, gap, ell)),
            ];
            if pin_w > 0 {
                let pinned = th.text(r.pinned.as_deref().unwrap_or_default()).into_owned();
                spans.push(Span::styled(fit(&pinned, pin_w, 0, ell), th.pinned()));
            }
            lines.push(Line::from(spans));
        }
        lines
    }

    /// Zone first on its own row, then pairs: e | e_fit, SPLmax | U0max, τ | R mean, impacts.
    /// With a pinned design: zone, e and SPLmax as live | pinned. Every value is cut to its
    /// column (see [`cut`]), one blank or more before the next.
    fn compact(&self, w: usize) -> Vec<Line<'static>> {
        let th = &self.theme;
        let ell = self.ell();
        let get = |label: &str| self.rows.iter().find(|r| r.label == label);
        let bold = Style::default().add_modifier(Modifier::BOLD);
        // A label and its value in `width` columns, `gap` of them left blank at the end.
        let cell = |r: Option<&Row>, width: usize, gap: usize| -> Vec<Span<'static>> {
            let Some(r) = r else { return vec![] };
            let label = th.text(r.label).into_owned();
            let value = th.text(&r.live).into_owned();
            let lw = label.chars().count().max(6) + 1;
            vec![
                Span::styled(format!("{label:<lw$}"), bold),
                Span::raw(fit(&value, width.saturating_sub(lw), gap, ell)),
            ]
        };
        let mut lines = Vec::new();
        if self.rows.iter().any(|r| r.pinned.is_some()) {
            let shown: Vec<&Row> = ["zone", "e", "SPLmax"].iter().filter_map(|l| get(l)).collect();
            let live: Vec<String> = shown.iter().map(|r| th.text(&r.live).into_owned()).collect();
            let pinned: Vec<String> =
                shown.iter().map(|r| th.text(r.pinned.as_deref().unwrap_or_default()).into_owned()).collect();
            let (live, pinned) =
                (widest(live.iter().map(String::as_str), ell, 4), widest(pinned.iter().map(String::as_str), ell, 6));
            let (live_w, pin_w) = split(w.saturating_sub(7), live, pinned);
            let head = format!("{:<7}{}{}", "", fit("live", live_w, 1, ell), fit("pinned", pin_w, 0, ell));
            lines.push(Line::from(Span::styled(head, Style::default().add_modifier(Modifier::UNDERLINED))));
            for r in shown {
                let pinned = th.text(r.pinned.as_deref().unwrap_or("")).into_owned();
                lines.push(Line::from(vec![
                    Span::styled(format!("{:<7}", th.text(r.label)), bold),
                    Span::raw(fit(&th.text(&r.live), live_w, 1, ell)),
                    Span::styled(fit(&pinned, pin_w, 0, ell), th.pinned()),
                ]));
            }
            return lines;
        }
        lines.push(Line::from(cell(get("zone"), w, 0)));
        if get("amp").is_none() && self.rows.iter().any(|r| r.live.contains(" [")) {
            for label in ["e", "e_fit", "SPLmax"] {
                lines.push(Line::from(cell(get(label), w, 0)));
            }
            return lines;
        }
        let pairs = if get("amp").is_some() {
            [("amp", "alone"), ("cut", "Leq"), ("imp/T", "SPLmax")]
        } else {
            [("e", "e_fit"), ("SPLmax", "U0max"), ("τ@U0max", "R mean")]
        };
        // The left column as wide as its widest entry (a negative e carries its marker).
        let width = |r: Option<&Row>| {
            r.map_or(0, |r| th.text(r.label).chars().count().max(6) + 1 + th.text(&r.live).chars().count())
        };
        let left = pairs.iter().map(|(a, _)| width(get(a))).max().unwrap_or(0) + 2;
        let left = left.max(w / 2).min(w.saturating_sub(12));
        for (a, b) in pairs {
            let mut spans = cell(get(a), left, 1);
            spans.extend(cell(get(b), w - left, 0));
            lines.push(Line::from(spans));
        }
        lines
    }
}

impl Widget for ReadoutView<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let inner = self.block.inner(area);
        (&self.block).render(area, buf);
        let w = inner.width as usize;
        let mut lines = if self.compact { self.compact(w) } else { self.tall(w) };
        if let Some(n) = self.note {
            let n = self.theme.text(n).into_owned();
            // Tall: the whole note, wrapped (its rows are free); compact: one line, cut.
            let parts = if self.compact { vec![n] } else { super::tour::wrap(&n, w.max(1)) };
            for part in parts {
                lines.push(Line::from(Span::styled(part, Style::default().add_modifier(Modifier::ITALIC))));
            }
        }
        let lines: Vec<Line> = lines.into_iter().map(|l| self.theme.fit_line(l, w)).collect();
        Paragraph::new(lines).render(inner, buf);
    }
}

/// A verdict as the explorer words it, in the readout's title and note and the bifurcation
/// view's line: `orbit 3/1`, `orbit settled`, `orbit NOT SETTLED`, `orbit TRUNCATED`
/// (capitals where the figures are not a steady state's).
pub fn verdict_words(v: &Verdict) -> String {
    if v.is_marked() {
        format!("orbit {}", v.label().to_uppercase())
    } else {
        format!("orbit {}", v.label())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cut_drops_the_bracketed_insides_first_then_the_end() {
        assert_eq!(cut("1.4000 m/s [1.4000–1.4498]", 26, "…"), "1.4000 m/s [1.4000–1.4498]");
        assert_eq!(cut("1.4000 m/s [1.4000–1.4498]", 20, "…"), "1.4000 m/s […]");
        assert_eq!(cut("4 quiet, weak (by e), 75%", 22, "…"), "4 quiet, weak (…), 75%");
        assert_eq!(cut("4 quiet, weak (by e), 75%", 14, "…"), "4 quiet, weak…");
        assert_eq!(cut("4 quiet, weak (by e), 75%", 10, "…"), "4 quiet,…");
        assert_eq!(cut("-0.33 cm/s [-0.5–0.1] (!)", 19, "…"), "-0.33 cm/s […] (!)");
        assert_eq!(cut("104.2 dB [103.1–104.9]", 11, "..."), "104.2 dB...");
        assert_eq!(cut("104.2 dB [103.1–104.9]", 8, "..."), "104.2...");
        assert_eq!(cut("abc", 0, "…"), "");
    }

    #[test]
    fn the_pinned_column_keeps_room_beside_a_wide_live_one() {
        assert_eq!(split(40, [10; 3], [10; 3]), (12, 28));
        // Whole live values, the pinned ones elided; then both elided; then both heads.
        assert_eq!(split(40, [20, 14, 10], [20, 14, 10]), (22, 18));
        assert_eq!(split(30, [20, 14, 10], [20, 14, 10]), (16, 14));
        assert_eq!(split(24, [20, 14, 10], [20, 14, 10]), (12, 12));
        let (live, pinned) = split(21, [25, 22, 14], [25, 22, 14]);
        assert_eq!(live + pinned, 21);
        assert!(pinned >= PINNED_MIN && live > pinned, "{live} {pinned}");
        assert_eq!(split(5, [25; 3], [25; 3]), (0, 5));
    }
}
