//! The design chart: the mass × gap grid with the zone number drawn in every cell (not colour
//! alone), the current design marked in the cell nearest its mass with its own zone; and the
//! second view, e against SPLmax (Fig 17) with the L* and e* lines.
//!
//! One truth: the marker's zone is the live design's own (the readout's), never a cell's. The
//! marker stays inside its cell, so the cells beside it show their own zones: `[n]` around the
//! glyph where the cell is three or more columns wide, else the zone glyph alone in the cursor
//! style (reversed, underlined). A gap between two rows' is drawn between them (on the spacer
//! lines of cells taller than a line); a design off the chart's range is an arrow in the edge
//! cell with a line saying so. The axes have titles with units and round ticks, each tick on
//! the glyph line (column) of the row (column) whose value is nearest it, so within half a
//! step of it and never on a spacer line; the legend (zones 1–4, no impact, pending) is always
//! drawn, below or beside the grid as space allows.
//!
//! An ensemble chart (N > 1 runs a cell) draws each cell in the zone of its medians; a cell
//! where fewer than 70 % of its runs are in that zone is shaded — its blank filled with `░`
//! (`:` in ASCII) and dim, or underlined where the cell is one character — so it reads without
//! colour too, and the legend says what the shading means.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::widgets::{Block, Paragraph, Widget};

pub mod panel;

use super::plot::{fit_bounds, tick_step, ticks, Curve, LinePlot};
use super::theme::{Palette, Role};
use crate::design::Zone;
use crate::units::sig;

/// What is known about one cell of the fine grid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CellView {
    /// Nothing yet.
    Empty,
    /// Borrowed from the nearest cell of the coarse grid (drawn dim).
    Approx(Option<Zone>),
    /// Computed on this grid. `None`: no zone (no impacts or fewer than two maxima).
    Exact(Option<Zone>),
    /// An ensemble cell in the zone of its medians where fewer than 70 % of its runs agree.
    Unsure(Option<Zone>),
}

/// What the marker of the live design shows: its own zone (the readout's), or that it is
/// still being computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DesignZone {
    Computing,
    /// The live design's zone; None: no zone (no impact or too few maxima).
    Known(Option<Zone>),
}

impl DesignZone {
    /// The marker's text: `[n]`, `[-]` (no zone) or `[?]` (computing).
    pub fn marker(self) -> String {
        format!("[{}]", self.glyph())
    }

    /// The zone's glyph alone: `n`, `-` or `?`.
    pub fn glyph(self) -> String {
        match self {
            DesignZone::Computing => "?".into(),
            DesignZone::Known(z) => glyph(z),
        }
    }
}

/// Width of the gap labels on the left of the grid ("  4.0 ").
pub const LABEL_W: u16 = 6;
/// Widest cell (columns) and tallest cell (rows).
const CELL_W_MAX: u16 = 6;
const CELL_H_MAX: u16 = 3;

/// Where the cells are on screen: used to draw them and to map a mouse click to a cell. When
/// the grid has more cells than the panel has room for, evenly spaced rows/columns are shown.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Geometry {
    /// The rectangle covered by the cells.
    pub cells: Rect,
    pub cell_w: u16,
    pub cell_h: u16,
    /// Grid mass index of each displayed column, left to right.
    pub cols: Vec<usize>,
    /// Grid gap index of each displayed row, bottom to top.
    pub rows: Vec<usize>,
}

/// `shown` indices evenly spread over `0..n` (all of them if they fit).
fn sample(n: usize, shown: usize) -> Vec<usize> {
    match shown {
        0 => vec![],
        1 => vec![0],
        _ if shown >= n => (0..n).collect(),
        _ => (0..shown).map(|i| (i * (n - 1) + (shown - 1) / 2) / (shown - 1)).collect(),
    }
}

