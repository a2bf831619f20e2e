//! The pressure pulse at the observer (the "M" shape): the loudest impact of the run, or one
//! impact at U0 = v0 on a fixed plate (the paper's Fig 2), in ms after the direct arrival on x
//! and Pa on y; the pinned design's pulse beside it.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::widgets::{Block, Widget};

use super::plot::{Curve, LinePlot};
use super::theme::{Palette, Role};

/// The panel's data: (t in ms after the direct arrival, p in Pa).
pub struct WaveformView<'a> {
    pub block: Block<'a>,
    pub live: &'a [(f64, f64)],
    pub pinned: Option<&'a [(f64, f64)]>,
    /// The humps of the M to name under the plot: (ms, Pa).
    pub peaks: &'a [(f64, f64)],
    pub empty: &'a str,
    pub theme: Palette,
}

/// The title of the pulse panel for the loudest impact (`single` None) or one plate impact at
/// U0 (m/s), the longest that fits in `width` columns.
/// `loudest`: the run's (U0max in m/s, SPLmax in dB) as the readout shows them, named in the
/// widest title when there is room.
pub fn title(single: Option<f64>, loudest: Option<(f64, f64)>, width: u16) -> String {
    let options: Vec<String> = match single {
        Some(u0) => vec![
            format!(" p(t) of one impact at U0 {} m/s on a fixed plate (Fig 2) ", crate::units::sig(u0, 3)),
            format!(" p(t), one impact at {} m/s on a plate ", crate::units::sig(u0, 3)),
            format!(" p(t), one impact, {} m/s ", crate::units::sig(u0, 3)),
            " p(t) one impact ".into(),
        ],
        None => loudest
            .map(|(u0, spl)| {
                format!(
                    " p(t) of the loudest impact: U0max {} m/s → SPLmax {} dB ",
                    crate::units::sig(u0, 5),
                    crate::units::sig(spl, 4)
                )
            })
            .into_iter()
            .chain([" p(t) of the loudest impact of the run ".into(), " p(t), loudest impact ".into(), " p(t) ".into()])
            .collect(),
    };
    let w = usize::from(width).saturating_sub(2);
    options.iter().find(|t| t.chars().count() <= w).unwrap_or(&options[options.len() - 1]).clone()
}

impl Widget for WaveformView<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let mut series = vec![Curve::line("live", self.live, self.theme.style(Role::Live), self.theme.line_marker())];
        if let Some(p) = self.pinned {
            series.insert(0, Curve::line("pinned", p, self.theme.pinned(), self.theme.mark('•', '.')));
        }
        let peaks = if self.peaks.is_empty() {
            String::new()
        } else {
            let v: Vec<String> = self.peaks.iter().take(3).map(|p| format!("{:+.3}", p.1)).collect();
            format!("p (Pa)  peaks {}", v.join(" "))
        };
        let y_title = if peaks.is_empty() { "p (Pa)" } else { peaks.as_str() };
        LinePlot {
            block: self.block,
            x_title: "ms after the direct arrival",
            y_title,
            series,
            empty: self.empty,
            theme: self.theme,
            y_zero: true,
            x_bounds: None,
            y_bounds: None,
            legend: self.pinned.is_some(),
        }
        .render(area, buf);
    }
}
