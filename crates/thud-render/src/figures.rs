//! The figures thud exports as SVG: pressure waveform, directivity, time history, restitution
//! curve, design chart, the Fig 17 zone chart, and a figure for each reproduced paper table.
//! Inputs are SI; the axes are labelled in the units people read (ms, cm, g, dB).

use crate::acoustics::{Field, Levels};
use crate::damper::{free_response, DamperParams, Run};
use crate::design::{Chart, Thresholds, Zone};
use crate::paper::{Table, Value};
use crate::units::{short, sig};

use super::svg::{
    draw_series_clipped, legend, line_plot, minus, nice_step, series_color, series_dash, Anchor, Axis, Frame, Look,
    Series, Shape, Style, Svg, HEIGHT, WIDTH,
};

/// The pressure of one impact against time after the direct wave arrives (ms, Pa).
pub fn waveform(field: &Field, points: usize, title: &str, look: &Look) -> String {
    let (t, p) = field.waveform(points);
    let t0 = field.arrival_s();
    let pts: Vec<(f64, f64)> = t.iter().zip(&p).map(|(&ti, &pi)| ((ti - t0) * 1e3, pi)).collect();
    let x = Axis::fit("time after the direct arrival (ms)", pts.iter().map(|p| p.0));
    let y = Axis::fit("sound pressure p (Pa)", pts.iter().map(|p| p.1).chain([0.0]));
    line_plot(title, look, x, y, &[Series::new("p", pts, Style::Line)])
}

/// SPL (rms over τ) and peak level against the observer angle θ: `points` are (θ in rad, levels).
pub fn directivity(points: &[(f64, Levels)], title: &str, look: &Look) -> String {
    let spl: Vec<(f64, f64)> = points.iter().map(|(th, l)| (th.to_degrees(), l.spl_db)).collect();
    let peak: Vec<(f64, f64)> = points.iter().map(|(th, l)| (th.to_degrees(), l.spl_peak_db)).collect();
    let x = Axis::fit("observer angle θ from the plate normal (deg)", spl.iter().map(|p| p.0));
    let y = Axis::fit("level (dB re 20 µPa)", spl.iter().chain(&peak).map(|p| p.1));
    line_plot(
        title,
        look,
        x,
        y,
        &[Series::new("SPL, rms over τ", spl, Style::LineMarkers), Series::new("peak level", peak, Style::Dashed)],
    )
}

/// The main mass's displacement with the damper and without it (cm against s).
pub fn history(run: &Run, damper: &DamperParams, title: &str, look: &Look) -> String {
    let with: Vec<(f64, f64)> = run.history.iter().map(|h| (h.t_s, h.x_m * 1e2)).collect();
    let without: Vec<(f64, f64)> = run.history.iter().map(|h| (h.t_s, free_response(damper, h.t_s) * 1e2)).collect();
    let x = Axis::fit("time t (s)", with.iter().map(|p| p.0));
    let y = Axis::fit("main-mass displacement x (cm)", with.iter().chain(&without).map(|p| p.1));
    line_plot(
        title,
        look,
        x,
        y,
        &[Series::new("with the damper", with, Style::Line), Series::new("without the damper", without, Style::Dashed)],
    )
}

/// Coefficient of restitution against impact mass (Fig 13): `curve` is (m in kg, R).
pub fn restitution(curve: &[(f64, f64)], title: &str, look: &Look) -> String {
    let pts: Vec<(f64, f64)> = curve.iter().map(|&(m, r)| (m * 1e3, r)).collect();
    let x = Axis::fit("impact mass m (g)", pts.iter().map(|p| p.0));
    let y = Axis::fit("coefficient of restitution R, rebound ÷ impact speed (1)", pts.iter().map(|p| p.1));
    line_plot(title, look, x, y, &[Series::new("R", pts, Style::LineMarkers)])
}

/// Fill colour of a zone (none: grey). Colours of the Okabe–Ito palette (zone 2's yellow
/// lightened), chosen so every pair, the grey included, stays apart for deuteranopes and
/// protanopes (CIEDE2000 ΔE ≥ 18 after the Machado et al. 2009 simulation; tests/cvd.rs) and a
/// black zone digit reads on each (contrast ≥ 4.5:1). The digit in every cell says the zone
/// without colour too.
pub fn zone_color(zone: Option<Zone>) -> &'static str {
    match zone {
        Some(Zone::NoisyWeak) => "#D55E00",
        Some(Zone::NoisyStrong) => "#F5ED84",
        Some(Zone::QuietStrong) => "#009E73",
        Some(Zone::QuietWeak) => "#56B4E9",
        None => "#DDDDDD",
    }
}

