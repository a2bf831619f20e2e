//! The design chart: the mass × gap grid coloured by zone with the zone number drawn in every
//! cell (not colour alone), the current design bracketed; and the second view, e against
//! SPLmax (Fig 17) with the L* and e* lines.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::symbols::Marker;
use ratatui::widgets::{Axis, Block, Chart, Dataset, GraphType, Paragraph, Widget};

use super::plot::{fit_bounds, labels};
use super::theme::Palette;
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
}

/// Width of the gap labels on the left of the grid.
const LABEL_W: u16 = 6;

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
    /// Lays out the `n_masses × n_gaps` grid in the inner area of the panel (None if too small).
    pub fn new(inner: Rect, n_masses: usize, n_gaps: usize) -> Option<Self> {
        let avail_w = inner.width.checked_sub(LABEL_W)?;
        let avail_h = inner.height.checked_sub(1)?;
        let (dm, dg) = (n_masses.min(avail_w as usize), n_gaps.min(avail_h as usize));
        if dm < 2 || dg < 2 {
            return None;
        }
        let (cell_w, cell_h) = ((avail_w / dm as u16).min(6), (avail_h / dg as u16).min(3));
        let cells = Rect::new(inner.x + LABEL_W, inner.y, cell_w * dm as u16, cell_h * dg as u16);
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

    /// The displayed (column, row) nearest to grid cell (m, g).
    pub fn shown(&self, m: usize, g: usize) -> (usize, usize) {
        let near =
            |v: &[usize], i: usize| v.iter().enumerate().min_by_key(|(_, &x)| x.abs_diff(i)).map_or(0, |(k, _)| k);
        (near(&self.cols, m), near(&self.rows, g))
    }
}

/// The zone grid's data.
pub struct ZoneGridView<'a> {
    pub masses_g: &'a [f64],
    pub gaps_cm: &'a [f64],
    /// `cells[g * masses.len() + m]`.
    pub cells: &'a [CellView],
    /// The grid cell nearest the current design.
    pub current: Option<(usize, usize)>,
    pub title: &'a str,
    pub focused: bool,
    pub theme: Palette,
}

/// The panel's block (shared by both views so the geometry matches the hit test).
pub fn block<'a>(title: &'a str, focused: bool, theme: &Palette) -> Block<'a> {
    Block::bordered().title(title).border_style(theme.focus(focused))
}

fn glyph(z: Option<Zone>) -> String {
    z.map_or("-".into(), |z| z.number().to_string())
}

impl ZoneGridView<'_> {
    fn draw_cell(&self, buf: &mut Buffer, r: Rect, cell: CellView, current: bool) {
        let (zone, known, exact) = match cell {
            CellView::Empty => (None, false, false),
            CellView::Approx(z) => (z, true, false),
            CellView::Exact(z) => (z, true, true),
        };
        let mut style = match zone {
            Some(z) if known => self.theme.zone(z),
            _ => Style::default(),
        };
        style = if exact { style.add_modifier(Modifier::BOLD) } else { style.add_modifier(Modifier::DIM) };
        if current {
            style = style.add_modifier(Modifier::REVERSED);
        }
        let text = if !known { "·".to_string() } else { glyph(zone) };
        let text = if current && r.width >= 3 {
            format!("[{text}]")
        } else if current {
            "*".into()
        } else {
            text
        };
        for y in r.y..r.y + r.height {
            for x in r.x..r.x + r.width {
                buf[(x, y)].set_symbol(" ").set_style(style);
            }
        }
        let tw = text.chars().count() as u16;
        let x = r.x + r.width.saturating_sub(tw) / 2;
        let y = r.y + r.height / 2;
        buf.set_stringn(x, y, &text, r.width as usize, style);
    }

    fn draw_labels(&self, buf: &mut Buffer, g: &Geometry, inner: Rect) {
        let dim = Style::default().add_modifier(Modifier::DIM);
        for (r, &gi) in g.rows.iter().enumerate() {
            let rect = g.rect(0, r);
            if r % 2 == 0 || g.cell_h > 1 {
                let text = format!("{:>5}", sig(self.gaps_cm[gi], 2));
                buf.set_stringn(inner.x, rect.y + rect.height / 2, text, LABEL_W as usize - 1, dim);
            }
        }
        let y = g.cells.y + g.cells.height;
        buf.set_stringn(inner.x, y, "d cm", LABEL_W as usize, dim);
        let step = (8 / g.cell_w.max(1)).max(1) as usize;
        for (c, &mi) in g.cols.iter().enumerate().step_by(step) {
            let r = g.rect(c, 0);
            let room = (inner.x + inner.width).saturating_sub(r.x) as usize;
            buf.set_stringn(r.x, y, sig(self.masses_g[mi], 2), room, dim);
        }
        if y + 1 < inner.y + inner.height {
            let legend = "m g →  1 noisy,weak  2 noisy,strong  3 quiet,strong  4 quiet,weak  · pending";
            buf.set_stringn(inner.x, y + 1, legend, inner.width as usize, dim);
        }
    }
}

