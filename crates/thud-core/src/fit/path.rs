//! The strike's speed v0 read by fitting the damper model's path to the first part of a
//! record (docs/model.md §13.2, "v0 fitted with the damper model").
//!
//! The momentum identity ([`super::strike`]) needs no model of the ball, and pays for it with
//! the noise of a double integral. Here the ball is modelled: the design is simulated by the
//! engine with v0, the ball's start z0 in the clearance and c1 free, and the simulated record
//! is fitted to the measured one by least squares over a short window from the strike (the
//! first impacts, where the ball's path is still predictable from those three numbers), the
//! sensor's offset and drift solved in closed form at each trial. The search: a coarse grid of
//! z0 and c1 at the identity's v0, then Nelder–Mead (Nelder & Mead 1965) from the best few
//! grid points. Its standard uncertainty is the Gauss–Newton covariance `s²·(JᵀJ)⁻¹` at the
//! optimum (`s²` the window's residual variance, J the model's derivatives in v0, z0, ln c1
//! and the offset and drift).
//!
//! The simplex is written here (about 60 lines) and not taken from `argmin`: that crate would
//! bring its own dependency tree into the engine, the wheel and the fuzz build for one
//! three-parameter search whose misfit is infinite outside the clearance; it is used only on
//! velocity records (docs/model.md §13.2).

use super::{Quantity, Series};
use crate::damper::{self, RunOptions};
use crate::design::Design;

/// What the model's path gives: v0, its standard uncertainty and the fitted nuisances.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathFit {
    /// The main mass's velocity at the strike (m/s).
    pub v0_m_s: f64,
    /// Its standard uncertainty (m/s), from the curvature of the misfit.
    pub stderr_m_s: f64,
    /// The ball's fitted start in the clearance (m) and the fitted contact damping (N·s/m).
    pub z0_m: f64,
    pub c1_n_s_m: f64,
    /// The window's residual standard deviation (the record's unit) and its sample count.
    pub residual_sd: f64,
    pub samples: usize,
    /// The residual sum of squares at the optimum.
    pub rss: f64,
}

/// How the path is fitted (the defaults are what [`super::strike`] uses; the others are for
/// measuring the choice).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathOptions {
    /// The window from the strike, in periods of the structure.
    pub periods: f64,
    /// Compare an acceleration with the ball's contact force included (else the structure's
    /// own −(K·x + C·x')/M, the spikes being left out of the record).
    pub contact_force: bool,
    /// Starts of the ball over the clearance on the coarse grid.
    pub starts: usize,
    /// Every how many c1 of the fit's grid the coarse grid takes.
    pub c1_every: usize,
    /// Nelder–Mead searches (from the best coarse points) and their evaluations each.
    pub searches: usize,
    pub evals: usize,
}

impl Default for PathOptions {
    fn default() -> Self {
        Self { periods: 1.0, contact_force: false, starts: 24, c1_every: 4, searches: 3, evals: 200 }
    }
}

/// History samples a period of the structure the model is read at (linear interpolation
/// between them: errors near 1e-6 of the swing).
const HISTORY_PER_PERIOD: f64 = 4000.0;

/// The measured samples of the window and how to compare a run with them.
struct Problem<'a> {
    d: &'a Design,
    q: Quantity,
    t: Vec<f64>,
    y: Vec<f64>,
    span: f64,
    contact_force: bool,
}

