//! The pressure waveform of the loudest impact at the observer (the "M" shape), ms after the
//! direct arrival on x, Pa on y; the pinned design's waveform beside it.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::Color;
use ratatui::widgets::Widget;

use super::plot::{Curve, LinePlot};
use super::theme::Palette;

/// The panel's data: (t in ms after the direct arrival, p in Pa).
pub struct WaveformView<'a> {
    pub live: &'a [(f64, f64)],
    pub pinned: Option<&'a [(f64, f64)]>,
    pub focused: bool,
    pub theme: Palette,
}

impl Widget for WaveformView<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let mut series = vec![Curve {
            name: "live",
            data: self.live,
            style: self.theme.fg(Color::Cyan),
            marker: self.theme.marker(),
        }];
        if let Some(p) = self.pinned {
            series.push(Curve {
                name: "pinned",
                data: p,
                style: self.theme.pinned(),
                marker: self.theme.pinned_marker(),
            });
        }
        LinePlot {
            title: "p(t) of the loudest impact, Pa vs ms",
            x_title: "ms",
            y_title: "Pa",
            series,
            empty: "no impact: no sound",
            focused: self.focused,
            theme: self.theme,
            y_zero: true,
            legend: self.pinned.is_some(),
        }
        .render(area, buf);
    }
}