/// Every zone colour of the cell charts, the no-impact grey last (for tests/cvd.rs).
pub fn zone_colors() -> [&'static str; 5] {
    [
        zone_color(Some(Zone::NoisyWeak)),
        zone_color(Some(Zone::NoisyStrong)),
        zone_color(Some(Zone::QuietStrong)),
        zone_color(Some(Zone::QuietWeak)),
        zone_color(None),
    ]
}

/// Every zone colour of Fig 17's points, the no-zone grey last (for tests/cvd.rs).
pub fn zone_dot_colors() -> [&'static str; 5] {
    [
        darker(Some(Zone::NoisyWeak)),
        darker(Some(Zone::NoisyStrong)),
        darker(Some(Zone::QuietStrong)),
        darker(Some(Zone::QuietWeak)),
        darker(None),
    ]
}

/// The marker shape of a zone's points on Fig 17 (zone 1 circle, 2 square, 3 triangle, 4
/// diamond, no zone a cross): the zone reads without colour.
pub fn zone_shape(zone: Option<Zone>) -> Shape {
    match zone {
        Some(Zone::NoisyWeak) => Shape::Circle,
        Some(Zone::NoisyStrong) => Shape::Square,
        Some(Zone::QuietStrong) => Shape::Triangle,
        Some(Zone::QuietWeak) => Shape::Diamond,
        None => Shape::Cross,
    }
}

const ZONES: [Zone; 4] = [Zone::NoisyWeak, Zone::NoisyStrong, Zone::QuietStrong, Zone::QuietWeak];

/// Cell edges (axis units) around grid values: midpoints, and half a step outside the ends.
pub fn edges(values: &[f64]) -> Vec<f64> {
    match values {
        [] => vec![],
        [v] => vec![v - 0.5 * v.abs().max(1e-9) * 0.1, v + 0.5 * v.abs().max(1e-9) * 0.1],
        _ => {
            let mut e = vec![values[0] - 0.5 * (values[1] - values[0])];
            e.extend(values.windows(2).map(|w| 0.5 * (w[0] + w[1])));
            let k = values.len() - 1;
            e.push(values[k] + 0.5 * (values[k] - values[k - 1]));
            e
        }
    }
}

/// Draws grid cells (`xs` × `ys` in axis units) with fill colours and labels from `cell(i, j)`,
/// over the frame's grid (drawn first) and under its axes: no grid line crosses a cell's digit.
fn draw_cells(
    svg: &mut Svg,
    frame: &Frame,
    title: &str,
    xs: &[f64],
    ys: &[f64],
    cell: impl Fn(usize, usize) -> (String, String),
) {
    frame.grid(svg);
    cells(svg, frame, xs, ys, cell);
    frame.axes(svg, Some(title), super::svg::CLIP);
}

/// The cells of a cell chart alone (no grid, no axes): for a panel that draws its own.
pub fn cells(svg: &mut Svg, frame: &Frame, xs: &[f64], ys: &[f64], cell: impl Fn(usize, usize) -> (String, String)) {
    let (ex, ey) = (edges(xs), edges(ys));
    let most = 14.0 * svg.scale();
    let font =
        ((frame.width / xs.len().max(1) as f64).min(frame.height / ys.len().max(1) as f64) * 0.5).clamp(6.0, most);
    for j in 0..ys.len() {
        for i in 0..xs.len() {
            let (fill, label) = cell(i, j);
            let (x0, x1) = (frame.px(ex[i]), frame.px(ex[i + 1]));
            let (y0, y1) = (frame.py(ey[j + 1]), frame.py(ey[j]));
            svg.rect(x0, y0, x1 - x0, y1 - y0, &fill, Some("white"));
            if !label.is_empty() {
                svg.text(0.5 * (x0 + x1), 0.5 * (y0 + y1) + 0.35 * font, &label, font, Anchor::Middle, 0.0);
            }
        }
    }
}

/// The design chart: impact mass × gap cells coloured by zone, with the zone number in each.
pub fn design_chart(chart: &Chart, title: &str, look: &Look) -> String {
    let xs: Vec<f64> = chart.masses_kg.iter().map(|m| m * 1e3).collect();
    let ys: Vec<f64> = chart.gaps_m.iter().map(|g| g * 1e2).collect();
    let (ex, ey) = (edges(&xs), edges(&ys));
    let x = Axis::fixed("impact mass m (g)", ex[0], ex[ex.len() - 1]);
    let y = Axis::fixed("total clearance d (cm)", ey[0], ey[ey.len() - 1]);
    let mut svg = Svg::figure(look, (WIDTH, HEIGHT), title);
    let frame = Frame::standard(&svg, x, y, true);
    draw_cells(&mut svg, &frame, title, &xs, &ys, |i, j| {
        let zone = chart.cell(i, j).and_then(|c| c.metrics.zone);
        (zone_color(zone).into(), zone.map_or(String::new(), |z| z.number().to_string()))
    });
    zone_legend(&mut svg, &frame, &chart.thresholds, false);
    svg.finish()
}

