//! Files of the studies and of the dynamics: the CSV tables of a study over
//! any parameter (`sweep --vary`), of a bifurcation diagram (one row per sample or impact),
//! of an impact map and of a basin map; and their figures (SVG, and PDF through [`super::pdf`]):
//! x(kT) and the impact speed against the parameter, the impact map, the basins.

use super::svg::{self, param_label, Anchor, Axis, Frame, Look, Shape, Svg};
use crate::response::Direction;
use crate::study::Study;
use crate::units::short;
use thud_core::dynamics::{Basins, Bifurcation, OrbitRun};

/// `header`, then one record per row, as CSV text (the `csv` crate; numbers in Rust's
/// shortest round-trip form).
fn to_csv(header: &[String], rows: impl IntoIterator<Item = Vec<String>>) -> Result<String, csv::Error> {
    let mut w = csv::WriterBuilder::new().has_headers(false).from_writer(Vec::new());
    w.write_record(header)?;
    for row in rows {
        w.write_record(&row)?;
    }
    let bytes = w.into_inner().map_err(|e| csv::Error::from(e.into_error()))?;
    String::from_utf8(bytes)
        .map_err(|e| csv::Error::from(std::io::Error::new(std::io::ErrorKind::InvalidData, e.utf8_error())))
}

/// A number as the CSV files write it.
fn n(v: f64) -> String {
    format!("{v}")
}

/// An optional number (empty when absent).
fn o(v: Option<f64>) -> String {
    v.map_or(String::new(), n)
}

/// The metric columns of a study cell, in the order (and with the names) of its JSON: the sweep
/// CSV's columns after its mass and gap.
const METRICS: &[thud_core::schema::Column] = csv_metrics();

const fn csv_metrics() -> &'static [thud_core::schema::Column] {
    match thud_core::schema::SWEEP.columns.split_first() {
        Some((_, rest)) => match rest.split_first() {
            Some((_, metrics)) => metrics,
            None => &[],
        },
        None => &[],
    }
}

/// A study over any parameter, one row per cell: `index`, each axis (`v0_m_s`, …), the
/// metrics, and with a force the steady amplitude and reduction.
pub fn study_csv(s: &Study) -> Result<String, csv::Error> {
    let forced = s.cells.iter().any(|c| c.steady.is_some());
    let mut header: Vec<String> = vec!["index".into()];
    header.extend(s.axes.iter().map(crate::study::Axis::column));
    header.extend(METRICS.iter().map(|m| m.name.to_string()));
    if forced {
        header.extend(["steady_amplitude_m".to_string(), "steady_reduction_db".to_string()]);
    }
    let rows = s.cells.iter().map(|c| {
        let m = &c.metrics;
        let mut r = vec![c.index.to_string()];
        r.extend(c.values.iter().map(|v| n(*v)));
        r.extend([
            m.n_impacts.to_string(),
            o(m.inclination_cm_s),
            o(m.inclination_fit_cm_s),
            n(m.u0_max_m_s),
            n(m.zdot_abs_max_m_s),
            o(m.spl_max_db),
            o(m.contact_duration_s),
            o(m.restitution_mean),
            m.zone.map_or(String::new(), |z| z.number().to_string()),
        ]);
        if forced {
            r.push(c.steady.map_or(String::new(), |st| n(st.amplitude_m)));
            r.push(o(c.steady.and_then(|st| st.reduction_db)));
        }
        r
    });
    to_csv(&header, rows)
}

/// The columns of a bifurcation's CSV after the parameter's own.
const BIFURCATION_COLUMNS: [&str; 12] = [
    "direction",
    "orbit",
    "record",
    "period",
    "x_m",
    "v_m_s",
    "z_m",
    "zdot_m_s",
    "phase",
    "wall",
    "u_in_m_s",
    "u_out_m_s",
];

/// The rows of one sampled run (one per sample, then one per impact), each led by `lead`.
fn run_rows(lead: &[String], run: &OrbitRun) -> Vec<Vec<String>> {
    let e = String::new;
    let mut rows = Vec::with_capacity(run.samples.len() + run.impacts.len());
    for s in &run.samples {
        let mut r = lead.to_vec();
        r.extend([
            "sample".into(),
            s.period.to_string(),
            n(s.x_m),
            n(s.v_m_s),
            n(s.z_m),
            n(s.zdot_m_s),
            e(),
            e(),
            e(),
            e(),
        ]);
        rows.push(r);
    }
    for i in &run.impacts {
        let mut r = lead.to_vec();
        r.extend([
            "impact".into(),
            i.period.to_string(),
            e(),
            e(),
            e(),
            e(),
            n(i.phase),
            i.wall.to_string(),
            n(i.u_in_m_s),
            n(i.u_out_m_s),
        ]);
        rows.push(r);
    }
    rows
}

