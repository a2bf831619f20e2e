//! Ensembles: how much of a design's answer is luck.
//!
//! The rattle is chaotic: e (Eq 27) jumps with the timing of the first impacts, and impact
//! counts of two accurate solvers part after about a second. So a design is run N times,
//! differing only in the ball's initial offset from the enclosure's centre, spread evenly over
//! the clearance d and at rest:
//!
//! `y0_k = −d/2 + (k + ½)·d/N`, `k = 0 … N−1` ([`ball_positions`]; N = 1 is the centred ball,
//! the paper's single trajectory).
//!
//! Every run is an ordinary [`design::evaluate`] of the design with
//! [`DamperParams::ball_position_m`](crate::damper::DamperParams::ball_position_m) = y0_k; its
//! metrics are kept as a [`Member`]. Over the N members each metric is summarised by its 10th
//! percentile, median and 90th percentile ([`Percentiles`]), by the **nearest-rank method**: the
//! p-th percentile is the value of rank `⌈p·N/100⌉` (1-based, at least 1) in ascending order,
//! so every reported number is the value of one actual run, N = 1 gives that run's value
//! exactly, and a monotone map (SPL of U0) commutes with it. A run without the metric (no impact
//! for SPLmax, fewer than two maxima for e) ranks below every run with it, so a percentile that
//! falls among such runs is "none". For N = 16: p10 is rank 2, the median rank 8 (the lower
//! middle), p90 rank 15.
//!
//! A summary ([`Ensemble`]) also carries the *medians as a design's metrics* (each field the
//! median of that field over the runs), whose zone — the zone of the median SPLmax and median
//! inclination under the design's thresholds — is the ensemble's zone; the fraction of runs in
//! zone 3 ([`Ensemble::zone3_probability`]); and the fraction of runs whose own zone is the
//! ensemble's ([`Ensemble::agreement`]). The design chart of ensembles ([`sweep`]) gives each
//! cell all of that. Runs and cells are spread over rayon's global pool.

use std::ops::Range;
use std::sync::atomic::AtomicBool;

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::damper::Truncation;
use crate::design::{self, Chart, Metrics, Thresholds, ValidDesign, Zone};
use crate::error::ThudError;

/// The N initial ball offsets (m) of an ensemble in a clearance of `gap_m`: `−d/2 + (k + ½)·d/N`,
/// k = 0 … N−1, evenly spread and strictly inside the clearance. N = 1 is exactly 0, the
/// centred ball.
#[must_use]
pub fn ball_positions(gap_m: f64, n: usize) -> Vec<f64> {
    (0..n).map(|k| -0.5 * gap_m + (k as f64 + 0.5) * gap_m / n as f64).collect()
}

/// The value of rank `⌈pct·N/100⌉` (1-based, at least 1) of `sorted` (ascending): the
/// nearest-rank percentile. `None` for an empty slice.
fn nearest_rank<T: Copy>(sorted: &[T], pct: usize) -> Option<T> {
    let n = sorted.len();
    let rank = (pct * n).div_ceil(100).max(1);
    sorted.get(rank - 1).copied()
}

/// The 10th percentile, median and 90th percentile of one metric over an ensemble's runs (by
/// nearest rank, see the module doc); each is `None` when it falls among runs without the
/// metric.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Percentiles {
    pub p10: Option<f64>,
    pub median: Option<f64>,
    pub p90: Option<f64>,
}

impl Percentiles {
    /// The percentiles of `values` (one per run; `None`: the run has no such value, ranked
    /// below every number).
    #[must_use]
    pub fn of(values: impl IntoIterator<Item = Option<f64>>) -> Self {
        let mut v: Vec<Option<f64>> = values.into_iter().collect();
        v.sort_by(|a, b| match (a, b) {
            (Some(x), Some(y)) => x.total_cmp(y),
            _ => a.is_some().cmp(&b.is_some()),
        });
        let at = |pct| nearest_rank(&v, pct).flatten();
        Percentiles { p10: at(10), median: at(50), p90: at(90) }
    }
}

