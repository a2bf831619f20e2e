#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a measurement fails
//! Measures NSGA-II's knobs (docs/model.md, "Design search") on four variables (mass, gap, c1,
//! the ball's material; min SPLmax, max e; reference 110 dB, 0 cm/s): the median hypervolume
//! over seeds against random search and a Latin hypercube of the same budget.
//!
//! `cargo run --release -p thud-core --example design_tune [BUDGET] [SEEDS] [POP,SIGMA,GENES,RATE,ETA[,LATIN,PM_ETA,DISTINCT,ALGO,KIDS,SHARE,MARGIN,THEN,FRONT,WIDEN,SIGMA_END]]…`
//!
//! LATIN 1: a Latin-hypercube first population; PM_ETA > 0: polynomial mutation of that index in
//! place of the Gaussian (SIGMA unused); DISTINCT 1: a generation's repeated children drawn again; ALGO 1: SPEA2, 2:
//! AGE-MOEA, 3: IBEA, 4: NSGA-II then IBEA (0: NSGA-II; the parser shared with design_search); KIDS > 0: children a generation (else the population).
//! SHARE > 0: two phases, the first over the whole box for that share of the budget, the second
//! over the box the front then spans widened by MARGIN of each range a side (default 0.05), by
//! THEN (3: IBEA, else NSGA-II), its first population the front's designs unless FRONT is 0; WIDEN: the box widened
//! besides by that share of the front's span a side. SIGMA_END > 0: the Gaussian step lowered
//! from SIGMA to it as the budget is spent.

use std::time::Instant;

#[path = "shared/knobs.rs"]
mod knobs;
use knobs::knobs;
use thud_core::design::search::{self, Objective, Outcome, Problem, Sense, Settings, Tuning, Variable};
use thud_core::design::Design;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let budget: usize = args.get(1).and_then(|a| a.parse().ok()).unwrap_or(150);
    let seeds: u64 = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(10);
    let p = Problem {
        base: Design::paper_table3().check().expect("the preset checks"),
        variables: vec![
            Variable::parse_range("mass=20g:120g").expect("range"),
            Variable::parse_range("gap=1cm:6cm").expect("range"),
            Variable::parse_range("c1=10:60").expect("range"),
            Variable::parse_choice("sphere=steel,acrylic,nylon").expect("choice"),
        ],
        objectives: vec![
            Objective::parse("spl_max_db", Sense::Minimize).expect("column"),
            Objective::parse("inclination_cm_s", Sense::Maximize).expect("column"),
        ],
        constraints: vec![],
        band_hz: vec![],
        robust: None,
    };
    let reference = [110.0, 0.0];
    let hv = |o: &Outcome| p.hypervolume(&o.all, &o.front, &reference).unwrap();
    let mut tunings = vec![Tuning::default()];
    for t in args.iter().skip(3) {
        tunings.push(knobs(t));
    }
    let (mut random, mut lhs) = (Vec::new(), Vec::new());
    let t = Instant::now();
    for seed in 1..=seeds {
        let s = Settings { evaluations: budget, seed };
        random.push(hv(&search::random_search(&p, s).unwrap()));
        lhs.push(hv(&search::latin_hypercube(&p, s).unwrap()));
    }
    println!(
        "budget {budget}, {seeds} seeds: random median {:.4}, LHS median {:.4} ({:.1} s)",
        median(random),
        median(lhs),
        t.elapsed().as_secs_f64()
    );
    for tuning in tunings {
        let t = Instant::now();
        let v: Vec<f64> = (1..=seeds)
            .map(|seed| {
                let s = Settings { evaluations: budget, seed };
                hv(&search::search_tuned(&p, s, tuning, Some(&reference), None, &|_, _, _| {}).unwrap())
            })
            .collect();
        println!("{tuning:?}: median {:.4} ({:.1} s) {v:.3?}", median(v.clone()), t.elapsed().as_secs_f64());
    }
}
