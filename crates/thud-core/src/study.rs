//! Studies over any numeric parameter: `thud sweep --vary NAME=FROM:TO:N`,
//! `thud bifurcation --vary …` and Python's `thud.sweep(v0=…, c1=…)` / `thud.bifurcation(…)`.
//!
//! One parser ([`Vary::parse`], [`Vary::of_values`]) turns a front end's text or list into a
//! [`Vary`]: a numeric row of the parameter table [`params::DESIGN`] (any quantity or count row:
//! `mass`, `gap`, `v0`, `c1`, `freq`, `force`, …) and its values in the row's plain unit, each
//! checked against the row's range, errors naming what the user typed (`--vary v0` on the
//! command line, `v0` in Python). A [`Grid`] of one or more axes is the product of their values
//! in C order (the last axis varies fastest, as NumPy and xarray lay out an array), and
//! [`Grid::point`] is the base design with one point's values set and the whole design checked
//! again ([`Design::check`]: K_HZ from materials follows a varied mass, |y0| < d/2 a varied gap).
//! [`sweep_cells`] evaluates the cells of a grid on rayon's pool, cancellable like
//! [`design::sweep`]; [`check_grid`] estimates and caps its work by the product of all axes and
//! the work of every point.

use std::ops::Range;
use std::sync::atomic::{AtomicBool, Ordering};

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::damper::Solver;
use crate::design::{self, Design, Metrics, Steady, ValidDesign};
use crate::error::ThudError;
use crate::limits::{self, Refusal};
use crate::params::{self, Accepts, DesignDraft, Param, Spelling};
use crate::units;

/// One varied parameter: a numeric row of [`params::DESIGN`] and its values (the row's plain
/// unit: kg, m, m/s, Hz, N, degrees, … as [`Param::unit`] names it; a count as a whole number).
#[derive(Clone)]
pub struct Vary {
    pub row: &'static Param<DesignDraft>,
    pub values: Vec<f64>,
}

impl std::fmt::Debug for Vary {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Vary").field("row", &self.row.name).field("values", &self.values).finish()
    }
}

impl PartialEq for Vary {
    fn eq(&self, other: &Self) -> bool {
        self.row.name == other.row.name && self.values == other.values
    }
}

/// How the study's parameter is named in messages: `--vary v0` on the command line, `v0` in
/// Python.
fn shown(spelling: Spelling, name: &str) -> String {
    match spelling {
        Spelling::Flag => format!("--vary {name}"),
        Spelling::Keyword => Spelling::Keyword.spell(name),
    }
}

/// The flag or keyword a study's refusal names when no parameter is known.
fn bare(spelling: Spelling) -> &'static str {
    match spelling {
        Spelling::Flag => "--vary",
        Spelling::Keyword => "vary",
    }
}

/// The numeric row called `name` (`main-mass` or `main_mass`, or an alias), or an error listing
/// the rows a study can vary.
pub fn numeric_row(name: &str, spelling: Spelling) -> Result<&'static Param<DesignDraft>, ThudError> {
    let canonical = name.trim().replace('_', "-");
    let row = params::DESIGN.iter().find(|p| p.name == canonical || p.alias == Some(canonical.as_str()));
    match row {
        Some(p) if is_numeric(p) => Ok(p),
        Some(p) => Err(ThudError::invalid(
            bare(spelling),
            format!("'{name}' is not a number to vary ({}); one of: {}", kind_of(p), numeric_names(spelling)),
        )),
        None => Err(ThudError::invalid(
            bare(spelling),
            format!("unknown parameter '{name}'; one of: {}", numeric_names(spelling)),
        )),
    }
}

/// What a row that is not numeric is, for a message.
fn kind_of(p: &Param<DesignDraft>) -> &'static str {
    match p.accepts {
        Accepts::Choice { .. } => "a choice",
        Accepts::Name { .. } => "a name",
        Accepts::Switch { .. } => "a switch",
        _ => "not a value of the design",
    }
}

/// Whether a study can vary the row: a quantity or a count that sets the design itself (the
/// Newmark step `dt` sets the solver, which [`set`] handles; the Poisson ratio needs materials).
fn is_numeric(p: &Param<DesignDraft>) -> bool {
    matches!(p.accepts, Accepts::Quantity { .. } | Accepts::Count { .. }) && p.get.is_some()
}