/// The legend of the four zones, with the thresholds: cell swatches for a cell chart, or the
/// dots of Fig 17 (`dots`) in their colours.
pub fn zone_legend(svg: &mut Svg, frame: &Frame, t: &Thresholds, dots: bool) {
    let labels: Vec<String> = ZONES.iter().map(|z| format!("{} {}", z.number(), z.describe())).collect();
    let mut entries: Vec<(&str, &str)> = ZONES
        .iter()
        .zip(&labels)
        .map(|(z, l)| (if dots { darker(Some(*z)) } else { zone_color(Some(*z)) }, l.as_str()))
        .collect();
    let k = svg.scale();
    if dots {
        let x = frame.left + frame.width + 15.0 * k;
        for (row, (zone, (color, label))) in ZONES.iter().zip(&entries).enumerate() {
            let y = frame.top + (10.0 + 20.0 * row as f64) * k;
            svg.marker(zone_shape(Some(*zone)), x + 9.0 * k, y - 4.0 * k, 4.0 * k, color);
            svg.text(x + 24.0 * k, y, label, 11.0 * k, Anchor::Start, 0.0);
        }
    } else {
        entries.push((zone_color(None), "no impact"));
        legend(svg, frame, &entries);
    }
    let x = frame.left + frame.width + 15.0 * k;
    let y = frame.top + (10.0 + 20.0 * entries.len() as f64 + 10.0) * k;
    // The thresholds as given (103 dB, 0.9 cm/s), not padded to digits they do not have.
    svg.text(x, y, &minus(&format!("L* = {} dB", short(t.spl_db))), 12.0 * k, Anchor::Start, 0.0);
    let e_star = minus(&format!("e* = {} cm/s", short(t.inclination_cm_s)));
    svg.text(x, y + 18.0 * k, &e_star, 12.0 * k, Anchor::Start, 0.0);
}

/// A design's point on the Fig 17 chart: SPLmax (dB), inclination (cm/s) and zone.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ZonePoint {
    pub spl_db: f64,
    pub e_cm_s: f64,
    pub zone: Option<Zone>,
}

/// The points of a chart for Fig 17 (the inclination the thresholds classify by).
pub fn zone_points(chart: &Chart) -> Vec<ZonePoint> {
    chart
        .cells
        .iter()
        .flatten()
        .filter_map(|c| {
            let e = c.metrics.inclination_by(chart.thresholds.zone_by)?;
            Some(ZonePoint { spl_db: c.metrics.spl_max_db?, e_cm_s: e, zone: c.metrics.zone })
        })
        .collect()
}

/// Fig 17: damping inclination against SPLmax for every design, coloured by zone, with the
/// L* and e* lines and the zone numbers in the four quadrants.
pub fn fig17_points(points: &[ZonePoint], t: &Thresholds, title: &str, look: &Look) -> String {
    let x = Axis::fit("SPLmax (dB re 20 µPa)", points.iter().map(|p| p.spl_db).chain([t.spl_db]));
    let y = Axis::fit("damping inclination e (cm/s)", points.iter().map(|p| p.e_cm_s).chain([t.inclination_cm_s]));
    let mut svg = Svg::figure(look, (WIDTH, HEIGHT), title);
    let frame = Frame::standard(&svg, x, y, true);
    frame.draw(&mut svg, title);
    let (xl, yl) = (frame.px(t.spl_db), frame.py(t.inclination_cm_s));
    let (left, right) = (frame.left, frame.left + frame.width);
    let (top, bottom) = (frame.top, frame.top + frame.height);
    let size = 22.0 * svg.scale();
    let dots: Vec<(f64, f64)> = points.iter().map(|p| (frame.px(p.spl_db), frame.py(p.e_cm_s))).collect();
    for (zone, quadrant) in [
        (Zone::NoisyWeak, [xl, yl, right, bottom]),
        (Zone::NoisyStrong, [xl, top, right, yl]),
        (Zone::QuietStrong, [left, top, xl, yl]),
        (Zone::QuietWeak, [left, yl, xl, bottom]),
    ] {
        // The label where it covers the fewest designs (none, where the quadrant has room).
        let (cx, cy) = label_spot(quadrant, (3.6 * size, size), &dots, 4.0 * svg.scale());
        svg.text_fill(cx, cy + 0.35 * size, &format!("zone {}", zone.number()), size, Anchor::Middle, "#b0b0b0");
    }
    frame.vline(&mut svg, t.spl_db, &format!("L* {} dB", short(t.spl_db)), "black");
    let r = 4.0 * svg.scale();
    // The e* line, its label at whichever end and side of the line covers the fewest designs.
    let k = svg.scale();
    svg.line((left, yl), (right, yl), "black", 1.5 * k, Some("6 4"));
    let label = minus(&format!("e* {} cm/s", short(t.inclination_cm_s)));
    let w = 0.6 * 12.0 * k * label.chars().count() as f64;
    let covered = |(x0, base): (f64, f64)| {
        let (x_in, y_in) = (x0 - r..=x0 + w + r, base - 12.0 * k - r..=base + 3.0 * k + r);
        dots.iter().filter(|(x, y)| x_in.contains(x) && y_in.contains(y)).count()
    };
    let spots = [
        (right - 4.0 * k - w, yl - 5.0 * k),
        (right - 4.0 * k - w, yl + 16.0 * k),
        (left + 4.0 * k, yl - 5.0 * k),
        (left + 4.0 * k, yl + 16.0 * k),
    ];
    let spot = spots.iter().copied().min_by_key(|s| covered(*s)).unwrap_or(spots[0]);
    svg.text(spot.0, spot.1, &label, 12.0 * k, Anchor::Start, 0.0);
    for p in points {
        svg.marker(zone_shape(p.zone), frame.px(p.spl_db), frame.py(p.e_cm_s), r, darker(p.zone));
    }
    zone_legend(&mut svg, &frame, t, true);
    svg.finish()
}