impl Geometry {
    /// Lays out an `n_masses × n_gaps` grid in `area` (gap labels on its left included);
    /// None if fewer than 2 × 2 cells fit.
    pub fn new(area: Rect, n_masses: usize, n_gaps: usize) -> Option<Self> {
        let avail_w = area.width.checked_sub(LABEL_W)?;
        let avail_h = area.height;
        let (dm, dg) = (n_masses.min(avail_w as usize), n_gaps.min(avail_h as usize));
        if dm < 2 || dg < 2 {
            return None;
        }
        let cell_w = (avail_w / dm as u16).min(CELL_W_MAX);
        let cell_h = (avail_h / dg as u16).min(CELL_H_MAX);
        let cells = Rect::new(area.x + LABEL_W, area.y, cell_w * dm as u16, cell_h * dg as u16);
        Some(Self { cells, cell_w, cell_h, cols: sample(n_masses, dm), rows: sample(n_gaps, dg) })
    }

    /// The screen rectangle of displayed column `c` and displayed row `r` (row 0 at the bottom).
    pub fn rect(&self, c: usize, r: usize) -> Rect {
        let top = (self.rows.len() - 1 - r) as u16;
        Rect::new(self.cells.x + c as u16 * self.cell_w, self.cells.y + top * self.cell_h, self.cell_w, self.cell_h)
    }

    /// Where displayed cell (c, r)'s zone glyph is drawn (row 0 at the bottom): see [`centre`].
    pub fn glyph_at(&self, c: usize, r: usize) -> (u16, u16) {
        centre(self.rect(c, r))
    }

    /// The displayed column whose grid mass is nearest `m` (`masses` the grid's, any unit).
    pub fn nearest_col(&self, masses: &[f64], m: f64) -> usize {
        nearest(&self.cols, masses, m)
    }

    /// The displayed row whose grid gap is nearest `d` (`gaps` the grid's, any unit).
    pub fn nearest_row(&self, gaps: &[f64], d: f64) -> usize {
        nearest(&self.rows, gaps, d)
    }

    /// The screen line of gap `d` (the unit of `gaps`): the glyph line of a displayed row at
    /// that row's own gap, moving linearly from one row's glyph line to the next over the
    /// spacer lines between them (cells taller than a line); the end rows' lines beyond them.
    pub fn line_of(&self, gaps: &[f64], d: f64) -> u16 {
        let at = |k: usize| (gaps.get(self.rows[k]).copied().unwrap_or(f64::NAN), self.glyph_at(0, k).1);
        let last = self.rows.len() - 1;
        if !d.is_finite() || d <= at(0).0 {
            return at(0).1;
        }
        for k in 0..last {
            let ((g0, y0), (g1, y1)) = (at(k), at(k + 1));
            if d < g1 && g1 > g0 {
                let t = (d - g0) / (g1 - g0);
                return y0 - (t * f64::from(y0 - y1)).round() as u16;
            }
        }
        at(last).1
    }

    /// The grid cell (mass index, gap index) under screen position (x, y), if any.
    pub fn hit(&self, x: u16, y: u16) -> Option<(usize, usize)> {
        let c = self.cells;
        if x < c.x || y < c.y || x >= c.x + c.width || y >= c.y + c.height {
            return None;
        }
        let col = ((x - c.x) / self.cell_w) as usize;
        let top = ((y - c.y) / self.cell_h) as usize;
        Some((self.cols[col], self.rows[self.rows.len() - 1 - top]))
    }
}

/// Where a cell's zone glyph goes in its rectangle: the middle column and line (the left and
/// upper of the two middles when even). Labels and the marker use the same place.
pub fn centre(r: Rect) -> (u16, u16) {
    (r.x + r.width.saturating_sub(1) / 2, r.y + r.height.saturating_sub(1) / 2)
}

/// The index into `shown` (displayed grid indices) whose grid value in `values` is nearest `v`:
/// the later one on a tie (`v` halfway, to rounding), as [`Geometry::line_of`] rounds a half up.
fn nearest(shown: &[usize], values: &[f64], v: f64) -> usize {
    let tie = 1e-9 * (1.0 + v.abs());
    let mut best = (0, f64::INFINITY);
    for (k, &i) in shown.iter().enumerate() {
        let dist = values.get(i).map_or(f64::INFINITY, |x| (x - v).abs());
        if dist <= best.1 + tie {
            best = (k, dist);
        }
    }
    best.0
}

/// A continuous axis over the cells: the grid's values at the cells' centres, the cells'
/// outer edges at the ends, mapped linearly onto `len` screen cells from `start`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CellAxis {
    /// Value at the outer edge of the first cell and of the last.
    pub lo: f64,
    pub hi: f64,
    pub start: u16,
    pub len: u16,
}