/// The spread of the metrics of an ensemble: e (Eq 27), e_fit, U0max and SPLmax.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Spread {
    /// Damping inclination e of Eq 27 (cm/s).
    pub inclination_cm_s: Percentiles,
    /// The robust inclination e_fit (cm/s).
    pub inclination_fit_cm_s: Percentiles,
    /// Largest contact speed by the design's U0max rule (m/s).
    pub u0_max_m_s: Percentiles,
    /// SPL of an impact at U0max (dB).
    pub spl_max_db: Percentiles,
}

/// One run of an ensemble: the ball's initial offset and that run's metrics (the fields of
/// [`Metrics`], written flat beside the offset, with the zone written as its number 1–4).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Member {
    /// Initial offset y0 of the ball from the enclosure's centre (m), at rest.
    pub ball_position_m: f64,
    /// The run's metrics.
    #[serde(flatten)]
    pub metrics: Metrics,
    /// Set when a solver work cap stopped this run before its duration.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub truncated: Option<Truncation>,
}

impl Member {
    /// The member for a run from `ball_position_m` with metrics `m`.
    #[must_use]
    pub fn new(ball_position_m: f64, m: &Metrics, truncated: Option<Truncation>) -> Self {
        Member { ball_position_m, metrics: *m, truncated }
    }
}

/// The zone numbered `n` (1–4): [`Zone::from_number`].
#[must_use]
pub fn zone_from_number(n: u8) -> Option<Zone> {
    Zone::from_number(n)
}

/// An ensemble of one design: its runs and what they say together (see the module doc).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Ensemble {
    /// Number of runs N.
    pub runs: usize,
    /// The medians as a design's metrics: each field the median of that field over the runs;
    /// the zone is that of the median SPLmax and median inclination.
    pub metrics: Metrics,
    /// p10, median and p90 of e, e_fit, U0max and SPLmax.
    pub spread: Spread,
    /// Fraction of the runs in zone 3 (quiet and strong).
    pub zone3_probability: f64,
    /// Fraction of the runs whose own zone is the zone of the medians.
    pub agreement: f64,
    /// Every run, in order of k (of the initial offset).
    pub ensemble: Vec<Member>,
}

impl Ensemble {
    /// The zone of the medians under thresholds `t`, and the fraction of runs whose own zone
    /// under `t` is that zone: what [`Ensemble::from_members`] gives for the same runs under
    /// `t`, without rebuilding the spread (thresholds move zones only). O(runs), no allocation:
    /// cheap enough for every chart cell on every frame.
    #[must_use]
    pub fn zone_under(&self, t: &Thresholds) -> (Option<Zone>, f64) {
        let zone = self.metrics.zone(t);
        let n = self.ensemble.len();
        let agree = self.ensemble.iter().filter(|m| m.metrics.zone(t) == zone).count();
        (zone, if n == 0 { 0.0 } else { agree as f64 / n as f64 })
    }

