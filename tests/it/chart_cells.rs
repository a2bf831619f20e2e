#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! The robust design chart reports, in every cell,
//! exactly what the engine says of that cell's design on its own: the cell is
//! `ensemble::evaluate` of the base design at the cell's (mass, gap), to the last bit, and each
//! of its runs is `design::evaluate` of that design with the ball at the run's offset. However
//! the chart is scheduled (rayon's global pool, one thread, a shard of its cells), it is the
//! same chart. The axes are the benchmark's (`benches/ensemble.rs`): the Fig 9 design over
//! mass 0.03–0.1 kg × gap 0.02–0.05 m, 20 × 20, 16 runs a cell; a few of its cells are taken.

use thud::design::{self, linspace, Design};
use thud::ensemble::{self, EnsembleCell};

/// The benchmark's axes.
fn axes() -> (Vec<f64>, Vec<f64>) {
    (linspace(0.03, 0.1, 20), linspace(0.02, 0.05, 20))
}

/// Corners and the middle of the benchmark's chart: masses 0, 9, 19 × gaps 0, 19.
fn some_cells() -> (Vec<f64>, Vec<f64>) {
    let (m, g) = axes();
    (vec![m[0], m[9], m[19]], vec![g[0], g[19]])
}

#[test]
fn every_cell_is_the_ensemble_of_its_own_design_to_the_last_bit() {
    let base = Design::paper_fig9();
    let (masses, gaps) = some_cells();
    let seen = std::sync::Mutex::new(Vec::new());
    let chart = ensemble::sweep(&base.clone().check().unwrap(), &masses, &gaps, 16, None, &|i, c: &EnsembleCell| {
        seen.lock().unwrap().push((i, c.clone()));
    })
    .unwrap();
    assert_eq!(chart.cells.len(), 6);
    for (gi, &gap) in gaps.iter().enumerate() {
        for (mi, &mass) in masses.iter().enumerate() {
            let cell = chart.cell(mi, gi).unwrap();
            assert_eq!((cell.mass_kg, cell.gap_m), (mass, gap));
            let alone =
                ensemble::evaluate(&design::variant(&base, mass, gap).check().unwrap(), 16, None).unwrap().unwrap();
            assert_eq!(cell.ensemble, alone, "mass {mass} kg, gap {gap} m");
            assert_eq!(cell.ensemble.runs, 16);
            assert!(cell.ensemble.ensemble.iter().all(|m| m.truncated.is_none()), "no run is cut short");
        }
    }
    // What `on_cell` was shown is what the chart holds.
    let mut seen = seen.into_inner().unwrap();
    seen.sort_by_key(|&(i, _)| i);
    let held: Vec<(usize, EnsembleCell)> =
        chart.cells.iter().enumerate().map(|(i, c)| (i, c.clone().unwrap())).collect();
    assert_eq!(seen, held);
}

/// One cell of the chart, each run against the single design run from its offset: the member's
/// metrics are `design::evaluate`'s.
#[test]
fn each_run_of_a_chart_cell_is_the_single_run_from_its_offset() {
    let base = Design::paper_fig9();
    let (masses, gaps) = axes();
    let (mass, gap) = (masses[13], gaps[6]);
    let chart = ensemble::sweep(&base.clone().check().unwrap(), &[mass], &[gap], 16, None, &|_, _| {}).unwrap();
    let cell = chart.cell(0, 0).unwrap();
    let offsets = ensemble::ball_positions(gap, 16);
    for (m, &y0) in cell.ensemble.ensemble.iter().zip(&offsets) {
        let mut alone = design::variant(&base, mass, gap);
        alone.damper.ball_position_m = y0;
        let single = design::evaluate(&alone.check().unwrap(), 0, None).unwrap();
        assert_eq!(m.ball_position_m, y0);
        assert_eq!(m.metrics, single.metrics, "y0 {y0}");
        assert_eq!(m.truncated, single.run.truncated);
    }
}

/// The chart does not depend on its scheduling: on one thread, on rayon's global pool, and as
/// shards of its cells, it is the same chart.
#[test]
fn the_chart_is_the_same_on_one_thread_and_in_shards() {
    let base = Design::paper_fig9().check().unwrap();
    let (masses, gaps) = some_cells();
    let all = ensemble::sweep(&base, &masses, &gaps, 16, None, &|_, _| {}).unwrap();
    let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    let alone = one.install(|| ensemble::sweep(&base, &masses, &gaps, 16, None, &|_, _| {}).unwrap());
    assert_eq!(all, alone);
    let n = all.cells.len();
    let mut parts = Vec::new();
    for k in 0..4 {
        let range = design::shard_range(n, k, 4);
        parts.extend(ensemble::sweep_cells(&base, &masses, &gaps, 16, range, None, &|_, _| {}).unwrap());
    }
    let held: Vec<(usize, EnsembleCell)> = all.cells.iter().enumerate().map(|(i, c)| (i, c.clone().unwrap())).collect();
    assert_eq!(parts, held);
}