/// A bifurcation diagram, one row per stroboscopic sample (`record` = `sample`: x, x', z, z'
/// at t = kT) and per impact (`record` = `impact`: its phase as a fraction of the period, its
/// wall, its relative speeds), each led by the parameter's value (`freq_hz`, …), the sweep's
/// direction and the orbit's type.
pub fn bifurcation_csv(b: &Bifurcation) -> Result<String, csv::Error> {
    let mut header = vec![b.axis.column()];
    header.extend(BIFURCATION_COLUMNS.iter().map(|c| (*c).to_string()));
    let rows = b.points.iter().flat_map(|p| {
        let lead = [n(p.value), direction(p.direction).to_string(), p.run.orbit.label()];
        run_rows(&lead, &p.run)
    });
    to_csv(&header, rows)
}

/// The impact map of one design: one row per sample and per impact, as [`bifurcation_csv`]
/// without the parameter and the direction.
pub fn impact_map_csv(run: &OrbitRun) -> Result<String, csv::Error> {
    let header: Vec<String> = BIFURCATION_COLUMNS[1..].iter().map(|c| (*c).to_string()).collect();
    to_csv(&header, run_rows(&[run.orbit.label()], run))
}

/// A basin map, one row per start: `y0_m`, `w0_m_s`, its attractor's id and type and the
/// amplitude it reached.
pub fn basins_csv(b: &Basins) -> Result<String, csv::Error> {
    let header: Vec<String> =
        ["y0_m", "w0_m_s", "attractor", "orbit", "amplitude_m"].iter().map(|c| (*c).to_string()).collect();
    let ny = b.y0_m.len();
    let rows = b.cells.iter().enumerate().map(|(i, &id)| {
        vec![
            n(b.y0_m[i % ny]),
            n(b.w0_m_s[i / ny]),
            id.to_string(),
            b.attractors.get(id).map_or(String::new(), |a| a.label.clone()),
            n(b.amplitudes_m[i]),
        ]
    });
    to_csv(&header, rows)
}

/// How the CSV and JSON spell a sweep's direction.
#[must_use]
pub fn direction(d: Direction) -> &'static str {
    match d {
        Direction::FromRest => "from_rest",
        Direction::Up => "up",
        Direction::Down => "down",
    }
}

/// Colour of the rising (or only) sweep and of the falling one (Okabe–Ito blue and vermilion).
const UP: &str = "#0072B2";
const DOWN: &str = "#D55E00";
/// Colour of the values whose orbit is not settled (grey) or whose run was cut short (black).
const UNSETTLED: &str = "#7F7F7F";
const TRUNCATED: &str = "#000000";

/// A short name of the design for a figure's title, each number as typed (`F0 3 N`, not
/// `3.0000 N`), without the parameter the figure varies (`varied`, its row's name: a diagram
/// over f is not "at f 7.5 Hz"; "" for none): the titles of `thud bifurcation`, `thud basins`
/// and `thud impact-map`, and of the Python figures of the same results.
pub fn short_design(d: &thud_core::design::Design, varied: &str) -> String {
    let p = &d.damper;
    [
        ("force", format!("F0 {} N", short(p.force_n))),
        ("freq", format!("f {} Hz", short(p.freq_hz))),
        ("gap", format!("gap {} mm", short(p.gap_m * 1e3))),
        ("mass", format!("m {} g", short(p.impact_mass_kg * 1e3))),
    ]
    .into_iter()
    .filter(|(name, _)| *name != varied)
    .map(|(_, text)| text)
    .collect::<Vec<_>>()
    .join(", ")
}

/// The title of a bifurcation diagram: what varies and over which range, then the design
/// without it ("Bifurcation diagram over freq 3–8 Hz — F0 3 N, gap 20 mm, m 40 g"); the
/// title of `thud bifurcation --svg` and of the Python figure of the same diagram.
pub fn bifurcation_title(d: &thud_core::design::Design, b: &Bifurcation) -> String {
    range_title("Bifurcation diagram", d, &b.axis.name, &b.axis.unit, &b.axis.values)
}

