//! The parameter panel: one row per field under its group's heading (the engine's table's
//! groups: design, forcing, listener, solver, study), the selected one reversed and pointed at.
//! When not every line fits (the teaching layout at 80×24) it scrolls to show the selected field
//! and its neighbours.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph, Widget};

use super::theme::Palette;

/// One line of the panel: a group's heading, or the field at an index of the rows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Entry {
    Heading(&'static str),
    Field(usize),
}

/// The panel's data: (label, value) rows, the group of each row (a heading opens each run of
/// rows of one group), the selected row, whether the panel has focus.
pub struct ParamsView<'a> {
    pub block: Block<'a>,
    pub rows: &'a [(String, String)],
    pub groups: &'a [&'static str],
    pub selected: usize,
    pub focused: bool,
    pub theme: Palette,
}

impl ParamsView<'_> {
    /// The lines of the panel: each group's heading before its first row.
    fn entries(&self) -> Vec<Entry> {
        let mut out = Vec::with_capacity(self.rows.len() + 5);
        let mut current = None;
        for i in 0..self.rows.len() {
            let group = self.groups.get(i).copied();
            if group.is_some() && group != current {
                out.extend(group.map(Entry::Heading));
                current = group;
            }
            out.push(Entry::Field(i));
        }
        out
    }

    /// The first line shown of `n`: all when they fit, else the selected field's line
    /// (`at`) in the middle of its neighbours.
    fn scroll(n: usize, at: usize, height: usize) -> usize {
        if height == 0 || n <= height {
            0
        } else {
            at.saturating_sub(height / 2).min(n - height)
        }
    }

    /// A group's heading, as wide as the panel: `─ forcing ───…`.
    fn heading(&self, title: &str, width: usize) -> Line<'static> {
        let head = format!("─ {title} ");
        let rule = "─".repeat(width.saturating_sub(head.chars().count()));
        let text = self.theme.text(&format!("{head}{rule}")).into_owned();
        // A label, so never dim (dim means "drawn behind", theme.rs).
        Line::from(Span::styled(text, self.theme.label()))
    }

    fn line(&self, i: usize, label: &str, value: &str, width: usize) -> Line<'static> {
        let selected = i == self.selected;
        let pointer = if selected { self.theme.pointer() } else { " " };
        let label_w = 10.min(width.saturating_sub(2));
        let value_w = width.saturating_sub(label_w + 2);
        let label = self.theme.text(label);
        let value = self.theme.text(value);
        let text = format!("{pointer}{label:<label_w$} {value:>value_w$}");
        let text = self.theme.fit(&text, width).into_owned();
        let style = if selected {
            let s = Style::default().add_modifier(Modifier::REVERSED);
            if self.focused {
                s.add_modifier(Modifier::BOLD)
            } else {
                s
            }
        } else {
            Style::default()
        };
        Line::from(Span::styled(text, style))
    }
}

impl ParamsView<'_> {
    /// The entries shown in `inner` (its height), from the first one the scroll shows.
    fn shown(&self, inner: Rect) -> Vec<Entry> {
        let entries = self.entries();
        let at = entries.iter().position(|e| *e == Entry::Field(self.selected)).unwrap_or(0);
        let first = Self::scroll(entries.len(), at, inner.height as usize);
        entries.into_iter().skip(first).take(inner.height as usize).collect()
    }

    /// Where each shown field is drawn when the panel fills `area`: its line and its index
    /// into the rows (for a click on a field).
    pub fn field_lines(&self, area: Rect) -> Vec<(Rect, usize)> {
        let inner = self.block.inner(area);
        self.shown(inner)
            .into_iter()
            .zip(inner.y..inner.bottom())
            .filter_map(|(e, y)| match e {
                Entry::Field(i) => Some((Rect::new(inner.x, y, inner.width, 1), i)),
                Entry::Heading(_) => None,
            })
            .collect()
    }
}

impl Widget for ParamsView<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let inner = self.block.inner(area);
        (&self.block).render(area, buf);
        let w = inner.width as usize;
        let entries = self.shown(inner);
        let lines: Vec<Line> = entries
            .iter()
            .filter_map(|e| match *e {
                Entry::Heading(title) => Some(self.heading(title, w)),
                Entry::Field(i) => self.rows.get(i).map(|(l, v)| self.line(i, l, v, w)),
            })
            .collect();
        Paragraph::new(lines).render(inner, buf);
    }
}