impl CellAxis {
    /// The axis of evenly spaced grid `values` drawn over `len` cells from `start`.
    pub fn new(values: &[f64], start: u16, len: u16) -> Self {
        let (first, last) = (values.first().copied().unwrap_or(0.0), values.last().copied().unwrap_or(1.0));
        let half = if values.len() > 1 { 0.5 * (last - first) / (values.len() - 1) as f64 } else { 0.5 };
        Self { lo: first - half, hi: last + half, start, len }
    }

    /// Where `v` falls: `Ok(offset)` inside (0 at the low edge), `Err(low side?)` outside.
    pub fn place(&self, v: f64) -> Result<u16, bool> {
        if !v.is_finite() || v < self.lo {
            return Err(true);
        }
        if v > self.hi {
            return Err(false);
        }
        let f = (v - self.lo) / (self.hi - self.lo);
        Ok(((f * f64::from(self.len)).floor() as u16).min(self.len.saturating_sub(1)))
    }
}

/// The zone grid's data.
pub struct ZoneGridView<'a> {
    pub block: Block<'a>,
    pub masses_g: &'a [f64],
    pub gaps_cm: &'a [f64],
    /// `cells[g * masses.len() + m]`.
    pub cells: &'a [CellView],
    /// The live design (m in g, d in cm) and its own zone.
    pub design: (f64, f64),
    pub zone: DesignZone,
    pub theme: Palette,
}

fn glyph(z: Option<Zone>) -> String {
    z.map_or("-".into(), |z| z.number().to_string())
}

/// True while some cell is not computed on the fine grid yet (the legend then explains `·`).
pub fn pending(cells: &[CellView]) -> bool {
    cells.iter().any(|c| !matches!(c, CellView::Exact(_) | CellView::Unsure(_)))
}

/// True if some cell is shaded as unsure (the legend then explains the shading).
pub fn unsure(cells: &[CellView]) -> bool {
    cells.iter().any(|c| matches!(c, CellView::Unsure(_)))
}

/// The legend's entry for the shading of unsure ensemble cells: no wider than a zone's entry,
/// so it never widens the legend beside the grid (which cost the grid a row).
pub fn unsure_legend(theme: &Palette) -> String {
    format!("{} <70% agree", theme.sym("░", ":"))
}

/// The legend's entries (text, zone for its colour); "pending" only while cells are, the
/// shading only when a cell is unsure.
fn legend_items(theme: &Palette, pending: bool, unsure: bool) -> Vec<(String, Option<Zone>)> {
    let mut v: Vec<(String, Option<Zone>)> = [Zone::NoisyWeak, Zone::NoisyStrong, Zone::QuietStrong, Zone::QuietWeak]
        .iter()
        .map(|z| (format!("{} {}", z.number(), z.describe().replace(", ", ",")), Some(*z)))
        .collect();
    v.push(("- no impact".into(), None));
    if pending {
        v.push((format!("{} pending", theme.sym("·", ".")), None));
    }
    if unsure {
        v.push((unsure_legend(theme), None));
    }
    v
}

/// The legend's entries flowed into lines of `width` columns (entries two spaces apart).
fn flow(items: &[(String, Option<Zone>)], width: usize) -> Vec<Vec<usize>> {
    let mut lines: Vec<Vec<usize>> = vec![];
    let mut used = 0;
    for (i, (text, _)) in items.iter().enumerate() {
        let w = text.chars().count();
        match lines.last_mut() {
            Some(line) if used + 2 + w <= width => {
                line.push(i);
                used += 2 + w;
            }
            _ => {
                lines.push(vec![i]);
                used = w;
            }
        }
    }
    lines
}

/// Where everything of the zone grid goes inside the panel.
#[derive(Debug, Clone, PartialEq)]
pub struct ChartLayout {
    pub geometry: Geometry,
    /// The grid's value axes (mass in g, gap in cm) over the drawn cells.
    pub mass_axis: CellAxis,
    pub gap_axis: CellAxis,
    /// The legend: one entry per row beside the grid (x, y), or flowed lines below it.
    pub legend: LegendPlace,
    /// Rows of the y title, the x labels, the x title and the design's line.
    pub y_title_y: u16,
    pub x_labels_y: u16,
    pub x_title_y: u16,
    pub info_y: u16,
    /// The right edge of the grid's area (the legend, when beside, starts after it).
    pub grid_right: u16,
}

