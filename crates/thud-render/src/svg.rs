// Over 800 lines: the writer, its axes and its legends share one private canvas; the rest is its tests.
//! A small SVG writer: an escaped document builder, axes with "nice" ticks (linear or log),
//! line/marker plots with a legend, and a cell map. No fonts or system libraries: text is left
//! to the viewer's sans-serif font. Coordinates are in SVG pixels; data values in the units of
//! the axis labels (the callers convert from SI for the labels).

use std::fmt::Write as _;

/// Width of every figure (px).
pub const WIDTH: f64 = 860.0;
/// Height of every figure (px).
pub const HEIGHT: f64 = 540.0;

/// Colours for series, in order: the Okabe–Ito palette (Okabe & Ito 2008, "Color Universal
/// Design"), without its yellow, which is too faint on white. Every pair stays apart under
/// deuteranopia and protanopia (CIEDE2000 ΔE ≥ 10 after the Machado et al. 2009 simulation:
/// tests/cvd.rs). A figure of more curves repeats a colour with another dash pattern
/// ([`series_dash`]) and marker ([`Shape::nth`]), so no two curves look alike.
pub const PALETTE: [&str; 7] = ["#0072B2", "#D55E00", "#009E73", "#E69F00", "#CC79A7", "#56B4E9", "#000000"];

/// The dash patterns that tell apart curves of one colour: solid, dashed, dotted, dash-dot.
pub const DASHES: [Option<&str>; 4] = [None, Some("7 4"), Some("2 3"), Some("8 3 2 3")];

/// The smallest figure size `--size` takes (px): room for the axes and a legend.
pub const MIN_SIZE: (f64, f64) = (480.0, 320.0);
/// The largest figure size `--size` takes (px).
pub const MAX_SIZE: (f64, f64) = (4000.0, 4000.0);

/// How a figure looks beyond its data: its size and whether its title is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Look {
    /// Width × height (px); None: the figure's own default ([`WIDTH`] × [`HEIGHT`], taller for
    /// the two-panel response).
    pub size: Option<(f64, f64)>,
    /// Draw the title above the plot (the SVG's `<title>` element is always there).
    pub title: bool,
}

impl Default for Look {
    fn default() -> Self {
        Look { size: None, title: true }
    }
}

/// Colour of curve `k` (from 0): the palette's, cycling.
pub fn series_color(k: usize) -> String {
    PALETTE[k % PALETTE.len()].to_string()
}

/// The dash pattern of curve `k`: solid for the first round of the palette's colours, then
/// dashed, dotted and dash-dot, so curve `k` and curve `k + 7` (one colour) differ.
pub fn series_dash(k: usize) -> Option<&'static str> {
    DASHES[(k / PALETTE.len()) % DASHES.len()]
}

/// `text` with the hyphen of every negative number set as a true minus sign (U+2212): `-2.5`
/// → `−2.5`, `1e-3` → `1e−3`; a hyphen between words stays.
pub fn minus(text: &str) -> String {
    let chars: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len() + 4);
    for (i, &c) in chars.iter().enumerate() {
        let next_is_digit = chars.get(i + 1).is_some_and(|d| d.is_ascii_digit() || *d == '.');
        let exponent = i > 1 && chars[i - 1] == 'e' && chars[i - 2].is_ascii_digit();
        let prev_is_word = i > 0 && (chars[i - 1] == '_' || chars[i - 1].is_alphabetic() && !exponent);
        if c == '-' && next_is_digit && !prev_is_word {
            out.push('\u{2212}');
        } else {
            out.push(c);
        }
    }
    out
}

/// Escapes text for XML content and attribute values.
pub fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c if (c as u32) < 0x20 && c != '\n' && c != '\t' => {}
            c => out.push(c),
        }
    }
    out
}

/// A number for an SVG attribute (two decimals are finer than a pixel).
fn n(v: f64) -> String {
    if v.is_finite() {
        let s = format!("{v:.2}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        "0".into()
    }
}

/// Horizontal anchoring of a text.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Anchor {
    Start,
    Middle,
    End,
}

impl Anchor {
    fn name(self) -> &'static str {
        match self {
            Anchor::Start => "start",
            Anchor::Middle => "middle",
            Anchor::End => "end",
        }
    }
}

/// An SVG document under construction, with a `<title>` (shown by viewers, read by tests).
#[derive(Debug, Clone)]
pub struct Svg {
    width: f64,
    height: f64,
    title: String,
    show_title: bool,
    defs: String,
    body: String,
}

impl Svg {
    /// An empty white canvas titled `title`.
    pub fn new(width: f64, height: f64, title: &str) -> Svg {
        let mut s =
            Svg { width, height, title: title.to_string(), show_title: true, defs: String::new(), body: String::new() };
        s.rect(0.0, 0.0, width, height, "white", None);
        s
    }

