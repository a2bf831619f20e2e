//! What both solvers record along a run: cycle maxima of `x`, the largest `|z'|`, uniform history
//! samples, and for a forced run the steady-state windows ([`Windows`]). Units: seconds, metres, m/s.

use std::collections::VecDeque;

use super::{EnergyLedger, HistoryPoint, ImpactEvent, Maximum, Run, Truncation};

/// Probes of `x` per forcing period in a steady-state window (for the periodicity check).
pub(crate) const PROBES_PER_PERIOD: usize = 32;

/// The steady-state windows of a forced run (docs/model.md §6.2): consecutive stretches of `N`
/// forcing periods `L = N·T` laid back from the run's duration `D` to `t = 0` (the first may
/// start before 0, and is then incomplete) and on past `D` for a settling run. Each window keeps
/// the largest `|x|` seen in it (at the extrema of x and at the probes) and `x` at `N·S + 1` uniform
/// probe times (`S` = [`PROBES_PER_PERIOD`]), the first and last on its ends; when its last
/// probe is taken it is closed: its figures are kept ([`WindowStats`] for the last three, the
/// amplitude for all) and its probes freed.
#[derive(Debug, Clone)]
pub(crate) struct Windows {
    /// `D` (s).
    d: f64,
    /// Probe spacing `T/S` (s).
    dtp: f64,
    /// Probes per window, `N·S`.
    per: usize,
    /// Windows that end by `D`.
    k0: usize,
    /// `1/L` (1/s), for attributing a time to its window.
    inv_len: f64,
    /// The windows still open, from the next to close on: `open[i]` is window `closed() + i`.
    /// A long flight touches many windows (its extrema) before its probes close them, so a
    /// window is found by its index, not searched for.
    open: VecDeque<WindowAcc>,
    /// The amplitude of every closed window (m), by index.
    amplitudes: Vec<f32>,
    /// The figures of the last three closed windows, oldest first.
    recent: Vec<WindowStats>,
    /// Index of the next probe; probe `i` is at `D + (i − k0·N·S)·T/S`.
    next_probe: usize,
    /// The probes of the last closed window (for its pattern, [`crate::verdict::window_pattern`]).
    last_probes: Vec<f64>,
}

/// What one window has seen so far.
#[derive(Debug, Clone, Default)]
struct WindowAcc {
    max_abs_x: f64,
    /// `x` at the window's probes, from the first one at `t ≥ 0`.
    probes: Vec<f64>,
    /// Index (within the window, 0 … N·S) of `probes[0]`.
    first: usize,
}

/// The figures of one window.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct WindowStats {
    pub start_s: f64,
    pub end_s: f64,
    /// Largest `|x|` in the window (m).
    pub amplitude_m: f64,
    /// Whether `x` repeats from each forcing period to the next within 1e-3 of the amplitude.
    pub periodic: bool,
    /// Whether the whole window lies inside the run (`t ≥ 0`, reached).
    pub complete: bool,
}

impl Windows {
    /// Windows of `periods` periods of `period_s` (s) for a run of `duration_s` (s).
    pub fn new(duration_s: f64, period_s: f64, periods: usize) -> Self {
        let per = periods * PROBES_PER_PERIOD;
        let dtp = period_s / PROBES_PER_PERIOD as f64;
        let len = per as f64 * dtp;
        let k0 = ((duration_s / len) * (1.0 - 1e-12)).ceil().max(1.0) as usize;
        let mut w = Windows {
            d: duration_s,
            dtp,
            per,
            k0,
            inv_len: 1.0 / len,
            open: VecDeque::new(),
            amplitudes: Vec::new(),
            recent: Vec::new(),
            next_probe: 0,
            last_probes: Vec::new(),
        };
        while w.probe_time(w.next_probe) < 0.0 {
            w.next_probe += 1;
        }
        w
    }

    /// Time (s) of probe `i`.
    #[inline]
    fn probe_time(&self, i: usize) -> f64 {
        self.d + (i as f64 - (self.k0 * self.per) as f64) * self.dtp
    }

    /// Start and end (s) of window `k` (the start may be < 0).
    pub fn bounds(&self, k: usize) -> (f64, f64) {
        (self.probe_time(k * self.per), self.probe_time((k + 1) * self.per))
    }