/// Where the legend goes.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum LegendPlace {
    /// One entry per row from (x, y).
    Beside(u16, u16),
    /// Lines of entry indices from row y.
    Below(u16, Vec<Vec<usize>>),
}

/// The grid in `area` and whether the x title fits on the labels row right of it (up to
/// column `title_right`); else the title takes a row of its own under the grid (taken from
/// the grid).
fn grid_in(area: Rect, nm: usize, ng: usize, title_right: u16) -> Option<(Geometry, bool)> {
    let x_title_w = 8u16;
    let geometry = Geometry::new(area, nm, ng)?;
    if title_right.max(area.right()).saturating_sub(geometry.cells.right()) > x_title_w {
        return Some((geometry, true));
    }
    let room = Rect { height: area.height.saturating_sub(1), ..area };
    Some((Geometry::new(room, nm, ng)?, false))
}

/// Lays out the zone grid, its axes, legend and the design's line in the panel's inner area;
/// None if the grid does not fit.
pub fn layout(
    inner: Rect,
    masses: &[f64],
    gaps: &[f64],
    theme: &Palette,
    pending: bool,
    unsure: bool,
) -> Option<ChartLayout> {
    let (nm, ng) = (masses.len(), gaps.len());
    let items = legend_items(theme, pending, unsure);
    let legend_w = items.iter().map(|(t, _)| t.chars().count() as u16).max().unwrap_or(0) + 1;
    // Fixed rows: y title, x labels, the design's line.
    let fixed = 3u16;
    let below_lines = flow(&items, inner.width as usize);
    let below_h = inner.height.checked_sub(fixed + below_lines.len() as u16)?;
    let beside_w = inner.width.saturating_sub(legend_w + 1);
    let grid_room_beside = beside_w.saturating_sub(LABEL_W) as usize;
    let beside_fits = inner.height >= fixed + items.len() as u16 && grid_room_beside >= nm;
    let wide = beside_fits && grid_room_beside >= 2 * nm;
    // The placement that draws the most gap rows (every computed one where any does); beside
    // where the grid is wide enough either way.
    let place = |beside: bool| {
        let (grid_w, grid_h) = if beside { (beside_w, inner.height - fixed) } else { (inner.width, below_h) };
        // Beside, the x title may run under the legend when the legend ends above its row.
        let title_right = if beside && grid_h >= items.len() as u16 { inner.right() } else { inner.x + grid_w };
        grid_in(Rect::new(inner.x, inner.y + 1, grid_w, grid_h), nm, ng, title_right)
            .map(|(g, t)| (beside, grid_w, g, t))
    };
    let rows = |p: &Option<(bool, u16, Geometry, bool)>| p.as_ref().map_or(0, |p| p.2.rows.len());
    let (below, side) = (place(false), if beside_fits { place(true) } else { None });
    let best = if rows(&side) > rows(&below) || (wide && rows(&side) == rows(&below)) { side } else { below };
    let (beside, grid_w, geometry, title_beside) = best?;
    let grid_right = inner.x + grid_w;
    let cells = geometry.cells;
    let x_labels_y = cells.bottom();
    let x_title_y = if title_beside { x_labels_y } else { x_labels_y + 1 };
    let info_y = x_title_y + 1;
    let legend = if beside {
        LegendPlace::Beside(inner.right().saturating_sub(legend_w), inner.y)
    } else {
        LegendPlace::Below(info_y + 1, below_lines)
    };
    Some(ChartLayout {
        mass_axis: CellAxis::new(masses, cells.x, cells.width),
        gap_axis: CellAxis::new(gaps, 0, cells.height),
        geometry,
        legend,
        y_title_y: inner.y,
        x_labels_y,
        x_title_y,
        info_y,
        grid_right,
    })
}

