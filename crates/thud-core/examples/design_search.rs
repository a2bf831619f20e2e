#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a measurement fails
//! Measures the design search (docs/model.md, "Design search"): on the acceptance problem
//! (paper-table3, mass 20–120 g × gap 1–6 cm, min SPLmax, max e, reference 106 dB, 0 cm/s) the
//! hypervolume of NSGA-II's front at a budget against the front of a 100 × 100 grid, beside
//! random search and a Latin hypercube of the same budget, with wall times.
//!
//! `cargo run --release -p thud-core --example design_search [BUDGET] [SEEDS] [GRID_HV|-] [POP,SIGMA,GENES,RATE,ETA[,LATIN,PM_ETA,DISTINCT,ALGO,KIDS,SHARE,MARGIN,THEN,FRONT,WIDEN,SIGMA_END]]…`
//!
//! LATIN 1: a Latin-hypercube first population; PM_ETA > 0: polynomial mutation of that index in
//! place of the Gaussian (SIGMA unused); DISTINCT 1: a generation's repeated children drawn again; ALGO 1: SPEA2, 2:
//! AGE-MOEA, 3: IBEA (hypervolume indicator against the reference 106 dB, 0 cm/s), 4: NSGA-II for
//! the first half of the generations, then IBEA (0: NSGA-II); KIDS > 0: children a generation (else the population).
//! SHARE > 0: two phases, the first over the whole box for that share of the budget, the second
//! over the box the front then spans widened by MARGIN of each range a side (default 0.05), by
//! THEN (3: IBEA, else NSGA-II), its first population the front's designs unless FRONT is 0; WIDEN: the box widened
//! besides by that share of the front's span a side. SIGMA_END > 0: the Gaussian step lowered
//! from SIGMA to it as the budget is spent.
//!
//! With knobs after the grid's hypervolume (`-`: compute it), each setting of NSGA-II is
//! measured on the same seeds instead of the defaults beside the baselines.

use std::time::Instant;

#[path = "shared/knobs.rs"]
mod knobs;
use knobs::knobs;
use thud_core::design::search::{self, Objective, Problem, Sense, Settings, Tuning, Variable};
use thud_core::design::Design;
use thud_core::params::Spelling;
use thud_core::study::{self, Grid, Vary};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let budget: usize = args.get(1).and_then(|a| a.parse().ok()).unwrap_or(400);
    let seeds: u64 = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(10);
    let base = Design::paper_table3().check().expect("the preset checks");
    let p = Problem {
        base: base.clone(),
        variables: vec![
            Variable::parse_range("mass=20g:120g").expect("range"),
            Variable::parse_range("gap=1cm:6cm").expect("range"),
        ],
        objectives: vec![
            Objective::parse("spl_max_db", Sense::Minimize).expect("column"),
            Objective::parse("inclination_cm_s", Sense::Maximize).expect("column"),
        ],
        constraints: vec![],
        band_hz: vec![],
        robust: None,
    };
    let reference = [106.0, 0.0];
    let t = Instant::now();
    let known: Option<f64> = args.get(3).and_then(|a| a.parse().ok()); // "-": computed
    let grid_hv = known.unwrap_or_else(|| {
        let grid = Grid::new(
            base,
            vec![
                Vary::parse("mass=20g:120g:100", Spelling::Flag).expect("axis"),
                Vary::parse("gap=1cm:6cm:100", Spelling::Flag).expect("axis"),
            ],
            Spelling::Flag,
        )
        .expect("grid");
        let s = study::sweep(&grid, None, &|_, _| {}).expect("sweep");
        let pts: Vec<[f64; 2]> =
            s.cells.iter().filter_map(|c| Some([c.metrics.spl_max_db?, -c.metrics.inclination_cm_s?])).collect();
        let grid_hv = search::hypervolume_2d(&pts, [106.0, 0.0]);
        println!("grid 100×100: hypervolume {grid_hv:.6} in {:.2} s", t.elapsed().as_secs_f64());
        grid_hv
    });
    let tunings: Vec<Tuning> = args.iter().skip(4).map(|t| knobs(t)).collect();
    if !tunings.is_empty() {
        for tuning in [Tuning::default()].into_iter().chain(tunings) {
            let t = Instant::now();
            let shares: Vec<f64> = (1..=seeds)
                .map(|seed| {
                    let s = Settings { evaluations: budget, seed };
                    let o = search::search_tuned(&p, s, tuning, Some(&reference), None, &|_, _, _| {}).expect("search");
                    100.0 * o.hypervolume.unwrap_or(0.0) / grid_hv
                })
                .collect();
            let at_97 = shares.iter().filter(|&&s| s >= 97.0).count();
            let mut sorted = shares.clone();
            sorted.sort_by(f64::total_cmp);
            let median = 0.5 * (sorted[(sorted.len() - 1) / 2] + sorted[sorted.len() / 2]);
            println!(
                "{tuning:?}: median {median:.2} %, {at_97} of {seeds} seeds at 97 % ({:.1} s) {shares:.1?}",
                t.elapsed().as_secs_f64()
            );
        }
        return;
    }
    println!("budget {budget}, {seeds} seeds: % of the grid's hypervolume (wall s)");
    for seed in 1..=seeds {
        let settings = Settings { evaluations: budget, seed };
        let mut row = format!("seed {seed:>2}");
        let t = Instant::now();
        let o = search::search(&p, settings, Some(&reference), None, &|_, _, _| {}).expect("search");
        let nsga = o.hypervolume.unwrap_or(0.0);
        row += &format!(
            "  nsga2 {:6.2} % ({:.2} s, {} evals)",
            100.0 * nsga / grid_hv,
            t.elapsed().as_secs_f64(),
            o.all.len()
        );
        for (name, f) in
            [("random", search::random_search as fn(&Problem, Settings) -> _), ("lhs", search::latin_hypercube)]
        {
            let t = Instant::now();
            let o = f(&p, settings).expect("baseline");
            let hv = p.hypervolume(&o.all, &o.front, &reference).unwrap_or(0.0);
            row += &format!("  {name} {:6.2} % ({:.2} s)", 100.0 * hv / grid_hv, t.elapsed().as_secs_f64());
        }
        println!("{row}");
    }
}