    /// What the runs `members` of a design with thresholds `t` say together.
    #[must_use]
    pub fn from_members(members: Vec<Member>, t: &Thresholds) -> Self {
        let n = members.len();
        let pct = |f: &dyn Fn(&Member) -> Option<f64>| Percentiles::of(members.iter().map(f));
        let spread = Spread {
            inclination_cm_s: pct(&|m| m.metrics.inclination_cm_s),
            inclination_fit_cm_s: pct(&|m| m.metrics.inclination_fit_cm_s),
            u0_max_m_s: pct(&|m| Some(m.metrics.u0_max_m_s)),
            spl_max_db: pct(&|m| m.metrics.spl_max_db),
        };
        let median = |f: &dyn Fn(&Member) -> Option<f64>| pct(f).median;
        let mut counts: Vec<usize> = members.iter().map(|m| m.metrics.n_impacts).collect();
        counts.sort_unstable();
        let mut metrics = Metrics {
            n_impacts: nearest_rank(&counts, 50).unwrap_or(0),
            inclination_cm_s: spread.inclination_cm_s.median,
            inclination_fit_cm_s: spread.inclination_fit_cm_s.median,
            u0_max_m_s: spread.u0_max_m_s.median.unwrap_or(0.0),
            zdot_abs_max_m_s: median(&|m| Some(m.metrics.zdot_abs_max_m_s)).unwrap_or(0.0),
            spl_max_db: spread.spl_max_db.median,
            contact_duration_s: median(&|m| m.metrics.contact_duration_s),
            restitution_mean: median(&|m| m.metrics.restitution_mean),
            zone: None,
        };
        metrics.zone = metrics.zone(t);
        let fraction = |k: usize| if n == 0 { 0.0 } else { k as f64 / n as f64 };
        let zone3 = members.iter().filter(|m| m.metrics.zone == Some(Zone::QuietStrong)).count();
        let agree = members.iter().filter(|m| m.metrics.zone == metrics.zone).count();
        Ensemble {
            runs: n,
            metrics,
            spread,
            zone3_probability: fraction(zone3),
            agreement: fraction(agree),
            ensemble: members,
        }
    }
}

/// One run of an ensemble: `design` with the ball starting at `y0` (m).
/// The offset keeps the design valid (|y0| < d/2 by [`ball_positions`]) and resolved (K_HZ
/// does not depend on it), so the run is not checked again.
fn member(design: &ValidDesign, y0: f64, cancel: Option<&AtomicBool>) -> Result<(Member, bool), ThudError> {
    let mut d = design.design().clone();
    d.damper.ball_position_m = y0;
    let e = design::evaluate_checked(&d, 0, cancel)?;
    Ok((Member::new(y0, &e.metrics, e.run.truncated), e.run.cancelled))
}

/// Runs the ensemble of `n` runs of `design` (offsets [`ball_positions`]) on rayon's global
/// pool. `Ok(None)` when `cancel` stopped a run before its end; the first failing run (in
/// order of k) gives the error.
pub fn evaluate(design: &ValidDesign, n: usize, cancel: Option<&AtomicBool>) -> Result<Option<Ensemble>, ThudError> {
    check_runs(n)?;
    let runs: Vec<(Member, bool)> = ball_positions(design.damper.gap_m, n)
        .into_par_iter()
        .map(|y0| member(design, y0, cancel))
        .collect::<Result<_, _>>()?;
    if runs.iter().any(|&(_, cancelled)| cancelled) {
        return Ok(None);
    }
    Ok(Some(Ensemble::from_members(runs.into_iter().map(|(m, _)| m).collect(), &design.thresholds)))
}

/// An ensemble needs at least one run.
fn check_runs(n: usize) -> Result<(), ThudError> {
    if n == 0 {
        return Err(ThudError::invalid("ensemble", "0 runs; an ensemble needs at least 1"));
    }
    Ok(())
}

/// One cell of the design chart of ensembles.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EnsembleCell {
    pub mass_kg: f64,
    pub gap_m: f64,
    #[serde(flatten)]
    pub ensemble: Ensemble,
}

/// The design chart of ensembles: a mass × gap grid, `cells[g * masses.len() + m]` as in
/// [`Chart`], each cell an ensemble of `runs` runs (None until computed).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EnsembleChart {
    pub masses_kg: Vec<f64>,
    pub gaps_m: Vec<f64>,
    /// Runs per cell N.
    pub runs: usize,
    pub cells: Vec<Option<EnsembleCell>>,
    pub thresholds: Thresholds,
}

impl EnsembleChart {
    /// A chart with no cell computed yet.
    #[must_use]
    pub fn empty(masses_kg: Vec<f64>, gaps_m: Vec<f64>, runs: usize, thresholds: Thresholds) -> Self {
        let n = masses_kg.len() * gaps_m.len();
        Self { masses_kg, gaps_m, runs, cells: vec![None; n], thresholds }
    }

