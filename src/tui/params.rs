//! The parameter panel: one row per field, the selected one reversed and pointed at. When not
//! every row fits (the teaching layout at 80×24) it shows the selected field and its
//! neighbours.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph, Widget};

use super::theme::Palette;

/// The panel's data: (label, value) rows, the selected row, whether the panel has focus.
pub struct ParamsView<'a> {
    pub block: Block<'a>,
    pub rows: &'a [(String, String)],
    pub selected: usize,
    pub focused: bool,
    pub theme: Palette,
}

impl ParamsView<'_> {
    /// The first row shown: all rows when they fit, else the selected one in the middle of
    /// its neighbours.
    fn scroll(&self, height: usize) -> usize {
        let n = self.rows.len();
        if height == 0 || n <= height {
            0
        } else {
            self.selected.saturating_sub(height / 2).min(n - height)
        }
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

impl Widget for ParamsView<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let inner = self.block.inner(area);
        (&self.block).render(area, buf);
        let h = inner.height as usize;
        let first = self.scroll(h);
        let lines: Vec<Line> = self
            .rows
            .iter()
            .enumerate()
            .skip(first)
            .take(h)
            .map(|(i, (l, v))| self.line(i, l, v, inner.width as usize))
            .collect();
        Paragraph::new(lines).render(inner, buf);
    }
}
