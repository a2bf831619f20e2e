#![allow(clippy::unwrap_used, clippy::expect_used)] // a measuring tool: a panic is how it fails
//! The robust design chart's cost (issue 27), for instruction counts that do not depend on the
//! machine's load:
//!
//! ```sh
//! cargo build --profile profiling -p thud-core --example chart_cost
//! RAYON_NUM_THREADS=1 valgrind --tool=callgrind target/profiling/examples/chart_cost 4 16
//! ```
//!
//! Sweeps the Fig 9 design over a `CELLS` × `CELLS` grid of the bench's axes (mass 0.03–0.1 kg,
//! gap 0.02–0.05 m) with `RUNS` ensemble runs a cell (`ensemble::sweep`), and prints the impacts
//! of all runs; with a third argument `newmark`, runs the Fig 9 design once by Newmark-β at
//! dt 1e-7 s instead (the bench's reference).

use thud_core::damper::Solver;
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
    let chart =
        ensemble::sweep(&base, &linspace(0.03, 0.1, cells), &linspace(0.02, 0.05, cells), runs, None, &|_, _| {})
            .unwrap();
    let impacts: usize = chart.cells.iter().flatten().flat_map(|c| &c.ensemble.ensemble).map(|m| m.n_impacts).sum();
    println!("{cells}x{cells} x {runs} runs: {impacts} impacts");
}