/// `what` over the range of the parameter `name` (`unit`) its `values` span, then the design
/// without it: the titles of the figures over one parameter (`thud bifurcation`, `thud
/// continue`).
pub fn range_title(what: &str, d: &thud_core::design::Design, name: &str, unit: &str, values: &[f64]) -> String {
    let (lo, hi) = values.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| (l.min(*v), h.max(*v)));
    let unit = if unit.is_empty() { String::new() } else { format!(" {unit}") };
    format!("{what} over {name} {}–{}{unit} — {}", short(lo), short(hi), short_design(d, name))
}

/// The bifurcation diagram: above, x(kT) (mm) against the parameter; below, the relative
/// impact speed (m/s) of every impact after the transient. With continuation the rising sweep
/// is drawn in blue dots, the falling one in vermilion squares, so hysteresis shows.
pub fn bifurcation_svg(b: &Bifurcation, title: &str, look: &Look) -> String {
    bifurcation_with_branches_svg(b, &[], title, look)
}

/// [`bifurcation_svg`] with continued `branches` over the x(kT) panel
/// ([`super::continuation::overlay`]): each branch's x(kT) at each of its orbit's periods,
/// stable solid, unstable dashed.
// Over 80 lines: two stacked panels drawn top to bottom, each step a few lines.
pub fn bifurcation_with_branches_svg(
    b: &Bifurcation,
    branches: &[thud_core::continuation::Branch],
    title: &str,
    look: &Look,
) -> String {
    let mut svg = Svg::figure(look, (svg::WIDTH, 760.0), title);
    let (width, height) = (svg.width(), svg.height());
    let top_margin = Frame::top_margin(&svg);
    let free = height - top_margin - 70.0 - 70.0;
    let h = free / 2.0;
    let values = || b.points.iter().map(|p| p.value);
    let x = Axis::fit(&param_label(&b.axis.name, &b.axis.unit), values());
    let xs = b.points.iter().flat_map(|p| p.run.samples.iter().map(|s| s.x_m * 1e3));
    let on_branches = branches.iter().flat_map(|br| br.points.iter().flat_map(|p| p.strobe_m.iter().map(|x| x * 1e3)));
    let y1 = Axis::fit("x(kT), main mass at the force's phase 0 (mm)", xs.chain(on_branches).chain([0.0]));
    let us = b.points.iter().flat_map(|p| p.run.impacts.iter().map(|i| i.u_in_m_s));
    let y2 = Axis::fit("relative impact speed (m/s)", us.chain([0.0]));
    let right = 190.0;
    let top = Frame { left: 85.0, top: top_margin, width: width - 85.0 - right, height: h, x: x.clone(), y: y1 };
    top.draw_panel(&mut svg, Some(title), "strobe");
    let bottom = Frame { left: 85.0, top: top_margin + h + 70.0, width: width - 85.0 - right, height: h, x, y: y2 };
    bottom.draw_panel(&mut svg, None, "impacts");
    let dot = |svg: &mut Svg, f: &Frame, vx: f64, vy: f64, d: Direction| {
        let (cx, cy) = (f.px(vx), f.py(vy));
        if (f.left..=f.left + f.width).contains(&cx) && (f.top..=f.top + f.height).contains(&cy) {
            match d {
                Direction::Down => svg.marker(Shape::Square, cx, cy, 1.3, DOWN),
                _ => svg.circle(cx, cy, 1.1, UP),
            }
        }
    };
    // A value whose orbit is not settled, or whose run a work cap cut short, is drawn apart:
    // its samples are not an orbit's.
    let apart = |svg: &mut Svg, f: &Frame, vx: f64, vy: f64, truncated: bool| {
        let (cx, cy) = (f.px(vx), f.py(vy));
        if (f.left..=f.left + f.width).contains(&cx) && (f.top..=f.top + f.height).contains(&cy) {
            let (shape, color) = if truncated { (Shape::TriangleDown, TRUNCATED) } else { (Shape::Cross, UNSETTLED) };
            svg.marker(shape, cx, cy, 1.6, color);
        }
    };
    for p in &b.points {
        let marked = p.run.orbit.is_marked();
        let truncated = p.run.orbit.is_truncated();
        for s in &p.run.samples {
            if marked {
                apart(&mut svg, &top, p.value, s.x_m * 1e3, truncated);
            } else {
                dot(&mut svg, &top, p.value, s.x_m * 1e3, p.direction);
            }
        }
        for i in &p.run.impacts {
            if marked {
                apart(&mut svg, &bottom, p.value, i.u_in_m_s, truncated);
            } else {
                dot(&mut svg, &bottom, p.value, i.u_in_m_s, p.direction);
            }
        }
    }
    let lx = left_of_legend(width, right);
    let mut y = top_margin + 12.0;
    let continuation = b.points.iter().any(|p| p.direction == Direction::Down);
    let mut entries: Vec<(&str, &str, Shape)> = if continuation {
        vec![(UP, "rising sweep", Shape::Circle), (DOWN, "falling sweep", Shape::Square)]
    } else {
        vec![(UP, "each value from the start", Shape::Circle)]
    };
    if b.points.iter().any(|p| p.run.orbit.is_marked() && !p.run.orbit.is_truncated()) {
        entries.push((UNSETTLED, "not settled", Shape::Cross));
    }
    if b.points.iter().any(|p| p.run.orbit.is_truncated()) {
        entries.push((TRUNCATED, "truncated (a work cap)", Shape::TriangleDown));
    }
    for (color, label, shape) in &entries {
        svg.marker(*shape, lx + 6.0, y - 4.0, 3.0, color);
        svg.text(lx + 16.0, y, label, 11.0, Anchor::Start, 0.0);
        y += 18.0;
    }
    if !branches.is_empty() {
        y = super::continuation::overlay(&mut svg, &top, "strobe", branches, (lx, y));
    }
    y += 10.0;
    svg.text(lx, y, "orbits (m impacts / n periods):", 11.0, Anchor::Start, 0.0);
    let listed: Vec<_> = b.bands.iter().filter(|band| band.values >= LISTED_BAND_VALUES).take(LISTED_BANDS).collect();
    for band in &listed {
        y += 15.0;
        let span = format!("{}–{}", crate::units::short(band.from), crate::units::short(band.to));
        svg.text(lx, y, &format!("{span}: {}", band.orbit), 10.0, Anchor::Start, 0.0);
    }
    // The list is not the whole story when it leaves bands out: it says so.
    let left_out = b.bands.len() - listed.len();
    if left_out > 0 {
        y += 15.0;
        let s = if left_out == 1 { "" } else { "s" };
        svg.text(lx, y, &format!("… and {left_out} band{s} more (in the CSV)"), 10.0, Anchor::Start, 0.0);
    }
    svg.finish()
}