/// The rows a study can vary, as `spelling` spells them.
pub fn numeric_names(spelling: Spelling) -> String {
    let names: Vec<String> = params::DESIGN
        .iter()
        .filter(|p| is_numeric(p))
        .map(|p| match spelling {
            Spelling::Flag => p.name.to_string(),
            Spelling::Keyword => Spelling::Keyword.spell(p.name),
        })
        .collect();
    names.join(", ")
}

impl Vary {
    /// `NAME=FROM:TO:N` (e.g. `v0=1:3:5`, `f=3Hz:8Hz:200`, `mass=30g:100g:20`): N evenly
    /// spaced values from FROM to TO inclusive, each in the row's units (a plain number in its
    /// plain unit), both ends checked against the row's range and N against
    /// [`limits::GRID_N`]; `freq` is also accepted as `f`.
    pub fn parse(text: &str, spelling: Spelling) -> Result<Vary, ThudError> {
        let Some((name, spec)) = text.split_once('=') else {
            return Err(ThudError::invalid(
                bare(spelling),
                format!("'{text}'; expected NAME=FROM:TO:N, e.g. v0=1:3:5 or freq=3Hz:8Hz:200"),
            ));
        };
        let row = numeric_row(alias(name), spelling)?;
        let param = shown(spelling, row.name);
        let parts: Vec<&str> = spec.split(':').collect();
        let [from, to, n] = parts[..] else {
            return Err(ThudError::invalid(&param, format!("'{spec}'; expected FROM:TO:N, e.g. {}", example(row))));
        };
        let from = parse_value(row, &param, from)?;
        let to = parse_value(row, &param, to)?;
        let n = limits::GRID_N.parse_count(&param, n)?;
        params::check_ends(bare(spelling), text, from, to, n)?;
        let mut values = design::linspace(from, to, n);
        if matches!(row.accepts, Accepts::Count { .. }) {
            for v in &mut values {
                *v = v.round();
            }
            values.dedup();
        }
        Ok(Vary { row, values })
    }

    /// The row `name` at `values` (the row's plain unit), each checked against its range; the
    /// error names the value as `spelling` spells the parameter (Python: `v0`).
    pub fn of_values(name: &str, values: &[f64], spelling: Spelling) -> Result<Vary, ThudError> {
        let row = numeric_row(alias(name), spelling)?;
        let param = shown(spelling, row.name);
        if values.is_empty() {
            return Err(ThudError::invalid(&param, "no values; give at least one"));
        }
        let n = limits::GRID_N.parse_count(&param, &values.len().to_string())?;
        debug_assert_eq!(n, values.len());
        let range = row.range().unwrap_or(&limits::GRID_N);
        let mut checked = Vec::with_capacity(values.len());
        for &v in values {
            let v = range.check_as(&param, v)?;
            if matches!(row.accepts, Accepts::Count { .. }) && v.fract() != 0.0 {
                return Err(ThudError::invalid(&param, format!("{v} is not a whole number")));
            }
            checked.push(v);
        }
        Ok(Vary { row, values: checked })
    }

    /// The row's name as in the table (`main-mass`).
    #[must_use]
    pub fn name(&self) -> &'static str {
        self.row.name
    }

    /// The plain unit of the values (`m/s`; empty for a count or a plain number).
    #[must_use]
    pub fn unit(&self) -> &'static str {
        self.row.unit()
    }

    /// The axis as results carry it.
    #[must_use]
    pub fn axis(&self) -> Axis {
        Axis { name: self.row.name.to_string(), unit: self.unit().to_string(), values: self.values.clone() }
    }
}

/// `f` is the frequency row `freq` (the and the physics' name for it).
fn alias(name: &str) -> &str {
    match name.trim() {
        "f" => "freq",
        "F0" | "f0" => "force",
        other => other,
    }
}

/// An example range for the row, for a message.
fn example(row: &Param<DesignDraft>) -> String {
    let name = row.name;
    match row.range() {
        Some(r) if r.min > 0.0 => {
            format!("{name}={}:{}:10", limits::short(r.min.max(r.max / 1e3)), limits::short(r.max))
        }
        Some(r) => format!("{name}={}:{}:10", limits::short(r.min), limits::short(r.max)),
        None => format!("{name}=1:10:10"),
    }
}

