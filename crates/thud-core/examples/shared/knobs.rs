//! The search's knobs as the design examples take them (`design_search`, `design_tune`): one
//! parser for both.

use thud_core::design::search::{self, Start, Tuning};

/// A setting of the search from `POP,SIGMA,GENES,RATE,ETA[,LATIN,PM_ETA,DISTINCT,ALGO,KIDS,SHARE,MARGIN,THEN,FRONT,WIDEN,SIGMA_END]`.
pub fn knobs(t: &str) -> Tuning {
    let v: Vec<f64> = t.split(',').map(|x| x.parse().unwrap()).collect();
    Tuning {
        population: (v[0] > 0.0).then_some(v[0] as usize),
        sigma: v[1],
        genes_mutated: v[2],
        mutation_rate: v[3],
        crossover_eta: v[4],
        start: if v.get(5).is_some_and(|&x| x > 0.0) { Start::Latin } else { Start::Uniform },
        polynomial_eta: v.get(6).copied().filter(|&x| x > 0.0),
        distinct: v.get(7).is_some_and(|&x| x > 0.0),
        algorithm: match v.get(8).map_or(0, |&x| x as u8) {
            1 => search::Algorithm::Spea2,
            2 => search::Algorithm::AgeMoea,
            3 => search::Algorithm::Ibea,
            4 => search::Algorithm::Nsga2ThenIbea,
            _ => search::Algorithm::Nsga2,
        },
        offspring: v.get(9).copied().filter(|&x| x > 0.0).map(|x| x as usize),
        sigma_end: v.get(15).copied().filter(|&x| x > 0.0),
        narrow: v.get(10).copied().filter(|&x| x > 0.0).map(|share| search::Narrowing {
            share,
            margin: v.get(11).copied().unwrap_or(0.05),
            widen: v.get(14).copied().unwrap_or(0.0),
            then: if v.get(12).is_some_and(|&x| x as u8 == 3) {
                search::Algorithm::Ibea
            } else {
                search::Algorithm::Nsga2
            },
            start_at_front: v.get(13).is_none_or(|&x| x > 0.0),
        }),
    }
}