/// Where a label of `size` (w, h) goes in `quadrant` [x0, y0, x1, y1] (pixels, either order):
/// its centre, on a 5 × 5 grid of spots inside the quadrant, whose box (grown by the markers'
/// radius `r`) holds the fewest of `dots`; of equals, the one nearest the quadrant's centre.
fn label_spot(quadrant: [f64; 4], size: (f64, f64), dots: &[(f64, f64)], r: f64) -> (f64, f64) {
    let (x0, x1) = (quadrant[0].min(quadrant[2]), quadrant[0].max(quadrant[2]));
    let (y0, y1) = (quadrant[1].min(quadrant[3]), quadrant[1].max(quadrant[3]));
    let centre = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
    let (hw, hh) = (0.5 * size.0, 0.5 * size.1);
    let span = |a: f64, b: f64, half: f64| {
        let (lo, hi) = (a + half, b - half);
        if hi > lo {
            (0..5).map(|i| lo + (hi - lo) * f64::from(i) / 4.0).collect()
        } else {
            vec![0.5 * (a + b)]
        }
    };
    let covered = |(cx, cy): (f64, f64)| {
        dots.iter().filter(|(x, y)| (x - cx).abs() <= hw + r && (y - cy).abs() <= hh + r).count()
    };
    let mut best = centre;
    let mut key = (covered(centre), 0.0);
    for cx in span(x0, x1, hw) {
        for &cy in &span(y0, y1, hh) {
            let k = (covered((cx, cy)), (cx - centre.0).hypot(cy - centre.1));
            if k.0 < key.0 || (k.0 == key.0 && k.1 < key.1) {
                (best, key) = ((cx, cy), k);
            }
        }
    }
    best
}

/// Fig 17 of a design chart.
pub fn fig17(chart: &Chart, title: &str, look: &Look) -> String {
    fig17_points(&zone_points(chart), &chart.thresholds, title, look)
}

/// Marker colour of a zone on Fig 17 (points on white: zone 2 is Okabe–Ito's orange, not the
/// cells' pale yellow; CVD-checked with the rest in tests/cvd.rs).
fn darker(zone: Option<Zone>) -> &'static str {
    match zone {
        Some(Zone::NoisyWeak) => "#D55E00",
        Some(Zone::NoisyStrong) => "#E69F00",
        Some(Zone::QuietStrong) => "#009E73",
        Some(Zone::QuietWeak) => "#0072B2",
        None => "#333333",
    }
}

/// How a paper table is drawn.
enum Plot {
    /// `ys` against `x` (each with its style), one set per value of `group` if given.
    Lines {
        x: &'static str,
        ys: &'static [(&'static str, Style)],
        group: Option<&'static str>,
        y_label: &'static str,
        log_x: bool,
    },
    /// A cell map of `v` over `x` × `y`.
    Cells { x: &'static str, y: &'static str, v: &'static str },
    /// Fig 17's zone chart.
    Zones,
}