/// The fewest values a band of one orbit has to be listed in the bifurcation figure's legend.
const LISTED_BAND_VALUES: usize = 3;
/// The most bands the bifurcation figure's legend lists.
const LISTED_BANDS: usize = 24;

/// The x of the legend column right of the frames.
fn left_of_legend(width: f64, right: f64) -> f64 {
    width - right + 12.0
}

/// The impact map (the Poincaré section on impacts): the force's phase at each impact (as a
/// fraction of the period) against its relative impact speed, one colour and marker per wall.
pub fn impact_map_svg(run: &OrbitRun, title: &str, look: &Look) -> String {
    let mut svg = Svg::figure(look, (svg::WIDTH, svg::HEIGHT), title);
    let x = Axis::fixed("phase of the force at impact (fraction of the period T)", 0.0, 1.0);
    let y = Axis::fit("relative impact speed (m/s)", run.impacts.iter().map(|i| i.u_in_m_s).chain([0.0]));
    let frame = Frame::standard(&svg, x, y, true);
    frame.draw(&mut svg, title);
    for i in &run.impacts {
        let (cx, cy) = (frame.px(i.phase), frame.py(i.u_in_m_s));
        if i.wall.sign() > 0.0 {
            svg.circle(cx, cy, 2.2, UP);
        } else {
            svg.marker(Shape::Square, cx, cy, 2.4, DOWN);
        }
    }
    let lx = frame.left + frame.width + 12.0;
    svg.circle(lx + 6.0, frame.top + 6.0, 3.0, UP);
    svg.text(lx + 16.0, frame.top + 10.0, "wall +1", 11.0, Anchor::Start, 0.0);
    svg.marker(Shape::Square, lx + 6.0, frame.top + 24.0, 3.0, DOWN);
    svg.text(lx + 16.0, frame.top + 28.0, "wall −1", 11.0, Anchor::Start, 0.0);
    svg.text(lx, frame.top + 52.0, &format!("orbit: {}", run.orbit.label()), 11.0, Anchor::Start, 0.0);
    svg.text(lx, frame.top + 68.0, &format!("{} impacts", run.impacts.len()), 11.0, Anchor::Start, 0.0);
    svg.finish()
}

