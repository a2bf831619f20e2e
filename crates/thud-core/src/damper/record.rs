//! What both solvers record along a run: cycle maxima of `x`, the largest `|z'|`, uniform history
//! samples. Units: seconds, metres, m/s.

use super::{EnergyLedger, HistoryPoint, ImpactEvent, Maximum, Run, Truncation};

/// Accumulates the run's outputs in time order.
pub(crate) struct Recorder {
    pub maxima: Vec<Maximum>,
    /// The best local maximum of `x` (> 0) in the current cycle (since the last upward crossing).
    best: Option<Maximum>,
    /// Largest `|z'|` seen (m/s).
    pub zdot_abs_max: f64,
    pub history: Vec<HistoryPoint>,
    n_hist: usize,
    next_hist: usize,
    duration: f64,
}

impl Recorder {
    pub fn new(history_samples: usize, duration: f64) -> Self {
        Recorder {
            maxima: Vec::new(),
            best: None,
            zdot_abs_max: 0.0,
            history: Vec::with_capacity(history_samples),
            n_hist: history_samples,
            next_hist: 0,
            duration,
        }
    }

    /// A local maximum of `x` at time `t`.
    #[inline]
    pub fn local_max(&mut self, t: f64, x: f64) {
        if x > 0.0 && self.best.is_none_or(|b| x > b.x_m) {
            self.best = Some(Maximum { t_s: t, x_m: x });
        }
    }

    /// An upward zero crossing of `x`: closes the current cycle.
    #[inline]
    pub fn up_cross(&mut self) {
        if let Some(b) = self.best.take() {
            self.maxima.push(b);
        }
    }

    /// Closes the last (partial) cycle if it holds an interior maximum, and assembles the run:
    /// what this recorder saw plus the solver's impacts, energy ledger, end time and how it
    /// ended (cancelled, or truncated at a work cap).
    pub fn into_run(
        mut self,
        impacts: Vec<ImpactEvent>,
        energy: EnergyLedger,
        final_time_s: f64,
        cancelled: bool,
        truncated: Option<Truncation>,
    ) -> Run {
        self.up_cross();
        Run {
            impacts,
            maxima: self.maxima,
            zdot_abs_max_m_s: self.zdot_abs_max,
            energy,
            history: self.history,
            final_time_s,
            cancelled,
            truncated,
        }
    }

    #[inline]
    pub fn zdot(&mut self, zd: f64) {
        let a = zd.abs();
        if a > self.zdot_abs_max {
            self.zdot_abs_max = a;
        }
    }

    /// The time of the next history sample still to be emitted, if any.
    #[inline]
    pub fn next_hist_time(&self) -> Option<f64> {
        if self.next_hist >= self.n_hist {
            return None;
        }
        if self.n_hist == 1 {
            return Some(0.0);
        }
        let last = self.n_hist - 1;
        Some(if self.next_hist == last { self.duration } else { self.next_hist as f64 * self.duration / last as f64 })
    }

    /// Emits every pending history sample with time `≤ t1`, evaluating `(x, y)` with `eval`.
    #[inline]
    pub fn history_until(&mut self, t1: f64, mut eval: impl FnMut(f64) -> (f64, f64)) {
        while let Some(ts) = self.next_hist_time() {
            if ts > t1 {
                break;
            }
            let (x, y) = eval(ts);
            self.history.push(HistoryPoint { t_s: ts, x_m: x, y_m: y });
            self.next_hist += 1;
        }
    }

    /// One step of a discrete integrator from `(t0, x0, v0)` to `(t1, x1, v1)` with relative
    /// velocity `zd1` at the end: maxima, crossings and `|z'|` from the step states. History is
    /// handled by the caller.
    #[inline]
    #[allow(clippy::too_many_arguments)]
    pub fn step(&mut self, t0: f64, x0: f64, v0: f64, t1: f64, x1: f64, v1: f64, zd1: f64) {
        self.zdot(zd1);
        if v0 > 0.0 && v1 <= 0.0 {
            if x1 >= x0 {
                self.local_max(t1, x1);
            } else {
                self.local_max(t0, x0);
            }
        }
        if x0 <= 0.0 && x1 > 0.0 {
            self.up_cross();
        }
    }
}

/// Cubic Hermite interpolation of `f` between `(0, f0, d0)` and `(h, f1, d1)` at `s ∈ [0, h]`.
#[inline]
pub(crate) fn hermite(f0: f64, d0: f64, f1: f64, d1: f64, h: f64, s: f64) -> f64 {
    if h <= 0.0 {
        return f1;
    }
    let u = s / h;
    let u2 = u * u;
    let u3 = u2 * u;
    (2.0 * u3 - 3.0 * u2 + 1.0) * f0 + (u3 - 2.0 * u2 + u) * h * d0 + (-2.0 * u3 + 3.0 * u2) * f1 + (u3 - u2) * h * d1
}