/// One end of a range as typed, for the row: a quantity with or without a unit, or a count.
fn parse_value(row: &Param<DesignDraft>, param: &str, text: &str) -> Result<f64, ThudError> {
    match row.accepts {
        Accepts::Quantity { kind, range, .. } => range.check_as(param, units::parse(param, text, kind)?),
        Accepts::Count { range, .. } => Ok(range.parse_count(param, text)? as f64),
        _ => Err(ThudError::invalid(param, "not a number to vary")),
    }
}

/// One axis of a study as results carry it: the parameter's name (as in the table), its unit
/// and its values.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Axis {
    pub name: String,
    pub unit: String,
    pub values: Vec<f64>,
}

impl Axis {
    /// The axis' column in a CSV table and its key: the name with `_` for `-` and the unit
    /// spelled in ASCII after it (`v0_m_s`, `c1_n_s_m`, `freq_hz`, `mass_kg`; a count or a
    /// plain number bare: `periods`).
    #[must_use]
    pub fn column(&self) -> String {
        column(&self.name, &self.unit)
    }
}

/// The key of a parameter `name` (as in the table) in unit `unit` ([`Axis::column`]).
#[must_use]
pub fn column(name: &str, unit: &str) -> String {
    let name = name.replace('-', "_");
    if unit.is_empty() {
        return name;
    }
    let unit: String =
        unit.to_lowercase().replace('^', "").chars().map(|c| if c.is_ascii_alphanumeric() { c } else { '_' }).collect();
    format!("{name}_{unit}")
}

/// `design` with the row set to `value` (the row's plain unit), unchecked. The Newmark step
/// sets the solver's step (a design on the event solver is moved to Newmark at that step).
pub(crate) fn set(design: Design, row: &Param<DesignDraft>, value: f64) -> Design {
    if row.name == "dt" {
        let mut d = design;
        d.solver = Solver::Newmark { dt_s: value };
        return d;
    }
    params::set_number(&design, row, value)
}

/// A product of axes over a base design: the cells of a study in C order.
#[derive(Debug, Clone)]
pub struct Grid {
    pub base: ValidDesign,
    pub axes: Vec<Vary>,
}

impl Grid {
    /// The grid of `axes` over `base`; no row twice.
    pub fn new(base: ValidDesign, axes: Vec<Vary>, spelling: Spelling) -> Result<Grid, ThudError> {
        if axes.is_empty() {
            return Err(ThudError::invalid(bare(spelling), "no parameter to vary; give NAME=FROM:TO:N"));
        }
        for (i, a) in axes.iter().enumerate() {
            if axes[..i].iter().any(|b| b.row.name == a.row.name) {
                return Err(ThudError::invalid(shown(spelling, a.row.name), "is given twice"));
            }
            // The ball's Poisson ratio counts only in K_HZ from materials.
            if a.row.requires == Some("sphere") && base.materials.is_none() {
                let needs = Spelling::Keyword.spell("sphere");
                let needs = if spelling == Spelling::Flag { "--sphere".to_string() } else { needs };
                return Err(ThudError::invalid(
                    shown(spelling, a.row.name),
                    format!("counts only with materials; give {needs}"),
                ));
            }
        }
        Ok(Grid { base, axes })
    }

    /// The number of values on each axis.
    #[must_use]
    pub fn shape(&self) -> Vec<usize> {
        self.axes.iter().map(|a| a.values.len()).collect()
    }

    /// The number of cells: the product of the axes' lengths.
    #[must_use]
    pub fn cells(&self) -> usize {
        self.axes.iter().map(|a| a.values.len()).product()
    }

    /// The index on each axis of cell `i` (C order: the last axis fastest).
    #[must_use]
    pub fn indices(&self, mut i: usize) -> Vec<usize> {
        let mut idx = vec![0; self.axes.len()];
        for (k, a) in self.axes.iter().enumerate().rev() {
            let n = a.values.len().max(1);
            idx[k] = i % n;
            i /= n;
        }
        idx
    }

    /// The values of cell `i`, one per axis.
    #[must_use]
    pub fn values(&self, i: usize) -> Vec<f64> {
        self.indices(i).iter().zip(&self.axes).map(|(&j, a)| a.values[j]).collect()
    }

    /// The design of cell `i`, unchecked.
    #[must_use]
    pub fn design_at(&self, i: usize) -> Design {
        let mut d = self.base.design().clone();
        for (v, a) in self.values(i).into_iter().zip(&self.axes) {
            d = set(d, a.row, v);
        }
        d
    }

