//! Figures of studies: `thud sweep --vary` over one parameter (each metric against it) or two
//! (a heat map of each metric with its colour bar), and the ensemble chart of `thud sweep
//! --ensemble N` (per cell, the median of each metric and the width of its p10–p90 band).
//!
//! The heat maps use viridis: its lightness rises from one end to the other, so the order of
//! the values reads without hue (in grey, and with red–green colour blindness).

use super::svg::{self, draw_series_clipped, minus, Anchor, Axis, Frame, Look, Series, Shape, Style, Svg};
use crate::ensemble::{EnsembleChart, Percentiles};
use crate::study::{Axis as StudyAxis, Study, StudyCell};
use crate::units::short;

/// Viridis at nine even stops (matplotlib's), from the lowest value to the highest.
const VIRIDIS: [(u8, u8, u8); 9] = [
    (0x44, 0x01, 0x54),
    (0x48, 0x28, 0x78),
    (0x3e, 0x49, 0x89),
    (0x31, 0x68, 0x8e),
    (0x26, 0x82, 0x8e),
    (0x1f, 0x9e, 0x89),
    (0x35, 0xb7, 0x79),
    (0x6e, 0xce, 0x58),
    (0xfd, 0xe7, 0x25),
];

/// The fill of a cell without a value (no impact, so no SPLmax or e).
pub const NO_VALUE: &str = "#d9d9d9";

