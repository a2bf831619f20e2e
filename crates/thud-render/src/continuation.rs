//! The figures of continued orbit families (docs/model.md §6.8): `thud continue --svg/--pdf`,
//! the orbit's amplitude against the varied parameter with stable parts solid, unstable parts
//! dashed and the special points marked; and the same branches drawn over a bifurcation
//! diagram's samples (`thud bifurcation --branches N`), where each branch's x(kT) at each of
//! its orbit's periods is a curve through the simulated dots.

use super::svg::{self, param_label, Anchor, Axis, Frame, Look, Shape, Svg};
use crate::units::sig;
use thud_core::continuation::{Branch, BranchPoint, Special};

/// Colour of the stable parts (Okabe–Ito orange) and of the unstable ones (sky blue), apart
/// from the bifurcation diagram's blue and vermilion sweeps, its grey unsettled points and from
/// each other under red–green colour blindness (ΔE00 ≥ 12.5, the figure check's measure);
/// unstable parts are dashed as well.
pub const STABLE: &str = "#E69F00";
pub const UNSTABLE: &str = "#56B4E9";
/// Dash pattern of the unstable parts.
const DASH: &str = "6 4";
/// Colour of the special points' markers.
const SPECIAL: &str = "#000000";

/// Each kind of special point's marker and its legend's words.
fn special_look(kind: Special) -> (Shape, &'static str) {
    match kind {
        Special::Fold => (Shape::Triangle, "fold"),
        Special::PeriodDoubling => (Shape::Square, "period doubling"),
        Special::NeimarkSacker => (Shape::Diamond, "Neimark–Sacker"),
        Special::BranchPoint => (Shape::TriangleDown, "branch point"),
        Special::Grazing => (Shape::Cross, "grazing (impacts change)"),
    }
}

/// The kinds in the legend's order.
const KINDS: [Special; 5] =
    [Special::Fold, Special::PeriodDoubling, Special::NeimarkSacker, Special::BranchPoint, Special::Grazing];

/// The start of a branch list's second line (drawn indented).
const INDENT: &str = "\t";

/// The most branches the legend lists by range and orbit types.
const LISTED_BRANCHES: usize = 10;

/// A branch's stretches of one stability, each with the first point of the next so the line
/// is unbroken: (stable, points).
pub fn stretches(points: &[BranchPoint]) -> Vec<(bool, &[BranchPoint])> {
    let mut out = Vec::new();
    let mut start = 0;
    for i in 1..=points.len() {
        if i == points.len() || points[i].stable != points[start].stable {
            let end = (i + 1).min(points.len());
            out.push((points[start].stable, &points[start..end]));
            start = i;
        }
    }
    out
}

/// Draws `line(point)` of every branch as stable (solid) and unstable (dashed) stretches, and
/// returns whether any stretch of each kind was drawn.
fn draw_branches(
    svg: &mut Svg,
    frame: &Frame,
    branches: &[Branch],
    clip: &str,
    lines: impl Fn(&BranchPoint) -> Vec<f64>,
) -> (bool, bool) {
    let k = svg.scale();
    let (mut stable, mut unstable) = (false, false);
    for b in branches {
        for (is_stable, run) in stretches(&b.points) {
            // One line per sample index: a period-n orbit has n of them (only where every
            // point of the stretch has that many: a stretch changes period at a grazing).
            let n = run.iter().map(|p| lines(p).len()).min().unwrap_or(0);
            for j in 0..n {
                let px: Vec<(f64, f64)> = run.iter().map(|p| (frame.px(p.value), frame.py(lines(p)[j]))).collect();
                let (color, dash) = if is_stable { (STABLE, None) } else { (UNSTABLE, Some(DASH)) };
                svg.polyline(&px, color, 1.6 * k, dash, Some(clip));
            }
            if n > 0 {
                stable |= is_stable;
                unstable |= !is_stable;
            }
        }
    }
    (stable, unstable)
}

