//! The operators the design search hands `moors`' NSGA-II beside its own: how the first
//! population is drawn ([`Start`]: uniform, or a Latin hypercube), how a child mutates
//! ([`Mutation`]: Gaussian, or Deb's polynomial mutation within [0, 1]) and whether a
//! generation's children repeating a parent or each other are drawn again ([`Distinct`]), and
//! the survival of the hypervolume-indicator search ([`HypervolumeSurvival`]: `moors`' IBEA
//! against the search's own reference point). Genes span [0, 1] (the search's decoding maps
//! them to the variables).

use std::cell::Cell;
use std::rc::Rc;

use moors::genetic::D12;
use moors::survival::moo::{IbeaHyperVolumeSurvivalOperator, Nsga2RankCrowdingSurvival};
use moors::survival::SurvivalOperator;
use moors::{
    ExactDuplicatesCleaner, GaussianMutation, MutationOperator, Population, PopulationCleaner, RandomGenerator,
    SamplingOperator,
};
use ndarray::{Array1, Array2, ArrayViewMut1, Axis, Ix2};

/// The algorithm of `moors` a search runs: its selection of parents and survival of children.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Algorithm {
    /// NSGA-II: non-dominated rank, then crowding distance.
    Nsga2,
    /// SPEA2: strength and density by nearest neighbours.
    Spea2,
    /// AGE-MOEA: rank, then a survival score from the front's estimated geometry.
    AgeMoea,
    /// IBEA with the hypervolume indicator against the search's reference point
    /// ([`HypervolumeSurvival`]).
    Ibea,
    /// NSGA-II for the first half of the budget's generations, then IBEA from its population.
    Nsga2ThenIbea,
}

/// How the first population is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Start {
    /// Each gene uniform in [0, 1].
    Uniform,
    /// A Latin hypercube: each gene's [0, 1] cut in as many equal strata as the population,
    /// one individual in each, the strata shuffled per gene.
    Latin,
}

impl SamplingOperator for Start {
    fn sample_individual(&self, num_vars: usize, rng: &mut impl RandomGenerator) -> Array1<f64> {
        (0..num_vars).map(|_| rng.gen_range_f64(0.0, 1.0)).collect()
    }

    fn operate(&self, population_size: usize, num_vars: usize, rng: &mut impl RandomGenerator) -> Array2<f64> {
        let n = population_size;
        let mut genes = Array2::zeros((n, num_vars));
        match self {
            Start::Uniform => {
                for mut row in genes.outer_iter_mut() {
                    row.assign(&self.sample_individual(num_vars, rng));
                }
            }
            Start::Latin => {
                for k in 0..num_vars {
                    let mut strata: Vec<usize> = (0..n).collect();
                    rng.shuffle_vec_usize(&mut strata);
                    for (i, s) in strata.into_iter().enumerate() {
                        genes[[i, k]] = (s as f64 + rng.gen_range_f64(0.0, 1.0)) / n as f64;
                    }
                }
            }
        }
        genes
    }
}

/// The first population: the rows given (at most the population), then rows drawn by
/// `start`; with none given, exactly `start`'s draw.
#[derive(Debug, Clone)]
pub struct Sampler {
    /// Genes in [0, 1].
    pub rows: Vec<Vec<f64>>,
    pub start: Start,
}

impl SamplingOperator for Sampler {
    fn sample_individual(&self, num_vars: usize, rng: &mut impl RandomGenerator) -> Array1<f64> {
        self.start.sample_individual(num_vars, rng)
    }

    fn operate(&self, population_size: usize, num_vars: usize, rng: &mut impl RandomGenerator) -> Array2<f64> {
        let given = self.rows.len().min(population_size);
        if given == 0 {
            return self.start.operate(population_size, num_vars, rng);
        }
        let mut genes = Array2::zeros((population_size, num_vars));
        for (i, r) in self.rows.iter().take(given).enumerate() {
            for (k, &g) in r.iter().enumerate().take(num_vars) {
                genes[[i, k]] = g;
            }
        }
        if population_size > given {
            let drawn = self.start.operate(population_size - given, num_vars, rng);
            for (mut row, d) in genes.outer_iter_mut().skip(given).zip(drawn.outer_iter()) {
                row.assign(&d);
            }
        }
        genes
    }
}

/// How a child mutates: each gene with chance `gene_rate`.
#[derive(Debug, Clone)]
pub enum Mutation {
    /// `moors`' normal step (the gene then clamped to [0, 1] by the search's bounds).
    Gaussian(GaussianMutation),
    /// Deb's polynomial mutation with distribution index `eta`, its step shaped by the
    /// distance to either end of [0, 1], so the gene stays inside (as pymoo's default).
    Polynomial { gene_rate: f64, eta: f64 },
    /// `moors`' normal step whose standard deviation is read at each child from `sigma`
    /// (which the search lowers as its budget is spent).
    Shrinking { gene_rate: f64, sigma: Rc<Cell<f64>> },
}