/// The colour of fraction `f` (0 to 1, clamped) of the scale.
#[must_use]
pub fn viridis(f: f64) -> String {
    let f = if f.is_finite() { f.clamp(0.0, 1.0) } else { 0.0 };
    let k = ((f * 8.0).floor() as usize).min(7);
    let (a, b, t) = (VIRIDIS[k], VIRIDIS[k + 1], f * 8.0 - k as f64);
    let mix = |p: u8, q: u8| (f64::from(p) + (f64::from(q) - f64::from(p)) * t).round() as u8;
    format!("#{:02x}{:02x}{:02x}", mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// One quantity drawn: its label (with unit) and its value in a study's cell.
struct Metric {
    label: &'static str,
    /// Its short name (`e`).
    name: &'static str,
    value: fn(&StudyCell) -> Option<f64>,
}

/// The metrics a study's figure draws: damping, loudness and, with a force, the steady amplitude.
fn metrics(s: &Study) -> Vec<Metric> {
    let mut m = vec![
        Metric { label: "damping inclination e (cm/s)", name: "e", value: |c| c.metrics.inclination_cm_s },
        Metric { label: "SPLmax (dB re 20 µPa)", name: "SPLmax", value: |c| c.metrics.spl_max_db },
    ];
    if s.cells.iter().any(|c| c.steady.is_some()) {
        m.push(Metric {
            label: "steady amplitude (mm)",
            name: "a steady amplitude",
            value: |c| c.steady.as_ref().map(|st| st.amplitude_m * 1e3),
        });
    }
    m
}

/// `v0 (m/s)`.
fn axis_label(a: &StudyAxis) -> String {
    if a.unit.is_empty() {
        a.name.clone()
    } else {
        format!("{} ({})", a.name, a.unit)
    }
}

/// Room right of each panel (px at scale 1): a colour bar with its ticks, or a legend.
const RIGHT: f64 = 190.0;
/// Room above each panel for its caption (px at scale 1).
const CAPTION: f64 = 24.0;

/// The frames of `n` panels stacked on `svg`, each with a caption line above it.
fn stacked(svg: &Svg, n: usize, x: &Axis, ys: &[Axis]) -> Vec<Frame> {
    let k = svg.scale();
    let top = Frame::top_margin(svg);
    let gap = Frame::bottom_margin(svg) + CAPTION * k;
    let h = ((svg.height() - top - n as f64 * gap) / n.max(1) as f64).max(40.0 * k);
    let left = Frame::left_margin(svg);
    let width = svg.width() - left - RIGHT * k;
    (0..n)
        .map(|i| Frame {
            left,
            top: top + CAPTION * k + i as f64 * (h + gap),
            width,
            height: h,
            x: x.clone(),
            y: ys[i].clone(),
        })
        .collect()
}

/// A panel's caption, above its frame on the left.
fn caption(svg: &mut Svg, frame: &Frame, text: &str) {
    let k = svg.scale();
    svg.text(frame.left, frame.top - 8.0 * k, &minus(text), 13.0 * k, Anchor::Start, 0.0);
}

/// The default height of a figure of `n` stacked panels (px).
fn height(n: usize) -> f64 {
    50.0 + n as f64 * (CAPTION + 70.0 + 190.0)
}

/// The title of a study's figure: what varies, over its whole range ("Study over v0 1–3 m/s ×
/// c1 10–20 N·s/m"), the command line's and Python's.
#[must_use]
pub fn study_title(s: &Study) -> String {
    let range = |a: &StudyAxis| {
        let (lo, hi) = a.values.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| (l.min(*v), h.max(*v)));
        let unit = if a.unit.is_empty() { String::new() } else { format!(" {}", a.unit) };
        if hi > lo {
            format!("{} {}–{}{unit}", a.name, short(lo), short(hi))
        } else {
            format!("{} {}{unit}", a.name, short(lo))
        }
    };
    let over: Vec<String> = s.axes.iter().map(range).collect();
    format!("Study over {}", over.join(" × "))
}

/// The figure of a study over one or two parameters; None over more (or none).
#[must_use]
pub fn study(s: &Study, title: &str, look: &Look) -> Option<String> {
    match s.axes.len() {
        1 => Some(one_axis(s, title, look)),
        2 => Some(two_axes(s, title, look)),
        _ => None,
    }
}

/// Each metric against the one varied parameter, a panel each. A forced cell whose steady
/// state is not settled (or was cut short) is marked apart on the amplitude's panel.
fn one_axis(s: &Study, title: &str, look: &Look) -> String {
    let ms = metrics(s);
    let mut svg = Svg::figure(look, (svg::WIDTH, height(ms.len())), title);
    let xs: Vec<f64> = s.cells.iter().map(|c| c.values[0]).collect();
    let x = Axis::fit(&axis_label(&s.axes[0]), xs.iter().copied());
    let ys: Vec<Axis> = ms
        .iter()
        .map(|m| {
            Axis::fit(
                m.label,
                s.cells.iter().filter_map(|c| (m.value)(c)).chain(if m.label.starts_with("steady") {
                    Some(0.0)
                } else {
                    None
                }),
            )
        })
        .collect();
    let frames = stacked(&svg, ms.len(), &x, &ys);
    for (i, (m, frame)) in ms.iter().zip(&frames).enumerate() {
        let clip = format!("panel{i}");
        frame.draw_panel(&mut svg, (i == 0).then_some(title), &clip);
        let pts: Vec<(f64, f64)> = s.cells.iter().map(|c| (c.values[0], (m.value)(c).unwrap_or(f64::NAN))).collect();
        let mut series = vec![Series::new("each value's run", pts, Style::LineMarkers)
            .colored(svg::PALETTE[0].to_string())
            .shaped(Shape::Circle)
            .dashed(None)];
        let unsettled: Vec<(f64, f64)> = s
            .cells
            .iter()
            .filter(|c| c.steady.as_ref().is_some_and(|st| st.verdict.is_marked()))
            .filter_map(|c| Some((c.values[0], (m.value)(c)?)))
            .collect();
        if !unsettled.is_empty() {
            series.push(
                Series::new("not settled", unsettled, Style::Markers).shaped(Shape::Cross).colored("#000000".into()),
            );
        }
        let none = s.cells.iter().filter(|c| (m.value)(c).is_none()).count();
        draw_series_clipped(&mut svg, frame, &series, &clip);
        if none > 0 {
            let k = svg.scale();
            let row = if series.len() > 1 { 2.0 } else { 0.0 };
            let text = format!("{none} value{} without {}", if none == 1 { "" } else { "s" }, m.name);
            let y = frame.top + (10.0 + 20.0 * row) * k;
            svg.text(frame.left + frame.width + 12.0 * k, y, &text, 11.0 * k, Anchor::Start, 0.0);
        }
    }
    svg.finish()
}

/// Each metric as a heat map over the two varied parameters (the first across, the second up),
/// a panel each with its colour bar.
fn two_axes(s: &Study, title: &str, look: &Look) -> String {
    let ms = metrics(s);
    let (a, b) = (&s.axes[0], &s.axes[1]);
    let n = b.values.len();
    let grid = |m: &Metric| {
        let value = m.value;
        move |i: usize, j: usize| s.cells.get(i * n + j).and_then(value)
    };
    let maps: Vec<HeatMap> =
        ms.iter().map(|m| HeatMap { caption: m.label.to_string(), value: Box::new(grid(m)) }).collect();
    heat_maps(&a.values, &b.values, (&axis_label(a), &axis_label(b)), &maps, title, look)
}

/// One heat map of a figure: its caption and its value at (across, up).
struct HeatMap<'a> {
    caption: String,
    value: Box<dyn Fn(usize, usize) -> Option<f64> + 'a>,
}

