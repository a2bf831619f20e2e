//! Directivity polar: SPL against θ at the current r, drawn as a polar curve on a Canvas.
//! θ is measured from the plate's normal (up on screen); the radius is the level above a floor
//! 30 dB under the loudest direction, with rings every 10 dB.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::Color;
use ratatui::widgets::canvas::{Canvas, Context, Line as CLine, Points};
use ratatui::widgets::{Block, Paragraph, Widget};

use super::theme::Palette;
use crate::units::sig;

/// Decibels shown between the floor and the loudest direction.
const SPAN_DB: f64 = 40.0;

/// The panel's data: (θ in degrees, SPL in dB) over the valid range of the source type.
pub struct PolarView<'a> {
    pub live: &'a [(f64, f64)],
    pub pinned: Option<&'a [(f64, f64)]>,
    pub theta_deg: f64,
    pub range_deg: (f64, f64),
    pub r_m: f64,
    pub focused: bool,
    pub theme: Palette,
}

/// Cartesian point of level `db` at angle `deg` above `floor`.
fn point(deg: f64, db: f64, floor: f64) -> (f64, f64) {
    let rho = (db - floor).max(0.0);
    let t = deg.to_radians();
    (rho * t.sin(), rho * t.cos())
}

/// Bounds that hold the arc of the valid angles (and the origin) at radius `r`, widened so a
/// circle looks round on cells about twice as tall as wide.
fn bounds(range: (f64, f64), r: f64, area: Rect) -> ([f64; 2], [f64; 2]) {
    let (mut x0, mut x1, mut y0, mut y1) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let n = 72;
    for i in 0..=n {
        let deg = range.0 + (range.1 - range.0) * i as f64 / n as f64;
        let (x, y) = point(deg, r, 0.0);
        (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
    }
    let pad = 0.08 * r;
    let (mut xb, mut yb) = ([x0 - pad, x1 + pad], [y0 - pad, y1 + pad]);
    let (w, h) = (f64::from(area.width.max(1)), 2.0 * f64::from(area.height.max(1)));
    let (sx, sy) = ((xb[1] - xb[0]) / w, (yb[1] - yb[0]) / h);
    if sx < sy {
        let extra = (sy * w - (xb[1] - xb[0])) / 2.0;
        xb = [xb[0] - extra, xb[1] + extra];
    } else {
        let extra = (sx * h - (yb[1] - yb[0])) / 2.0;
        yb = [yb[0] - extra, yb[1] + extra];
    }
    (xb, yb)
}

/// Draws a curve of (deg, dB) points as connected segments.
fn curve(ctx: &mut Context, pts: &[(f64, f64)], floor: f64, color: Color) {
    for w in pts.windows(2) {
        let (a, b) = (point(w[0].0, w[0].1, floor), point(w[1].0, w[1].1, floor));
        ctx.draw(&CLine { x1: a.0, y1: a.1, x2: b.0, y2: b.1, color });
    }
}

impl Widget for PolarView<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let title = format!(" SPL(θ) dB at r {} m ", sig(self.r_m, 3));
        let block = Block::bordered().title(title).border_style(self.theme.focus(self.focused));
        if self.live.is_empty() {
            let inner = block.inner(area);
            block.render(area, buf);
            Paragraph::new("no impact: no sound").render(inner, buf);
            return;
        }
        let max = self.live.iter().chain(self.pinned.unwrap_or(&[])).map(|p| p.1).fold(f64::NEG_INFINITY, f64::max);
        let top = (max / 10.0).ceil() * 10.0;
        let floor = top - SPAN_DB;
        let (xb, yb) = bounds(self.range_deg, SPAN_DB, block.inner(area));
        let color = |c: Color| if self.theme.color { c } else { Color::Reset };
        let marker = self.theme.marker();
        let theta = self.theta_deg;
        let current = self.live.iter().min_by(|a, b| (a.0 - theta).abs().total_cmp(&(b.0 - theta).abs())).copied();
        Canvas::default()
            .block(block)
            .marker(marker)
            .x_bounds(xb)
            .y_bounds(yb)
            .paint(|ctx| {
                // Rings every 10 dB, dotted so they do not read as curves.
                let (lo, hi) = self.range_deg;
                let ring: Vec<(f64, f64)> = (1..=4)
                    .flat_map(|k| {
                        let n = ((hi - lo) / 6.0).round() as usize;
                        (0..=n).map(move |i| point(lo + (hi - lo) * i as f64 / n.max(1) as f64, 10.0 * k as f64, 0.0))
                    })
                    .collect();
                ctx.draw(&Points { coords: &ring, color: color(Color::DarkGray) });
                // The walls / reference axes: the plate normal (θ = 0) and the range's ends.
                for deg in [0.0, lo, hi] {
                    let (x, y) = point(deg, floor + SPAN_DB, floor);
                    ctx.draw(&CLine { x1: 0.0, y1: 0.0, x2: x, y2: y, color: color(Color::DarkGray) });
                }
                ctx.layer();
                if let Some(p) = self.pinned {
                    ctx.marker(self.theme.pinned_marker());
                    curve(ctx, p, floor, color(Color::DarkGray));
                    ctx.layer();
                    ctx.marker(marker);
                }
                curve(ctx, self.live, floor, color(Color::Cyan));
                let (tx, ty) = point(theta, current.map_or(floor + SPAN_DB, |c| c.1), floor);
                ctx.draw(&CLine { x1: 0.0, y1: 0.0, x2: tx, y2: ty, color: color(Color::Yellow) });
                let (nx, ny) = point(0.0, floor + SPAN_DB, floor);
                ctx.print(nx, ny, "0°");
                for k in 1..=4 {
                    let (x, y) = point(hi.min(90.0), floor + 10.0 * k as f64, floor);
                    ctx.print(x, y, format!("{}", floor + 10.0 * k as f64));
                }
                let label = match current {
                    Some((_, db)) => format!("θ {}° {} dB", sig(theta, 3), sig(db, 4)),
                    None => format!("θ {}°", sig(theta, 3)),
                };
                ctx.print(tx, ty, label);
            })
            .render(area, buf);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn up_is_theta_zero_and_right_is_ninety() {
        let (x, y) = point(0.0, 20.0, 10.0);
        assert!(x.abs() < 1e-12 && (y - 10.0).abs() < 1e-12);
        let (x, y) = point(90.0, 20.0, 10.0);
        assert!((x - 10.0).abs() < 1e-12 && y.abs() < 1e-9);
        assert_eq!(point(0.0, 5.0, 10.0), (0.0, 0.0));
    }
}