impl MutationOperator for Mutation {
    fn mutate(&self, mut individual: ArrayViewMut1<'_, f64>, rng: &mut impl RandomGenerator) {
        match *self {
            Mutation::Gaussian(ref m) => m.mutate(individual, rng),
            Mutation::Shrinking { gene_rate, ref sigma } => {
                GaussianMutation::new(gene_rate, sigma.get()).mutate(individual, rng);
            }
            Mutation::Polynomial { gene_rate, eta } => {
                for g in &mut individual {
                    if rng.gen_bool(gene_rate) {
                        *g = polynomial_step(g.clamp(0.0, 1.0), eta, rng.gen_range_f64(0.0, 1.0));
                    }
                }
            }
        }
    }
}

/// The polynomial mutation of `y` in [0, 1] with index `eta` for the uniform draw `r`
/// (Deb and Goyal 1996, the bounded form): a step below for r < ½, above otherwise, never past
/// an end.
fn polynomial_step(y: f64, eta: f64, r: f64) -> f64 {
    let power = 1.0 / (eta + 1.0);
    let dq = if r < 0.5 {
        let v = 2.0 * r + (1.0 - 2.0 * r) * (1.0 - y).powf(eta + 1.0);
        v.powf(power) - 1.0
    } else {
        let v = 2.0 * (1.0 - r) + 2.0 * (r - 0.5) * y.powf(eta + 1.0);
        1.0 - v.powf(power)
    };
    (y + dq).clamp(0.0, 1.0)
}

/// Whether a generation's children that repeat a parent or an earlier child are dropped (and
/// more drawn) rather than kept.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Distinct(pub bool);

impl PopulationCleaner for Distinct {
    fn remove(&self, population: Array2<f64>, reference: Option<&Array2<f64>>) -> Array2<f64> {
        if self.0 {
            ExactDuplicatesCleaner::new().remove(population, reference)
        } else {
            population
        }
    }
}

/// The survival of the hypervolume-indicator search: `moors`' IBEA (Zitzler and Künzli 2004,
/// the hypervolume indicator) over the feasible individuals, against `reference` (in the
/// objectives minimised, as `moors` reads them): `moors` scales each generation's objectives
/// to [0, 1] by their least and greatest values, so the reference is scaled the same way each
/// generation. With fewer feasible individuals than survive, all of them survive and the
/// infeasible ones with the least violation fill the rest. The first `nsga2_calls` calls
/// survive by NSGA-II's rank and crowding instead.
pub struct HypervolumeSurvival<'r> {
    /// The reference point, minimised; None: 1.1 times the scaled span (no feasible design
    /// fixed one yet).
    pub reference: &'r dyn Fn() -> Option<Vec<f64>>,
    /// IBEA's κ (times the largest indicator value of the generation, as `moors` scales it).
    pub kappa: f64,
    /// Calls left under NSGA-II's survival.
    pub nsga2_calls: usize,
}

impl SurvivalOperator for HypervolumeSurvival<'_> {
    type FDim = Ix2;

    fn operate<C: D12>(
        &mut self,
        population: Population<Ix2, C>,
        num_survive: usize,
        rng: &mut impl RandomGenerator,
    ) -> Population<Ix2, C> {
        if self.nsga2_calls > 0 {
            self.nsga2_calls -= 1;
            return Nsga2RankCrowdingSurvival::new().operate(population, num_survive, rng);
        }
        let n = population.len();
        let cv = |i: usize| population.constraint_violation_totals.as_ref().map_or(0.0, |c| c[i]);
        let feasible: Vec<usize> = (0..n).filter(|&i| cv(i) <= 0.0).collect();
        if feasible.len() > num_survive {
            let sub = population.selected(&feasible);
            let r = scaled_reference(&sub.fitness, (self.reference)().as_deref());
            return IbeaHyperVolumeSurvivalOperator::new(r, self.kappa).operate(sub, num_survive, rng);
        }
        let mut rest: Vec<usize> = (0..n).filter(|&i| cv(i) > 0.0).collect();
        rest.sort_by(|&a, &b| cv(a).total_cmp(&cv(b)).then(a.cmp(&b)));
        let keep: Vec<usize> = feasible.into_iter().chain(rest).take(num_survive).collect();
        let score: Array1<f64> = keep.iter().map(|&i| -cv(i)).collect();
        let mut out = population.selected(&keep);
        out.set_survival_score(score);
        out
    }
}