impl Problem<'_> {
    /// The model's record at the samples for (v0, z0, c1); `None` where the engine fails.
    fn model(&self, v0: f64, z0: f64, c1: f64) -> Option<Vec<f64>> {
        let mut p = self.d.damper;
        p.v0_m_s = v0;
        p.ball_position_m = z0;
        p.c1_n_s_m = c1;
        p.duration_s = self.span;
        let period = 1.0 / p.natural_frequency_hz();
        let n = (self.span / period * HISTORY_PER_PERIOD).ceil() as usize + 2;
        let run = damper::simulate(&p, self.d.solver, &RunOptions { history_samples: n, cancel: None }).ok()?;
        if run.truncated.is_some() || run.history.len() < 3 {
            return None;
        }
        let ht: Vec<f64> = run.history.iter().map(|h| h.t_s).collect();
        let hx: Vec<f64> = run.history.iter().map(|h| h.x_m).collect();
        let m = ht.len();
        // x' by central differences (one-sided at the ends).
        let hv: Vec<f64> = (0..m)
            .map(|i| {
                let (a, b) = (i.saturating_sub(1), (i + 1).min(m - 1));
                (hx[b] - hx[a]) / (ht[b] - ht[a])
            })
            .collect();
        let (w2, s2) = (p.stiffness_n_m / p.main_mass_kg, p.damping_n_s_m / p.main_mass_kg);
        let hy: Vec<f64> = run.history.iter().map(|h| h.y_m).collect();
        let hw: Vec<f64> = (0..m)
            .map(|i| {
                let (a, b) = (i.saturating_sub(1), (i + 1).min(m - 1));
                (hy[b] - hy[a]) / (ht[b] - ht[a])
            })
            .collect();
        // The main mass's acceleration, the ball's contact force included (Eqs 25–26): a
        // long contact (the ball riding a wall) is smooth and not among the spikes left out.
        let ha: Vec<f64> = (0..m)
            .map(|i| {
                let z = hy[i] - hx[i];
                let delta = z.abs() - 0.5 * p.gap_m;
                let f_ball = if delta > 0.0 {
                    let sg = z.signum();
                    let mut push = p.k_hz * delta.powf(1.5) + c1 * sg * (hw[i] - hv[i]);
                    if p.no_tension {
                        push = push.max(0.0);
                    }
                    -sg * push
                } else {
                    0.0
                };
                (-p.stiffness_n_m * hx[i] - p.damping_n_s_m * hv[i] - f_ball) / p.main_mass_kg
            })
            .collect();
        let at = |ti: f64, y: &[f64]| {
            let j = ht.partition_point(|&h| h <= ti).clamp(1, m - 1);
            let u = (ti - ht[j - 1]) / (ht[j] - ht[j - 1]);
            y[j - 1] + u * (y[j] - y[j - 1])
        };
        Some(
            self.t
                .iter()
                .map(|&ti| match self.q {
                    Quantity::Displacement => at(ti, &hx),
                    Quantity::Velocity => at(ti, &hv),
                    Quantity::Acceleration if self.contact_force => at(ti, &ha),
                    // In flight M·x'' = −K·x − C·x' (the spikes are not among the samples).
                    Quantity::Acceleration => -w2 * at(ti, &hx) - s2 * at(ti, &hv),
                })
                .collect(),
        )
    }

    /// The residual sum of squares of the record against `model` with the offset and drift
    /// solved by linear least squares.
    fn rss(&self, model: &[f64]) -> f64 {
        let r: Vec<f64> = self.y.iter().zip(model).map(|(y, m)| y - m).collect();
        self.detrended(&r).iter().map(|r| r * r).sum()
    }

    /// `r` less its least-squares offset and drift.
    fn detrended(&self, r: &[f64]) -> Vec<f64> {
        let n = r.len() as f64;
        let (st, stt) = (self.t.iter().sum::<f64>(), self.t.iter().map(|t| t * t).sum::<f64>());
        let (sr, str_) = (r.iter().sum::<f64>(), self.t.iter().zip(r).map(|(t, r)| t * r).sum::<f64>());
        let det = n * stt - st * st;
        let (o, dr) =
            if det.abs() > 0.0 { ((stt * sr - st * str_) / det, (n * str_ - st * sr) / det) } else { (sr / n, 0.0) };
        self.t.iter().zip(r).map(|(t, r)| r - o - dr * t).collect()
    }
}

/// Nelder–Mead minimisation of `f` from `x0` with initial steps `step`, at most `evals`
/// evaluations (standard coefficients 1, 2, ½, ½).
fn nelder_mead<const N: usize>(
    f: &dyn Fn(&[f64; N]) -> f64,
    x0: [f64; N],
    step: [f64; N],
    evals: usize,
) -> ([f64; N], f64) {
    let mut pts: Vec<([f64; N], f64)> = Vec::with_capacity(N + 1);
    pts.push((x0, f(&x0)));
    for (i, h) in step.iter().enumerate() {
        let mut x = x0;
        x[i] += h;
        pts.push((x, f(&x)));
    }
    let mut used = N + 1;
    while used < evals {
        pts.sort_by(|a, b| a.1.total_cmp(&b.1));
        if (pts[N].1 - pts[0].1).abs() <= 1e-10 * pts[0].1.abs() {
            break;
        }
        let mut c = [0.0; N];
        for p in &pts[..N] {
            for (ci, pi) in c.iter_mut().zip(&p.0) {
                *ci += pi / N as f64;
            }
        }
        let along = |a: f64| {
            let mut x = c;
            for (xi, wi) in x.iter_mut().zip(&pts[N].0) {
                *xi += a * (wi - *xi);
            }
            x
        };
        let xr = along(-1.0);
        let fr = f(&xr);
        used += 1;
        if fr < pts[0].1 {
            let xe = along(-2.0);
            let fe = f(&xe);
            used += 1;
            pts[N] = if fe < fr { (xe, fe) } else { (xr, fr) };
        } else if fr < pts[N - 1].1 {
            pts[N] = (xr, fr);
        } else {
            let xc = if fr < pts[N].1 { along(-0.5) } else { along(0.5) };
            let fc = f(&xc);
            used += 1;
            if fc < fr.min(pts[N].1) {
                pts[N] = (xc, fc);
            } else {
                let best = pts[0].0;
                for p in pts.iter_mut().skip(1) {
                    for (pi, bi) in p.0.iter_mut().zip(&best) {
                        *pi = bi + 0.5 * (*pi - bi);
                    }
                    p.1 = f(&p.0);
                }
                used += N;
            }
        }
    }
    pts.sort_by(|a, b| a.1.total_cmp(&b.1));
    pts[0]
}

