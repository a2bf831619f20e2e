//! The readout: what the design is worth, live beside pinned.

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
    pub rows: &'a [Row],
    /// A line under the rows (e.g. "no impacts" or an error), if any.
    pub note: Option<&'a str>,
    pub theme: Palette,
    pub focused: bool,
}

impl Widget for ReadoutView<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let block = Block::bordered().title(" readout ").border_style(self.theme.focus(self.focused));
        let inner = block.inner(area);
        block.render(area, buf);
        let any_pinned = self.rows.iter().any(|r| r.pinned.is_some());
        let w = inner.width as usize;
        let pin_w = if any_pinned && w >= 30 { 13 } else { 0 };
        let mut lines: Vec<Line> = Vec::new();
        if pin_w > 0 {
            let head = format!("{:<8}{:<w2$}{:<pin_w$}", "", "live", "pinned", w2 = w.saturating_sub(8 + pin_w));
            lines.push(Line::from(Span::styled(head, Style::default().add_modifier(Modifier::UNDERLINED))));
        }
        for r in self.rows {
            let mut spans = vec![
                Span::styled(format!("{:<8}", r.label), Style::default().add_modifier(Modifier::BOLD)),
                Span::raw(format!("{:<w2$}", r.live, w2 = w.saturating_sub(8 + pin_w))),
            ];
            if pin_w > 0 {
                spans.push(Span::styled(r.pinned.clone().unwrap_or_default(), self.theme.pinned()));
            }
            lines.push(Line::from(spans));
        }
        if let Some(n) = self.note {
            lines.push(Line::from(Span::styled(n.to_string(), Style::default().add_modifier(Modifier::ITALIC))));
        }
        Paragraph::new(lines).render(inner, buf);
    }
}