impl ZoneGridView<'_> {
    fn draw_cell(&self, buf: &mut Buffer, r: Rect, cell: CellView) {
        let (zone, known, exact, unsure) = match cell {
            CellView::Empty => (None, false, false, false),
            CellView::Approx(z) => (z, true, false, false),
            CellView::Exact(z) => (z, true, true, false),
            CellView::Unsure(z) => (z, true, true, true),
        };
        let mut style = match zone {
            Some(z) if known => self.theme.zone(z),
            _ => Style::default(),
        };
        // A guessed cell is drawn behind (dim); an exact one plain (not bold: a bold black digit
        // turns grey in terminals that brighten bold, and loses its contrast on the fill).
        if !exact || unsure {
            style = self.theme.behind(style);
        }
        let text = if known { glyph(zone) } else { self.theme.sym("·", ".").to_string() };
        let fill = if unsure { self.theme.sym("░", ":") } else { " " };
        for y in r.y..r.y + r.height {
            for x in r.x..r.x + r.width {
                buf[(x, y)].set_symbol(fill).set_style(style);
            }
        }
        if unsure && r.width == 1 && r.height == 1 {
            // No room for the shade: the digit itself is marked.
            style = style.add_modifier(Modifier::UNDERLINED);
        }
        let (x, y) = centre(r);
        buf.set_stringn(x, y, &text, 1, style);
    }

    fn draw_axes(&self, buf: &mut Buffer, l: &ChartLayout, inner: Rect) {
        let cells = l.geometry.cells;
        let th = &self.theme;
        let dim = th.label(); // not dim: the labels read on a projector
        buf.set_stringn(inner.x, l.y_title_y, th.text("d (cm) ↑"), inner.width as usize, dim);
        // Gap ticks: round values, each on the glyph line of the row whose gap is nearest it
        // (never a spacer line of a tall cell), one label a row.
        let geo = &l.geometry;
        let g = &l.gap_axis;
        // Where two ticks share a row, the one nearer its gap labels it.
        let n = usize::from(cells.height / 2 + 1).clamp(2, 8);
        if let Some(step) = tick_step(g.lo, g.hi, n) {
            let decimals = ((-step.log10().floor()).max(1.0)) as usize;
            let mut best: Vec<Option<(f64, f64)>> = vec![None; geo.rows.len()];
            for v in ticks(g.lo, g.hi, n) {
                let r = geo.nearest_row(self.gaps_cm, v);
                let off = self.gaps_cm.get(geo.rows[r]).map_or(f64::INFINITY, |gap| (gap - v).abs());
                if best[r].is_none_or(|(_, o)| off < o) {
                    best[r] = Some((v, off));
                }
            }
            for (r, b) in best.iter().enumerate() {
                if let Some((v, _)) = b {
                    let (_, y) = geo.glyph_at(0, r);
                    buf.set_stringn(inner.x, y, format!("{v:>5.decimals$} "), LABEL_W as usize, dim);
                }
            }
        }
        // Mass ticks: round values centred at their columns, none touching the next.
        let m = &l.mass_axis;
        let mut n = (usize::from(cells.width) / 4).clamp(2, 10);
        let labels = loop {
            let t = ticks(m.lo, m.hi, n);
            let step = tick_step(m.lo, m.hi, n).unwrap_or(1.0);
            let w = t.iter().map(|v| super::plot::tick_label(*v, step).len()).max().unwrap_or(1);
            if n <= 2 || (w + 1) * t.len() <= usize::from(cells.width) {
                break t.iter().map(|v| (*v, super::plot::tick_label(*v, step))).collect::<Vec<_>>();
            }
            n -= 1;
        };
        let mut next_free = inner.x;
        for (v, text) in labels {
            if m.place(v).is_err() {
                continue;
            }
            // Centred on the glyph column of the column whose mass is nearest it.
            let (gx, _) = geo.glyph_at(geo.nearest_col(self.masses_g, v), 0);
            let w = text.len() as u16;
            let x = gx.saturating_sub(w.saturating_sub(1) / 2).min(l.grid_right.saturating_sub(w));
            if x < next_free {
                continue;
            }
            buf.set_stringn(x, l.x_labels_y, &text, w as usize, dim);
            next_free = x + w + 1;
        }
        let title = th.text("m (g) →").into_owned();
        let tw = title.chars().count() as u16;
        let tx =
            if l.x_title_y == l.x_labels_y { cells.right() + 1 } else { cells.right().saturating_sub(tw).max(inner.x) };
        if l.x_title_y < inner.bottom() {
            buf.set_stringn(tx, l.x_title_y, &title, inner.right().saturating_sub(tx) as usize, dim);
        }
    }

    fn draw_legend(&self, buf: &mut Buffer, l: &ChartLayout, inner: Rect) {
        let items = legend_items(&self.theme, pending(self.cells), unsure(self.cells));
        let style = |z: Option<Zone>| z.map_or(Style::default(), |z| self.theme.zone(z));
        let put = |buf: &mut Buffer, x: u16, y: u16, i: usize| {
            let (text, z) = &items[i];
            if y >= inner.bottom() || x >= inner.right() {
                return 0;
            }
            let room = (inner.right() - x) as usize;
            let cut = text.char_indices().nth(1).map_or(text.len(), |(i, _)| i);
            let (head, tail) = text.split_at(cut);
            buf.set_stringn(x, y, head, room, style(*z).add_modifier(Modifier::BOLD));
            buf.set_stringn(x + 1, y, tail, room.saturating_sub(1), Style::default());
            text.chars().count() as u16
        };
        match &l.legend {
            LegendPlace::Beside(x, y) => {
                for i in 0..items.len() {
                    put(buf, *x, *y + i as u16, i);
                }
            }
            LegendPlace::Below(y, lines) => {
                for (k, line) in lines.iter().enumerate() {
                    let mut x = inner.x;
                    for &i in line {
                        x += put(buf, x, *y + k as u16, i) + 2;
                    }
                }
            }
        }
    }

    /// The marker in displayed column `c` on line `y`, inside that column's cell so it never
    /// covers a neighbour's glyph or fill: `[n]` around the glyph where the cell is three or
    /// more columns wide, else the design's zone glyph in the glyph's place and the cell's
    /// width on that line in the cursor style (reversed, underlined).
    fn put_marker(&self, buf: &mut Buffer, geo: &Geometry, c: usize, y: u16, style: Style) {
        let (gx, _) = geo.glyph_at(c, 0);
        if geo.cell_w >= 3 {
            buf.set_stringn(gx - 1, y, self.zone.marker(), 3, style);
        } else {
            let cursor = style.add_modifier(Modifier::UNDERLINED);
            let r = geo.rect(c, 0);
            for x in r.x..r.right() {
                buf[(x, y)].set_style(cursor);
            }
            buf.set_stringn(gx, y, self.zone.glyph(), 1, cursor);
        }
    }

    /// The design's marker at its exact place with its own zone, or an arrow at the edge;
    /// and the line under the grid saying which zone it is in and whether it is on the chart.
    fn draw_design(&self, buf: &mut Buffer, l: &ChartLayout, inner: Rect) {
        let th = &self.theme;
        let (m, d) = self.design;
        let mark_style = Style::default().add_modifier(Modifier::BOLD | Modifier::REVERSED);
        let marker = self.zone.marker();
        let (pm, pd) = (l.mass_axis.place(m), l.gap_axis.place(d));
        let geo = &l.geometry;
        // The cell nearest the design across (its column), and its line: a row's glyph line,
        // or a spacer line between two rows (see `Geometry::line_of`).
        let c = geo.nearest_col(self.masses_g, m);
        let (x, _) = geo.glyph_at(c, 0);
        let y = geo.line_of(self.gaps_cm, d);
        let off = if let (Ok(_), Ok(_)) = (pm, pd) {
            self.put_marker(buf, geo, c, y, mark_style);
            None
        } else {
            let arrow = match (pm, pd) {
                (Err(true), _) => th.sym("←", "<"),
                (Err(false), _) => th.sym("→", ">"),
                (_, Err(true)) => th.sym("↓", "v"),
                _ => th.sym("↑", "^"),
            };
            buf.set_stringn(x, y, arrow, 1, mark_style.add_modifier(Modifier::UNDERLINED));
            let mut why = Vec::new();
            if let Err(low) = pm {
                let (cmp, edge) = if low { ("<", l.mass_axis.lo) } else { (">", l.mass_axis.hi) };
                why.push(format!("m {} g {cmp} {} g", sig(m, 3), sig(edge, 3)));
            }
            if let Err(low) = pd {
                let (cmp, edge) = if low { ("<", l.gap_axis.lo) } else { (">", l.gap_axis.hi) };
                why.push(format!("d {} cm {cmp} {} cm", sig(d, 3), sig(edge, 3)));
            }
            Some(format!("off the chart {arrow} ({})", why.join(", ")))
        };
        let (zone, short) = match self.zone {
            DesignZone::Computing => ("computing".to_string(), "computing".to_string()),
            DesignZone::Known(Some(z)) => {
                (format!("zone {} {}", z.number(), z.describe()), format!("zone {}", z.number()))
            }
            DesignZone::Known(None) => ("no zone (no impact or < 2 maxima)".to_string(), "no zone".to_string()),
        };
        let options = match &off {
            None => vec![format!(" this design: {zone}"), format!(" this design: {short}"), format!(" {short}")],
            Some(o) => {
                let head = o.split(" (").next().unwrap_or(o);
                vec![
                    format!(" this design: {zone}, {o}"),
                    format!(" this design: {short}, {o}"),
                    format!(" {short}, {o}"),
                    format!(" {short}, {head}"),
                    format!(" {head}"),
                ]
            }
        };
        // Beside a legend that reaches this row the line stops at the grid's edge.
        let right = match &l.legend {
            LegendPlace::Beside(_, y)
                if l.info_y < y + legend_items(th, pending(self.cells), unsure(self.cells)).len() as u16 =>
            {
                l.grid_right
            }
            _ => inner.right(),
        };
        let room = right.saturating_sub(inner.x + 3) as usize;
        let text = options
            .iter()
            .map(|o| th.text(o).into_owned())
            .find(|o| o.chars().count() <= room)
            .unwrap_or_else(|| th.fit(&th.text(&options[options.len() - 1]), room).into_owned());
        if l.info_y < inner.bottom() {
            buf.set_stringn(inner.x, l.info_y, &marker, 3, mark_style);
            buf.set_stringn(inner.x + 3, l.info_y, &text, room, Style::default());
        }
    }
}

