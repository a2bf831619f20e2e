//! A line plot shared by the waveform and history panels: series of (x, y) points on a
//! ratatui `Chart` with bounds that fit the data and labelled axes.

use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Rect};
use ratatui::style::Style;
use ratatui::symbols::Marker;
use ratatui::text::Span;
use ratatui::widgets::{Axis, Block, Chart, Dataset, GraphType, LegendPosition, Paragraph, Widget};

use super::theme::Palette;
use crate::units::sig;

/// One curve.
pub struct Curve<'a> {
    pub name: &'a str,
    pub data: &'a [(f64, f64)],
    pub style: Style,
    pub marker: Marker,
}

/// A line plot with a title, axis titles and a message shown when there is nothing to plot.
pub struct LinePlot<'a> {
    pub title: &'a str,
    pub x_title: &'a str,
    pub y_title: &'a str,
    pub series: Vec<Curve<'a>>,
    pub empty: &'a str,
    pub focused: bool,
    pub theme: Palette,
    /// Draw the y = 0 line.
    pub y_zero: bool,
    /// Show the legend box (else the title names the curves).
    pub legend: bool,
}

/// The [min, max] of the values, widened a little; a degenerate range becomes ±1 around it.
pub fn fit_bounds(values: impl Iterator<Item = f64>, pad: f64) -> [f64; 2] {
    let (lo, hi) =
        values.filter(|v| v.is_finite()).fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
    if !lo.is_finite() {
        return [0.0, 1.0];
    }
    if hi - lo <= f64::EPSILON * lo.abs().max(1.0) {
        return [lo - 1.0, hi + 1.0];
    }
    let p = (hi - lo) * pad;
    [lo - p, hi + p]
}

/// Three labels: low, middle, high.
pub fn labels(b: [f64; 2]) -> Vec<Span<'static>> {
    let mid = 0.5 * (b[0] + b[1]);
    [b[0], mid, b[1]].iter().map(|v| Span::raw(short(*v))).collect()
}

/// A short number for an axis label.
fn short(v: f64) -> String {
    if v.abs() < 1e-12 {
        "0".into()
    } else if v.abs() >= 1e4 || v.abs() < 1e-3 {
        format!("{v:.1e}")
    } else {
        sig(v, 3)
    }
}

impl Widget for LinePlot<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let block = Block::bordered().title(format!(" {} ", self.title)).border_style(self.theme.focus(self.focused));
        let has_data = self.series.iter().any(|s| !s.data.is_empty());
        if !has_data {
            let inner = block.inner(area);
            block.render(area, buf);
            Paragraph::new(self.empty).render(inner, buf);
            return;
        }
        let xb = fit_bounds(self.series.iter().flat_map(|s| s.data.iter().map(|p| p.0)), 0.0);
        let mut yb = fit_bounds(self.series.iter().flat_map(|s| s.data.iter().map(|p| p.1)), 0.05);
        if self.y_zero {
            yb = [yb[0].min(0.0), yb[1].max(0.0)];
        }
        let zero = [(xb[0], 0.0), (xb[1], 0.0)];
        let mut sets: Vec<Dataset> = Vec::new();
        if self.y_zero {
            sets.push(
                Dataset::default()
                    .data(&zero)
                    .graph_type(GraphType::Line)
                    .marker(self.theme.marker())
                    .style(self.theme.pinned()),
            );
        }
        for s in &self.series {
            let d = Dataset::default().data(s.data).graph_type(GraphType::Line).marker(s.marker).style(s.style);
            sets.push(if s.name.is_empty() { d } else { d.name(s.name) });
        }
        Chart::new(sets)
            .block(block)
            .x_axis(Axis::default().title(self.x_title).bounds(xb).labels(labels(xb)))
            .y_axis(Axis::default().title(self.y_title).bounds(yb).labels(labels(yb)))
            .legend_position(self.legend.then_some(LegendPosition::TopRight))
            .hidden_legend_constraints((Constraint::Ratio(1, 3), Constraint::Ratio(1, 3)))
            .render(area, buf);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounds_handle_empty_flat_and_nan() {
        assert_eq!(fit_bounds(std::iter::empty(), 0.1), [0.0, 1.0]);
        assert_eq!(fit_bounds([2.0, 2.0].into_iter(), 0.1), [1.0, 3.0]);
        assert_eq!(fit_bounds([f64::NAN, 0.0, 10.0].into_iter(), 0.0), [0.0, 10.0]);
    }
}
