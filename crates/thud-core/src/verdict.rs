//! The one verdict on a forced motion (docs/model.md §6.6): what every surface of thud says of
//! a forced run or orbit — `simulate`, `response`, `bifurcation`, `impact-map`, `basins`, the
//! explorer, their tables and figures.
//!
//! A verdict is reached from three pieces of evidence about one motion ([`judge`]):
//! - whether the run was **cut** short (a work cap or cancellation): then it is
//!   [`Verdict::Truncated`], whatever else was seen;
//! - the **pattern** of its samples ([`find_period`], shared by the stroboscopic samples of an
//!   orbit and the probes of a steady-state window): periodic with `m` impacts per `n` periods,
//!   chaotic by the 0–1 test, or neither;
//! - whether its amplitude **settled** (the windows' test, docs/model.md §6.2), where that test
//!   was run: a motion with neither a period nor chaos is then [`Verdict::Settled`] (its
//!   amplitude steady, its period longer than the samples show or none), else
//!   [`Verdict::NotSettled`].
//!
//! A periodic orbit says where it was found ([`Source`]): read off a simulated run's samples,
//! or computed exactly (a periodic orbit solved for, e.g. by shooting).

use serde::{Deserialize, Serialize};

use crate::damper::Truncation;

/// The longest period (in forcing periods) a pattern is looked for over.
pub const MAX_PERIOD: usize = 16;
/// How close (relative to the samples' scale) two samples must be to count as the same point
/// of an orbit.
pub const PERIODIC_TOLERANCE: f64 = 1e-3;

/// How a periodic orbit was found.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Source {
    /// Read off a simulated run's samples (to [`PERIODIC_TOLERANCE`]).
    #[default]
    Sampled,
    /// Solved for as a fixed point of the stroboscopic map (exact to the solver's tolerance).
    Exact,
}

impl Source {
    fn is_sampled(&self) -> bool {
        *self == Source::Sampled
    }
}

/// What a forced motion is: the one verdict every surface prints ([`Verdict::label`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Verdict {
    /// Period `periods`·T with `impacts` impacts in each period; `symmetric`: x(t + T/2) = −x(t).
    Periodic {
        impacts: u32,
        periods: u32,
        symmetric: bool,
        #[serde(default, skip_serializing_if = "Source::is_sampled")]
        source: Source,
    },
    /// Neither periodic (within [`MAX_PERIOD`] periods) nor chaotic, but its amplitude has
    /// settled: a longer period or a quasi-periodic motion of steady size.
    Settled,
    /// The 0–1 test's `k` ≥ [`crate::dynamics::CHAOS_K`].
    Chaotic { k: f64 },
    /// Neither periodic nor chaotic, and its amplitude not settled (or the settling test not
    /// run): still settling, or a period longer than the samples show; `k` the 0–1 test's K
    /// when there were samples enough to run it.
    NotSettled { k: Option<f64> },
    /// A work cap (`cap`, see `thud limits`) or cancellation (`cap` absent) stopped the run
    /// before it was judged.
    Truncated {
        #[serde(default, skip_serializing_if = "Option::is_none")]
        cap: Option<Truncation>,
    },
}

impl Default for Verdict {
    /// Nothing known: not settled.
    fn default() -> Self {
        Verdict::NotSettled { k: None }
    }
}

impl Verdict {
    /// A periodic orbit read off samples.
    #[must_use]
    pub fn periodic(impacts: u32, periods: u32, symmetric: bool) -> Self {
        Verdict::Periodic { impacts, periods, symmetric, source: Source::Sampled }
    }

    /// `2/1 sym` (2 impacts per period, symmetric), `1/2` (1 impact per 2 periods), `0/1`
    /// (no impact), `settled`, `chaotic`, `not settled`, `truncated`.
    #[must_use]
    pub fn label(&self) -> String {
        match *self {
            Verdict::Periodic { impacts, periods, symmetric, .. } => {
                format!("{impacts}/{periods}{}", if symmetric { " sym" } else { "" })
            }
            Verdict::Settled => "settled".to_string(),
            Verdict::Chaotic { .. } => "chaotic".to_string(),
            Verdict::NotSettled { .. } => "not settled".to_string(),
            Verdict::Truncated { .. } => "truncated".to_string(),
        }
    }