impl Widget for ZoneGridView<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let inner = self.block.inner(area);
        (&self.block).render(area, buf);
        let Some(l) = layout(inner, self.masses_g, self.gaps_cm, &self.theme, pending(self.cells), unsure(self.cells))
        else {
            Paragraph::new(self.theme.fit("too small for the chart", inner.width.into()).into_owned())
                .render(inner, buf);
            return;
        };
        let g = &l.geometry;
        for (r, &gi) in g.rows.iter().enumerate() {
            for (c, &mi) in g.cols.iter().enumerate() {
                let cell = self.cells.get(gi * self.masses_g.len() + mi).copied().unwrap_or(CellView::Empty);
                self.draw_cell(buf, g.rect(c, r), cell);
            }
        }
        self.draw_axes(buf, &l, inner);
        self.draw_legend(buf, &l, inner);
        self.draw_design(buf, &l, inner);
    }
}

/// The e–SPLmax view's data (Fig 17): one point per computed cell, drawn as its zone digit.
pub struct ScatterView<'a> {
    pub block: Block<'a>,
    /// (e in cm/s, SPLmax in dB, zone).
    pub points: &'a [(f64, f64, Zone)],
    pub current: Option<(f64, f64)>,
    pub l_star_db: f64,
    pub e_star_cm_s: f64,
    pub theme: Palette,
}