/// The window's samples of record `s` (an acceleration's without its spikes); `None` with
/// fewer than 16.
fn problem<'a>(s: &Series, d: &'a Design, o: &PathOptions) -> Option<Problem<'a>> {
    let period = 1.0 / d.damper.natural_frequency_hz();
    let span = (o.periods * period).min(s.span_s());
    let t0 = s.t_s()[0];
    let times: Vec<f64> = s.t_s().iter().map(|&ti| ti - t0).collect();
    let (t, y): (Vec<f64>, Vec<f64>) = match s.quantity() {
        Quantity::Acceleration => super::without_spikes(&times, s.values()),
        _ => (times, s.values().to_vec()),
    };
    let keep = t.partition_point(|&ti| ti <= span);
    (keep >= 16).then(|| Problem {
        d,
        q: s.quantity(),
        t: t[..keep].to_vec(),
        y: y[..keep].to_vec(),
        span,
        contact_force: o.contact_force,
    })
}

/// The misfit (residual sum of squares, offset and drift solved) of record `s` against the
/// model run with strike speed `v0` (m/s), the ball's start `z0` (m) and contact damping `c1`
/// over the window of `o`.
#[must_use]
pub fn misfit(s: &Series, d: &Design, v0: f64, z0: f64, c1: f64, o: &PathOptions) -> Option<f64> {
    let pr = problem(s, d, o)?;
    pr.model(v0, z0, c1).map(|m| pr.rss(&m))
}

/// v0 of record `s` of design `d` (struck at its first sample, the ball at rest somewhere in
/// the clearance) by the model's path over the window of `o`, starting from `v0_start` (the
/// momentum identity's) and searching c1 over `c1_grid`. `None` when the window holds too few
/// samples or the engine fails.
#[must_use]
pub fn path_speed(s: &Series, d: &Design, v0_start: f64, c1_grid: &[f64], o: &PathOptions) -> Option<PathFit> {
    let p = &d.damper;
    if !(v0_start.is_finite() && v0_start != 0.0) {
        return None;
    }
    let pr = problem(s, d, o)?;
    let half = 0.5 * p.gap_m;
    // The parameters: (v0 / v0_start, z0 / (d/2), ln c1).
    let value = |x: &[f64; 3]| -> f64 {
        if x[1].abs() >= 0.999 || x[0] <= 0.0 {
            return f64::INFINITY;
        }
        pr.model(x[0] * v0_start, x[1] * half, x[2].exp()).map_or(f64::INFINITY, |m| pr.rss(&m))
    };
    let starts = crate::ensemble::ball_positions(2.0, o.starts.max(1));
    let c1s: Vec<f64> = c1_grid.iter().step_by(o.c1_every.max(1)).map(|c| c.ln()).collect();
    let mut coarse = coarse_grid(&pr, v0_start, half, &starts, &c1s, &value);
    coarse.sort_by(|a, b| a.1.total_cmp(&b.1));
    let step_c = if c1s.len() > 1 { (c1s[1] - c1s[0]).abs() } else { 0.3 };
    let best = coarse
        .iter()
        .take(o.searches.max(1))
        .map(|&(x, _)| nelder_mead(&value, x, [0.01, 1.0 / o.starts.max(1) as f64, 0.5 * step_c], o.evals))
        .min_by(|a, b| a.1.total_cmp(&b.1))?;
    let ([r, z, lc], rss) = best;
    if !rss.is_finite() {
        return None;
    }
    let base = [r * v0_start, z * half, lc];
    let (sd, s2, n) = v0_sd(&pr, base, [1e-4 * v0_start.abs(), 1e-4 * half, 1e-3], rss)?;
    Some(PathFit {
        v0_m_s: base[0],
        stderr_m_s: sd,
        z0_m: base[1],
        c1_n_s_m: lc.exp(),
        residual_sd: s2.sqrt(),
        samples: n,
        rss,
    })
}