    /// Whether a point with this verdict is marked apart in tables and figures: its figures
    /// are not a steady state's (not settled, or cut short).
    #[must_use]
    pub fn is_marked(&self) -> bool {
        matches!(self, Verdict::NotSettled { .. } | Verdict::Truncated { .. })
    }

    /// Whether the run was cut short.
    #[must_use]
    pub fn is_truncated(&self) -> bool {
        matches!(self, Verdict::Truncated { .. })
    }
}

/// The verdict on one motion from its evidence (see the module documentation): `cut` whether a
/// work cap (`Some(Some(cap))`) or cancellation (`Some(None)`) stopped the run; `pattern` what
/// its samples show ([`Verdict::Periodic`], [`Verdict::Chaotic`] or [`Verdict::NotSettled`]);
/// `settled` the amplitude's settling test where it was run.
#[must_use]
pub fn judge(cut: Option<Option<Truncation>>, pattern: Verdict, settled: Option<bool>) -> Verdict {
    if let Some(cap) = cut {
        return Verdict::Truncated { cap };
    }
    match pattern {
        Verdict::Periodic { .. } | Verdict::Chaotic { .. } | Verdict::Settled | Verdict::Truncated { .. } => pattern,
        Verdict::NotSettled { k } => {
            if settled == Some(true) {
                Verdict::Settled
            } else {
                Verdict::NotSettled { k }
            }
        }
    }
}

/// The verdict on one design's motion seen twice from the same start — by its settling run
/// (`steady`: its last window's pattern, the settling test; [`judge`]) and by the sampled orbit
/// (`orbit`: 100 or more stroboscopic samples after a transient) — as the explorer names it in
/// its readout: a run cut short is truncated; else the orbit's period or chaos where its
/// samples show one (they are more than a window's, so they see longer periods, and the 0–1
/// test); else the settling run's verdict.
#[must_use]
pub fn of_design(steady: Option<Verdict>, orbit: Option<Verdict>) -> Option<Verdict> {
    if let Some(t) = steady.into_iter().chain(orbit).find(Verdict::is_truncated) {
        return Some(t);
    }
    match orbit {
        Some(o @ (Verdict::Periodic { .. } | Verdict::Chaotic { .. })) => Some(o),
        _ => steady.or(orbit),
    }
}

/// The smallest period `p ≤ min(MAX_PERIOD, n/3)` (a period must repeat at least twice over
/// the samples) of `n` per-period samples with `same(k, k + p)` for every `k`, over which the
/// `impacts` of the `n` periods split evenly: `(m, p)` with `m` impacts per `p` periods. The
/// one rule of periodicity of both the stroboscopic samples and the window probes.
pub fn find_period(n: usize, impacts: usize, same: impl Fn(usize, usize) -> bool) -> Option<(u32, u32)> {
    let longest = MAX_PERIOD.min(n / 3);
    for p in 1..=longest {
        if (0..n - p).all(|k| same(k, k + p)) {
            let blocks = n / p;
            let m = impacts as f64 * p as f64 / n as f64;
            // The impacts must split evenly over the blocks of p periods.
            if blocks > 0 && (m - m.round()).abs() < 0.5 / blocks as f64 + 1e-9 {
                return Some((m.round() as u32, u32::try_from(p).unwrap_or(u32::MAX)));
            }
        }
    }
    None
}

