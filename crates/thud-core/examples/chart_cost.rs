#![allow(clippy::unwrap_used, clippy::expect_used)] // a measuring tool: a panic is how it fails
//! The robust design chart's cost, for instruction counts that do not depend on the
//! machine's load:
//!
//! ```sh
//! cargo build --profile profiling -p thud-core --example chart_cost
//! RAYON_NUM_THREADS=1 valgrind --tool=callgrind target/profiling/examples/chart_cost 4 16
//! ```
//!
//! Sweeps the Fig 9 design over a `CELLS` × `CELLS` grid of the bench's axes (mass 0.03–0.1 kg,
//! gap 0.02–0.05 m) with `RUNS` ensemble runs a cell (`ensemble::sweep`), and prints the impacts
//! of all runs. A third argument:
//!
//! - `newmark`: the Fig 9 design once by Newmark-β at dt 1e-7 s instead (the bench's reference);
//! - `json`: the chart itself, as JSON (to compare two builds' charts bit for bit);
//! - a contact scheme (`DormandPrince`, `SundmanTaylor`, `SundmanDop853`, `SundmanAdams`): the same runs and
//!   metrics one by one on one thread with that scheme (`damper::simulate_with`, then
//!   `design::metrics`), for what the chart would cost with it. With `SundmanAdams` (the
//!   default, the chart's own scheme) the impacts are the chart's.
//!
//! Where the chart's instructions went (20 × 20 × 16 on one thread, 19.13 G): the
//! contact integrator `damper::contact::integrate` 92.7 % (its step control's `log2`/`exp2`
//! alone 7.8 %), the rest of each contact 0.3 %, the flights (contact search, recording,
//! energies) 4.2 %, the per-run metrics 2.7 % (the SPL's rms over τ 2.5 %, e, e_fit, U0max and
//! the zone 0.1 %), the ensemble's summary 0.06 %, rayon and the sweep 0.01 %. One Newmark
//! design (Fig 9, dt 1e-7 s, 2 s) is 3.26 G. With `SundmanDop853` the runs take 15.23 G. (These
//! counts are of the chart with `DormandPrince`, its scheme before `SundmanAdams` became the
//! default.) With `SundmanAdams` (5 × 5 × 16, one thread, 0.95 G): about 53 Adams steps a
//! contact at about 670 instructions each, and 8.4 k a contact besides (docs/model.md §11).

use thud_core::damper::{simulate_with, ContactScheme, RunOptions, Solver};
use thud_core::design::{self, linspace, Design};
use thud_core::ensemble;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let cells: usize = args.get(1).map_or(4, |r| r.parse().expect("CELLS is a count"));
    let runs: usize = args.get(2).map_or(16, |r| r.parse().expect("RUNS is a count"));
    if args.get(3).is_some_and(|a| a == "newmark") {
        let d = Design { solver: Solver::Newmark { dt_s: 1e-7 }, ..Design::paper_fig9() }.check().unwrap();
        let e = design::evaluate(&d, 0, None).unwrap();
        println!("newmark: {} impacts", e.metrics.n_impacts);
        return;
    }
    let base = Design::paper_fig9().check().unwrap();
    let (masses, gaps) = (linspace(0.03, 0.1, cells), linspace(0.02, 0.05, cells));
    let scheme = match args.get(3).map(String::as_str) {
        None => None,
        Some("DormandPrince") => Some(ContactScheme::DormandPrince),
        Some("SundmanTaylor") => Some(ContactScheme::SundmanTaylor),
        Some("SundmanDop853") => Some(ContactScheme::SundmanDop853),
        Some("SundmanAdams") => Some(ContactScheme::SundmanAdams),
        Some("json") => None,
        Some(other) => panic!("unknown scheme {other}"),
    };
    if let Some(scheme) = scheme {
        let mut impacts = 0;
        for &gap in &gaps {
            for &mass in &masses {
                let cell = design::variant(&base, mass, gap).check().unwrap();
                for y0 in ensemble::ball_positions(gap, runs) {
                    let p = thud_core::damper::DamperParams { ball_position_m: y0, ..cell.damper };
                    let run = simulate_with(&p, cell.solver, &RunOptions::default(), scheme).unwrap();
                    impacts += design::metrics(&run, &cell).unwrap().n_impacts;
                }
            }
        }
        println!("{cells}x{cells} x {runs} runs by {scheme:?}: {impacts} impacts");
        return;
    }
    let chart =
        ensemble::sweep(&base, &linspace(0.03, 0.1, cells), &linspace(0.02, 0.05, cells), runs, None, &|_, _| {})
            .unwrap();
    if args.get(3).is_some_and(|a| a == "json") {
        println!("{}", serde_json::to_string(&chart).unwrap());
        return;
    }
    let impacts: usize =
        chart.cells.iter().flatten().flat_map(|c| &c.ensemble.ensemble).map(|m| m.metrics.n_impacts).sum();
    println!("{cells}x{cells} x {runs} runs: {impacts} impacts");
}
