//! Displacement history x(t) of the main mass with and without the damper (Fig 9), drawn so
//! the damping shows at a glance: each curve's decay envelope (its positive cycle maxima X_k,
//! the points of Eq 27, as the engine's run found them) bold over the faint oscillation, and
//! the e line of Eq 27 through the first two maxima. The y axis spans the band of the peaks
//! (its ticks say so), where the envelopes part; the oscillation shows as it rises into it.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::widgets::{Block, Widget};

use super::plot::{fit_bounds, Curve, LinePlot};
use super::theme::{Palette, Role};

/// The panel's data: (t in s, x in cm) samples and maxima with and without the damper, and the
/// pinned design's.
pub struct HistoryView<'a> {
    pub block: Block<'a>,
    pub with_damper: &'a [(f64, f64)],
    pub without: &'a [(f64, f64)],
    /// The damped run's cycle maxima X_k (t in s, x in cm).
    pub maxima: &'a [(f64, f64)],
    /// The cycle maxima without the damper.
    pub free_maxima: &'a [(f64, f64)],
    /// The pinned design's maxima.
    pub pinned: Option<&'a [(f64, f64)]>,
    pub theme: Palette,
}

/// The panel's title, the longest that fits in `width` columns.
pub fn title(width: u16) -> &'static str {
    let options = [
        " x(t) of the main mass near its peaks: damper vs none ",
        " x(t) near its peaks: damper vs none ",
        " x(t) peaks: damper vs none ",
        " x(t) ",
    ];
    let w = usize::from(width).saturating_sub(2);
    options.iter().find(|t| t.chars().count() <= w).unwrap_or(&options[3])
}

/// The e line of Eq 27 through the first two maxima, from t1 to `t_end` (s, cm); empty with
/// fewer than two maxima.
pub fn e_line(maxima: &[(f64, f64)], t_end: f64) -> Vec<(f64, f64)> {
    let (Some(&(t1, x1)), Some(&(t2, x2))) = (maxima.first(), maxima.get(1)) else { return vec![] };
    if t2 <= t1 {
        return vec![];
    }
    let slope = (x2 - x1) / (t2 - t1);
    vec![(t1, x1), (t_end, x1 + slope * (t_end - t1))]
}

/// The y window (cm) that shows the peaks: from a little under the lowest maximum to a little
/// over the highest, so the two envelopes part visibly; the oscillation is seen where it rises
/// into the window. None without maxima.
pub fn window(maxima: &[(f64, f64)], free: &[(f64, f64)]) -> Option<[f64; 2]> {
    let xs = maxima.iter().chain(free).map(|p| p.1).filter(|x| x.is_finite());
    let (lo, hi) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| (a.min(x), b.max(x)));
    if !lo.is_finite() {
        return None;
    }
    let span = (hi - lo).max(0.1 * hi.abs()).max(1e-6);
    Some([lo - 0.8 * span, hi + 0.15 * span])
}

impl Widget for HistoryView<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let th = self.theme;
        let t_end = self.with_damper.last().map_or(0.0, |p| p.0);
        let e = e_line(self.maxima, t_end);
        let yb = window(self.maxima, self.free_maxima)
            .unwrap_or_else(|| fit_bounds(self.with_damper.iter().chain(self.without).map(|p| p.1), 0.05));
        let xb = fit_bounds(self.with_damper.iter().map(|p| p.0), 0.0);
        let mut series = vec![
            Curve::line("", self.without, th.behind(th.ink(Role::Grid)), th.mark('·', ':')),
            Curve::line("", self.with_damper, th.behind(th.ink(Role::Damper)), th.line_marker_faint()),
            Curve::line("e", &e, th.style(Role::Fit), th.mark('╌', '=')),
        ];
        if let Some(p) = self.pinned {
            series.push(Curve::line("pinned", p, th.pinned(), th.mark('◇', '%')).ranked(1));
        }
        // The legend keeps "damper" and "none" (the panel's point) before the others.
        series.push(Curve::line("none", self.free_maxima, th.style(Role::Alone), th.mark('○', 'o')).ranked(2));
        series.push(Curve::line("damper", self.maxima, th.style(Role::Damper), th.mark('●', '#')).ranked(3));
        LinePlot {
            block: self.block,
            x_title: "t (s)",
            y_title: "x (cm)",
            series,
            empty: "simulating…",
            theme: th,
            y_zero: false,
            x_bounds: Some(xb),
            y_bounds: Some(yb),
            legend: true,
        }
        .render(area, buf);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_e_line_goes_through_the_first_two_maxima() {
        let m = [(0.05, 6.9), (0.25, 6.8), (0.45, 6.75)];
        let l = e_line(&m, 2.05);
        assert_eq!(l[0], (0.05, 6.9));
        // Through (t2, X2): slope −0.5 cm/s.
        let at_t2 = l[0].1 + (l[1].1 - l[0].1) / (l[1].0 - l[0].0) * (0.25 - 0.05);
        assert!((at_t2 - 6.8).abs() < 1e-12);
        assert!(e_line(&m[..1], 2.0).is_empty());
    }
}
