//! The design chart: the mass × gap grid with the zone number drawn in every cell (not colour
//! alone) on continuous axes, the current design marked at its exact (m, d) with its own zone;
//! and the second view, e against SPLmax (Fig 17) with the L* and e* lines.
//!
//! One truth: the marker's zone is the live design's own (the readout's), never a cell's; a
//! design between cells is drawn between them, one off the chart's range as an arrow at the
//! edge with a line saying so. The axes have titles with units and round ticks; the legend
//! (zones 1–4, no impact, pending) is always drawn, below or beside the grid as space allows.
//!
//! An ensemble chart (N > 1 runs a cell) draws each cell in the zone of its medians; a cell
//! where fewer than 70 % of its runs are in that zone is shaded — its blank filled with `░`
//! (`:` in ASCII) and dim, or underlined where the cell is one character — so it reads without
//! colour too, and the legend says what the shading means.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::widgets::{Block, Paragraph, Widget};

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
        match self {
            DesignZone::Computing => "[?]".into(),
            DesignZone::Known(z) => format!("[{}]", glyph(z)),
        }
    }
}

/// Width of the gap labels on the left of the grid ("  4.0 ").
const LABEL_W: u16 = 6;
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

/// The grid in `area` and whether the x title fits on the labels row right of it; else the
/// title takes a row of its own under the grid (taken from the grid).
fn grid_in(area: Rect, nm: usize, ng: usize) -> Option<(Geometry, bool)> {
    let x_title_w = 8u16;
    let geometry = Geometry::new(area, nm, ng)?;
    if area.right().saturating_sub(geometry.cells.right()) > x_title_w {
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
        grid_in(Rect::new(inner.x, inner.y + 1, grid_w, grid_h), nm, ng).map(|(g, t)| (beside, grid_w, g, t))
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
        let x = r.x + r.width.saturating_sub(1) / 2;
        let y = r.y + r.height.saturating_sub(1) / 2;
        buf.set_stringn(x, y, &text, 1, style);
    }

    fn draw_axes(&self, buf: &mut Buffer, l: &ChartLayout, inner: Rect) {
        let cells = l.geometry.cells;
        let th = &self.theme;
        let dim = th.label(); // not dim: the labels read on a projector
        buf.set_stringn(inner.x, l.y_title_y, th.text("d (cm) ↑"), inner.width as usize, dim);
        // Gap ticks: round values at the rows they fall in.
        let (g, rows) = (&l.gap_axis, cells.height);
        let n = usize::from(rows / 2 + 1).clamp(2, 8);
        if let Some(step) = tick_step(g.lo, g.hi, n) {
            let decimals = ((-step.log10().floor()).max(1.0)) as usize;
            for v in ticks(g.lo, g.hi, n) {
                if let Ok(off) = g.place(v) {
                    let y = cells.bottom() - 1 - off;
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
            let Ok(off) = m.place(v) else { continue };
            let w = text.len() as u16;
            let x = (m.start + off).saturating_sub(w / 2).min(l.grid_right.saturating_sub(w));
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

    /// The design's marker at its exact place with its own zone, or an arrow at the edge;
    /// and the line under the grid saying which zone it is in and whether it is on the chart.
    fn draw_design(&self, buf: &mut Buffer, l: &ChartLayout, inner: Rect) {
        let cells = l.geometry.cells;
        let th = &self.theme;
        let (m, d) = self.design;
        let mark_style = Style::default().add_modifier(Modifier::BOLD | Modifier::REVERSED);
        let marker = self.zone.marker();
        let (pm, pd) = (l.mass_axis.place(m), l.gap_axis.place(d));
        let row = |p: Result<u16, bool>| match p {
            Ok(off) => cells.bottom() - 1 - off,
            Err(true) => cells.bottom() - 1,
            Err(false) => cells.y,
        };
        let col = |p: Result<u16, bool>| match p {
            Ok(off) => l.mass_axis.start + off,
            Err(true) => cells.x,
            Err(false) => cells.right() - 1,
        };
        let (x, y) = (col(pm), row(pd));
        let off = if let (Ok(_), Ok(_)) = (pm, pd) {
            let x0 = x.saturating_sub(1).clamp(cells.x, cells.right().saturating_sub(3));
            buf.set_stringn(x0, y, &marker, 3, mark_style);
            None
        } else {
            let arrow = match (pm, pd) {
                (Err(true), _) => th.sym("←", "<"),
                (Err(false), _) => th.sym("→", ">"),
                (_, Err(true)) => th.sym("↓", "v"),
                _ => th.sym("↑", "^"),
            };
            buf.set_stringn(x, y, arrow, 1, mark_style);
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