    /// The open window `k`, opened if need be; None if it is closed already.
    fn window(&mut self, k: usize) -> Option<&mut WindowAcc> {
        let at = k.checked_sub(self.amplitudes.len())?;
        if self.open.len() <= at {
            self.open.resize_with(at + 1, WindowAcc::default);
        }
        self.open.get_mut(at)
    }

    /// `x` (m) at time `t` (s): counts towards the amplitude of the window holding `t`.
    #[inline]
    pub fn x_at(&mut self, t: f64, x: f64) {
        let k = ((t - self.d) * self.inv_len + self.k0 as f64).floor();
        if k >= 0.0 && t >= 0.0 {
            if let Some(w) = self.window(k as usize) {
                w.max_abs_x = w.max_abs_x.max(x.abs());
            }
        }
    }

    /// Time (s) of the next probe to take.
    #[inline]
    pub fn next_probe_time(&self) -> f64 {
        self.probe_time(self.next_probe)
    }

    /// Takes every probe due by `t1`, `x` (m) from `eval`.
    #[cold]
    fn probes_until(&mut self, t1: f64, mut eval: impl FnMut(f64) -> f64) {
        loop {
            let tp = self.next_probe_time();
            if tp > t1 {
                break;
            }
            self.probe(eval(tp));
        }
    }

    /// Takes the next probe, `x` (m) at [`Windows::next_probe_time`]. A probe on the boundary
    /// of two windows belongs to both, and closes the earlier one.
    pub fn probe(&mut self, x: f64) {
        let i = self.next_probe;
        let (k, j) = (i / self.per, i % self.per);
        let per = self.per;
        let push = |w: &mut WindowAcc, j: usize| {
            if w.probes.is_empty() {
                w.first = j;
            }
            w.probes.push(x);
            w.max_abs_x = w.max_abs_x.max(x.abs());
        };
        if let Some(w) = self.window(k) {
            push(w, j);
        }
        if j == 0 && k > 0 {
            if let Some(w) = self.window(k - 1) {
                push(w, per);
            }
            self.close(k - 1);
        }
        self.next_probe += 1;
    }

    /// Closes window `k` (the next one to close) with what it has seen.
    fn close(&mut self, k: usize) {
        debug_assert_eq!(k, self.amplitudes.len());
        let acc = self.open.pop_front().unwrap_or_default();
        let (start_s, end_s) = self.bounds(k);
        let amplitude_m = acc.max_abs_x;
        let complete = acc.first == 0 && acc.probes.len() == self.per + 1;
        let s = PROBES_PER_PERIOD;
        let drift = acc.probes.windows(s + 1).map(|p| (p[s] - p[0]).abs()).fold(0.0, f64::max);
        let periodic = acc.probes.len() > s && drift <= 1e-3 * amplitude_m;
        self.amplitudes.push(amplitude_m as f32);
        if self.recent.len() == 3 {
            self.recent.remove(0);
        }
        self.recent.push(WindowStats { start_s: start_s.max(0.0), end_s, amplitude_m, periodic, complete });
        self.last_probes = acc.probes;
    }

    /// The probes of `x` (m) of the last closed window, `T/S` apart from its start on (all of
    /// them when it is complete).
    pub fn last_probes(&self) -> &[f64] {
        &self.last_probes
    }

    /// Closes the window the run stopped in (a run cut short by a work cap or cancellation).
    pub fn close_open(&mut self) {
        self.close(self.amplitudes.len());
    }

    /// Windows closed so far.
    pub fn closed(&self) -> usize {
        self.amplitudes.len()
    }

    /// The figures of the last (up to three) closed windows, oldest first.
    pub fn recent(&self) -> &[WindowStats] {
        &self.recent
    }

    /// The amplitude (m, to single precision) of closed window `k`.
    pub fn amplitude(&self, k: usize) -> f64 {
        f64::from(self.amplitudes[k])
    }