    /// A figure's canvas: `look`'s size (else `default`), its title drawn unless `look` says not.
    pub fn figure(look: &Look, default: (f64, f64), title: &str) -> Svg {
        let (w, h) = look.size.unwrap_or(default);
        let mut s = Svg::new(w, h, title);
        s.show_title = look.title;
        s
    }

    /// Width of the canvas (px).
    pub fn width(&self) -> f64 {
        self.width
    }

    /// Height of the canvas (px).
    pub fn height(&self) -> f64 {
        self.height
    }

    /// How much the figure's text and margins grow with its size: 1 at the default 860 × 540,
    /// in proportion to the smaller of the two ratios to it (`--size 1720x1080` draws text twice
    /// as large), never below 0.75 (the smallest size, 480 × 320) or above 4.
    pub fn scale(&self) -> f64 {
        (self.width / WIDTH).min(self.height / HEIGHT).clamp(0.75, 4.0)
    }

    /// Whether the title is drawn above the plot.
    pub fn shows_title(&self) -> bool {
        self.show_title
    }

    /// Adds raw definitions (e.g. a clip path) to `<defs>`; the caller escapes its text.
    pub fn def(&mut self, raw: &str) {
        self.defs.push_str(raw);
    }

    /// A straight line; `dash` is an SVG dash pattern like "6 4".
    pub fn line(&mut self, (x1, y1): (f64, f64), (x2, y2): (f64, f64), stroke: &str, width: f64, dash: Option<&str>) {
        let _ = writeln!(
            self.body,
            r#"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{}" stroke-width="{}"{}/>"#,
            n(x1),
            n(y1),
            n(x2),
            n(y2),
            escape(stroke),
            n(width),
            dash.map_or(String::new(), |d| format!(r#" stroke-dasharray="{}""#, escape(d)))
        );
    }

    /// A polyline through `points`, clipped to clip path `clip` if given.
    pub fn polyline(
        &mut self,
        points: &[(f64, f64)],
        stroke: &str,
        width: f64,
        dash: Option<&str>,
        clip: Option<&str>,
    ) {
        if points.is_empty() {
            return;
        }
        let pts: Vec<String> = points.iter().map(|&(x, y)| format!("{},{}", n(x), n(y))).collect();
        let _ = writeln!(
            self.body,
            r#"<polyline points="{}" fill="none" stroke="{}" stroke-width="{}" stroke-linejoin="round"{}{}/>"#,
            pts.join(" "),
            escape(stroke),
            n(width),
            dash.map_or(String::new(), |d| format!(r#" stroke-dasharray="{}""#, escape(d))),
            clip.map_or(String::new(), |c| format!(r#" clip-path="url(#{})""#, escape(c)))
        );
    }

    /// A rectangle filled with `fill`, outlined with `stroke` if given.
    pub fn rect(&mut self, x: f64, y: f64, w: f64, h: f64, fill: &str, stroke: Option<&str>) {
        let _ = writeln!(
            self.body,
            r#"<rect x="{}" y="{}" width="{}" height="{}" fill="{}"{}/>"#,
            n(x),
            n(y),
            n(w.max(0.0)),
            n(h.max(0.0)),
            escape(fill),
            stroke.map_or(String::new(), |s| format!(r#" stroke="{}" stroke-width="1""#, escape(s)))
        );
    }

    /// A filled circle.
    pub fn circle(&mut self, cx: f64, cy: f64, r: f64, fill: &str) {
        let _ = writeln!(self.body, r#"<circle cx="{}" cy="{}" r="{}" fill="{}"/>"#, n(cx), n(cy), n(r), escape(fill));
    }

    /// Marker `shape` (see [`Shape`]) of size `r` px at (`cx`, `cy`), filled with `fill`.
    pub fn marker(&mut self, shape: Shape, cx: f64, cy: f64, r: f64, fill: &str) {
        let poly = |pts: &[(f64, f64)]| {
            pts.iter().map(|(x, y)| format!("{},{}", n(cx + x * r), n(cy + y * r))).collect::<Vec<_>>().join(" ")
        };
        match shape {
            Shape::Circle => self.circle(cx, cy, r, fill),
            Shape::Square => self.rect(cx - 0.85 * r, cy - 0.85 * r, 1.7 * r, 1.7 * r, fill, None),
            Shape::Triangle => {
                let _ = writeln!(
                    self.body,
                    r#"<polygon points="{}" fill="{}"/>"#,
                    poly(&[(0.0, -1.2), (1.1, 0.9), (-1.1, 0.9)]),
                    escape(fill)
                );
            }
            Shape::Diamond => {
                let _ = writeln!(
                    self.body,
                    r#"<polygon points="{}" fill="{}"/>"#,
                    poly(&[(0.0, -1.25), (1.1, 0.0), (0.0, 1.25), (-1.1, 0.0)]),
                    escape(fill)
                );
            }
            Shape::TriangleDown => {
                let _ = writeln!(
                    self.body,
                    r#"<polygon points="{}" fill="{}"/>"#,
                    poly(&[(0.0, 1.2), (1.1, -0.9), (-1.1, -0.9)]),
                    escape(fill)
                );
            }
            Shape::Cross => {
                let (a, b) = (1.1, 0.38);
                let _ = writeln!(
                    self.body,
                    r#"<polygon points="{}" fill="{}"/>"#,
                    poly(&[
                        (-b, -a),
                        (b, -a),
                        (b, -b),
                        (a, -b),
                        (a, b),
                        (b, b),
                        (b, a),
                        (-b, a),
                        (-b, b),
                        (-a, b),
                        (-a, -b),
                        (-b, -b)
                    ]),
                    escape(fill)
                );
            }
        }
    }

    /// A text of font size `size` px, rotated by `rotate` degrees about its anchor point.
    pub fn text(&mut self, x: f64, y: f64, text: &str, size: f64, anchor: Anchor, rotate: f64) {
        let transform = if rotate == 0.0 {
            String::new()
        } else {
            format!(r#" transform="rotate({} {} {})""#, n(rotate), n(x), n(y))
        };
        let _ = writeln!(
            self.body,
            r#"<text x="{}" y="{}" font-size="{}" text-anchor="{}"{}>{}</text>"#,
            n(x),
            n(y),
            n(size),
            anchor.name(),
            transform,
            escape(text)
        );
    }

    /// A text in colour `fill` (e.g. a faint label behind data).
    pub fn text_fill(&mut self, x: f64, y: f64, text: &str, size: f64, anchor: Anchor, fill: &str) {
        let _ = writeln!(
            self.body,
            r#"<text x="{}" y="{}" font-size="{}" text-anchor="{}" fill="{}">{}</text>"#,
            n(x),
            n(y),
            n(size),
            anchor.name(),
            escape(fill),
            escape(text)
        );
    }

    /// The finished document.
    pub fn finish(self) -> String {
        format!(
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\" font-family=\"sans-serif\">\n<title>{}</title>\n<defs>{}</defs>\n{}</svg>\n",
            escape(&self.title),
            self.defs,
            self.body,
            w = n(self.width),
            h = n(self.height),
        )
    }
}

/// Linear or logarithmic axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scale {
    Linear,
    Log,
}

/// An axis: label (with unit), range and scale.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    pub label: String,
    pub lo: f64,
    pub hi: f64,
    pub scale: Scale,
}

impl Axis {
    /// A linear axis over the finite `values` that ends on round ticks around them, chosen
    /// to waste the least room ([`tick_step`]): ±90° data span −90 to 90 (ticks every 30°),
    /// 0.13–2.71 spans 0 to 3.
    pub fn fit(label: &str, values: impl IntoIterator<Item = f64>) -> Axis {
        let (lo, hi) = finite_range(values).unwrap_or((0.0, 1.0));
        let (lo, hi) = if hi - lo > 0.0 {
            (lo, hi)
        } else {
            let w = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
            (lo - w, hi + w)
        };
        let step = tick_step(lo, hi, is_angle(label));
        Axis {
            label: label.into(),
            lo: (lo / step + 1e-9).floor() * step,
            hi: (hi / step - 1e-9).ceil() * step,
            scale: Scale::Linear,
        }
    }

    /// A logarithmic axis over the positive `values`, from the largest 1-2-5 value at or below
    /// the smallest to the smallest at or above the largest: 0.05–20 m data span 0.05 to 20.
    pub fn fit_log(label: &str, values: impl IntoIterator<Item = f64>) -> Axis {
        let (lo, hi) = finite_range(values.into_iter().filter(|v| *v > 0.0)).unwrap_or((1.0, 10.0));
        let (lo, hi) = (round_125(lo, false), round_125(hi, true));
        Axis { label: label.into(), lo, hi: if hi > lo { hi } else { round_125(lo * 1.01, true) }, scale: Scale::Log }
    }

    /// A linear axis from `lo` to `hi` exactly.
    pub fn fixed(label: &str, lo: f64, hi: f64) -> Axis {
        Axis { label: label.into(), lo, hi, scale: Scale::Linear }
    }

    /// Where `v` falls on the axis, 0 at `lo` and 1 at `hi`.
    pub fn fraction(&self, v: f64) -> f64 {
        match self.scale {
            Scale::Linear => (v - self.lo) / (self.hi - self.lo),
            Scale::Log => (v.log10() - self.lo.log10()) / (self.hi.log10() - self.lo.log10()),
        }
    }

    /// Tick values and their labels (a true minus sign for negative values).
    pub fn ticks(&self) -> Vec<(f64, String)> {
        match self.scale {
            Scale::Linear => {
                let step = tick_step(self.lo, self.hi, is_angle(&self.label));
                let decimals = decimals(step);
                let first = (self.lo / step - 1e-9).ceil() as i64;
                let last = (self.hi / step + 1e-9).floor() as i64;
                (first..=last)
                    .map(|k| {
                        let v = k as f64 * step;
                        let v = if v.abs() < 1e-12 * step { 0.0 } else { v };
                        (v, minus(&format!("{v:.decimals$}")))
                    })
                    .collect()
            }
            Scale::Log => {
                let (a, b) = (self.lo.log10().floor() as i32, self.hi.log10().ceil() as i32);
                let mults: &[f64] = if self.hi / self.lo <= 1e4 { &[1.0, 2.0, 5.0] } else { &[1.0] };
                let inside = |v: &f64| *v >= self.lo * (1.0 - 1e-9) && *v <= self.hi * (1.0 + 1e-9);
                let mut values: Vec<f64> =
                    (a..=b).flat_map(|k| mults.iter().map(move |m| m * 10f64.powi(k))).filter(inside).collect();
                // The axis ends on its two ends' values (1-2-5 values, from Axis::fit_log).
                for end in [self.lo, self.hi] {
                    if !values.iter().any(|v| (v / end - 1.0).abs() < 1e-9) {
                        values.push(end);
                    }
                }
                values.sort_by(f64::total_cmp);
                values.into_iter().map(|v| (v, minus(&format_log_tick(v)))).collect()
            }
        }
    }
}

/// Whether an axis label is of an angle in degrees (its ticks may step by 15°, 30°, 45°, 90°).
fn is_angle(label: &str) -> bool {
    label.ends_with("(deg)") || label.ends_with("(°)")
}

/// Decimals a tick label of step `step` needs (2.5 → 1).
fn decimals(step: f64) -> usize {
    (0..=12)
        .find(|&d| {
            ((step * 10f64.powi(d)).round() - step * 10f64.powi(d)).abs() < 1e-6 * step.max(1e-300) * 10f64.powi(d)
        })
        .unwrap_or(12) as usize
}

/// The tick step for data `lo..hi`: of the round steps (1, 2, 2.5 and 5 times a power of ten,
/// and 15°, 30°, 45° and 90° on an angle axis), the one whose ticks around the data leave the
/// least empty room, with 3 to 10 intervals (a near tie goes to about six intervals).
pub fn tick_step(lo: f64, hi: f64, angle: bool) -> f64 {
    let span = hi - lo;
    if !(span.is_finite() && span > 0.0) {
        return 1.0;
    }
    let mag = 10f64.powf((span / 6.0).log10().floor());
    let mut candidates: Vec<f64> =
        [0.1, 0.2, 0.25, 0.5, 1.0, 2.0, 2.5, 5.0, 10.0, 20.0, 25.0, 50.0].iter().map(|m| m * mag).collect();
    if angle {
        candidates.extend([15.0, 30.0, 45.0, 90.0]);
    }
    let score = |step: f64| {
        let (a, b) = ((lo / step + 1e-9).floor(), (hi / step - 1e-9).ceil());
        let n = b - a;
        if !(3.0..=10.0).contains(&n) {
            return f64::INFINITY;
        }
        (1.0 - span / (n * step)) + 0.02 * (n - 6.0).abs()
    };
    candidates
        .into_iter()
        .min_by(|a, b| score(*a).total_cmp(&score(*b)))
        .filter(|s| score(*s).is_finite())
        .unwrap_or_else(|| nice_step(span / 6.0))
}

/// The nearest 1-2-5 value (1, 2 or 5 times a power of ten) at or above `v` (`up`), or at or
/// below it.
fn round_125(v: f64, up: bool) -> f64 {
    let mag = 10f64.powf(v.log10().floor());
    let steps = [1.0, 2.0, 5.0, 10.0];
    if up {
        steps.iter().map(|s| s * mag).find(|s| *s >= v * (1.0 - 1e-9)).unwrap_or(10.0 * mag)
    } else {
        steps.iter().rev().map(|s| s * mag).find(|s| *s <= v * (1.0 + 1e-9)).unwrap_or(mag)
    }
}

/// A log tick label: plain for 0.001–99999, else scientific.
fn format_log_tick(v: f64) -> String {
    if (1e-3..1e5).contains(&v) {
        let s = format!("{v:.3}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        format!("{v:.0e}")
    }
}

/// Smallest and largest of the finite values, if any.
fn finite_range(values: impl IntoIterator<Item = f64>) -> Option<(f64, f64)> {
    values.into_iter().filter(|v| v.is_finite()).fold(None, |acc, v| match acc {
        None => Some((v, v)),
        Some((a, b)) => Some((a.min(v), b.max(v))),
    })
}

/// The 1-2-5 step nearest above `raw`.
pub fn nice_step(raw: f64) -> f64 {
    if !(raw.is_finite() && raw > 0.0) {
        return 1.0;
    }
    let mag = 10f64.powf(raw.log10().floor());
    let f = raw / mag;
    mag * if f <= 1.0 {
        1.0
    } else if f <= 2.0 {
        2.0
    } else if f <= 5.0 {
        5.0
    } else {
        10.0
    }
}

/// The label of the varied parameter on an axis: `freq (Hz)`.
pub fn param_label(name: &str, unit: &str) -> String {
    if unit.is_empty() {
        name.to_string()
    } else {
        format!("{name} ({unit})")
    }
}

/// The plotting area of a figure and its axes: maps data to pixels and draws the frame.
#[derive(Debug, Clone)]
pub struct Frame {
    pub left: f64,
    pub top: f64,
    pub width: f64,
    pub height: f64,
    pub x: Axis,
    pub y: Axis,
}

/// Id of the clip path of the plotting area.
pub const CLIP: &str = "plot-area";

/// Colour of the grid lines.
pub const GRID: &str = "#e6e6e6";

impl Frame {
    /// The standard frame of a figure on `svg`'s canvas; `legend` leaves room on the right, a
    /// drawn title room at the top.
    pub fn standard(svg: &Svg, x: Axis, y: Axis, legend: bool) -> Frame {
        let s = svg.scale();
        let right = if legend { 200.0 } else { 30.0 } * s;
        let (top, left) = (Frame::top_margin(svg), Frame::left_margin(svg));
        Frame {
            left,
            top,
            width: svg.width() - left - right,
            height: svg.height() - top - Frame::bottom_margin(svg),
            x,
            y,
        }
    }

    /// Room above the plotting area (px): for the title if drawn; grows with the text.
    pub fn top_margin(svg: &Svg) -> f64 {
        if svg.shows_title() {
            50.0 * svg.scale()
        } else {
            20.0 * svg.scale()
        }
    }

    /// Room left of the plotting area (px): the tick labels and the y axis's label.
    pub fn left_margin(svg: &Svg) -> f64 {
        85.0 * svg.scale()
    }

    /// Room below the plotting area (px): the tick labels and the x axis's label.
    pub fn bottom_margin(svg: &Svg) -> f64 {
        70.0 * svg.scale()
    }

    /// Pixel x of data value `v`.
    pub fn px(&self, v: f64) -> f64 {
        self.left + self.x.fraction(v) * self.width
    }

    /// Pixel y of data value `v`.
    pub fn py(&self, v: f64) -> f64 {
        self.top + (1.0 - self.y.fraction(v)) * self.height
    }

    /// Draws the grid, then the title, the box, ticks with labels and the axis labels, and
    /// defines the clip path [`CLIP`]. Call it before drawing data, so the grid lies under it.
    pub fn draw(&self, svg: &mut Svg, title: &str) {
        self.draw_panel(svg, Some(title), CLIP);
    }

    /// As [`Frame::draw`] for one panel of a figure of several: the title only if given (and
    /// the canvas shows titles), and the clip path under the id `clip` (one per panel).
    pub fn draw_panel(&self, svg: &mut Svg, title: Option<&str>, clip: &str) {
        self.grid(svg);
        self.axes(svg, title, clip);
    }

    /// The light grid lines at the ticks, alone: drawn first, under the data (cells, curves).
    pub fn grid(&self, svg: &mut Svg) {
        let bottom = self.top + self.height;
        for (v, _) in self.x.ticks() {
            let x = self.px(v);
            svg.line((x, self.top), (x, bottom), GRID, 1.0, None);
        }
        for (v, _) in self.y.ticks() {
            let y = self.py(v);
            svg.line((self.left, y), (self.left + self.width, y), GRID, 1.0, None);
        }
    }

    /// Everything of [`Frame::draw_panel`] but the grid: the clip path, the title, the ticks
    /// outside the box, the box and the axis labels (none of it over the plotting area's inside).
    pub fn axes(&self, svg: &mut Svg, title: Option<&str>, clip: &str) {
        svg.def(&format!(
            r#"<clipPath id="{}"><rect x="{}" y="{}" width="{}" height="{}"/></clipPath>"#,
            escape(clip),
            n(self.left),
            n(self.top),
            n(self.width),
            n(self.height)
        ));
        let k = svg.scale();
        if let Some(title) = title.filter(|_| svg.shows_title()) {
            let room = svg.width() / WIDTH;
            let size = (17.0 * 78.0 * room / title.chars().count().max(1) as f64).clamp(11.0 * k, 17.0 * k);
            svg.text(svg.width() / 2.0, 28.0 * k, &minus(title), size, Anchor::Middle, 0.0);
        }
        let bottom = self.top + self.height;
        for (v, label) in self.x.ticks() {
            let x = self.px(v);
            svg.line((x, bottom), (x, bottom + 5.0 * k), "black", k, None);
            svg.text(x, bottom + 20.0 * k, &label, 12.0 * k, Anchor::Middle, 0.0);
        }
        for (v, label) in self.y.ticks() {
            let y = self.py(v);
            svg.line((self.left - 5.0 * k, y), (self.left, y), "black", k, None);
            svg.text(self.left - 8.0 * k, y + 4.0 * k, &label, 12.0 * k, Anchor::End, 0.0);
        }
        svg.rect(self.left, self.top, self.width, self.height, "none", Some("black"));
        svg.text(self.left + self.width / 2.0, bottom + 48.0 * k, &self.x.label, 14.0 * k, Anchor::Middle, 0.0);
        let yc = self.top + self.height / 2.0;
        svg.text(22.0 * k, yc, &self.y.label, 14.0 * k, Anchor::Middle, -90.0);
    }

    /// A horizontal reference line at `v` with a label at its right end.
    pub fn hline(&self, svg: &mut Svg, v: f64, label: &str, color: &str) {
        let (y, k) = (self.py(v), svg.scale());
        svg.line((self.left, y), (self.left + self.width, y), color, 1.5 * k, Some("6 4"));
        svg.text(self.left + self.width - 4.0 * k, y - 5.0 * k, &minus(label), 12.0 * k, Anchor::End, 0.0);
    }

    /// A vertical reference line at `v` with a label at its top.
    pub fn vline(&self, svg: &mut Svg, v: f64, label: &str, color: &str) {
        let (x, k) = (self.px(v), svg.scale());
        svg.line((x, self.top), (x, self.top + self.height), color, 1.5 * k, Some("6 4"));
        svg.text(x + 4.0 * k, self.top + 14.0 * k, &minus(label), 12.0 * k, Anchor::Start, 0.0);
    }
}

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Style {
    Line,
    Dashed,
    Markers,
    LineMarkers,
}

/// The shape of a series' markers; series of one figure get different shapes, so they differ
/// without colour too.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Shape {
    Circle,
    Square,
    Triangle,
    Diamond,
    TriangleDown,
    Cross,
}

impl Shape {
    /// The shapes, in the order curves take them.
    pub const ALL: [Shape; 6] =
        [Shape::Circle, Shape::Square, Shape::Triangle, Shape::Diamond, Shape::TriangleDown, Shape::Cross];

    /// Shape number `k` (cycling through the six).
    pub fn nth(k: usize) -> Shape {
        Shape::ALL[k % Shape::ALL.len()]
    }
}

/// One named series of (x, y) points in axis units.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
    pub style: Style,
    /// Its colour; None: the figure's k-th ([`series_color`]).
    pub color: Option<String>,
    /// Its marker shape; None: the k-th ([`Shape::nth`]).
    pub shape: Option<Shape>,
    /// Its line's dash pattern (None inside: solid); None: a [`Style::Dashed`] series' dashes,
    /// else the k-th's ([`series_dash`]).
    pub dash: Option<Option<&'static str>>,
}

impl Series {
    pub fn new(label: &str, points: Vec<(f64, f64)>, style: Style) -> Series {
        Series { label: label.into(), points, style, color: None, shape: None, dash: None }
    }

    /// The series' line drawn with dash pattern `dash` (None: solid).
    #[must_use]
    pub fn dashed(mut self, dash: Option<&'static str>) -> Series {
        self.dash = Some(dash);
        self
    }

    /// The series drawn in `color`.
    #[must_use]
    pub fn colored(mut self, color: String) -> Series {
        self.color = Some(color);
        self
    }

    /// The series' markers drawn as `shape`.
    #[must_use]
    pub fn shaped(mut self, shape: Shape) -> Series {
        self.shape = Some(shape);
        self
    }
}

/// How one series is drawn: colour, marker shape and dash pattern (None: solid).
#[derive(Debug, Clone, PartialEq)]
struct SeriesLook {
    color: String,
    shape: Shape,
    dash: Option<&'static str>,
}

/// The look each series is drawn with: its own, else the k-th colour, shape and dash.
fn looks(series: &[Series]) -> Vec<SeriesLook> {
    series
        .iter()
        .enumerate()
        .map(|(k, s)| SeriesLook {
            color: s.color.clone().unwrap_or_else(|| series_color(k)),
            shape: s.shape.unwrap_or(Shape::nth(k)),
            dash: s.dash.unwrap_or(if s.style == Style::Dashed { Some("7 4") } else { series_dash(k) }),
        })
        .collect()
}

/// Draws the series into `frame` with the palette's colours, and a legend on the right when
/// there is more than one series. Points that are not finite break the line.
pub fn draw_series(svg: &mut Svg, frame: &Frame, series: &[Series]) {
    draw_series_clipped(svg, frame, series, CLIP);
}

/// As [`draw_series`], clipped to the clip path `clip` (a panel's, see [`Frame::draw_panel`]).
pub fn draw_series_clipped(svg: &mut Svg, frame: &Frame, series: &[Series], clip: &str) {
    let looks = looks(series);
    let k = svg.scale();
    for (s, look) in series.iter().zip(&looks) {
        let color = look.color.as_str();
        let lines = matches!(s.style, Style::Line | Style::Dashed | Style::LineMarkers);
        if lines {
            for run in s.points.split(|p| !(p.0.is_finite() && p.1.is_finite())) {
                let px: Vec<(f64, f64)> = run.iter().map(|&(x, y)| (frame.px(x), frame.py(y))).collect();
                svg.polyline(&px, color, 1.8 * k, look.dash, Some(clip));
            }
        }
        if matches!(s.style, Style::Markers | Style::LineMarkers) {
            for &(x, y) in s.points.iter().filter(|p| p.0.is_finite() && p.1.is_finite()) {
                let (cx, cy) = (frame.px(x), frame.py(y));
                let inside = (frame.left..=frame.left + frame.width).contains(&cx)
                    && (frame.top..=frame.top + frame.height).contains(&cy);
                if inside {
                    svg.marker(look.shape, cx, cy, 3.2 * k, color);
                }
            }
        }
    }
    if series.len() > 1 {
        series_legend(svg, frame, series, &looks);
    }
}

/// The order of the legend's entries: the curves' own order top to bottom where they end (by
/// the last finite value of each, highest first), so the legend reads as the curves lie.
pub fn legend_order(series: &[Series]) -> Vec<usize> {
    let last = |s: &Series| s.points.iter().rev().find(|p| p.0.is_finite() && p.1.is_finite()).map(|p| p.1);
    let mut order: Vec<usize> = (0..series.len()).collect();
    order.sort_by(|&a, &b| match (last(&series[a]), last(&series[b])) {
        (Some(x), Some(y)) => y.total_cmp(&x).then(a.cmp(&b)),
        (Some(_), None) => std::cmp::Ordering::Less,
        (None, Some(_)) => std::cmp::Ordering::Greater,
        (None, None) => a.cmp(&b),
    });
    order
}

/// The legend of `series`, each entry drawn as the series is: a short line (with its dashes)
/// and its marker, in its colour, in the curves' order top to bottom ([`legend_order`]).
fn series_legend(svg: &mut Svg, frame: &Frame, series: &[Series], looks: &[SeriesLook]) {
    let k = svg.scale();
    let x = frame.left + frame.width + 12.0 * k;
    for (row, i) in legend_order(series).into_iter().enumerate() {
        let (s, look) = (&series[i], &looks[i]);
        let y = frame.top + (10.0 + 20.0 * row as f64) * k;
        if matches!(s.style, Style::Line | Style::Dashed | Style::LineMarkers) {
            svg.line((x, y - 4.0 * k), (x + 24.0 * k, y - 4.0 * k), &look.color, 1.8 * k, look.dash);
        }
        if matches!(s.style, Style::Markers | Style::LineMarkers) {
            svg.marker(look.shape, x + 12.0 * k, y - 4.0 * k, 3.2 * k, &look.color);
        }
        svg.text(x + 30.0 * k, y, &minus(&s.label), 11.0 * k, Anchor::Start, 0.0);
    }
}

/// A legend of coloured swatches (cell fills) to the right of the frame.
pub fn legend(svg: &mut Svg, frame: &Frame, entries: &[(&str, &str)]) {
    let s = svg.scale();
    let x = frame.left + frame.width + 15.0 * s;
    for (k, (color, label)) in entries.iter().enumerate() {
        let y = frame.top + (10.0 + 20.0 * k as f64) * s;
        svg.rect(x, y - 9.0 * s, 18.0 * s, 10.0 * s, color, Some("#333333"));
        svg.text(x + 24.0 * s, y, label, 11.0 * s, Anchor::Start, 0.0);
    }
}

/// A complete x–y figure: title, axes, series (and a legend when there are several).
pub fn line_plot(title: &str, look: &Look, x: Axis, y: Axis, series: &[Series]) -> String {
    let mut svg = Svg::figure(look, (WIDTH, HEIGHT), title);
    let mut frame = Frame::standard(&svg, x, y, series.len() > 1);
    if series.len() > 1 {
        // Room for the longest label right of the frame (a character of 11 px text is at most
        // about 0.6 em wide), with a margin: the legend never touches the figure's edge.
        let k = svg.scale();
        let longest = series.iter().map(|s| minus(&s.label).chars().count()).max().unwrap_or(0) as f64;
        let need = (12.0 + 30.0 + 0.6 * 11.0 * longest + 12.0) * k;
        let have = svg.width() - frame.left - frame.width;
        if need > have {
            frame.width -= need - have;
        }
    }
    frame.draw(&mut svg, title);
    draw_series(&mut svg, &frame, series);
    svg.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A legend's longest label ends inside the figure, a margin from its edge.
    #[test]
    fn a_long_legend_label_keeps_clear_of_the_edge() {
        let pts = vec![(0.0, 1.0), (1.0, 2.0)];
        let series = [
            Series::new("measured envelope", pts.clone(), Style::LineMarkers),
            Series::new("median run at the fitted c1", pts.clone(), Style::Dashed),
        ];
        let doc = line_plot("t", &Look::default(), Axis::fit("x", [0.0, 1.0]), Axis::fit("y", [1.0, 2.0]), &series);
        let at = doc.find(">median run at the fitted c1<").unwrap();
        let tag = &doc[doc[..at].rfind("<text").unwrap()..at];
        let x: f64 = tag.split("x=\"").nth(1).unwrap().split('"').next().unwrap().parse().unwrap();
        let end = x + 0.6 * 11.0 * "median run at the fitted c1".len() as f64;
        assert!(end + 10.0 <= WIDTH, "the label ends at {end} of {WIDTH}");
    }

    #[test]
    fn text_is_escaped() {
        assert_eq!(escape(r#"a<b & "c" 'd'>"#), "a&lt;b &amp; &quot;c&quot; &apos;d&apos;&gt;");
        let mut s = Svg::new(10.0, 10.0, "<x>");
        s.text(1.0, 1.0, "p & q", 10.0, Anchor::Start, 0.0);
        let doc = s.finish();
        assert!(doc.contains("<title>&lt;x&gt;</title>") && doc.contains(">p &amp; q</text>"));
    }

    #[test]
    fn ticks_are_nice_and_inside() {
        let a = Axis::fit("x", [0.13, 2.71]);
        let t = a.ticks();
        assert!(t.len() >= 4 && t.len() <= 15, "{t:?}");
        assert!(t.iter().all(|(v, _)| *v >= a.lo - 1e-12 && *v <= a.hi + 1e-12));
        assert_eq!(nice_step(0.33), 0.5);
        // Figs 7 and 12: 0.05–20 m of data span 0.05 to 20 m, not whole decades.
        let l = Axis::fit_log("r", [0.05, 20.0]);
        assert_eq!((l.lo, l.hi), (0.05, 20.0));
        let labels: Vec<String> = l.ticks().into_iter().map(|t| t.1).collect();
        assert_eq!(labels, ["0.05", "0.1", "0.2", "0.5", "1", "2", "5", "10", "20"]);
        // Fig 3: ±90° of data span −90 to 90, ticks every 30°, with a true minus sign.
        let a = Axis::fit("observer angle θ (deg)", [-90.0, -45.0, 90.0]);
        assert_eq!((a.lo, a.hi), (-90.0, 90.0));
        let labels: Vec<String> = a.ticks().into_iter().map(|t| t.1).collect();
        assert_eq!(labels, ["\u{2212}90", "\u{2212}60", "\u{2212}30", "0", "30", "60", "90"]);
        // A plain axis ends on ticks around its data and wastes little room.
        let b = Axis::fit("x", [0.13, 2.71]);
        assert!(b.lo <= 0.13 && b.hi >= 2.71 && (b.hi - b.lo) <= 1.3 * (2.71 - 0.13), "{b:?}");
        assert_eq!(minus("-2.5 and 1e-3, a well-known x-1"), "\u{2212}2.5 and 1e\u{2212}3, a well-known x-1");
    }
}