/// The plot of each paper item that is a figure or a table worth plotting.
fn plot_of(id: &str) -> Option<Plot> {
    use Style::{Dashed, Line, LineMarkers, Markers};
    let lines = |x, ys, group, y_label, log_x| Some(Plot::Lines { x, ys, group, y_label, log_x });
    match id {
        "table1" => lines(
            "u0_m_s",
            &[("spl_experiment_db", Markers), ("spl_paper_db", Markers), ("spl_model_db", Line)],
            Some("radius_mm"),
            "SPL (dB re 20 µPa)",
            false,
        ),
        "fig2" | "fig5" => lines("t_ms", &[("p_pa", Line)], None, "sound pressure p (Pa)", false),
        "fig3" | "fig6" => {
            lines("theta_deg", &[("spl_db", LineMarkers), ("spl_peak_db", Dashed)], None, "level (dB re 20 µPa)", false)
        }
        "fig7" => lines(
            "r_m",
            &[("delta_spl_db", LineMarkers), ("delta_peak_db", Dashed), ("delta_sel_db", Line)],
            None,
            "quadrupole − dipole (dB)",
            true,
        ),
        "fig12" => lines("r_m", &[("p_max_pa", LineMarkers), ("p_min_pa", LineMarkers)], None, "pressure (Pa)", true),
        "table3" => lines(
            "mass_g",
            &[("spl_max_paper_db", Markers), ("spl_max_model_db", Line)],
            Some("gap_cm"),
            "SPLmax (dB re 20 µPa)",
            false,
        ),
        "table4" => lines(
            "u0_m_s",
            &[
                ("paper_newmark_us", Markers),
                ("paper_exact_us", Markers),
                ("closed_form_us", Line),
                ("closed_form_40_5g_us", Dashed),
                ("newmark_us", Markers),
                ("damped_c1_20_us", Line),
            ],
            None,
            "contact duration τ (µs)",
            false,
        ),
        "table5" => lines(
            "e_lo_cm_s",
            &[("spl_min_db", LineMarkers), ("spl_max_db", LineMarkers)],
            None,
            "SPLmax (dB re 20 µPa)",
            false,
        ),
        "fig9" => {
            lines("t_s", &[("x_damper_m", Line), ("x_free_m", Dashed)], None, "main-mass displacement x (m)", false)
        }
        "fig10" => lines("gap_cm", &[("inclination_cm_s", LineMarkers)], Some("mass_g"), "e (cm/s)", false),
        "fig11" => lines("mass_g", &[("spl_max_db", LineMarkers)], Some("gap_cm"), "SPLmax (dB re 20 µPa)", false),
        "fig13" => lines(
            "mass_g",
            &[("restitution", LineMarkers), ("restitution_reference", Markers)],
            None,
            "coefficient of restitution R",
            false,
        ),
        "fig14" => lines("mass_g", &[("inclination_cm_s", LineMarkers)], Some("gap_cm"), "e (cm/s)", false),
        "fig15" => Some(Plot::Cells { x: "mass_g", y: "gap_cm", v: "inclination_cm_s" }),
        "fig16" => Some(Plot::Cells { x: "mass_g", y: "gap_cm", v: "spl_max_db" }),
        "fig17" => Some(Plot::Zones),
        _ => None,
    }
}

/// "SPLmax paper (dB)" → ("SPLmax paper", "dB"); a label without a unit → (label, "").
fn split_unit(label: &str) -> (String, String) {
    match (label.rfind(" ("), label.ends_with(')')) {
        (Some(i), true) => (label[..i].to_string(), label[i + 2..label.len() - 1].to_string()),
        _ => (label.to_string(), String::new()),
    }
}

/// The title of a paper item's figure: the table's own, except where the figure plots only
/// part of the table, so the title says what is drawn.
pub fn figure_title(table: &Table) -> String {
    match table.id {
        "table3" => {
            "Table 3: SPLmax against impact mass for each gap (preset paper-table3), paper (points) vs model (lines)"
                .to_string()
        }
        "fig3" => "Fig 3: dipole directivity, SPL and peak level against θ at r 0.7 m".to_string(),
        "fig6" => "Fig 6: quadrupole directivity, SPL and peak level against θ at r 0.7 m".to_string(),
        "fig12" => "Fig 12: the quadrupole's largest and smallest pressure against r".to_string(),
        _ => table.title.clone(),
    }
}

/// Whether the paper item `id` is drawn as a figure by [`paper_figure`].
pub fn has_figure(id: &str) -> bool {
    plot_of(id).is_some()
}

/// Column `key` of `table` as numbers (NaN where not a number); None if there is no such column.
fn column(table: &Table, key: &str) -> Option<Vec<f64>> {
    let i = table.columns.iter().position(|c| c.key == key)?;
    Some(table.rows.iter().map(|r| if let Some(Value::Num(x)) = r.get(i) { *x } else { f64::NAN }).collect())
}

