//! The readout: what the design is worth, live beside pinned. Tall (one row per number) where
//! there is room, compact (two numbers a row, the zone first) in the teaching layout at 80×24.
//! A forced design's compact readout pairs its steady figures instead (amplitude with and
//! without the damper, cut, Leq, impacts a period); an ensemble's gives e, e_fit and SPLmax
//! a row each, with their [p10–p90].

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph, Widget};

use super::theme::Palette;

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

impl ReadoutView<'_> {
    fn tall(&self, w: usize) -> Vec<Line<'static>> {
        let th = &self.theme;
        let any_pinned = self.rows.iter().any(|r| r.pinned.is_some());
        let pin_w = if any_pinned && w >= 30 { 13 } else { 0 };
        // The labels' column: 8 wide, or wider for a label spelled out in ASCII (tau@U0max).
        let lw = self.rows.iter().map(|r| th.text(r.label).chars().count() + 1).max().unwrap_or(0).max(8);
        let mut lines: Vec<Line> = Vec::new();
        if pin_w > 0 {
            let head = format!("{:<lw$}{:<w2$}{:<pin_w$}", "", "live", "pinned", w2 = w.saturating_sub(lw + pin_w));
            lines.push(Line::from(Span::styled(head, Style::default().add_modifier(Modifier::UNDERLINED))));
        }
        for r in self.rows {
            let mut spans = vec![
                Span::styled(format!("{:<lw$}", th.text(r.label)), Style::default().add_modifier(Modifier::BOLD)),
                Span::raw(format!("{:<w2$}", th.text(&r.live), w2 = w.saturating_sub(lw + pin_w))),
            ];
            if pin_w > 0 {
                spans.push(Span::styled(th.text(&r.pinned.clone().unwrap_or_default()).into_owned(), th.pinned()));
            }
            lines.push(Line::from(spans));
        }
        lines
    }

    /// Zone first on its own row, then pairs: e | e_fit, SPLmax | U0max, τ | R mean, impacts.
    /// With a pinned design: zone, e and SPLmax as live | pinned.
    fn compact(&self, w: usize) -> Vec<Line<'static>> {
        let th = &self.theme;
        let get = |label: &str| self.rows.iter().find(|r| r.label == label);
        let bold = Style::default().add_modifier(Modifier::BOLD);
        let cell = |r: Option<&Row>, width: usize| -> Vec<Span<'static>> {
            let Some(r) = r else { return vec![] };
            let label = th.text(r.label).into_owned();
            let value = th.text(&r.live).into_owned();
            let lw = label.chars().count().max(6) + 1;
            vec![
                Span::styled(format!("{label:<lw$}"), bold),
                Span::raw(format!("{value:<vw$}", vw = width.saturating_sub(lw))),
            ]
        };
        let mut lines = Vec::new();
        if self.rows.iter().any(|r| r.pinned.is_some()) {
            let shown: Vec<&Row> = ["zone", "e", "SPLmax"].iter().filter_map(|l| get(l)).collect();
            // The live column as wide as its widest value, so the pinned one never runs into it.
            let live_w = shown.iter().map(|r| th.text(&r.live).chars().count()).max().unwrap_or(0) + 2;
            let head = format!("{:<7}{:<live_w$}pinned", "", "live");
            lines.push(Line::from(Span::styled(head, Style::default().add_modifier(Modifier::UNDERLINED))));
            for r in shown {
                lines.push(Line::from(vec![
                    Span::styled(format!("{:<7}", th.text(r.label)), bold),
                    Span::raw(format!("{:<live_w$}", th.text(&r.live))),
                    Span::styled(th.text(r.pinned.as_deref().unwrap_or("")).into_owned(), th.pinned()),
                ]));
            }
            return lines;
        }
        lines.push(Line::from(cell(get("zone"), w)));
        if get("amp").is_none() && self.rows.iter().any(|r| r.live.contains(" [")) {
            for label in ["e", "e_fit", "SPLmax"] {
                lines.push(Line::from(cell(get(label), w)));
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
            let mut spans = cell(get(a), left);
            spans.extend(cell(get(b), w - left));
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
            lines.push(Line::from(Span::styled(n, Style::default().add_modifier(Modifier::ITALIC))));
        }
        let lines: Vec<Line> = lines.into_iter().map(|l| self.theme.fit_line(l, w)).collect();
        Paragraph::new(lines).render(inner, buf);
    }
}
