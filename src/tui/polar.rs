//! Directivity polar: SPL against θ at the current r, drawn as a polar curve on a canvas.
//! θ is measured from the plate's normal (up on screen); the radius is the level above a floor
//! 40 dB under the loudest direction's round 10 dB, with rings every 10 dB.
//!
//! No label is ever drawn over the curve: the rings' levels are a scale on their own row under
//! the canvas (where each ring crosses θ = 90°, which every source's range contains), the
//! normal's "θ 0" on a row above it and the listener's angle and level on the last row. The
//! curve, the rings (and walls) and the θ ray each have their own glyph, so they read apart
//! without colour and in ASCII.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Style};
use ratatui::widgets::canvas::{Context, Line as CLine, Points};
use ratatui::widgets::{Block, Paragraph, Widget};

use super::plot::stamp;
use super::theme::{Palette, Role};
use crate::units::sig;

/// Decibels shown between the floor and the loudest direction's round 10 dB.
const SPAN_DB: f64 = 40.0;

/// The panel's data: (θ in degrees, SPL in dB) over the valid range of the source type.
pub struct PolarView<'a> {
    pub block: Block<'a>,
    pub live: &'a [(f64, f64)],
    pub pinned: Option<&'a [(f64, f64)]>,
    pub theta_deg: f64,
    pub range_deg: (f64, f64),
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
        let deg = range.0 + (range.1 - range.0) * f64::from(i) / f64::from(n);
        let (x, y) = point(deg, r, 0.0);
        (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
    }
    let pad = 0.04 * r;
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
fn curve(ctx: &mut Context, pts: &[(f64, f64)], floor: f64) {
    for w in pts.windows(2) {
        let (a, b) = (point(w[0].0, w[0].1, floor), point(w[1].0, w[1].1, floor));
        ctx.draw(&CLine { x1: a.0, y1: a.1, x2: b.0, y2: b.1, color: Color::Reset });
    }
}

/// The column of canvas x-coordinate `x` in `area` with bounds `xb` (the canvas's mapping).
fn col(x: f64, xb: [f64; 2], area: Rect) -> u16 {
    let w = f64::from(area.width.max(1));
    let c = ((x - xb[0]) / (xb[1] - xb[0]) * (w - 1.0)).round().clamp(0.0, w - 1.0);
    area.x + c as u16
}

/// Where the polar's canvas is and what it spans: the canvas rectangle, its bounds and the
/// level of the centre (dB).
struct PolarLayout {
    canvas: Rect,
    xb: [f64; 2],
    yb: [f64; 2],
    floor: f64,
    top: f64,
}

/// Where the polar's canvas was drawn, for a click or a drag that sets θ there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PolarHit {
    canvas: Rect,
    xb: [f64; 2],
    yb: [f64; 2],
    range_deg: (f64, f64),
}

impl PolarHit {
    /// The angle θ (degrees, whole, inside the source's range) of the direction from the
    /// polar's centre to the cell at (x, y); None outside the canvas or at the centre itself.
    pub fn theta_at(&self, x: u16, y: u16) -> Option<f64> {
        let c = self.canvas;
        if x < c.x || y < c.y || x >= c.right() || y >= c.bottom() {
            return None;
        }
        // The cell's centre in the canvas's coordinates (y up; the canvas maps its bounds to
        // the cells' range as `col` does).
        let (w, h) = (f64::from(c.width.max(2)) - 1.0, f64::from(c.height.max(2)) - 1.0);
        let cx = self.xb[0] + f64::from(x - c.x) / w * (self.xb[1] - self.xb[0]);
        let cy = self.yb[1] - f64::from(y - c.y) / h * (self.yb[1] - self.yb[0]);
        if cx.hypot(cy) < 1e-9 {
            return None;
        }
        let deg = cx.atan2(cy).to_degrees().round();
        Some(deg.clamp(self.range_deg.0, self.range_deg.1))
    }
}

impl PolarView<'_> {
    /// Where the canvas is drawn when the panel fills `area` (None when it is not drawn).
    pub fn hit_area(&self, area: Rect) -> Option<PolarHit> {
        let l = self.layout(self.block.inner(area))?;
        Some(PolarHit { canvas: l.canvas, xb: l.xb, yb: l.yb, range_deg: self.range_deg })
    }

    /// The canvas between the "θ 0" row above and the scale and listener rows below; None when
    /// there is nothing to draw or no room.
    fn layout(&self, inner: Rect) -> Option<PolarLayout> {
        if self.live.is_empty() || inner.height < 5 || inner.width < 10 {
            return None;
        }
        let max = self.live.iter().chain(self.pinned.unwrap_or(&[])).map(|p| p.1).fold(f64::NEG_INFINITY, f64::max);
        if !max.is_finite() {
            return None;
        }
        let top = (max / 10.0).ceil() * 10.0;
        let canvas = Rect::new(inner.x, inner.y + 1, inner.width, inner.height - 3);
        let (xb, yb) = bounds(self.range_deg, SPAN_DB, canvas);
        Some(PolarLayout { canvas, xb, yb, floor: top - SPAN_DB, top })
    }

    /// The live curve alone, drawn where the full picture draws it (for checking that
    /// nothing covers it).
    pub fn curve_layer(&self, area: Rect) -> Buffer {
        let mut buf = Buffer::empty(area);
        if let Some(l) = self.layout(self.block.inner(area)) {
            let live = self.live;
            stamp(&mut buf, l.canvas, l.xb, l.yb, self.theme.line_marker(), Style::default(), |ctx| {
                curve(ctx, live, l.floor);
            });
        }
        buf
    }
}

