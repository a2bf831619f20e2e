//! A small seeded generator (SplitMix64, Steele, Lea and Flood 2014) for the engine's
//! repeatable draws: the design search's baselines and the fits' noise draws.

use std::f64::consts::PI;

/// SplitMix64 from a seed: the same seed, the same draws on every machine.
pub(crate) struct SplitMix64(pub(crate) u64);

impl SplitMix64 {
    /// The next 64 random bits.
    pub(crate) fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1): the top 53 bits.
    pub(crate) fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Standard normal (Box–Muller, the cosine branch).
    pub(crate) fn normal(&mut self) -> f64 {
        let (u, v) = (self.uniform().max(1e-300), self.uniform());
        (-2.0 * u.ln()).sqrt() * (2.0 * PI * v).cos()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The first outputs from seed 0 of the reference implementation (splitmix64.c, Vigna).
    #[test]
    fn seed_zero_gives_the_reference_sequence() {
        let mut g = SplitMix64(0);
        assert_eq!(g.next_u64(), 0xE220_A839_7B1D_CDAF);
        assert_eq!(g.next_u64(), 0x6E78_9E6A_A1B9_65F4);
        assert_eq!(g.next_u64(), 0x06C4_5D18_8009_454F);
    }

    #[test]
    fn uniform_draws_stay_in_the_unit_interval_and_spread_over_it() {
        let mut g = SplitMix64(7);
        let u: Vec<f64> = (0..10_000).map(|_| g.uniform()).collect();
        assert!(u.iter().all(|&x| (0.0..1.0).contains(&x)));
        let mean = u.iter().sum::<f64>() / u.len() as f64;
        // The mean of 10 000 uniform draws has standard deviation 1/√(12·10⁴) ≈ 0.0029.
        assert!((mean - 0.5).abs() < 0.015, "mean {mean}");
    }

    #[test]
    fn normal_draws_have_unit_spread() {
        let mut g = SplitMix64(11);
        let z: Vec<f64> = (0..20_000).map(|_| g.normal()).collect();
        let mean = z.iter().sum::<f64>() / z.len() as f64;
        let var = z.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (z.len() - 1) as f64;
        // Standard errors: mean 1/√N ≈ 0.007, variance √(2/N) ≈ 0.01.
        assert!(mean.abs() < 0.035, "mean {mean}");
        assert!((var - 1.0).abs() < 0.05, "variance {var}");
    }
}