    /// The design of cell `i`, checked again as a whole ([`Design::check`]).
    pub fn point(&self, i: usize) -> Result<ValidDesign, ThudError> {
        self.design_at(i).check()
    }

    /// The axes as results carry them.
    #[must_use]
    pub fn axes(&self) -> Vec<Axis> {
        self.axes.iter().map(Vary::axis).collect()
    }
}

/// Refuses a study over `grid` whose work is over a cap: the cells (the product of every axis,
/// against [`limits::SWEEP_CELLS`]), then each point's own run ([`limits::check_run`]) and the
/// sum of the points' work ([`limits::sweep_work`] per point: simulated seconds, Newmark
/// steps, main-mass cycles), each point's design as the study builds it. `runs_per_point`
/// multiplies the work (a bifurcation's periods are its duration).
pub fn check_grid(grid: &Grid, given: &dyn Fn(&str) -> bool) -> Result<(), Refusal> {
    let n = grid.cells();
    limits::check_cells(n)?;
    let mut total = [0.0; 3];
    let mut worst: Option<ValidDesign> = None;
    for i in 0..n {
        let d = grid.design_at(i);
        let Ok(v) = d.check() else { continue };
        limits::check_run(&v, given, 0)?;
        let work = limits::sweep_work(&v, 1);
        for (t, w) in total.iter_mut().zip(work) {
            *t += w.value;
        }
        if worst.as_ref().is_none_or(|w| v.damper.duration_s > w.damper.duration_s) {
            worst = Some(v);
        }
    }
    match worst {
        Some(w) => limits::check_work_sum(&w, given, n, total),
        None => Ok(()),
    }
}

/// One cell of a study: its index, the value on each axis, and the metrics of its run (and
/// the steady state of a forced one).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StudyCell {
    pub index: usize,
    pub values: Vec<f64>,
    #[serde(flatten)]
    pub metrics: Metrics,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub steady: Option<Steady>,
}

/// A study: its axes and its cells in C order.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Study {
    pub axes: Vec<Axis>,
    pub cells: Vec<StudyCell>,
}

/// The whole study over `grid` ([`sweep_cells`] of every cell).
pub fn sweep(
    grid: &Grid,
    cancel: Option<&AtomicBool>,
    on_cell: &(dyn Fn(usize, &StudyCell) + Sync),
) -> Result<Study, ThudError> {
    let cells = sweep_cells(grid, 0..grid.cells(), cancel, on_cell)?;
    Ok(Study { axes: grid.axes(), cells })
}

/// The cells `range` of a study over `grid` on rayon's global pool, in index order (the part
/// one shard computes). `cancel` stops it between cells (cells not started are left out); the
/// first failing cell in index order gives the error; a panic propagates.
pub fn sweep_cells(
    grid: &Grid,
    range: Range<usize>,
    cancel: Option<&AtomicBool>,
    on_cell: &(dyn Fn(usize, &StudyCell) + Sync),
) -> Result<Vec<StudyCell>, ThudError> {
    let range = range.start..range.end.min(grid.cells());
    let mut out: Vec<(usize, Result<StudyCell, ThudError>)> = range
        .into_par_iter()
        .filter_map(|i| {
            if cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
                return None;
            }
            let cell = grid.point(i).and_then(|d| design::evaluate(&d, 0, cancel)).map(|e| StudyCell {
                index: i,
                values: grid.values(i),
                metrics: e.metrics,
                steady: e.steady,
            });
            if let Ok(c) = &cell {
                if e_cancelled(cancel) {
                    return None;
                }
                on_cell(i, c);
            }
            Some((i, cell))
        })
        .collect();
    out.sort_unstable_by_key(|&(i, _)| i);
    out.into_iter().map(|(_, c)| c).collect()
}