impl Widget for ZoneGridView<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let block = block(self.title, self.focused, &self.theme);
        let inner = block.inner(area);
        block.render(area, buf);
        let Some(g) = Geometry::new(inner, self.masses_g.len(), self.gaps_cm.len()) else {
            Paragraph::new("too small for the chart").render(inner, buf);
            return;
        };
        let current = self.current.map(|(m, gi)| g.shown(m, gi));
        for (r, &gi) in g.rows.iter().enumerate() {
            for (c, &mi) in g.cols.iter().enumerate() {
                let cell = self.cells.get(gi * self.masses_g.len() + mi).copied().unwrap_or(CellView::Empty);
                self.draw_cell(buf, g.rect(c, r), cell, current == Some((c, r)));
            }
        }
        self.draw_labels(buf, &g, inner);
    }
}

/// The e–SPLmax view's data (Fig 17): one point per computed cell.
pub struct ScatterView<'a> {
    /// (e in cm/s, SPLmax in dB, zone).
    pub points: &'a [(f64, f64, Zone)],
    pub current: Option<(f64, f64)>,
    pub l_star_db: f64,
    pub e_star_cm_s: f64,
    pub title: &'a str,
    pub focused: bool,
    pub theme: Palette,
}

impl Widget for ScatterView<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let block = block(self.title, self.focused, &self.theme);
        let xb = fit_bounds(self.points.iter().map(|p| p.0).chain([self.e_star_cm_s]), 0.05);
        let yb = fit_bounds(self.points.iter().map(|p| p.1).chain([self.l_star_db]), 0.05);
        let by_zone: Vec<Vec<(f64, f64)>> = [Zone::NoisyWeak, Zone::NoisyStrong, Zone::QuietStrong, Zone::QuietWeak]
            .iter()
            .map(|z| self.points.iter().filter(|p| p.2 == *z).map(|p| (p.0, p.1)).collect())
            .collect();
        let l_line = [(xb[0], self.l_star_db), (xb[1], self.l_star_db)];
        let e_line = [(self.e_star_cm_s, yb[0]), (self.e_star_cm_s, yb[1])];
        let cur: Vec<(f64, f64)> = self.current.into_iter().collect();
        let colors = [Color::Red, Color::Yellow, Color::Green, Color::Blue];
        let names = ["1", "2", "3", "4"];
        let mut sets = vec![
            Dataset::default()
                .name("L*")
                .data(&l_line)
                .graph_type(GraphType::Line)
                .marker(Marker::Dot)
                .style(self.theme.pinned()),
            Dataset::default()
                .name("e*")
                .data(&e_line)
                .graph_type(GraphType::Line)
                .marker(Marker::Dot)
                .style(self.theme.pinned()),
        ];
        for (i, pts) in by_zone.iter().enumerate() {
            sets.push(
                Dataset::default()
                    .name(names[i])
                    .data(pts)
                    .graph_type(GraphType::Scatter)
                    .marker(self.theme.marker())
                    .style(self.theme.fg(colors[i])),
            );
        }
        sets.push(
            Dataset::default()
                .name("this")
                .data(&cur)
                .graph_type(GraphType::Scatter)
                .marker(Marker::Block)
                .style(Style::default().add_modifier(Modifier::BOLD)),
        );
        Chart::new(sets)
            .block(block)
            .x_axis(Axis::default().title("e cm/s").bounds(xb).labels(labels(xb)))
            .y_axis(Axis::default().title("SPLmax dB").bounds(yb).labels(labels(yb)))
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
        let g = Geometry::new(Rect::new(0, 0, 40, 9), 16, 12).unwrap();
        assert_eq!(g.rows.len(), 8);
        assert_eq!((g.rows[0], g.rows[7]), (0, 11));
        assert!(g.rows.windows(2).all(|w| w[0] < w[1]));
        let r = g.rect(3, 0);
        assert_eq!(g.hit(r.x, r.y), Some((g.cols[3], 0)));
        assert_eq!(sample(5, 3), vec![0, 2, 4]);
    }
}