    /// Whether closed window `k` started at or after `t = 0`.
    pub fn starts_in_run(&self, k: usize) -> bool {
        self.bounds(k).0 >= 0.0
    }
}

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
    /// The steady-state windows of a forced run.
    pub windows: Option<Windows>,
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
            windows: None,
        }
    }

    /// `x` (m) at time `t` (s) on the way (an extremum, a step end): for the steady windows.
    #[inline]
    pub fn x_at(&mut self, t: f64, x: f64) {
        if let Some(w) = &mut self.windows {
            w.x_at(t, x);
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
            steady: None,
        }
    }

    #[inline]
    pub fn zdot(&mut self, zd: f64) {
        let a = zd.abs();
        if a > self.zdot_abs_max {
            self.zdot_abs_max = a;
        }
    }

    /// The time of the next sample (history or steady-window probe) still to be taken, if any.
    #[inline]
    pub fn next_sample_time(&self) -> Option<f64> {
        match (&self.windows, self.next_hist_time()) {
            (None, h) => h,
            (Some(w), None) => Some(w.next_probe_time()),
            (Some(w), Some(h)) => Some(h.min(w.next_probe_time())),
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

    /// Emits every pending history sample (and steady-window probe) with time `≤ t1`,
    /// evaluating `(x, y)` with `eval`. Inlined down to the test of whether there is any
    /// sampling at all (a chart's run has none), as it is called at every integrator step.
    #[inline(always)]
    pub fn history_until(&mut self, t1: f64, eval: impl FnMut(f64) -> (f64, f64)) {
        if self.next_hist < self.n_hist || self.windows.is_some() {
            self.samples_until(t1, eval);
        }
    }

    /// [`Recorder::history_until`] when there are samples or probes still to take.
    fn samples_until(&mut self, t1: f64, mut eval: impl FnMut(f64) -> (f64, f64)) {
        while let Some(ts) = self.next_hist_time() {
            if ts > t1 {
                break;
            }
            let (x, y) = eval(ts);
            self.history.push(HistoryPoint { t_s: ts, x_m: x, y_m: y });
            self.next_hist += 1;
        }
        if let Some(w) = &mut self.windows {
            w.probes_until(t1, |t| eval(t).0);
        }
    }

    /// One step of a discrete integrator from `(t0, x0, v0)` to `(t1, x1, v1)` with relative
    /// velocity `zd1` at the end: maxima, crossings and `|z'|` from the step states. History is
    /// handled by the caller.
    #[inline(always)]
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
        // The largest |x| of a window is at an extremum of x inside it or at one of its ends
        // (a probe): x' is continuous through contacts, so only steps where it changes sign
        // can hold one.
        if let Some(w) = &mut self.windows {
            if (v0 > 0.0 && v1 <= 0.0) || (v0 < 0.0 && v1 >= 0.0) {
                w.extremum_in_step(t0, x0, v0, t1, x1, v1);
            }
        }
    }
}

impl Recorder {
    /// One step inside a contact of a Sundman scheme (`sundman.rs`, `dop853.rs`, `adams.rs`, the
    /// last the default), from `(t0, x0, v0)`
    /// to `(t1, x1, v1)` with relative velocity `zd1` at the end: as [`Recorder::step`], but
    /// with the extremum of `x` inside the step located on the step's interpolant
    /// (`extremum() → (t, x)`, called only where `x'` changes sign) rather than taken at an end,
    /// and the largest `|z'|` inside it (`zd_inside`, where the relative speed turns).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub fn contact_step(
        &mut self,
        (_t0, x0, v0): (f64, f64, f64),
        (t1, x1, v1): (f64, f64, f64),
        zd1: f64,
        zd_inside: Option<f64>,
        extremum: impl FnOnce() -> (f64, f64),
    ) {
        self.zdot(zd1);
        if let Some(z) = zd_inside {
            self.zdot(z);
        }
        let down = v0 > 0.0 && v1 <= 0.0;
        if down || (v0 < 0.0 && v1 >= 0.0) {
            let (te, xe) = extremum();
            if down {
                self.local_max(te, xe);
            }
            if let Some(w) = &mut self.windows {
                w.x_at(t1, x1);
                w.x_at(te, xe);
            }
        }
        if x0 <= 0.0 && x1 > 0.0 {
            self.up_cross();
        }
    }
}