/// The legend's entries for the stretches and special points drawn, from `(x, y)` down; the
/// y after the last.
fn legend(svg: &mut Svg, (x, mut y): (f64, f64), drawn: (bool, bool), kinds: &[Special]) -> f64 {
    let k = svg.scale();
    let lines = [(drawn.0, STABLE, None, "stable orbit"), (drawn.1, UNSTABLE, Some(DASH), "unstable orbit")];
    for (_, color, dash, label) in lines.into_iter().filter(|l| l.0) {
        svg.line((x, y - 4.0 * k), (x + 24.0 * k, y - 4.0 * k), color, 1.6 * k, dash);
        svg.text(x + 30.0 * k, y, label, 11.0 * k, Anchor::Start, 0.0);
        y += 18.0 * k;
    }
    for kind in KINDS.iter().filter(|kd| kinds.contains(kd)) {
        let (shape, label) = special_look(*kind);
        svg.marker(shape, x + 12.0 * k, y - 4.0 * k, 4.0 * k, SPECIAL);
        svg.text(x + 30.0 * k, y, label, 11.0 * k, Anchor::Start, 0.0);
        y += 18.0 * k;
    }
    y
}

/// The special points of every branch as markers at (value, `y(point)`).
fn draw_specials(svg: &mut Svg, frame: &Frame, branches: &[Branch], y: impl Fn(f64) -> f64) -> Vec<Special> {
    let k = svg.scale();
    let mut kinds = Vec::new();
    for s in branches.iter().flat_map(|b| &b.specials) {
        let (cx, cy) = (frame.px(s.value), frame.py(y(s.amplitude_m)));
        let inside = (frame.left..=frame.left + frame.width).contains(&cx)
            && (frame.top..=frame.top + frame.height).contains(&cy);
        if inside {
            svg.marker(special_look(s.kind).0, cx, cy, 4.0 * k, SPECIAL);
            if !kinds.contains(&s.kind) {
                kinds.push(s.kind);
            }
        }
    }
    kinds
}

/// Each branch's range and orbit types, one or two lines each, for the legend; the lines left
/// out said with "…".
fn branch_list(branches: &[Branch], unit: &str) -> Vec<String> {
    let mut out = vec!["branches (orbits along each):".to_string()];
    for (i, b) in branches.iter().enumerate().take(LISTED_BRANCHES) {
        let (lo, hi) =
            b.points.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| (lo.min(p.value), hi.max(p.value)));
        let cut = if b.truncated() { ", cut by the work cap" } else { "" };
        out.push(format!("{}: {}–{} {unit}{cut}", i + 1, sig(lo, 4), sig(hi, 4)));
        let mut types: Vec<&str> = Vec::new();
        for p in &b.points {
            if !types.contains(&p.orbit.as_str()) {
                types.push(&p.orbit);
            }
        }
        let shown: Vec<&str> = types.iter().take(4).copied().collect();
        let more = if types.len() > shown.len() { ", …" } else { "" };
        out.push(format!("{INDENT}{}{more}", shown.join(", ")));
    }
    if branches.len() > LISTED_BRANCHES {
        out.push(format!("… and {} more (in the CSV)", branches.len() - LISTED_BRANCHES));
    }
    out
}

/// Room right of the frame for the legend (px before scaling).
const RIGHT: f64 = 250.0;