/// Whether `cancel` is set (a cell finished after it was set may be cut short: left out).
fn e_cancelled(cancel: Option<&AtomicBool>) -> bool {
    cancel.is_some_and(|c| c.load(Ordering::Relaxed))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_units_and_checks_each_end() {
        let v = Vary::parse("f=3Hz:8Hz:6", Spelling::Flag).unwrap();
        assert_eq!(v.name(), "freq");
        assert_eq!(v.values, vec![3.0, 4.0, 5.0, 6.0, 7.0, 8.0]);
        let m = Vary::parse("mass=30g:50g:3", Spelling::Flag).unwrap();
        assert!((m.values[1] - 0.04).abs() < 1e-15);
        let e = Vary::parse("v0=1:1e9:3", Spelling::Flag).unwrap_err();
        assert_eq!(e.param(), "--vary v0");
        let e = Vary::parse("c1=10:60", Spelling::Flag).unwrap_err();
        assert!(e.to_string().contains("FROM:TO:N"), "{e}");
        let e = Vary::parse("solver=1:2:2", Spelling::Flag).unwrap_err();
        assert!(e.to_string().contains("a choice"), "{e}");
        let e = Vary::parse("nope=1:2:2", Spelling::Flag).unwrap_err();
        assert_eq!(e.param(), "--vary");
        let e = Vary::of_values("main_mass", &[0.5, -1.0], Spelling::Keyword).unwrap_err();
        assert_eq!(e.param(), "main_mass");
        let nu = Vary::parse("sphere-poisson=0.2:0.3:2", Spelling::Flag).unwrap();
        let e = Grid::new(Design::default().check().unwrap(), vec![nu], Spelling::Flag).unwrap_err();
        assert_eq!(e.param(), "--vary sphere-poisson");
    }

    #[test]
    fn one_value_at_both_ends_with_several_is_refused() {
        // 30 g twice, spelled two ways: three identical rows.
        for text in ["mass=30g:30g:3", "mass=30g:0.03kg:3"] {
            let e = Vary::parse(text, Spelling::Flag).unwrap_err();
            assert_eq!(e.param(), "--vary", "{text}");
            assert!(e.to_string().contains(&format!("'{text}'")), "{e}");
            assert!(e.to_string().contains("all its values would be the same"), "{e}");
        }
        assert_eq!(Vary::parse("v0=2:2:2", Spelling::Keyword).unwrap_err().param(), "vary");
        // One value once is a plain axis.
        assert_eq!(Vary::parse("mass=30g:30g:1", Spelling::Flag).unwrap().values, vec![0.03]);
    }

    #[test]
    fn columns_carry_their_unit() {
        assert_eq!(column("v0", "m/s"), "v0_m_s");
        assert_eq!(column("c1", "N·s/m"), "c1_n_s_m");
        assert_eq!(column("main-mass", "kg"), "main_mass_kg");
        assert_eq!(column("periods", ""), "periods");
    }

    #[test]
    fn grid_is_c_ordered_and_sets_every_axis() {
        let base = Design::default().check().unwrap();
        let g = Grid::new(
            base,
            vec![Vary::parse("v0=1:3:3", Spelling::Flag).unwrap(), Vary::parse("c1=10:60:6", Spelling::Flag).unwrap()],
            Spelling::Flag,
        )
        .unwrap();
        assert_eq!(g.cells(), 18);
        assert_eq!(g.values(7), vec![2.0, 20.0]);
        let d = g.design_at(7);
        assert_eq!((d.damper.v0_m_s, d.damper.c1_n_s_m), (2.0, 20.0));
        let twice = Grid::new(
            Design::default().check().unwrap(),
            vec![Vary::parse("v0=1:3:3", Spelling::Flag).unwrap(), Vary::parse("v0=1:3:3", Spelling::Flag).unwrap()],
            Spelling::Flag,
        );
        assert!(twice.is_err());
    }

    #[test]
    fn a_study_cell_is_the_design_run_at_its_point() {
        let base = Design::default().check().unwrap();
        let g = Grid::new(base, vec![Vary::parse("v0=1:2:2", Spelling::Flag).unwrap()], Spelling::Flag).unwrap();
        let s = sweep(&g, None, &|_, _| {}).unwrap();
        let mut d = Design::default();
        d.damper.v0_m_s = 2.0;
        let direct = design::evaluate(&d.check().unwrap(), 0, None).unwrap();
        assert_eq!(s.cells[1].metrics, direct.metrics);
        assert_ne!(s.cells[0].metrics, s.cells[1].metrics);
    }

    #[test]
    fn a_varied_mass_moves_k_hz_with_materials() {
        let d = Design { materials: Some(design::Materials::new("steel", "steel")), ..Design::default() };
        let g =
            Grid::new(d.check().unwrap(), vec![Vary::parse("mass=30g:90g:2", Spelling::Flag).unwrap()], Spelling::Flag)
                .unwrap();
        let (a, b) = (g.point(0).unwrap(), g.point(1).unwrap());
        assert!(b.damper.k_hz > a.damper.k_hz, "a bigger ball is stiffer (Eq 2)");
    }
}