/// Cell edges (axis units) around grid values: midpoints, and half a step outside the ends.
fn edges(values: &[f64]) -> Vec<f64> {
    match values {
        [] => vec![],
        [v] => {
            let w = 0.05 * v.abs().max(1e-9);
            vec![v - w, v + w]
        }
        _ => {
            let mut e = vec![values[0] - 0.5 * (values[1] - values[0])];
            e.extend(values.windows(2).map(|w| 0.5 * (w[0] + w[1])));
            let k = values.len() - 1;
            e.push(values[k] + 0.5 * (values[k] - values[k - 1]));
            e
        }
    }
}

/// Heat maps stacked over `xs` × `ys`, each with a colour bar of its own range.
fn heat_maps(xs: &[f64], ys: &[f64], labels: (&str, &str), maps: &[HeatMap], title: &str, look: &Look) -> String {
    let mut svg = Svg::figure(look, (svg::WIDTH, height(maps.len())), title);
    let (ex, ey) = (edges(xs), edges(ys));
    let (x0, x1) = (ex[0].min(ex[ex.len() - 1]), ex[0].max(ex[ex.len() - 1]));
    let (y0, y1) = (ey[0].min(ey[ey.len() - 1]), ey[0].max(ey[ey.len() - 1]));
    let x = Axis::fixed(labels.0, x0, x1);
    let yaxes: Vec<Axis> = maps.iter().map(|_| Axis::fixed(labels.1, y0, y1)).collect();
    let frames = stacked(&svg, maps.len(), &x, &yaxes);
    let k = svg.scale();
    for (n, (map, frame)) in maps.iter().zip(&frames).enumerate() {
        let values: Vec<f64> =
            (0..xs.len()).flat_map(|i| (0..ys.len()).filter_map(move |j| (map.value)(i, j))).collect();
        let (lo, hi) = values
            .iter()
            .filter(|v| v.is_finite())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &v| (l.min(v), h.max(v)));
        frame.grid(&mut svg);
        let mut missing = false;
        for i in 0..xs.len() {
            for j in 0..ys.len() {
                let value = (map.value)(i, j).filter(|v| v.is_finite());
                missing |= value.is_none();
                let fill = value.map_or_else(
                    || NO_VALUE.to_string(),
                    |v| viridis(if hi > lo { (v - lo) / (hi - lo) } else { 0.5 }),
                );
                let (px0, px1) = (frame.px(ex[i]), frame.px(ex[i + 1]));
                let (py0, py1) = (frame.py(ey[j + 1]), frame.py(ey[j]));
                let (l, t) = (px0.min(px1), py0.min(py1));
                svg.rect(l, t, (px1 - px0).abs(), (py1 - py0).abs(), &fill, None);
            }
        }
        frame.axes(&mut svg, (n == 0).then_some(title), &format!("map{n}"));
        caption(&mut svg, frame, &map.caption);
        let bx = frame.left + frame.width + 15.0 * k;
        let mut bottom = frame.top;
        if lo.is_finite() {
            let bar_h = frame.height.min(200.0 * k);
            color_bar(&mut svg, bx, frame.top, bar_h, (lo, hi));
            bottom = frame.top + bar_h;
        }
        if missing {
            let y = bottom + 18.0 * k;
            svg.rect(bx, y - 9.0 * k, 18.0 * k, 10.0 * k, NO_VALUE, Some("#333333"));
            svg.text(bx + 24.0 * k, y, "no value (no impact)", 11.0 * k, Anchor::Start, 0.0);
        }
    }
    svg.finish()
}

