//! The design chart: the sweep over mass × gap on the shared thread pool, and its shards.

use std::ops::Range;
use std::sync::atomic::{AtomicBool, Ordering};

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::error::{check_positive, ThudError};

use super::{evaluate, Design, Metrics, Thresholds, ValidDesign};

/// `n` evenly spaced values from `from` to `to` inclusive.
pub fn linspace(from: f64, to: f64, n: usize) -> Vec<f64> {
    match n {
        0 => vec![],
        1 => vec![from],
        _ => (0..n).map(|i| from + (to - from) * i as f64 / (n - 1) as f64).collect(),
    }
}

/// One cell of the design chart.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Cell {
    pub mass_kg: f64,
    pub gap_m: f64,
    pub metrics: Metrics,
}

/// The design chart: a mass × gap grid of metrics. `cells[g * masses.len() + m]` is gap `g`,
/// mass `m`; a cell is None until computed (or if the sweep was cancelled first).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Chart {
    pub masses_kg: Vec<f64>,
    pub gaps_m: Vec<f64>,
    pub cells: Vec<Option<Cell>>,
    pub thresholds: Thresholds,
}

impl Chart {
    pub fn empty(masses_kg: Vec<f64>, gaps_m: Vec<f64>, thresholds: Thresholds) -> Self {
        let n = masses_kg.len() * gaps_m.len();
        Self { masses_kg, gaps_m, cells: vec![None; n], thresholds }
    }

    pub fn cell(&self, mass_index: usize, gap_index: usize) -> Option<&Cell> {
        self.cells.get(gap_index * self.masses_kg.len() + mass_index)?.as_ref()
    }

    pub fn done(&self) -> usize {
        self.cells.iter().filter(|c| c.is_some()).count()
    }
}

/// The design `base` with this impact mass and gap, unchecked (a chart cell's parameters, or
/// a key; [`sweep`] checks each cell again).
pub fn variant(base: &Design, mass_kg: f64, gap_m: f64) -> Design {
    let mut d = base.clone();
    d.damper.impact_mass_kg = mass_kg;
    d.damper.gap_m = gap_m;
    d
}

/// Sweeps `base` over `masses × gaps` on rayon's global thread pool (one pool for the whole
/// process, so sweeps running at once share the cores instead of each taking all of them).
/// `on_cell(index, cell)` is called as each cell finishes (from pool threads, in no particular
/// order); `cancel` stops the sweep between cells (cells not started stay `None`). The chart
/// does not depend on the scheduling; the first failing cell (in index order) gives the error.
/// A panic in a cell (or in `on_cell`) propagates to the caller. Each cell is `base` at its
/// (mass, gap) checked again by the physics' own checks ([`Design::validate`]) with K_HZ
/// resolved again: the axes do not make a cell valid (K_HZ from materials and the observer's
/// distance follow the ball's radius, |y0| < d/2 the gap). The axes' ranges are the caller's
/// to check (every front end checks them against the mass and gap ranges; here they must be
/// > 0); inside them the derived radius and K_HZ stay inside their ranges.
pub fn sweep(
    base: &ValidDesign,
    masses_kg: &[f64],
    gaps_m: &[f64],
    cancel: Option<&AtomicBool>,
    on_cell: &(dyn Fn(usize, &Cell) + Sync),
) -> Result<Chart, ThudError> {
    let mut chart = Chart::empty(masses_kg.to_vec(), gaps_m.to_vec(), base.thresholds);
    let cells = sweep_cells(base, masses_kg, gaps_m, 0..chart.cells.len(), cancel, on_cell)?;
    place(&mut chart.cells, cells);
    Ok(chart)
}

/// The `(index, cell)` pairs `cells` put in their places of a chart's `slots` (row-major).
pub(crate) fn place<C>(slots: &mut [Option<C>], cells: Vec<(usize, C)>) {
    for (i, cell) in cells {
        slots[i] = Some(cell);
    }
}