    /// The ordinary chart of the medians: each cell's [`Ensemble::metrics`] (its zone the zone
    /// of the medians). What the zone map and Table 5 of an ensemble chart are drawn from.
    #[must_use]
    pub fn medians(&self) -> Chart {
        Chart {
            masses_kg: self.masses_kg.clone(),
            gaps_m: self.gaps_m.clone(),
            cells: self
                .cells
                .iter()
                .map(|c| {
                    c.as_ref().map(|c| design::Cell { mass_kg: c.mass_kg, gap_m: c.gap_m, metrics: c.ensemble.metrics })
                })
                .collect(),
            thresholds: self.thresholds,
        }
    }

    /// The ensemble of cell (mass index, gap index), if computed.
    #[must_use]
    pub fn cell(&self, mass_index: usize, gap_index: usize) -> Option<&EnsembleCell> {
        self.cells.get(gap_index * self.masses_kg.len() + mass_index)?.as_ref()
    }
}

/// The design chart of ensembles: `base` over `masses × gaps`, `n` runs per cell, on rayon's
/// global pool (runs of a cell in parallel too). `on_cell(index, cell)` is called as each cell
/// finishes; `cancel` stops the sweep (cells not finished stay `None`). The first failing cell
/// (in index order) gives the error; a panic propagates.
pub fn sweep(
    base: &ValidDesign,
    masses_kg: &[f64],
    gaps_m: &[f64],
    n: usize,
    cancel: Option<&AtomicBool>,
    on_cell: &(dyn Fn(usize, &EnsembleCell) + Sync),
) -> Result<EnsembleChart, ThudError> {
    let mut chart = EnsembleChart::empty(masses_kg.to_vec(), gaps_m.to_vec(), n, base.thresholds);
    let cells = sweep_cells(base, masses_kg, gaps_m, n, 0..chart.cells.len(), cancel, on_cell)?;
    design::place(&mut chart.cells, cells);
    Ok(chart)
}

