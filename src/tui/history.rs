//! Displacement history x(t) of the main mass with and without the damper (Fig 9).

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::Color;
use ratatui::symbols::Marker;
use ratatui::widgets::Widget;

use super::plot::{Curve, LinePlot};
use super::theme::Palette;

/// The panel's data: (t in s, x in cm) with the damper, without it, and the pinned design's.
pub struct HistoryView<'a> {
    pub with_damper: &'a [(f64, f64)],
    pub without: &'a [(f64, f64)],
    pub pinned: Option<&'a [(f64, f64)]>,
    pub focused: bool,
    pub theme: Palette,
}

impl Widget for HistoryView<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        // Without colour the two curves differ by their marker.
        let free_marker = if self.theme.ascii || !self.theme.color { Marker::Dot } else { Marker::Braille };
        let title = if self.theme.color {
            "x(t) cm: damper (yellow), none (grey)"
        } else {
            "x(t) cm: damper (fine), none (•)"
        };
        let mut series = vec![
            Curve { name: "no damper", data: self.without, style: self.theme.fg(Color::DarkGray), marker: free_marker },
            Curve {
                name: "damper",
                data: self.with_damper,
                style: self.theme.fg(Color::Yellow),
                marker: self.theme.marker(),
            },
        ];
        if let Some(p) = self.pinned {
            series.push(Curve {
                name: "pinned",
                data: p,
                style: self.theme.pinned(),
                marker: self.theme.pinned_marker(),
            });
        }
        LinePlot {
            title,
            x_title: "s",
            y_title: "cm",
            series,
            empty: "simulating…",
            focused: self.focused,
            theme: self.theme,
            y_zero: false,
            legend: self.pinned.is_some(),
        }
        .render(area, buf);
    }
}