/// The cells `range` of the chart [`sweep`] would compute (row-major indices, `g·masses + m`),
/// as `(index, cell)` in index order: the part of the chart one shard computes. Scheduling,
/// cancellation, errors and panics as in [`sweep`] (a cancelled run returns the cells it
/// finished). Indices past the grid are ignored.
pub fn sweep_cells(
    base: &ValidDesign,
    masses_kg: &[f64],
    gaps_m: &[f64],
    range: Range<usize>,
    cancel: Option<&AtomicBool>,
    on_cell: &(dyn Fn(usize, &Cell) + Sync),
) -> Result<Vec<(usize, Cell)>, ThudError> {
    grid_cells(masses_kg, gaps_m, range, cancel, on_cell, |mass_kg, gap_m| {
        let cell = base.variant(mass_kg, gap_m).and_then(|d| evaluate(&d, 0, cancel));
        Some(cell.map(|e| Cell { mass_kg, gap_m, metrics: e.metrics }))
    })
}

/// The cells `range` (row-major indices) of a mass × gap grid, each `cell(mass, gap)` evaluated
/// on rayon's global pool, as `(index, cell)` in index order: the one scheduling of the plain
/// and the ensemble charts. `cell` returns `None` for a cell it gave up on (cancelled); a cell
/// is not started once `cancel` is set. `on_cell` sees each good cell as it finishes; the first
/// failing cell in index order gives the error; a panic propagates.
pub(crate) fn grid_cells<C: Send>(
    masses_kg: &[f64],
    gaps_m: &[f64],
    range: Range<usize>,
    cancel: Option<&AtomicBool>,
    on_cell: &(dyn Fn(usize, &C) + Sync),
    cell: impl Fn(f64, f64) -> Option<Result<C, ThudError>> + Sync,
) -> Result<Vec<(usize, C)>, ThudError> {
    check_grid(masses_kg, gaps_m)?;
    let range = range.start..range.end.min(masses_kg.len() * gaps_m.len());
    // `par_bridge` hands the cells out in index order as threads come free, so the chart fills
    // row by row and a cancelled sweep leaves (about) a prefix.
    let mut results: Vec<(usize, Result<C, ThudError>)> = range
        .par_bridge()
        .filter_map(|i| {
            if cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
                return None;
            }
            let (mass_kg, gap_m) = grid_point(masses_kg, gaps_m, i);
            let c = cell(mass_kg, gap_m)?;
            if let Ok(c) = &c {
                on_cell(i, c);
            }
            Some((i, c))
        })
        .collect();
    results.sort_unstable_by_key(|&(i, _)| i);
    results.into_iter().map(|(i, c)| Ok((i, c?))).collect()
}

/// Checks the axes of a chart: every mass and gap finite and > 0.
pub(crate) fn check_grid(masses_kg: &[f64], gaps_m: &[f64]) -> Result<(), ThudError> {
    for &m in masses_kg {
        check_positive("mass", m, "kg")?;
    }
    for &g in gaps_m {
        check_positive("gap", g, "m")?;
    }
    Ok(())
}

/// The (mass kg, gap m) of the chart cell with row-major index `i` (`g·masses + m`).
pub(crate) fn grid_point(masses_kg: &[f64], gaps_m: &[f64], i: usize) -> (f64, f64) {
    (masses_kg[i % masses_kg.len()], gaps_m[i / masses_kg.len()])
}

/// The cells of part `k` (0-based) of `n` equal parts of a chart of `cells` cells: the
/// contiguous row-major indices `⌊k·cells/n⌋ .. ⌊(k+1)·cells/n⌋`. The parts cover every cell
/// once, in order, and differ in size by at most one cell; each is non-empty when
/// `n ≤ cells`. `k < n` and `n > 0` are the caller's to check (the result is empty otherwise).
#[must_use]
pub fn shard_range(cells: usize, k: usize, n: usize) -> Range<usize> {
    if n == 0 || k >= n {
        return 0..0;
    }
    // u128: k·cells cannot overflow.
    let at = |j: usize| (j as u128 * cells as u128 / n as u128) as usize;
    at(k)..at(k + 1)
}