impl Windows {
    /// A step of a discrete integrator (see [`Recorder::step`]) across which `x'` changes sign:
    /// `|x|` at the extremum inside it, from the cubic through both ends' `x` and `x'`.
    #[cold]
    fn extremum_in_step(&mut self, t0: f64, x0: f64, v0: f64, t1: f64, x1: f64, v1: f64) {
        self.x_at(t1, x1);
        let h = t1 - t0;
        if h > 0.0 {
            let p = cubic_extremum(x0, v0 * h, x1, v1 * h);
            self.x_at(t0 + p.0 * h, p.1);
        }
    }
}

/// The extremum of the cubic Hermite `p(u)`, `u ∈ [0, 1]`, with `p(0) = f0`, `p'(0) = d0`,
/// `p(1) = f1`, `p'(1) = d1` where `p'` changes sign: `(u, p(u))`.
pub(crate) fn cubic_extremum(f0: f64, d0: f64, f1: f64, d1: f64) -> (f64, f64) {
    // p'(u) = A·u² + B·u + d0 with A = 6(f0 − f1) + 3(d0 + d1), B = 6(f1 − f0) − 4d0 − 2d1.
    let a = 6.0 * (f0 - f1) + 3.0 * (d0 + d1);
    let b = 6.0 * (f1 - f0) - 4.0 * d0 - 2.0 * d1;
    let u = if a.abs() < 1e-12 * (b.abs() + d0.abs()) {
        if b == 0.0 {
            0.5
        } else {
            -d0 / b
        }
    } else {
        let disc = (b * b - 4.0 * a * d0).max(0.0).sqrt();
        let q = -0.5 * (b + b.signum() * disc);
        let (r1, r2) = (q / a, if q == 0.0 { f64::NAN } else { d0 / q });
        if (0.0..=1.0).contains(&r1) {
            r1
        } else if (0.0..=1.0).contains(&r2) {
            r2
        } else {
            0.5
        }
    }
    .clamp(0.0, 1.0);
    let (u2, u3) = (u * u, u * u * u);
    let p = (2.0 * u3 - 3.0 * u2 + 1.0) * f0 + (u3 - 2.0 * u2 + u) * d0 + (-2.0 * u3 + 3.0 * u2) * f1 + (u3 - u2) * d1;
    (u, p)
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cubic_extremum_finds_the_top_of_a_parabola() {
        // x(u) = 1 − (u − 0.3)²: x' = −2(u − 0.3); the cubic through the ends is the parabola.
        let (u, p) = cubic_extremum(1.0 - 0.09, 0.6, 1.0 - 0.49, -1.4);
        assert!((u - 0.3).abs() < 1e-12 && (p - 1.0).abs() < 1e-12, "{u} {p}");
    }

    #[test]
    fn windows_split_probes_close_and_judge_periodicity() {
        // D = 3 s, T = 0.5 s, N = 2: windows [0, 1], [1, 2], [2, 3], then [3, 4] …
        let mut w = Windows::new(3.0, 0.5, 2);
        assert_eq!(w.bounds(0), (0.0, 1.0));
        assert_eq!(w.bounds(2), (2.0, 3.0));
        assert_eq!(w.bounds(3), (3.0, 4.0));
        let x = |t: f64| 0.01 * (2.0 * std::f64::consts::PI * t / 0.5).sin();
        while w.next_probe_time() <= 3.0 {
            let t = w.next_probe_time();
            w.probe(x(t));
        }
        assert_eq!(w.closed(), 3, "the probe at D closes the window ending there");
        let s = w.recent()[2];
        assert!(s.complete && s.periodic && (s.amplitude_m - 0.01).abs() < 1e-6, "{s:?}");
        assert!((w.amplitude(0) - 0.01).abs() < 1e-6 && w.starts_in_run(0));
        // A window whose motion grows by 1 % a period is not periodic.
        let mut g = Windows::new(3.0, 0.5, 2);
        while g.next_probe_time() <= 3.0 {
            let t = g.next_probe_time();
            g.probe(x(t) + 1e-4 * t);
        }
        assert!(!g.recent()[2].periodic);
        // A run that is not a whole number of windows starts with an incomplete one.
        let mut short = Windows::new(2.5, 0.5, 2);
        while short.next_probe_time() <= 2.5 {
            short.probe(0.0);
        }
        let r = short.recent();
        assert_eq!(short.closed(), 3);
        assert!(!r[0].complete && !short.starts_in_run(0) && r[1].complete && r[2].complete);
    }
}