/// The coarse grid of [`path_speed`]: the ball's start at each of `starts` (shares of the half
/// gap `half`, m) and c1 at each of `c1s` (ln N·s/m), v0 at each by one Gauss–Newton step from
/// `v0_start` (m/s; the record is nearly linear in v0); each point in the scaled unknowns
/// (v0 / v0_start, z0 / (d/2), ln c1) with its misfit `value`.
fn coarse_grid(
    pr: &Problem,
    v0_start: f64,
    half: f64,
    starts: &[f64],
    c1s: &[f64],
    value: &dyn Fn(&[f64; 3]) -> f64,
) -> Vec<([f64; 3], f64)> {
    let mut coarse = Vec::new();
    for &z in starts {
        for &lc in c1s {
            let (Some(m0), Some(m1)) =
                (pr.model(v0_start, z * half, lc.exp()), pr.model(1.01 * v0_start, z * half, lc.exp()))
            else {
                continue;
            };
            let r: Vec<f64> = pr.y.iter().zip(&m0).map(|(y, m)| y - m).collect();
            let g: Vec<f64> = m1.iter().zip(&m0).map(|(a, b)| a - b).collect();
            let (r, g) = (pr.detrended(&r), pr.detrended(&g));
            let gg: f64 = g.iter().map(|g| g * g).sum();
            let step = if gg > 0.0 { g.iter().zip(&r).map(|(g, r)| g * r).sum::<f64>() / gg } else { 0.0 };
            let x = [1.0 + 0.01 * step.clamp(-20.0, 20.0), z, lc];
            coarse.push((x, value(&x)));
        }
    }
    coarse
}

/// v0's standard uncertainty (m/s) at the fit `base` = (v0 m/s, z0 m, ln c1) with misfit
/// `rss`, by the Gauss–Newton covariance: J of the model in the three by central differences
/// of steps `hs`, with the offset and drift as two more columns (a pseudo-inverse: c1 may not
/// act in the window); with the residual variance and the samples. None where it is not
/// finite.
fn v0_sd(pr: &Problem, base: [f64; 3], hs: [f64; 3], rss: f64) -> Option<(f64, f64, usize)> {
    let n = pr.t.len();
    let mut jac = nalgebra::DMatrix::<f64>::zeros(n, 5);
    for (k, h) in hs.iter().enumerate() {
        let mut up = base;
        let mut dn = base;
        up[k] += h;
        dn[k] -= h;
        let mu = pr.model(up[0], up[1], up[2].exp())?;
        let md = pr.model(dn[0], dn[1], dn[2].exp())?;
        for (i, (a, b)) in mu.iter().zip(&md).enumerate() {
            jac[(i, k)] = (a - b) / (2.0 * h);
        }
    }
    for (i, t) in pr.t.iter().enumerate() {
        jac[(i, 3)] = 1.0;
        jac[(i, 4)] = *t;
    }
    // Columns scaled to unit norm so the pseudo-inverse's cut is relative.
    let norms: Vec<f64> = (0..5).map(|k| jac.column(k).norm()).collect();
    for (k, &nk) in norms.iter().enumerate() {
        if nk > 0.0 {
            jac.column_mut(k).unscale_mut(nk);
        }
    }
    let s2 = rss / (n as f64 - 5.0);
    let cov = (jac.transpose() * &jac).pseudo_inverse(1e-12).ok()?;
    let sd = (s2 * cov[(0, 0)]).sqrt() / norms[0];
    (sd.is_finite() && norms[0] > 0.0).then_some((sd, s2, n))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A noise-free displacement record of the engine's own run (the default design with its
    /// c1, the ball at rest off centre) gives back its v0 from a start 3 % off, and the ball's
    /// start: the fit inverts the model it runs.
    #[test]
    fn a_noise_free_record_gives_back_its_strike_speed() {
        let d = Design::default().check().unwrap();
        let mut p = d.damper;
        let period = 1.0 / p.natural_frequency_hz();
        p.ball_position_m = 0.3 * p.gap_m;
        p.duration_s = 1.5 * period;
        let run = damper::simulate(&p, d.solver, &RunOptions { history_samples: 1500, cancel: None }).unwrap();
        assert!(!run.impacts.is_empty(), "the ball is hit in the window");
        let t: Vec<f64> = run.history.iter().map(|h| h.t_s).collect();
        let x: Vec<f64> = run.history.iter().map(|h| h.x_m).collect();
        let s = Series::new(t, x, Quantity::Displacement).unwrap();
        let mut dd = d.design().clone();
        dd.damper.c1_n_s_m = 1.0;
        let grid = crate::fit::grid(&d).unwrap();
        let f = path_speed(&s, &dd, 1.03 * p.v0_m_s, &grid, &PathOptions::default()).unwrap();
        assert!((f.v0_m_s / p.v0_m_s - 1.0).abs() < 1e-3, "{f:?}");
        assert!((f.z0_m - p.ball_position_m).abs() < 0.01 * p.gap_m, "{f:?}");
    }
}