fn label(table: &Table, key: &str) -> String {
    table.columns.iter().find(|c| c.key == key).map_or(key.to_string(), |c| c.label.to_string())
}

/// The SVG of a reproduced paper table, or None when it is not worth plotting. Fig 17 uses
/// `thresholds` for its zone lines (those of the chart it was computed with).
pub fn paper_figure(table: &Table, thresholds: &Thresholds, look: &Look) -> Option<String> {
    let title = table.title.as_str();
    match plot_of(table.id)? {
        Plot::Lines { x, ys, group, y_label, log_x } => {
            let xv = column(table, x)?;
            let gv = group.and_then(|g| column(table, g));
            let mut groups: Vec<f64> = Vec::new();
            for g in gv.iter().flatten() {
                if !groups.iter().any(|h| h == g) {
                    groups.push(*g);
                }
            }
            let mut series = Vec::new();
            for (yi, &(yk, style)) in ys.iter().enumerate() {
                let yv = column(table, yk)?;
                let name = label(table, yk);
                let pick = |g: Option<f64>| -> Vec<(f64, f64)> {
                    (0..xv.len())
                        .filter(|&i| g.is_none_or(|g| gv.as_ref().is_some_and(|v| v[i] == g)))
                        .map(|i| (xv[i], yv[i]))
                        .filter(|p| !(style == Style::Markers && p.1.is_nan()))
                        .collect()
                };
                if groups.is_empty() {
                    series.push(Series::new(&split_unit(&name).0, pick(None), style));
                } else {
                    // One colour per group (the paper's and the model's curve of one gap alike),
                    // one marker shape per column: no colour stands for two groups.
                    let (gname, gunit) = split_unit(&label(table, group.unwrap_or_default()));
                    for (gi, &g) in groups.iter().enumerate() {
                        let glabel = format!("{gname} {} {gunit}", short(g)).trim_end().to_string();
                        let name = if ys.len() > 1 { format!("{}, {glabel}", split_unit(&name).0) } else { glabel };
                        // Past the palette's colours a group repeats a colour with another
                        // dash pattern, and (one column) another marker: no two curves alike.
                        let shape = if ys.len() > 1 { Shape::nth(yi) } else { Shape::nth(gi) };
                        let dash = if style == Style::Dashed { Some("7 4") } else { series_dash(gi) };
                        let s = Series::new(&minus(&name), pick(Some(g)), style).colored(series_color(gi));
                        series.push(s.shaped(shape).dashed(dash));
                    }
                }
            }
            let all_y = series.iter().flat_map(|s| s.points.iter().map(|p| p.1)).collect::<Vec<_>>();
            let xa = if log_x {
                Axis::fit_log(&label(table, x), xv.clone())
            } else {
                Axis::fit(&label(table, x), xv.clone())
            };
            Some(line_plot(&figure_title(table), look, xa, Axis::fit(y_label, all_y), &series))
        }
        Plot::Cells { x, y, v } => Some(cell_map(table, x, y, v, look)),
        Plot::Zones => {
            let (s, e, z) = (column(table, "spl_max_db")?, column(table, "inclination_cm_s")?, column(table, "zone")?);
            let pts: Vec<ZonePoint> = (0..s.len())
                .filter(|&i| s[i].is_finite() && e[i].is_finite())
                .map(|i| ZonePoint {
                    spl_db: s[i],
                    e_cm_s: e[i],
                    zone: ZONES.iter().copied().find(|zz| f64::from(zz.number()) == z[i]),
                })
                .collect();
            Some(fig17_points(&pts, thresholds, title, look))
        }
    }
}