/// `thud continue`'s figure: each branch's amplitude (the largest |x| over its orbit, mm)
/// against the varied parameter, stable stretches solid, unstable ones dashed, the special
/// points marked; the legend lists each branch's range and orbit types.
pub fn continuation_svg(branches: &[Branch], title: &str, look: &Look) -> String {
    let mut svg = Svg::figure(look, (svg::WIDTH, svg::HEIGHT), title);
    let k = svg.scale();
    let (name, unit) = branches.first().map_or(("", ""), |b| (b.name.as_str(), b.unit.as_str()));
    let points = || branches.iter().flat_map(|b| &b.points);
    let x = Axis::fit(&param_label(name, unit), points().map(|p| p.value));
    let y = Axis::fit("largest |x| over the orbit, main mass (mm)", points().map(|p| p.amplitude_m * 1e3).chain([0.0]));
    let mut frame = Frame::standard(&svg, x, y, true);
    frame.width = svg.width() - frame.left - RIGHT * k;
    frame.draw(&mut svg, title);
    let drawn = draw_branches(&mut svg, &frame, branches, svg::CLIP, |p| vec![p.amplitude_m * 1e3]);
    let kinds = draw_specials(&mut svg, &frame, branches, |a| a * 1e3);
    let x0 = frame.left + frame.width + 12.0 * k;
    let mut y = legend(&mut svg, (x0, frame.top + 10.0 * k), drawn, &kinds) + 8.0 * k;
    for line in branch_list(branches, unit) {
        let (dx, line) = line.strip_prefix(INDENT).map_or((0.0, line.as_str()), |l| (12.0 * k, l));
        svg.text(x0 + dx, y, line, 10.0 * k, Anchor::Start, 0.0);
        y += 14.0 * k;
    }
    svg.finish()
}

/// Plot points (parameter, mm), lines apart by a NaN point.
pub type Line = Vec<(f64, f64)>;

/// Each branch's x(kT) (mm) against the parameter as plot lines, (stable, unstable): one line
/// per sample index of each stretch ([`stretches`]), the lines apart by a NaN point (a break).
/// The explorer's bifurcation view draws these.
#[must_use]
pub fn strobe_lines(branches: &[Branch]) -> (Line, Line) {
    let (mut stable, mut unstable) = (Vec::new(), Vec::new());
    for (is_stable, run) in branches.iter().flat_map(|b| stretches(&b.points)) {
        let into = if is_stable { &mut stable } else { &mut unstable };
        let n = run.iter().map(|p| p.strobe_m.len()).min().unwrap_or(0);
        for j in 0..n {
            into.extend(run.iter().map(|p| (p.value, p.strobe_m[j] * 1e3)));
            into.push((f64::NAN, f64::NAN));
        }
    }
    (stable, unstable)
}

/// The branches over a bifurcation diagram's strobe panel (`frame`, clip path `clip`): each
/// branch's x(kT) (mm) at each of its orbit's periods, stable solid, unstable dashed; their
/// legend entries from `at` down. Returns the y after the legend.
pub fn overlay(svg: &mut Svg, frame: &Frame, clip: &str, branches: &[Branch], at: (f64, f64)) -> f64 {
    let drawn = draw_branches(svg, frame, branches, clip, |p| p.strobe_m.iter().map(|x| x * 1e3).collect::<Vec<f64>>());
    legend(svg, at, drawn, &[])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(value: f64, stable: bool) -> BranchPoint {
        BranchPoint {
            value,
            amplitude_m: 0.01,
            stable,
            multiplier_abs_max: 0.5,
            impacts_per_orbit: 1,
            periods: 1,
            orbit: "1/1".into(),
            x_m: 0.0,
            v_m_s: 0.0,
            z_m: 0.0,
            zdot_m_s: 0.0,
            strobe_m: vec![0.0],
        }
    }

    /// Stretches of one stability meet: each ends at the next one's first point.
    #[test]
    fn stretches_split_where_stability_changes_and_join() {
        let pts: Vec<BranchPoint> =
            [true, true, false, false, true].iter().enumerate().map(|(i, &s)| point(i as f64, s)).collect();
        let runs = stretches(&pts);
        let shape: Vec<(bool, Vec<f64>)> =
            runs.iter().map(|(s, r)| (*s, r.iter().map(|p| p.value).collect())).collect();
        assert_eq!(shape, vec![(true, vec![0.0, 1.0, 2.0]), (false, vec![2.0, 3.0, 4.0]), (true, vec![4.0])]);
        assert!(stretches(&[]).is_empty());
    }
}
