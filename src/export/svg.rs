//! A small SVG writer: an escaped document builder, axes with "nice" ticks (linear or log),
//! line/marker plots with a legend, and a cell map. No fonts or system libraries: text is left
//! to the viewer's sans-serif font. Coordinates are in SVG pixels; data values in the units of
//! the axis labels (the callers convert from SI for the labels).

use std::fmt::Write as _;

/// Width of every figure (px).
pub const WIDTH: f64 = 860.0;
/// Height of every figure (px).
pub const HEIGHT: f64 = 540.0;

/// Colours for series, in order (colour-blind friendly "tableau 10"); a figure of more series
/// takes its colours from [`sequential`] instead, so no colour is used twice.
pub const PALETTE: [&str; 10] =
    ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"];

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

/// Colour `k` of `n` distinct colours: the palette for up to 10, else evenly spaced along a
/// sequential map ([`sequential`]).
pub fn series_color(k: usize, n: usize) -> String {
    if n <= PALETTE.len() {
        PALETTE[k % PALETTE.len()].to_string()
    } else {
        sequential(k as f64 / (n - 1).max(1) as f64)
    }
}

/// A colour of the sequential "viridis" map at `f` in [0, 1] (dark purple to green; stops at
/// 0.85 of the map, before its pale yellow end, so every colour reads on white).
pub fn sequential(f: f64) -> String {
    let f = if f.is_finite() { f.clamp(0.0, 1.0) } else { 0.0 } * 0.85;
    let stops: [(f64, f64, f64); 5] =
        [(68.0, 1.0, 84.0), (59.0, 82.0, 139.0), (33.0, 145.0, 140.0), (94.0, 201.0, 98.0), (253.0, 231.0, 37.0)];
    let k = ((f * 4.0).floor() as usize).min(3);
    let (a, b, t) = (stops[k], stops[k + 1], f * 4.0 - k as f64);
    let mix = |p: f64, q: f64| (p + (q - p) * t).round() as u8;
    format!("#{:02x}{:02x}{:02x}", mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
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
    /// A linear axis over the finite `values`, widened by 5 % each side and to nice ticks.
    pub fn fit(label: &str, values: impl IntoIterator<Item = f64>) -> Axis {
        let (lo, hi) = finite_range(values).unwrap_or((0.0, 1.0));
        let (lo, hi) = if hi - lo > 0.0 {
            let pad = 0.05 * (hi - lo);
            (lo - pad, hi + pad)
        } else {
            let w = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
            (lo - w, hi + w)
        };
        let step = nice_step((hi - lo) / 20.0);
        Axis {
            label: label.into(),
            lo: (lo / step).floor() * step,
            hi: (hi / step).ceil() * step,
            scale: Scale::Linear,
        }
    }

    /// A logarithmic axis over the positive `values`, to whole decades.
    pub fn fit_log(label: &str, values: impl IntoIterator<Item = f64>) -> Axis {
        let (lo, hi) = finite_range(values.into_iter().filter(|v| *v > 0.0)).unwrap_or((1.0, 10.0));
        let (lo, hi) = (10f64.powf(lo.log10().floor()), 10f64.powf(hi.log10().ceil()));
        Axis { label: label.into(), lo, hi: if hi > lo { hi } else { lo * 10.0 }, scale: Scale::Log }
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

    /// Tick values and their labels.
    pub fn ticks(&self) -> Vec<(f64, String)> {
        match self.scale {
            Scale::Linear => {
                let step = nice_step((self.hi - self.lo) / 7.0);
                let decimals = (-step.log10().floor()).max(0.0) as usize;
                let first = (self.lo / step - 1e-9).ceil() as i64;
                let last = (self.hi / step + 1e-9).floor() as i64;
                (first..=last)
                    .map(|k| {
                        let v = k as f64 * step;
                        let v = if v.abs() < 1e-12 * step { 0.0 } else { v };
                        (v, format!("{v:.decimals$}"))
                    })
                    .collect()
            }
            Scale::Log => {
                let (a, b) = (self.lo.log10().round() as i32, self.hi.log10().round() as i32);
                let mults: &[f64] = if b - a <= 2 { &[1.0, 2.0, 5.0] } else { &[1.0] };
                (a..=b)
                    .flat_map(|k| mults.iter().map(move |m| m * 10f64.powi(k)))
                    .filter(|v| *v >= self.lo * (1.0 - 1e-9) && *v <= self.hi * (1.0 + 1e-9))
                    .map(|v| (v, format_log_tick(v)))
                    .collect()
            }
        }
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
        let right = if legend { 200.0 } else { 30.0 };
        let top = Frame::top_margin(svg);
        Frame { left: 85.0, top, width: svg.width() - 85.0 - right, height: svg.height() - top - 70.0, x, y }
    }

    /// Room above the plotting area (px): for the title if drawn.
    pub fn top_margin(svg: &Svg) -> f64 {
        if svg.shows_title() {
            50.0
        } else {
            20.0
        }
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
        if let Some(title) = title.filter(|_| svg.shows_title()) {
            let room = svg.width() / WIDTH;
            let size = (17.0 * 78.0 * room / title.chars().count().max(1) as f64).clamp(11.0, 17.0);
            svg.text(svg.width() / 2.0, 28.0, title, size, Anchor::Middle, 0.0);
        }
        let bottom = self.top + self.height;
        for (v, label) in self.x.ticks() {
            let x = self.px(v);
            svg.line((x, bottom), (x, bottom + 5.0), "black", 1.0, None);
            svg.text(x, bottom + 20.0, &label, 12.0, Anchor::Middle, 0.0);
        }
        for (v, label) in self.y.ticks() {
            let y = self.py(v);
            svg.line((self.left - 5.0, y), (self.left, y), "black", 1.0, None);
            svg.text(self.left - 8.0, y + 4.0, &label, 12.0, Anchor::End, 0.0);
        }
        svg.rect(self.left, self.top, self.width, self.height, "none", Some("black"));
        svg.text(self.left + self.width / 2.0, bottom + 48.0, &self.x.label, 14.0, Anchor::Middle, 0.0);
        let yc = self.top + self.height / 2.0;
        svg.text(22.0, yc, &self.y.label, 14.0, Anchor::Middle, -90.0);
    }

    /// A horizontal reference line at `v` with a label at its right end.
    pub fn hline(&self, svg: &mut Svg, v: f64, label: &str, color: &str) {
        let y = self.py(v);
        svg.line((self.left, y), (self.left + self.width, y), color, 1.5, Some("6 4"));
        svg.text(self.left + self.width - 4.0, y - 5.0, label, 12.0, Anchor::End, 0.0);
    }

    /// A vertical reference line at `v` with a label at its top.
    pub fn vline(&self, svg: &mut Svg, v: f64, label: &str, color: &str) {
        let x = self.px(v);
        svg.line((x, self.top), (x, self.top + self.height), color, 1.5, Some("6 4"));
        svg.text(x + 4.0, self.top + 14.0, label, 12.0, Anchor::Start, 0.0);
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
}

impl Shape {
    /// Shape number `k` (cycling through the four).
    pub fn nth(k: usize) -> Shape {
        [Shape::Circle, Shape::Square, Shape::Triangle, Shape::Diamond][k % 4]
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
}

impl Series {
    pub fn new(label: &str, points: Vec<(f64, f64)>, style: Style) -> Series {
        Series { label: label.into(), points, style, color: None, shape: None }
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

/// The colour and marker shape each series is drawn with: its own, else the k-th of `n`.
fn looks(series: &[Series]) -> Vec<(String, Shape)> {
    let n = series.len();
    series
        .iter()
        .enumerate()
        .map(|(k, s)| (s.color.clone().unwrap_or_else(|| series_color(k, n)), s.shape.unwrap_or(Shape::nth(k))))
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
    for (s, (color, shape)) in series.iter().zip(&looks) {
        let color = color.as_str();
        let lines = matches!(s.style, Style::Line | Style::Dashed | Style::LineMarkers);
        let dash = (s.style == Style::Dashed).then_some("7 4");
        if lines {
            for run in s.points.split(|p| !(p.0.is_finite() && p.1.is_finite())) {
                let px: Vec<(f64, f64)> = run.iter().map(|&(x, y)| (frame.px(x), frame.py(y))).collect();
                svg.polyline(&px, color, 1.8, dash, Some(clip));
            }
        }
        if matches!(s.style, Style::Markers | Style::LineMarkers) {
            for &(x, y) in s.points.iter().filter(|p| p.0.is_finite() && p.1.is_finite()) {
                let (cx, cy) = (frame.px(x), frame.py(y));
                let inside = (frame.left..=frame.left + frame.width).contains(&cx)
                    && (frame.top..=frame.top + frame.height).contains(&cy);
                if inside {
                    svg.marker(*shape, cx, cy, 3.2, color);
                }
            }
        }
    }
    if series.len() > 1 {
        series_legend(svg, frame, series, &looks);
    }
}

/// The legend of `series`, each entry drawn as the series is: a short line (dashed if the
/// series is) and its marker, in its colour.
fn series_legend(svg: &mut Svg, frame: &Frame, series: &[Series], looks: &[(String, Shape)]) {
    let x = frame.left + frame.width + 12.0;
    for (k, (s, (color, shape))) in series.iter().zip(looks).enumerate() {
        let y = frame.top + 10.0 + 20.0 * k as f64;
        if matches!(s.style, Style::Line | Style::Dashed | Style::LineMarkers) {
            let dash = (s.style == Style::Dashed).then_some("7 4");
            svg.line((x, y - 4.0), (x + 24.0, y - 4.0), color, 1.8, dash);
        }
        if matches!(s.style, Style::Markers | Style::LineMarkers) {
            svg.marker(*shape, x + 12.0, y - 4.0, 3.2, color);
        }
        svg.text(x + 30.0, y, &s.label, 11.0, Anchor::Start, 0.0);
    }
}

/// A legend of coloured swatches (cell fills) to the right of the frame.
pub fn legend(svg: &mut Svg, frame: &Frame, entries: &[(&str, &str)]) {
    let x = frame.left + frame.width + 15.0;
    for (k, (color, label)) in entries.iter().enumerate() {
        let y = frame.top + 10.0 + 20.0 * k as f64;
        svg.rect(x, y - 9.0, 18.0, 10.0, color, None);
        svg.text(x + 24.0, y, label, 11.0, Anchor::Start, 0.0);
    }
}

/// A complete x–y figure: title, axes, series (and a legend when there are several).
pub fn line_plot(title: &str, look: &Look, x: Axis, y: Axis, series: &[Series]) -> String {
    let mut svg = Svg::figure(look, (WIDTH, HEIGHT), title);
    let frame = Frame::standard(&svg, x, y, series.len() > 1);
    frame.draw(&mut svg, title);
    draw_series(&mut svg, &frame, series);
    svg.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

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
        let l = Axis::fit_log("r", [0.05, 20.0]);
        assert_eq!((l.lo, l.hi), (0.01, 100.0));
        assert_eq!(l.ticks().iter().map(|t| t.1.as_str()).collect::<Vec<_>>(), ["0.01", "0.1", "1", "10", "100"]);
    }
}