/// A colour from blue (0) through pale yellow to red (1) (the "RdYlBu" scheme, reversed).
fn ramp(f: f64) -> String {
    let f = if f.is_finite() { f.clamp(0.0, 1.0) } else { 0.0 };
    let stops =
        [(49.0, 54.0, 149.0), (116.0, 173.0, 209.0), (255.0, 255.0, 191.0), (244.0, 109.0, 67.0), (165.0, 0.0, 38.0)];
    let k = ((f * 4.0).floor() as usize).min(3);
    let (a, b, t) = (stops[k], stops[k + 1], f * 4.0 - k as f64);
    let mix = |p: f64, q: f64| (p + (q - p) * t).round() as u8;
    format!("#{:02x}{:02x}{:02x}", mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// A cell map of column `v` over the grid of columns `x` × `y`, with a colour scale.
fn cell_map(table: &Table, x: &str, y: &str, v: &str, look: &Look) -> String {
    let (xv, yv, vv) = (
        column(table, x).unwrap_or_default(),
        column(table, y).unwrap_or_default(),
        column(table, v).unwrap_or_default(),
    );
    let distinct = |vals: &[f64]| {
        let mut d: Vec<f64> = vals.iter().copied().filter(|a| a.is_finite()).collect();
        d.sort_by(f64::total_cmp);
        d.dedup();
        d
    };
    let (xs, ys) = (distinct(&xv), distinct(&yv));
    let (lo, hi) =
        vv.iter().filter(|a| a.is_finite()).fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &c| (a.min(c), b.max(c)));
    let title = table.title.as_str();
    let mut svg = Svg::figure(look, (WIDTH, HEIGHT), title);
    if xs.is_empty() || ys.is_empty() {
        return svg.finish();
    }
    let (ex, ey) = (edges(&xs), edges(&ys));
    let frame = Frame::standard(
        &svg,
        Axis::fixed(&label(table, x), ex[0], ex[ex.len() - 1]),
        Axis::fixed(&label(table, y), ey[0], ey[ey.len() - 1]),
        true,
    );
    let value_at = |i: usize, j: usize| (0..vv.len()).find(|&k| xv[k] == xs[i] && yv[k] == ys[j]).map(|k| vv[k]);
    draw_cells(&mut svg, &frame, title, &xs, &ys, |i, j| match value_at(i, j).filter(|a| a.is_finite()) {
        Some(a) => (ramp((a - lo) / (hi - lo).max(1e-300)), String::new()),
        None => ("#dddddd".into(), String::new()),
    });
    let k = svg.scale();
    let lx = frame.left + frame.width + 15.0 * k;
    svg.text(lx, frame.top + 4.0 * k, &label(table, v), 12.0 * k, Anchor::Start, 0.0);
    if lo.is_finite() {
        color_bar(&mut svg, lx, frame.top + 14.0 * k, (frame.height - 14.0 * k).min(240.0 * k), (lo, hi));
    }
    svg.finish()
}

/// A continuous colour bar of [`ramp`] for values `lo..hi` (top: `hi`), `height` px tall at
/// (`x`, `top`), with ticks at round values (multiples of a 1-2-5 step).
fn color_bar(svg: &mut Svg, x: f64, top: f64, height: f64, (lo, hi): (f64, f64)) {
    const SLICES: usize = 48;
    let span = (hi - lo).max(1e-300);
    let s = svg.scale();
    for k in 0..SLICES {
        let f = 1.0 - (k as f64 + 0.5) / SLICES as f64;
        let h = height / SLICES as f64;
        svg.rect(x, top + h * k as f64, 22.0 * s, h + 0.5, &ramp(f), None);
    }
    svg.rect(x, top, 22.0 * s, height, "none", Some("black"));
    for (v, text) in round_ticks(lo, hi) {
        let y = top + (1.0 - (v - lo) / span) * height;
        svg.line((x + 22.0 * s, y), (x + 27.0 * s, y), "black", s, None);
        svg.text(x + 30.0 * s, y + 4.0 * s, &minus(&text), 12.0 * s, Anchor::Start, 0.0);
    }
}

/// Round tick values in `lo..=hi` (multiples of the 1-2-5 step that gives about five) with
/// their labels (as many decimals as the step needs); `lo` alone when the range is empty.
fn round_ticks(lo: f64, hi: f64) -> Vec<(f64, String)> {
    if hi <= lo {
        return vec![(lo, sig(lo, 4))];
    }
    let step = nice_step((hi - lo) / 5.0);
    let decimals = (-step.log10().floor()).max(0.0) as usize;
    let (first, last) = ((lo / step - 1e-9).ceil() as i64, (hi / step + 1e-9).floor() as i64);
    (first..=last)
        .map(|k| {
            let v = k as f64 * step;
            let v = if v.abs() < 1e-12 * step { 0.0 } else { v };
            (v, format!("{v:.decimals$}"))
        })
        .collect()
}

/// The frequency response (docs/model.md §6.4): the steady amplitude against the forcing
/// frequency with the damper (one series per sweep) and without it (the closed form), on a log
/// scale in mm; below, `Leq` at the observer against the frequency.
// Over 80 lines: two stacked panels (amplitude, Leq) drawn top to bottom.
pub fn response(r: &crate::response::Response, title: &str, look: &Look) -> String {
    use crate::response::Direction;
    let mut svg = Svg::figure(look, (WIDTH, 760.0), title);
    let (width, height) = (svg.width(), svg.height());
    // The two panels share the height left by the margins, 2 : 1.
    let top_margin = Frame::top_margin(&svg);
    let (k, left) = (svg.scale(), Frame::left_margin(&svg));
    let free = height - top_margin - 2.0 * Frame::bottom_margin(&svg);
    let (h_top, h_bottom) = (free * 2.0 / 3.0, free / 3.0);
    let label = |d: Direction| match d {
        Direction::FromRest => "with the damper".to_string(),
        d => format!("damper, {} sweep", d.name()),
    };
    let mut amp: Vec<Series> = r
        .sweeps
        .iter()
        .map(|s| {
            let pts = s.points.iter().map(|p| (p.freq_hz, p.steady.amplitude_m * 1e3)).collect();
            Series::new(&label(s.direction), pts, Style::LineMarkers)
        })
        .collect();
    let mut linear: Vec<(f64, f64)> = r
        .sweeps
        .first()
        .map(|s| {
            s.points.iter().map(|p| (p.freq_hz, p.steady.amplitude_linear_m.map_or(f64::NAN, |a| a * 1e3))).collect()
        })
        .unwrap_or_default();
    linear.sort_by(|a, b| a.0.total_cmp(&b.0));
    amp.push(Series::new("without (closed form)", linear, Style::Dashed));
    // Points that are not a steady state (not settled, or cut short by a work cap) are
    // marked over their sweep's, with a legend entry of their own.
    for (what, truncated, shape) in [("not settled", false, Shape::Cross), ("truncated", true, Shape::TriangleDown)] {
        let pts: Vec<(f64, f64)> = r
            .sweeps
            .iter()
            .flat_map(|s| &s.points)
            .filter(|p| p.steady.verdict.is_marked() && p.steady.verdict.is_truncated() == truncated)
            .map(|p| (p.freq_hz, p.steady.amplitude_m * 1e3))
            .collect();
        if !pts.is_empty() {
            amp.push(Series::new(what, pts, Style::Markers).shaped(shape).colored("#000000".to_string()));
        }
    }
    let leq: Vec<Series> = r
        .sweeps
        .iter()
        .map(|s| {
            let pts = s.points.iter().map(|p| (p.freq_hz, p.steady.leq_db.unwrap_or(f64::NAN))).collect();
            Series::new(&label(s.direction), pts, Style::LineMarkers)
        })
        .collect();
    let freqs = || r.sweeps.iter().flat_map(|s| s.points.iter().map(|p| p.freq_hz));
    let x = Axis::fit("forcing frequency f (Hz)", freqs());
    let y = Axis::fit_log("steady amplitude (mm)", amp.iter().flat_map(|s| s.points.iter().map(|p| p.1)));
    let top = Frame { left, top: top_margin, width: width - left - 200.0 * k, height: h_top, x: x.clone(), y };
    top.draw_panel(&mut svg, Some(title), "amplitude");
    draw_series_clipped(&mut svg, &top, &amp, "amplitude");
    let levels: Vec<f64> = leq.iter().flat_map(|s| s.points.iter().map(|p| p.1)).filter(|v| v.is_finite()).collect();
    let y2 = Axis::fit("Leq at the observer (dB)", levels.iter().copied());
    let bottom = Frame {
        left,
        top: top_margin + h_top + Frame::bottom_margin(&svg),
        width: width - left - 200.0 * k,
        height: h_bottom,
        x,
        y: y2,
    };
    bottom.draw_panel(&mut svg, None, "level");
    if levels.is_empty() {
        svg.text(
            bottom.left + bottom.width / 2.0,
            bottom.top + bottom.height / 2.0,
            "no impact at any frequency",
            13.0 * k,
            Anchor::Middle,
            0.0,
        );
    }
    draw_series_clipped(&mut svg, &bottom, &leq, "level");
    svg.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A label goes where it covers no design when the quadrant has room, nearest the centre.
    #[test]
    fn a_zone_label_keeps_clear_of_the_designs() {
        let quadrant = [0.0, 0.0, 400.0, 300.0];
        let size = (80.0, 22.0);
        assert_eq!(label_spot(quadrant, size, &[], 4.0), (200.0, 150.0), "no designs: the centre");
        // A cloud over the centre: the label moves off it, onto none of the designs.
        let cloud: Vec<(f64, f64)> =
            (0..40).map(|i| (150.0 + 2.5 * f64::from(i), 120.0 + 1.5 * f64::from(i % 40))).collect();
        let (cx, cy) = label_spot(quadrant, size, &cloud, 4.0);
        let on = cloud.iter().filter(|(x, y)| (x - cx).abs() <= 44.0 && (y - cy).abs() <= 15.0).count();
        assert_eq!(on, 0, "at ({cx}, {cy})");
        assert!((cx - 40.0..=360.0).contains(&cx) && (11.0..=289.0).contains(&cy), "inside the quadrant: ({cx}, {cy})");
    }
}