/// `reference` scaled as `moors`' IBEA scales `fitness` (each objective from its least to its
/// greatest value onto [0, 1], a span under 1e-12 taken as 1); None: 1.1 in each.
fn scaled_reference(fitness: &Array2<f64>, reference: Option<&[f64]>) -> Array1<f64> {
    let lo = fitness.fold_axis(Axis(0), f64::INFINITY, |a, &b| a.min(b));
    let hi = fitness.fold_axis(Axis(0), f64::NEG_INFINITY, |a, &b| a.max(b));
    (0..fitness.ncols())
        .map(|k| {
            let span = if (hi[k] - lo[k]).abs() < 1e-12 { 1.0 } else { hi[k] - lo[k] };
            reference.and_then(|r| r.get(k)).map_or(1.1, |r| (r - lo[k]) / span)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use moors::MOORandomGenerator;

    #[test]
    fn a_latin_start_puts_one_individual_in_each_stratum_of_each_gene() {
        let mut rng = MOORandomGenerator::new_from_seed(Some(3));
        let g = Start::Latin.operate(40, 3, &mut rng);
        for k in 0..3 {
            let mut strata: Vec<usize> = g.column(k).iter().map(|&x| (x * 40.0) as usize).collect();
            strata.sort_unstable();
            assert_eq!(strata, (0..40).collect::<Vec<_>>(), "gene {k}");
        }
        let u = Start::Uniform.operate(40, 3, &mut rng);
        assert_eq!(u.dim(), (40, 3));
        assert!(u.iter().all(|x| (0.0..1.0).contains(x)));
    }

    #[test]
    fn a_first_population_given_comes_first_and_the_rest_is_drawn() {
        let draw = |s: &Sampler| s.operate(6, 2, &mut MOORandomGenerator::new_from_seed(Some(5)));
        // None given: exactly the start's draw.
        let none = Sampler { rows: vec![], start: Start::Uniform };
        let plain = Start::Uniform.operate(6, 2, &mut MOORandomGenerator::new_from_seed(Some(5)));
        assert_eq!(draw(&none), plain);
        let given = Sampler { rows: vec![vec![0.25, 0.5], vec![0.75, 1.0]], start: Start::Uniform };
        let g = draw(&given);
        assert_eq!(g.row(0).to_vec(), vec![0.25, 0.5]);
        assert_eq!(g.row(1).to_vec(), vec![0.75, 1.0]);
        assert_eq!(g.row(2), plain.row(0), "the rest drawn as the start draws");
        // More given than the population: the first ones.
        let many = Sampler { rows: vec![vec![0.1, 0.1]; 9], start: Start::Uniform };
        assert_eq!(draw(&many), ndarray::Array2::from_elem((6, 2), 0.1));
    }

    #[test]
    fn a_polynomial_step_stays_inside_and_is_small_for_a_large_index() {
        for &y in &[0.0, 0.01, 0.5, 0.99, 1.0] {
            for i in 0..=100 {
                let r = f64::from(i) / 100.0;
                let z = polynomial_step(y, 20.0, r);
                assert!((0.0..=1.0).contains(&z), "y {y}, r {r}: {z}");
            }
        }
        // r = ½ is no step; r below moves down, above moves up.
        assert!((polynomial_step(0.5, 20.0, 0.5) - 0.5).abs() < 1e-12);
        assert!(polynomial_step(0.5, 20.0, 0.2) < 0.5 && polynomial_step(0.5, 20.0, 0.8) > 0.5);
        // A larger index takes a smaller step for the same draw.
        let step = |eta: f64| (polynomial_step(0.5, eta, 0.9) - 0.5).abs();
        assert!(step(50.0) < step(20.0) && step(20.0) < step(5.0));
        // Drawn at the extremes it reaches an end and no further.
        assert!(polynomial_step(0.5, 20.0, 0.0) < 1e-9);
        assert!(polynomial_step(0.5, 20.0, 1.0) > 1.0 - 1e-9);
    }

    #[test]
    fn the_reference_is_scaled_as_the_objectives_are() {
        // Objectives spanning 90–100 and −2–0: the reference (106, 0) lies at 1.6 and 1.
        let f = ndarray::array![[90.0, -2.0], [100.0, 0.0], [95.0, -1.0]];
        let r = scaled_reference(&f, Some(&[106.0, 0.0]));
        assert!((r[0] - 1.6).abs() < 1e-12 && (r[1] - 1.0).abs() < 1e-12, "{r}");
        assert_eq!(scaled_reference(&f, None), ndarray::array![1.1, 1.1]);
    }

    #[test]
    fn distinct_drops_repeats_of_the_reference_and_of_each_other() {
        let parents = ndarray::array![[0.1, 0.2], [0.3, 0.4]];
        let kids = ndarray::array![[0.1, 0.2], [0.5, 0.6], [0.5, 0.6]];
        assert_eq!(Distinct(true).remove(kids.clone(), Some(&parents)), ndarray::array![[0.5, 0.6]]);
        assert_eq!(Distinct(false).remove(kids.clone(), Some(&parents)), kids);
    }
}