/// A continuous colour bar of [`viridis`] for values `lo..hi` (top: `hi`), `height` px tall at
/// (`x`, `top`), with ticks at round values.
fn color_bar(svg: &mut Svg, x: f64, top: f64, height: f64, (lo, hi): (f64, f64)) {
    const SLICES: usize = 48;
    let s = svg.scale();
    let h = height / SLICES as f64;
    for k in 0..SLICES {
        let f = 1.0 - (k as f64 + 0.5) / SLICES as f64;
        svg.rect(x, top + h * k as f64, 18.0 * s, h + 0.5, &viridis(f), None);
    }
    svg.rect(x, top, 18.0 * s, height, "none", Some("black"));
    let ticks = if hi > lo { Axis::fixed("", lo, hi).ticks() } else { vec![(lo, short(lo))] };
    for (v, text) in ticks {
        let y = if hi > lo { top + (1.0 - (v - lo) / (hi - lo)) * height } else { top + height / 2.0 };
        svg.line((x + 18.0 * s, y), (x + 23.0 * s, y), "black", s, None);
        svg.text(x + 26.0 * s, y + 4.0 * s, &minus(&text), 11.0 * s, Anchor::Start, 0.0);
    }
}

/// The ensemble chart: per cell of impact mass × gap, the median of the runs' damping and
/// SPLmax, and the width of each one's p10–p90 band (how much the ball's start matters).
#[must_use]
pub fn ensemble_chart(e: &EnsembleChart, title: &str, look: &Look) -> String {
    let xs: Vec<f64> = e.masses_kg.iter().map(|m| m * 1e3).collect();
    let ys: Vec<f64> = e.gaps_m.iter().map(|g| g * 1e2).collect();
    let spread = |pick: fn(&crate::ensemble::Spread) -> &Percentiles, band: bool| {
        move |i: usize, j: usize| {
            let p = pick(&e.cell(i, j)?.ensemble.spread);
            if band {
                Some(p.p90? - p.p10?)
            } else {
                p.median
            }
        }
    };
    let runs = e.runs;
    let maps = [
        HeatMap {
            caption: format!("median damping inclination e of the {runs} runs (cm/s)"),
            value: Box::new(spread(|s| &s.inclination_cm_s, false)),
        },
        HeatMap {
            caption: "spread of e: p90 − p10 (cm/s)".into(),
            value: Box::new(spread(|s| &s.inclination_cm_s, true)),
        },
        HeatMap {
            caption: format!("median SPLmax of the {runs} runs (dB re 20 µPa)"),
            value: Box::new(spread(|s| &s.spl_max_db, false)),
        },
        HeatMap {
            caption: "spread of SPLmax: p90 − p10 (dB)".into(),
            value: Box::new(spread(|s| &s.spl_max_db, true)),
        },
    ];
    heat_maps(&xs, &ys, ("impact mass m (g)", "total clearance d (cm)"), &maps, title, look)
}

/// The base design in a figure's title: what the chart holds fixed.
pub fn short_base(d: &crate::design::Design) -> String {
    let p = &d.damper;
    let mut s = format!("v0 {} m/s", short(p.v0_m_s));
    if p.force_n != 0.0 {
        s += &format!(", F0 {} N at {} Hz", short(p.force_n), short(p.freq_hz));
    }
    s
}

/// The title of the ensemble chart `e` of the base design `d` (`thud sweep --ensemble N --svg`,
/// and Python's `Chart.to_svg` of an ensemble).
pub fn ensemble_title(e: &EnsembleChart, d: &crate::design::Design) -> String {
    format!("Ensemble chart: {} runs a cell over impact mass × gap — {}", e.runs, short_base(d))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Viridis's lightness rises all the way: the order of values reads without hue.
    #[test]
    fn viridis_grows_lighter_from_end_to_end() {
        let luminance = |hex: &str| {
            let c = |i: usize| f64::from(u8::from_str_radix(&hex[i..i + 2], 16).unwrap()) / 255.0;
            0.2126 * c(1) + 0.7152 * c(3) + 0.0722 * c(5)
        };
        let l: Vec<f64> = (0..=40).map(|i| luminance(&viridis(f64::from(i) / 40.0))).collect();
        assert!(l.windows(2).all(|w| w[1] > w[0]), "{l:?}");
        assert_eq!(viridis(0.0), "#440154");
        assert_eq!(viridis(1.0), "#fde725");
        assert_eq!(viridis(f64::NAN), viridis(0.0));
    }

    #[test]
    fn cell_edges_are_midpoints_and_half_steps() {
        assert_eq!(edges(&[1.0, 2.0, 4.0]), [0.5, 1.5, 3.0, 5.0]);
        let one = edges(&[2.0]);
        assert!(one[0] < 2.0 && one[1] > 2.0);
    }
}