impl Widget for PolarView<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let inner = self.block.inner(area);
        (&self.block).render(area, buf);
        let th = self.theme;
        let Some(PolarLayout { canvas, xb, yb, floor, top }) = self.layout(inner) else {
            let text = if self.live.is_empty() { "no impact: no sound" } else { "too small for the polar" };
            Paragraph::new(th.fit(&th.text(text), inner.width.into()).into_owned()).render(inner, buf);
            return;
        };
        let (lo, hi) = self.range_deg;
        let label = th.label();
        let ring_style = th.style(Role::Grid);
        // Rings every 10 dB and the walls (the range's ends and the normal).
        stamp(buf, canvas, xb, yb, th.mark('·', '.'), ring_style, |ctx| {
            let n = (((hi - lo) / 10.0).round() as usize).max(2);
            let ring: Vec<(f64, f64)> = (1..=4)
                .flat_map(|k| {
                    (0..=n).map(move |i| point(lo + (hi - lo) * i as f64 / n as f64, 10.0 * f64::from(k), 0.0))
                })
                .collect();
            ctx.draw(&Points { coords: &ring, color: Color::Reset });
            for deg in [0.0, lo, hi] {
                let (x, y) = point(deg, SPAN_DB, 0.0);
                ctx.draw(&CLine { x1: 0.0, y1: 0.0, x2: x, y2: y, color: Color::Reset });
            }
        });
        let theta = self.theta_deg;
        // The level at the listener's own θ, which the polar computes exactly; none while a
        // polar of another θ is still shown (never the nearest grid angle's level).
        let current = self.live.iter().find(|a| a.0 == theta).copied();
        let (tx, ty) = point(theta, current.map_or(top, |c| c.1), floor);
        stamp(buf, canvas, xb, yb, th.mark('•', '+'), th.style(Role::Listener), |ctx| {
            ctx.draw(&CLine { x1: 0.0, y1: 0.0, x2: tx, y2: ty, color: Color::Reset });
        });
        if let Some(p) = self.pinned {
            stamp(buf, canvas, xb, yb, th.mark('◇', '%'), th.pinned(), |ctx| curve(ctx, p, floor));
        }
        let live = self.live;
        stamp(buf, canvas, xb, yb, th.line_marker(), th.style(Role::Live), |ctx| {
            curve(ctx, live, floor);
        });
        // "θ 0" above the normal.
        let zero = th.text("θ 0°").into_owned();
        let zx = col(0.0, xb, canvas).saturating_sub(1).min(inner.right().saturating_sub(zero.len() as u16));
        buf.set_stringn(zx.max(inner.x), inner.y, &zero, inner.width as usize, label);
        // The ring scale: each ring's level where it crosses θ = 90°.
        let scale_y = canvas.bottom();
        let mut next_free = inner.x;
        for k in 0..=4 {
            let ring = format!("{}", floor + 10.0 * f64::from(k));
            let c = col(10.0 * f64::from(k), xb, canvas);
            let x = c.saturating_sub(ring.len() as u16 / 2).max(inner.x);
            if x < next_free || x + ring.len() as u16 > inner.right() {
                continue;
            }
            buf.set_stringn(x, scale_y, &ring, ring.len(), label);
            next_free = x + ring.len() as u16 + 1;
        }
        let unit = " dB";
        if next_free + 2 < inner.right() {
            buf.set_stringn(next_free.saturating_sub(1), scale_y, unit, (inner.right() - next_free) as usize, label);
        }
        // The listener: angle and level, with the ray's glyph.
        let ray = th.sym("•", "+");
        let text = match current {
            Some((_, db)) => format!("{ray} θ {}° → {} dB", sig(theta, 3), sig(db, 4)),
            None => format!("{ray} θ {}°", sig(theta, 3)),
        };
        let text = th.fit(&th.text(&text), inner.width.into()).into_owned();
        buf.set_stringn(inner.x, inner.bottom() - 1, &text, inner.width as usize, Style::default());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_click_reads_the_angle_from_the_centre() {
        let hit = PolarHit {
            canvas: Rect::new(0, 0, 41, 21),
            xb: [-20.0, 20.0],
            yb: [-20.0, 20.0],
            range_deg: (-90.0, 90.0),
        };
        assert_eq!(hit.theta_at(20, 0), Some(0.0), "straight up: the normal");
        assert_eq!(hit.theta_at(40, 10), Some(90.0), "right");
        assert_eq!(hit.theta_at(0, 10), Some(-90.0), "left");
        assert_eq!(hit.theta_at(40, 0), Some(45.0));
        assert_eq!(hit.theta_at(20, 20), Some(90.0), "straight down: clamped into the range");
        assert_eq!(hit.theta_at(20, 10), None, "the centre has no direction");
        assert_eq!(hit.theta_at(41, 0), None, "outside");
    }

    #[test]
    fn up_is_theta_zero_and_right_is_ninety() {
        let (x, y) = point(0.0, 20.0, 10.0);
        assert!(x.abs() < 1e-12 && (y - 10.0).abs() < 1e-12);
        let (x, y) = point(90.0, 20.0, 10.0);
        assert!((x - 10.0).abs() < 1e-12 && y.abs() < 1e-9);
        assert_eq!(point(0.0, 5.0, 10.0), (0.0, 0.0));
    }
}