/// The cells `range` (row-major indices) of the chart [`sweep`] would compute, as
/// `(index, cell)` in index order: the part one shard computes (see
/// [`design::shard_range`]). A cancelled run returns the cells it finished.
pub fn sweep_cells(
    base: &ValidDesign,
    masses_kg: &[f64],
    gaps_m: &[f64],
    n: usize,
    range: Range<usize>,
    cancel: Option<&AtomicBool>,
    on_cell: &(dyn Fn(usize, &EnsembleCell) + Sync),
) -> Result<Vec<(usize, EnsembleCell)>, ThudError> {
    check_runs(n)?;
    design::grid_cells(masses_kg, gaps_m, range, cancel, on_cell, |mass_kg, gap_m| {
        match base.variant(mass_kg, gap_m).and_then(|d| evaluate(&d, n, cancel)) {
            Ok(None) => None,
            Ok(Some(ensemble)) => Some(Ok(EnsembleCell { mass_kg, gap_m, ensemble })),
            Err(e) => Some(Err(e)),
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::design::Design;

    #[test]
    fn offsets_are_evenly_spread_inside_the_clearance() {
        assert_eq!(ball_positions(0.04, 1), vec![0.0], "N = 1: the centred ball, exactly");
        let y = ball_positions(0.04, 4);
        assert_eq!(y.len(), 4);
        for (k, want) in [-0.015, -0.005, 0.005, 0.015].iter().enumerate() {
            assert!((y[k] - want).abs() < 1e-15, "{k}: {}", y[k]);
        }
        for n in [2usize, 3, 7, 16, 101] {
            let y = ball_positions(0.04, n);
            assert!(y.iter().all(|v| v.abs() < 0.02), "{n}: inside");
            assert!(y.windows(2).all(|w| ((w[1] - w[0]) - 0.04 / n as f64).abs() < 1e-15), "{n}: spacing d/N");
            assert_eq!(y.iter().any(|v| v.abs() < 1e-15), n % 2 == 1, "{n}: an odd N has the centre");
        }
    }

    #[test]
    fn nearest_rank_percentiles() {
        let ten: Vec<Option<f64>> = (1..=10).map(|i| Some(f64::from(i))).collect();
        let p = Percentiles::of(ten.iter().rev().copied());
        assert_eq!((p.p10, p.median, p.p90), (Some(1.0), Some(5.0), Some(9.0)), "ranks 1, 5, 9 of 10");
        let sixteen = (1..=16).map(|i| Some(f64::from(i)));
        let p = Percentiles::of(sixteen);
        assert_eq!((p.p10, p.median, p.p90), (Some(2.0), Some(8.0), Some(15.0)), "ranks 2, 8, 15 of 16");
        let one = Percentiles::of([Some(0.61)]);
        assert_eq!((one.p10, one.median, one.p90), (Some(0.61), Some(0.61), Some(0.61)));
        // 30 runs: 0.1·30 in floating point is 3.0000000000000004; the rank must still be 3.
        let p = Percentiles::of((1..=30).map(|i| Some(f64::from(i))));
        assert_eq!((p.p10, p.median, p.p90), (Some(3.0), Some(15.0), Some(27.0)));
        // Runs without the value rank lowest.
        let p = Percentiles::of([None, Some(3.0), None, Some(1.0), None]);
        assert_eq!((p.p10, p.median, p.p90), (None, None, Some(3.0)));
        assert_eq!(Percentiles::of([]).median, None);
    }

    fn member_with(zone: Option<Zone>, e: f64, spl: f64) -> Member {
        let metrics = Metrics {
            n_impacts: 5,
            u0_max_m_s: 1.0,
            zdot_abs_max_m_s: 1.0,
            spl_max_db: Some(spl),
            contact_duration_s: Some(1e-4),
            restitution_mean: Some(0.9),
            inclination_cm_s: Some(e),
            inclination_fit_cm_s: Some(e),
            zone,
        };
        Member { ball_position_m: 0.0, metrics, truncated: None }
    }

    #[test]
    fn zone_of_the_medians_probability_and_agreement() {
        let t = Thresholds { spl_db: 100.0, inclination_cm_s: 1.0, ..Thresholds::default() };
        // Four runs: e 0.5, 1.5, 2, 3 and SPL 99, 99, 99, 101; median rank 2: e 1.5, SPL 99 → zone 3.
        let runs = vec![
            member_with(Some(Zone::QuietWeak), 0.5, 99.0),
            member_with(Some(Zone::QuietStrong), 1.5, 99.0),
            member_with(Some(Zone::QuietStrong), 2.0, 99.0),
            member_with(Some(Zone::NoisyStrong), 3.0, 101.0),
        ];
        let e = Ensemble::from_members(runs, &t);
        assert_eq!(e.metrics.inclination_cm_s, Some(1.5));
        assert_eq!(e.metrics.spl_max_db, Some(99.0));
        assert_eq!(e.metrics.zone, Some(Zone::QuietStrong));
        assert_eq!(e.zone3_probability, 0.5);
        assert_eq!(e.agreement, 0.5);
        assert_eq!(e.runs, 4);
    }

    #[test]
    fn zone_under_is_the_ensemble_rebuilt_under_other_thresholds() {
        let t = Thresholds { spl_db: 100.0, inclination_cm_s: 1.0, ..Thresholds::default() };
        let runs: Vec<Member> = [(0.5, 99.0), (1.5, 99.0), (2.0, 102.0), (3.0, 101.0), (0.2, 98.0)]
            .into_iter()
            .map(|(e, spl)| member_with(None, e, spl))
            .map(|m| Member { metrics: Metrics { zone: m.metrics.zone(&t), ..m.metrics }, ..m })
            .collect();
        let e = Ensemble::from_members(runs, &t);
        for (spl_db, inclination_cm_s) in [(100.0, 1.0), (98.5, 0.4), (101.5, 2.5), (110.0, 0.1), (90.0, 5.0)] {
            let u = Thresholds { spl_db, inclination_cm_s, ..t };
            let rebuilt = Ensemble::from_members(
                e.ensemble
                    .iter()
                    .map(|m| Member { metrics: Metrics { zone: m.metrics.zone(&u), ..m.metrics }, ..*m })
                    .collect(),
                &u,
            );
            assert_eq!(
                e.zone_under(&u),
                (rebuilt.metrics.zone, rebuilt.agreement),
                "L* {spl_db}, e* {inclination_cm_s}"
            );
        }
    }

    #[test]
    fn a_member_keeps_the_metrics_it_was_made_of_and_writes_the_zone_as_a_number() {
        let m = member_with(Some(Zone::QuietStrong), 1.5, 99.0);
        assert_eq!(Member::new(m.ball_position_m, &m.metrics, None), m);
        let json = serde_json::to_string(&m).unwrap();
        assert!(json.contains(r#""zone":3"#) && !json.contains("truncated"), "{json}");
        assert_eq!(serde_json::from_str::<Member>(&json).unwrap(), m);
        assert!(serde_json::from_str::<Member>(&json.replace(r#""zone":3"#, r#""zone":5"#)).is_err());
        assert_eq!(zone_from_number(0), None);
    }

    #[test]
    fn an_ensemble_needs_a_run() {
        let e = evaluate(&Design::default().check().unwrap(), 0, None).unwrap_err().to_string();
        assert!(e.starts_with("invalid ensemble: "), "{e}");
    }

    /// Short runs, so the debug test build stays quick.
    fn short() -> ValidDesign {
        let mut d = Design::default();
        d.damper.duration_s = 0.3;
        d.check().unwrap()
    }

    #[test]
    fn each_run_is_the_single_run_with_the_ball_at_its_offset() {
        let d = short();
        let e = evaluate(&d, 5, None).unwrap().unwrap();
        assert_eq!(e.ensemble.len(), 5);
        for (m, y0) in e.ensemble.iter().zip(ball_positions(d.damper.gap_m, 5)) {
            let mut alone = d.clone().into_design();
            alone.damper.ball_position_m = y0;
            assert_eq!(m.ball_position_m, y0);
            let alone = alone.check().unwrap();
            assert_eq!(m.metrics, design::evaluate(&alone, 0, None).unwrap().metrics, "y0 {y0}");
        }
        let spread: Vec<f64> = e.ensemble.iter().filter_map(|m| m.metrics.inclination_cm_s).collect();
        assert!(spread.iter().any(|&x| x != spread[0]), "the offsets change e: {spread:?}");
    }

    #[test]
    fn an_ensemble_of_one_is_the_single_run() {
        let d = short();
        let single = design::evaluate(&d, 0, None).unwrap().metrics;
        let e = evaluate(&d, 1, None).unwrap().unwrap();
        assert_eq!(e.metrics, single);
        assert_eq!(e.ensemble[0].metrics, single);
        let s = e.spread.inclination_cm_s;
        assert_eq!(
            (s.p10, s.median, s.p90),
            (single.inclination_cm_s, single.inclination_cm_s, single.inclination_cm_s)
        );
        assert_eq!(e.agreement, 1.0);
        let (m, g) = ([0.03, 0.06], [0.02, 0.04]);
        let chart = sweep(&d, &m, &g, 1, None, &|_, _| {}).unwrap();
        assert_eq!(chart.medians(), design::sweep(&d, &m, &g, None, &|_, _| {}).unwrap());
    }

    #[test]
    fn a_cancelled_ensemble_sweep_starts_no_cell() {
        let stop = AtomicBool::new(true);
        let chart = sweep(&short(), &[0.03], &[0.02], 4, Some(&stop), &|_, _| panic!("no cell may finish")).unwrap();
        assert!(chart.cells.iter().all(Option::is_none));
        assert_eq!(evaluate(&short(), 3, Some(&stop)).unwrap(), None);
    }
}