impl Widget for ScatterView<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let th = self.theme;
        let cur: Vec<(f64, f64)> = self.current.into_iter().collect();
        let xb =
            fit_bounds(self.points.iter().map(|p| p.0).chain([self.e_star_cm_s]).chain(cur.iter().map(|c| c.0)), 0.05);
        let yb =
            fit_bounds(self.points.iter().map(|p| p.1).chain([self.l_star_db]).chain(cur.iter().map(|c| c.1)), 0.05);
        let zones = [Zone::NoisyWeak, Zone::NoisyStrong, Zone::QuietStrong, Zone::QuietWeak];
        let by_zone: Vec<Vec<(f64, f64)>> =
            zones.iter().map(|z| self.points.iter().filter(|p| p.2 == *z).map(|p| (p.0, p.1)).collect()).collect();
        let l_line = [(xb[0], self.l_star_db), (xb[1], self.l_star_db)];
        let e_line = [(self.e_star_cm_s, yb[0]), (self.e_star_cm_s, yb[1])];
        let line = th.style(Role::Grid);
        let mut series = vec![
            Curve::line("L*", &l_line, line, th.mark('─', '-')),
            Curve::line("e*", &e_line, line, th.mark('│', '|')),
        ];
        for (i, pts) in by_zone.iter().enumerate() {
            let digit = char::from(b'1' + i as u8);
            // Each point is its zone's digit: no legend entry needed.
            series.push(Curve::points("", pts, th.zone_ink(zones[i]), th.mark(digit, digit)));
        }
        series.push(Curve::points(
            "this design",
            &cur,
            Style::default().add_modifier(Modifier::BOLD | Modifier::REVERSED),
            th.mark('@', '@'),
        ));
        LinePlot {
            block: self.block,
            x_title: "e (cm/s)",
            y_title: "SPLmax (dB)",
            series,
            empty: "no computed cells yet",
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
    fn hit_test_inverts_rect() {
        let g = Geometry::new(Rect::new(1, 1, 60, 20), 6, 5).unwrap();
        for m in 0..6 {
            for gi in 0..5 {
                let r = g.rect(m, gi);
                assert_eq!(g.hit(r.x, r.y), Some((m, gi)));
                assert_eq!(g.hit(r.x + r.width - 1, r.y + r.height - 1), Some((m, gi)));
            }
        }
        assert_eq!(g.hit(0, 0), None);
        assert!(Geometry::new(Rect::new(0, 0, 5, 3), 6, 5).is_none());
    }

    #[test]
    fn big_grid_in_small_panel_shows_evenly_spaced_rows_with_both_ends() {
        let g = Geometry::new(Rect::new(0, 0, 40, 8), 16, 12).unwrap();
        assert_eq!(g.rows.len(), 8);
        assert_eq!((g.rows[0], g.rows[7]), (0, 11));
        assert!(g.rows.windows(2).all(|w| w[0] < w[1]));
        let r = g.rect(3, 0);
        assert_eq!(g.hit(r.x, r.y), Some((g.cols[3], 0)));
        assert_eq!(sample(5, 3), vec![0, 2, 4]);
    }

    #[test]
    fn a_cell_axis_puts_grid_values_at_cell_centres_and_edges_outside() {
        // 12 gaps 1..7 cm over 12 rows: each value in its own row, the edges half a step out.
        let gaps: Vec<f64> = (0..12).map(|i| 1.0 + 6.0 * f64::from(i) / 11.0).collect();
        let a = CellAxis::new(&gaps, 0, 12);
        for (i, g) in gaps.iter().enumerate() {
            assert_eq!(a.place(*g), Ok(i as u16));
        }
        // Between two rows' values it moves with the value (4.82 → 5.36 cm: rows 7 and 8).
        assert_ne!(a.place(4.82), a.place(5.36));
        assert_eq!(a.place(0.5), Err(true));
        assert_eq!(a.place(7.5), Err(false));
        assert_eq!(a.place(f64::NAN), Err(true));
        // Over 7 rows (a small panel) the design still moves with d.
        let small = CellAxis::new(&gaps, 0, 7);
        assert!(small.place(4.0).unwrap() < small.place(5.4).unwrap());
    }

    #[test]
    fn the_legend_flows_into_lines_that_fit() {
        let items = legend_items(&Palette::default(), true, true);
        assert!(items.iter().any(|(t, _)| t == "- no impact"));
        assert!(legend_items(&Palette::default(), false, false).iter().all(|(t, _)| !t.contains("pending")));
        for w in [20usize, 38, 60, 120] {
            let lines = flow(&items, w);
            assert_eq!(lines.iter().map(Vec::len).sum::<usize>(), items.len());
            for line in &lines {
                let width: usize =
                    line.iter().map(|&i| items[i].0.chars().count()).sum::<usize>() + 2 * (line.len() - 1);
                assert!(width <= w || line.len() == 1, "{width} > {w}");
            }
        }
    }
}