/// The pattern of a steady-state window from its probes of `x` (`per` a period, the first and
/// last on the window's ends: `periods·per + 1` of them) and the impacts whose onset is in it:
/// periodic when `x` repeats over `p` periods at every probe ([`find_period`], within
/// [`PERIODIC_TOLERANCE`] of the largest `|x|`), symmetric when `x(t + T/2) = −x(t)` at every
/// probe; else [`Verdict::NotSettled`] (a window is too short for the 0–1 test).
#[must_use]
pub fn window_pattern(probes: &[f64], per: usize, impacts: usize) -> Verdict {
    let n = probes.len().saturating_sub(1).checked_div(per).unwrap_or(0);
    if n == 0 {
        return Verdict::NotSettled { k: None };
    }
    let scale = probes.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let tol = PERIODIC_TOLERANCE * scale.max(f64::MIN_POSITIVE);
    let same = |k: usize, l: usize| (0..=per).all(|j| (probes[k * per + j] - probes[l * per + j]).abs() <= tol);
    match find_period(n, impacts, same) {
        Some((m, p)) => {
            let half = per / 2;
            let symmetric = p == 1
                && per.is_multiple_of(2)
                && (0..probes.len() - half).all(|i| (probes[i] + probes[i + half]).abs() <= tol);
            Verdict::periodic(m, p, symmetric)
        }
        None => Verdict::NotSettled { k: None },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cut_run_is_truncated_whatever_it_showed() {
        let p = Verdict::periodic(2, 1, true);
        assert_eq!(judge(Some(Some(Truncation::ContactSteps)), p, Some(true)).label(), "truncated");
        assert_eq!(judge(Some(None), p, None), Verdict::Truncated { cap: None });
        assert_eq!(judge(None, p, Some(false)), p);
        assert_eq!(judge(None, Verdict::NotSettled { k: Some(0.1) }, Some(true)), Verdict::Settled);
        assert_eq!(judge(None, Verdict::NotSettled { k: None }, None).label(), "not settled");
        assert!(judge(None, Verdict::NotSettled { k: None }, Some(false)).is_marked());
        assert!(!Verdict::Settled.is_marked());
    }

    #[test]
    fn a_design_has_one_verdict_from_its_two_runs() {
        let three = Verdict::periodic(3, 1, false);
        let cut = Verdict::Truncated { cap: Some(Truncation::ContactSteps) };
        let unsettled = Verdict::NotSettled { k: Some(0.2) };
        assert_eq!(of_design(Some(Verdict::Settled), Some(three)), Some(three));
        assert_eq!(of_design(Some(Verdict::Settled), Some(unsettled)), Some(Verdict::Settled));
        assert_eq!(of_design(Some(unsettled), Some(three)), Some(three));
        assert_eq!(of_design(Some(three), Some(cut)), Some(cut));
        assert_eq!(of_design(Some(cut), Some(three)), Some(cut));
        assert_eq!(of_design(None, Some(unsettled)), Some(unsettled));
        assert_eq!(of_design(None, None), None);
    }

    #[test]
    fn window_probes_give_the_period_and_the_symmetry() {
        let per = 32;
        let tau = std::f64::consts::TAU;
        // Ten periods of a sine: 1/1 sym with ten impacts; 0/1 without.
        let sine: Vec<f64> = (0..=10 * per).map(|i| (tau * i as f64 / per as f64).sin()).collect();
        assert_eq!(window_pattern(&sine, per, 10), Verdict::periodic(1, 1, true));
        assert_eq!(window_pattern(&sine, per, 0), Verdict::periodic(0, 1, true));
        // A subharmonic added: period 2, not symmetric; 9 impacts do not split over 5 blocks.
        let sub: Vec<f64> =
            sine.iter().enumerate().map(|(i, x)| x + 0.3 * (tau * i as f64 / (2 * per) as f64).cos()).collect();
        assert_eq!(window_pattern(&sub, per, 10), Verdict::periodic(2, 2, false));
        assert_eq!(window_pattern(&sub, per, 9), Verdict::NotSettled { k: None });
        // A growing motion repeats nowhere.
        let grow: Vec<f64> = sine.iter().enumerate().map(|(i, x)| x * (1.0 + 1e-3 * i as f64)).collect();
        assert_eq!(window_pattern(&grow, per, 10), Verdict::NotSettled { k: None });
    }
}