/// The basins of attraction: the ball's start (y0 across, w0 up), each cell coloured and
/// lettered by the attractor it reaches, with each attractor's type, amplitude and share.
pub fn basins_svg(b: &Basins, title: &str, look: &Look) -> String {
    let mut svg = Svg::figure(look, (svg::WIDTH, svg::HEIGHT), title);
    let (ny, nw) = (b.y0_m.len(), b.w0_m_s.len());
    let cell = |v: &[f64], i: usize| {
        let step = if v.len() > 1 { (v[v.len() - 1] - v[0]) / (v.len() - 1) as f64 } else { 1.0 };
        (v[i] - step / 2.0, v[i] + step / 2.0)
    };
    let ys: Vec<f64> = b.y0_m.iter().map(|y| y * 1e3).collect();
    let x = Axis::fixed("ball's start offset y0 (mm)", cell(&ys, 0).0, cell(&ys, ny - 1).1);
    let y = Axis::fixed("ball's start velocity w0 (m/s)", cell(&b.w0_m_s, 0).0, cell(&b.w0_m_s, nw - 1).1);
    let frame = Frame::standard(&svg, x, y, true);
    frame.grid(&mut svg);
    let color = |id: usize| svg::series_color(id);
    for (i, &id) in b.cells.iter().enumerate() {
        let (x0, x1) = cell(&ys, i % ny);
        let (w0, w1) = cell(&b.w0_m_s, i / ny);
        let (px0, px1, py0, py1) = (frame.px(x0), frame.px(x1), frame.py(w1), frame.py(w0));
        svg.rect(px0, py0, px1 - px0, py1 - py0, &color(id), None);
        if px1 - px0 >= 12.0 && py1 - py0 >= 12.0 {
            svg.text_fill(
                f64::midpoint(px0, px1),
                f64::midpoint(py0, py1) + 4.0,
                &letter(id),
                10.0,
                Anchor::Middle,
                "white",
            );
        }
    }
    frame.axes(&mut svg, Some(title), svg::CLIP);
    let lx = frame.left + frame.width + 12.0;
    for (k, a) in b.attractors.iter().enumerate().take(LISTED_ATTRACTORS) {
        let yy = frame.top + 10.0 + 20.0 * k as f64;
        svg.rect(lx, yy - 9.0, 14.0, 12.0, &color(a.id), None);
        svg.text_fill(lx + 7.0, yy + 1.0, &letter(a.id), 9.0, Anchor::Middle, "white");
        let mirror = a.mirror.map_or(String::new(), |m| format!(", mirror of {}", letter(m)));
        let text = format!("{} {:.1} mm, {:.0} %{mirror}", a.label, a.amplitude_m * 1e3, a.share * 100.0);
        svg.text(lx + 20.0, yy, &text, 10.0, Anchor::Start, 0.0);
    }
    // The legend is not the whole story when it leaves attractors out: it says so.
    let left_out = b.attractors.len().saturating_sub(LISTED_ATTRACTORS);
    if left_out > 0 {
        let yy = frame.top + 10.0 + 20.0 * LISTED_ATTRACTORS as f64;
        let s = if left_out == 1 { "" } else { "s" };
        svg.text(lx, yy, &format!("… and {left_out} attractor{s} more (in --csv)"), 10.0, Anchor::Start, 0.0);
    }
    svg.finish()
}

/// The most attractors the basins figure's legend lists.
const LISTED_ATTRACTORS: usize = 20;

/// The letter of attractor `id` on a map: A … Z, then a … z, then `#`.
#[must_use]
pub fn letter(id: usize) -> String {
    let letters = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz";
    letters.get(id).map_or("#".to_string(), |&c| char::from(c).to_string())
}
