// Over 800 lines: one shooting method (the section's map, Newton, multipliers, report) and its searches.
//! Periodic orbits of a forced design found, not waited for (docs/model.md §6.7): shooting on
//! the stroboscopic map with Floquet multipliers.
//!
//! Let `P` map the state `s = (x, x', y, y')` at the force's phase `φ` to the state one forcing
//! period `T` later (the event solver's ordinary forced run, [`crate::damper`]). A periodic
//! orbit of period `n·T` is a root of `Pⁿ(s) − s = 0`, found here by Newton's method with a
//! backtracking line search (damped Newton) from a guess, whether the orbit is stable or not.
//! The Jacobian `DPⁿ` is taken by forward differences of step [`JACOBIAN_STEP`] (in units of
//! the state's scale: the half gap plus the linear amplitude for positions, that times `Ω` for
//! speeds); the truncation error of the step and the map's round-off (about 1e-13 of the scale)
//! make the Jacobian good to about 1e-6 relative, which Newton's convergence and the
//! multipliers' precision both need no better than. The Newton step is the least-squares
//! solution of `(DPⁿ − I)·δ = −r` by SVD, so that a singular system (a ball that never
//! touches a wall floats anywhere: a line of fixed points) still gives the shortest step.
//!
//! The eigenvalues of `DPⁿ` at the orbit are its **Floquet multipliers** (the monodromy of the
//! stroboscopic map): stable when every `|λ| < 1`; the multiplier of largest modulus says how
//! the orbit loses (or lost) stability: at +1 (a fold), at −1 (a period doubling), or as a
//! complex pair (Neimark–Sacker). A **symmetric** orbit (`x(t + T/2) = −x(t)`, Masri &
//! Caughey's) is found as a fixed point of the half-period map followed by the reflection
//! `s → −s`; its full-period multipliers are the squares of that map's.
//!
//! The section phase `φ` is put where the orbit is in flight (the middle of the longest stretch
//! of the force's cycle with no contact), so that a small change of the state changes the map
//! smoothly; the orbit is then reported from the force's phase 0.
//!
//! Why not a crate's solver: the map is expensive (every evaluation is `n` forcing periods of
//! simulation), and the solvers at hand (levenberg-marquardt, used by `fit`) re-evaluate the
//! Jacobian at every accepted step and hide their evaluation count; a damped Newton on a 4×4
//! system, with the last Jacobian kept for the multipliers, is a few lines and needs about
//! half the evaluations.

use std::sync::atomic::{AtomicBool, Ordering};

use nalgebra::{Matrix4, Vector4};
use serde::{Deserialize, Serialize};

use crate::damper::{self, linear_amplitude_m, DamperParams, Flowed, Wall};
use crate::design::ValidDesign;
use crate::error::ThudError;

/// The forward-difference step of the Jacobian, in units of the state's scale.
pub const JACOBIAN_STEP: f64 = 1e-7;
/// The residual `|Pⁿ(s) − s|` (largest component, in units of the state's scale) at which
/// Newton's method stops.
pub const RESIDUAL_TOLERANCE: f64 = 1e-11;
/// The longest period (in forcing periods) looked for.
pub const MAX_ORBIT_PERIODS: u32 = 16;
/// Forcing periods simulated from the design's start before the first shooting attempt.
pub const FIRST_TRANSIENT_PERIODS: u32 = 8;
/// The most forcing periods simulated from the design's start while looking for an orbit.
pub const MAX_TRANSIENT_PERIODS: u32 = 1024;
/// Newton iterations allowed per attempt.
const MAX_NEWTON: u32 = 30;
/// Newton iterations allowed to a speculative attempt (before the motion is seen to repeat).
const SPECULATIVE_NEWTON: u32 = 8;
/// Forcing periods simulated to see the motion approach a speculative orbit.
const APPROACH_PERIODS: u32 = 4;

/// What to look for.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Request {
    /// The orbit's period in forcing periods `n`; `None`: the smallest that the design's
    /// motion repeats with.
    pub periods: Option<u32>,
    /// Look for a symmetric orbit, `x(t + T/2) = −x(t)` (period one forcing period).
    pub symmetric: bool,
    /// Start Newton's method here instead of from the design's own motion.
    pub guess: Option<Guess>,
}

/// A state at the force's phase 0: where an orbit is guessed to pass, or passes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Guess {
    /// Main-mass displacement x (m).
    pub x_m: f64,
    /// Main-mass velocity x' (m/s).
    pub v_m_s: f64,
    /// The ball relative to the enclosure's centre, z = y − x (m).
    pub z_m: f64,
    /// z' (m/s).
    pub zdot_m_s: f64,
}

/// How an orbit loses (or lost) stability: where its multiplier of largest modulus crosses, or
/// would cross, the unit circle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Loss {
    /// A real multiplier at +1: a fold (saddle-node), or a symmetry-breaking pitchfork.
    Fold,
    /// A real multiplier at −1: a period doubling.
    PeriodDoubling,
    /// A complex pair: a Neimark–Sacker (torus) bifurcation.
    NeimarkSacker,
}

impl Loss {
    /// `+1 (fold)`, `−1 (period doubling)`, `complex pair (Neimark–Sacker)`.
    #[must_use]
    pub fn describe(self) -> &'static str {
        match self {
            Loss::Fold => "+1 (fold)",
            Loss::PeriodDoubling => "-1 (period doubling)",
            Loss::NeimarkSacker => "complex pair (Neimark-Sacker)",
        }
    }
}

/// One Floquet multiplier.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Multiplier {
    pub re: f64,
    pub im: f64,
    /// |λ|.
    pub abs: f64,
}

/// One impact of an orbit, counted from the force's phase 0.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct OrbitImpact {
    /// The forcing period of the orbit it falls in (0 … n − 1).
    pub period: u32,
    /// The force's phase at onset, as a fraction of the period (0 to 1).
    pub phase: f64,
    /// The wall struck (−1 or 1).
    pub wall: Wall,
    /// Relative normal speed at onset (m/s).
    pub u_in_m_s: f64,
    /// Relative normal speed at exit (m/s).
    pub u_out_m_s: f64,
}

/// A periodic orbit found by shooting.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PeriodicOrbit {
    /// Its period in forcing periods, n.
    pub periods: u32,
    /// Impacts over the n periods, m (the orbit is "m/n").
    pub impacts_per_orbit: u32,
    /// Whether `x(t + T/2) = −x(t)` (to 1e-6 of the scale).
    pub symmetric: bool,
    /// The state at the force's phase 0: main mass (m, m/s) and the ball relative to the
    /// enclosure's centre (m, m/s).
    pub x_m: f64,
    pub v_m_s: f64,
    pub z_m: f64,
    pub zdot_m_s: f64,
    /// The main mass at the force's phase 0 at each of the orbit's periods in turn, x(kT) for
    /// k = 0 … periods − 1 (m): the stroboscopic samples a bifurcation diagram draws. Not
    /// written to files (x_m is the first).
    #[serde(skip)]
    pub strobe_m: Vec<f64>,
    /// Largest |x| over the orbit (m).
    pub amplitude_m: f64,
    /// The same main mass without the ball, in its steady state (m); None where unbounded.
    pub amplitude_linear_m: Option<f64>,
    pub impacts: Vec<OrbitImpact>,
    /// The Floquet multipliers, largest modulus first. An orbit without impacts lists the
    /// structure's two: the ball floats, a neutral pair at +1 that is not listed.
    pub multipliers: Vec<Multiplier>,
    /// Every |λ| < 1.
    pub stable: bool,
    /// How the largest multiplier crosses the unit circle (an unstable orbit: how it lost
    /// stability; a stable one: how it would lose it).
    pub critical: Loss,
    /// `|Pⁿ(s) − s|` at the orbit, the largest component (m or m/s).
    pub residual: f64,
    /// Newton iterations taken.
    pub iterations: u32,
    /// Forcing periods simulated to find it and its multipliers.
    pub periods_simulated: f64,
    /// The force's phase (rad) at the orbit's section, in a flight, and the state there
    /// `(x, x', y, y')` (m, m/s): where a run of the orbit starts clear of any contact (the
    /// state at phase 0 may lie inside one). Not written to files.
    #[serde(skip)]
    pub(crate) section: Option<(f64, [f64; 4])>,
}

impl PeriodicOrbit {
    /// `3/1`, `2/1 sym`, `4/2` (impacts per periods).
    #[must_use]
    pub fn label(&self) -> String {
        format!("{}/{}{}", self.impacts_per_orbit, self.periods, if self.symmetric { " sym" } else { "" })
    }
}

/// The stroboscopic map at one section, in scaled coordinates `u = (x/L, x'/V, y/L, y'/V)`.
#[derive(Debug, Clone)]
pub(crate) struct Section<'a> {
    pub p: DamperParams,
    /// The force's phase at the section (rad).
    pub phase: f64,
    pub periods: u32,
    pub symmetric: bool,
    /// Scales: length L (m), speed V = L·Ω (m/s).
    pub l: f64,
    pub v: f64,
    cancel: Option<&'a AtomicBool>,
    /// Forcing periods simulated so far.
    pub spent: f64,
    /// The last point mapped (scaled) and the contacts of its flow: the Jacobian there is
    /// chained from them.
    last: Option<(Vector4<f64>, Vec<damper::ImpactEvent>)>,
    /// Newton iterations allowed.
    pub max_newton: u32,
}

impl<'a> Section<'a> {
    pub fn new(p: DamperParams, phase: f64, periods: u32, symmetric: bool, cancel: Option<&'a AtomicBool>) -> Self {
        let (l, v) = scales(&p);
        Section { p, phase, periods, symmetric, l, v, cancel, spent: 0.0, last: None, max_newton: MAX_NEWTON }
    }

    pub fn scale(&self, s: [f64; 4]) -> Vector4<f64> {
        Vector4::new(s[0] / self.l, s[1] / self.v, s[2] / self.l, s[3] / self.v)
    }

    pub fn unscale(&self, u: &Vector4<f64>) -> [f64; 4] {
        [u[0] * self.l, u[1] * self.v, u[2] * self.l, u[3] * self.v]
    }

    /// The time (s) the map spans: n periods, or half of one for the symmetric map.
    fn span(&self) -> f64 {
        let t = 1.0 / self.p.freq_hz;
        if self.symmetric {
            0.5 * t
        } else {
            f64::from(self.periods) * t
        }
    }

    /// The map (scaled): `Pⁿ(u)`, or `−P_{T/2}(u)` for the symmetric orbit.
    pub fn map(&mut self, u: &Vector4<f64>) -> Result<Vector4<f64>, ThudError> {
        let span = self.span();
        let f = damper::flow(&self.p, self.unscale(u), self.phase, &[span], self.cancel);
        self.spent += span * self.p.freq_hz;
        if self.cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
            return Err(ThudError::Cancelled);
        }
        let end = f.states.last().copied().filter(|_| !f.halted).ok_or_else(|| {
            ThudError::invalid("orbit", "a solver work cap stopped the shooting run; the orbit was not found")
        })?;
        if f.in_contact {
            return Err(not_found(IN_CONTACT));
        }
        let sign = if self.symmetric { -1.0 } else { 1.0 };
        let e = self.scale(end);
        self.last = Some((*u, f.impacts));
        Ok(e * sign)
    }

    /// `DPⁿ` at `u` (scaled), given `Pⁿ(u)`: chained from the flights' exact factors and the
    /// contacts' differenced ones ([`damper::chained_jacobian`]), or by forward differences of
    /// the whole map where a perturbed contact leaves its window.
    pub fn jacobian(&mut self, u: &Vector4<f64>, pu: &Vector4<f64>) -> Result<Matrix4<f64>, ThudError> {
        if self.last.as_ref().is_none_or(|(at, _)| at != u) {
            self.map(u)?;
        }
        let impacts = self.last.as_ref().map_or(&[][..], |(_, i)| i.as_slice());
        let h = JACOBIAN_STEP;
        let steps = [h * self.l, h * self.v, h * self.l, h * self.v];
        let chained =
            damper::chained_jacobian(&self.p, self.unscale(u), self.phase, self.span(), impacts, steps, self.cancel);
        if let Some((j, simulated)) = chained {
            self.spent += simulated * self.p.freq_hz;
            let d = Vector4::new(self.l, self.v, self.l, self.v);
            let sign = if self.symmetric { -1.0 } else { 1.0 };
            return Ok(Matrix4::from_fn(|r, c| sign * j[(r, c)] * d[c] / d[r]));
        }
        self.full_jacobian(u, pu)
    }

    /// `DPⁿ` at `u` (scaled) by forward differences of the whole map, given `Pⁿ(u)`.
    fn full_jacobian(&mut self, u: &Vector4<f64>, pu: &Vector4<f64>) -> Result<Matrix4<f64>, ThudError> {
        let mut j = Matrix4::zeros();
        for k in 0..4 {
            let mut du = *u;
            du[k] += JACOBIAN_STEP;
            let col = (self.map(&du)? - pu) / JACOBIAN_STEP;
            j.set_column(k, &col);
        }
        Ok(j)
    }
}

/// The state's scales: L (m) the half gap plus the linear steady amplitude (or the half gap
/// alone where that is unbounded), V = L·Ω (m/s).
fn scales(p: &DamperParams) -> (f64, f64) {
    let l = 0.5 * p.gap_m + linear_amplitude_m(p).unwrap_or(0.0);
    (l, l * std::f64::consts::TAU * p.freq_hz)
}

/// A root of the map found by Newton's method.
#[derive(Debug, Clone)]
pub(crate) struct Root {
    pub u: Vector4<f64>,
    /// The Jacobian of the map, taken at the last iterate that was within 1e-6 of the root.
    pub jac: Matrix4<f64>,
    /// Largest component of the scaled residual.
    pub residual: f64,
    pub iterations: u32,
}

/// Damped Newton on `map(u) − u = 0` from `u0`. Fails when the residual does not fall below
/// [`RESIDUAL_TOLERANCE`] within the section's `max_newton` iterations.
pub(crate) fn newton(sec: &mut Section, u0: Vector4<f64>) -> Result<Root, ThudError> {
    let mut u = u0;
    let mut pu = sec.map(&u)?;
    let mut r = pu - u;
    let mut jac_at: Option<(Matrix4<f64>, f64)> = None;
    for it in 0..=sec.max_newton {
        let rn = r.amax();
        if !rn.is_finite() {
            break;
        }
        let fresh = jac_at.is_some_and(|(_, at)| at <= 1e-6);
        if rn <= RESIDUAL_TOLERANCE && fresh {
            let (jac, _) = jac_at.unwrap_or((Matrix4::zeros(), 0.0));
            return Ok(Root { u, jac, residual: rn, iterations: it });
        }
        let j = sec.jacobian(&u, &pu)?;
        jac_at = Some((j, rn));
        if rn <= RESIDUAL_TOLERANCE {
            return Ok(Root { u, jac: j, residual: rn, iterations: it });
        }
        let a = j - Matrix4::identity();
        let step = a.svd(true, true).solve(&(-r), 1e-12).map_err(|e| ThudError::invalid("orbit", e.to_string()))?;
        // Backtracking: halve the step until the residual falls (Armijo on |r|).
        let mut alpha = 1.0;
        loop {
            let un = u + step * alpha;
            let pn = sec.map(&un)?;
            let rnew = pn - un;
            if rnew.amax() <= (1.0 - 0.25 * alpha) * rn || (alpha < 1e-3 && rnew.amax() < rn) {
                u = un;
                pu = pn;
                r = rnew;
                break;
            }
            alpha *= 0.5;
            if alpha < 1e-4 {
                return Err(not_found("Newton's method stalled"));
            }
        }
    }
    Err(not_found("Newton's method did not converge"))
}

/// Why a map evaluation failed when its end fell inside a contact (the section must lie in
/// flight).
pub(crate) const IN_CONTACT: &str = "the section fell inside a contact";

pub(crate) fn not_found(why: &str) -> ThudError {
    ThudError::invalid("orbit", format!("no periodic orbit found: {why}"))
}

/// The multipliers of a map's Jacobian, largest modulus first.
pub(crate) fn multipliers(j: &Matrix4<f64>) -> Vec<Multiplier> {
    let mut m: Vec<Multiplier> =
        j.complex_eigenvalues().iter().map(|c| Multiplier { re: c.re, im: c.im, abs: c.norm() }).collect();
    m.sort_by(|a, b| b.abs.total_cmp(&a.abs).then(b.im.total_cmp(&a.im)));
    m
}

/// How the multiplier of largest modulus `m` crosses the unit circle.
pub(crate) fn loss(m: &Multiplier) -> Loss {
    if m.im.abs() > 1e-9 * m.abs.max(f64::MIN_POSITIVE) {
        Loss::NeimarkSacker
    } else if m.re >= 0.0 {
        Loss::Fold
    } else {
        Loss::PeriodDoubling
    }
}

/// The middle (rad, in [0, 2π)) of the longest stretch of the force's cycle in which no contact
/// of `impacts` lies; `phase0` is the force's phase at time 0 of their run. 0 without impacts.
pub(crate) fn flight_phase(impacts: &[damper::ImpactEvent], phase0: f64, omega: f64) -> f64 {
    let tau = std::f64::consts::TAU;
    if impacts.is_empty() {
        return 0.0;
    }
    let mut spans: Vec<(f64, f64)> = impacts
        .iter()
        .map(|i| {
            let a = (phase0 + omega * i.t_s).rem_euclid(tau);
            let len = (omega * (i.t_end_s - i.t_s)).clamp(0.0, tau);
            (a, a + len)
        })
        .collect();
    spans.sort_by(|a, b| a.0.total_cmp(&b.0));
    // The gaps between consecutive contacts around the circle.
    let mut best = (0.0, 0.0);
    let mut reach = spans[0].1;
    for w in 1..=spans.len() {
        let (next_start, next_end) = if w == spans.len() { (spans[0].0 + tau, spans[0].1 + tau) } else { spans[w] };
        let gap = next_start - reach;
        if gap > best.1 {
            best = (reach + 0.5 * gap, gap);
        }
        reach = reach.max(next_end);
    }
    best.0.rem_euclid(tau)
}

/// The smallest `n ≤ MAX_ORBIT_PERIODS` with the last two samples each within `tol` (scaled) of
/// the one `n` periods before.
fn detect_period(samples: &[Vector4<f64>], tol: f64) -> Option<u32> {
    let k = samples.len();
    (1..=MAX_ORBIT_PERIODS as usize)
        .find(|&n| k >= n + 2 && (0..2).all(|j| (samples[k - 1 - j] - samples[k - 1 - j - n]).amax() <= tol))
        .map(|n| n as u32)
}

/// Finds a periodic orbit of the forced design `d` ([`Request`]): from the design's own start
/// (its motion simulated [`FIRST_TRANSIENT_PERIODS`] periods, then twice as long each time
/// until Newton's method converges, at most [`MAX_TRANSIENT_PERIODS`]), or from `guess`.
/// From the design's start, an unstable orbit of period n is passed over for a stable one of
/// period 2n where Newton's method finds one (the attractor the motion settles to).
pub fn find(d: &ValidDesign, req: &Request, cancel: Option<&AtomicBool>) -> Result<PeriodicOrbit, ThudError> {
    if d.solver != damper::Solver::Event {
        return Err(ThudError::invalid(
            "solver",
            "newmark: orbits are found with the event solver; use --solver event",
        ));
    }
    find_damper(&d.damper, req, cancel)
}

/// [`find`] for the damper's parameters alone (checked by [`DamperParams::validate`]).
pub fn find_damper(p: &DamperParams, req: &Request, cancel: Option<&AtomicBool>) -> Result<PeriodicOrbit, ThudError> {
    p.validate()?;
    let p = *p;
    if !p.forced() {
        return Err(ThudError::invalid(
            "force",
            "0 N: a periodic orbit needs a harmonic force; give a force and a frequency",
        ));
    }
    if let Some(n) = req.periods {
        if n == 0 || n > MAX_ORBIT_PERIODS {
            return Err(ThudError::invalid("period", format!("{n}; must be 1 to {MAX_ORBIT_PERIODS} forcing periods")));
        }
        if req.symmetric && n != 1 {
            return Err(ThudError::invalid("period", format!("{n}; a symmetric orbit has period 1")));
        }
    }
    match req.guess {
        Some(g) => from_guess(&p, req, g, cancel),
        None => from_start(&p, req, cancel),
    }
}

/// How many of the design's scales (L, V) a guess may lie from rest.
const GUESS_SCALES: f64 = 1e3;

/// The state (x, x', y, y') of a guess.
fn absolute(g: &Guess) -> [f64; 4] {
    [g.x_m, g.v_m_s, g.x_m + g.z_m, g.v_m_s + g.zdot_m_s]
}

fn from_guess(
    p: &DamperParams,
    req: &Request,
    g: Guess,
    cancel: Option<&AtomicBool>,
) -> Result<PeriodicOrbit, ThudError> {
    let s = absolute(&g);
    if !s.iter().all(|v| v.is_finite()) || g.z_m.abs() >= 0.5 * p.gap_m {
        return Err(ThudError::invalid(
            "guess",
            "the ball must start inside the clearance, |z| < d/2, with finite numbers",
        ));
    }
    // A guess far beyond any orbit of the design (its scale L, the half gap plus the linear
    // steady amplitude, and V = L·2πf) is no guess at an orbit: its run overflows.
    let (l, v) = scales(p);
    let far = g.x_m.abs() > GUESS_SCALES * l || g.v_m_s.abs() > GUESS_SCALES * v || g.zdot_m_s.abs() > GUESS_SCALES * v;
    if far {
        return Err(ThudError::invalid(
            "guess",
            format!(
                "|x| at most {} m and speeds at most {} m/s: {GUESS_SCALES} times the orbit's scale (the half gap plus the linear steady amplitude, and that times 2πf)",
                crate::units::short(GUESS_SCALES * l),
                crate::units::short(GUESS_SCALES * v)
            ),
        ));
    }
    let n = if req.symmetric { 1 } else { req.periods.unwrap_or(1) };
    // One orbit's worth of motion from the guess tells where the contacts fall.
    let t = f64::from(n) / p.freq_hz;
    let probe = damper::flow(p, s, 0.0, &[t], cancel);
    let phase = flight_phase(&probe.impacts, 0.0, std::f64::consts::TAU * p.freq_hz);
    let at_section = if phase > 0.0 {
        damper::flow(p, s, 0.0, &[phase / (std::f64::consts::TAU * p.freq_hz)], cancel).states.first().copied()
    } else {
        Some(s)
    };
    let s0 = at_section.ok_or_else(|| not_found("the guess's run stopped"))?;
    shoot(p, req.symmetric, n, phase, s0, (f64::from(n) + phase / std::f64::consts::TAU, MAX_NEWTON), cancel)
}

/// Newton's method for period `n` at the section `phase` (rad) from `s0`, `spent` forcing
/// periods simulated already, at most `budget` Newton steps; an orbit whose true period is a divisor of `n` is solved again
/// with that period, so that its multipliers are its own.
fn shoot(
    p: &DamperParams,
    symmetric: bool,
    n: u32,
    phase: f64,
    s0: [f64; 4],
    (spent, budget): (f64, u32),
    cancel: Option<&AtomicBool>,
) -> Result<PeriodicOrbit, ThudError> {
    let mut sec = Section::new(*p, phase, n, symmetric, cancel);
    sec.spent = spent;
    sec.max_newton = budget;
    let u0 = sec.scale(s0);
    let root = newton(&mut sec, u0)?;
    let orbit = report(&mut sec, &root)?;
    if orbit.periods == n || symmetric {
        return Ok(orbit);
    }
    let at = sec.unscale(&root.u);
    let mut again = Section::new(*p, phase, orbit.periods, false, cancel);
    again.spent = sec.spent;
    let u0 = again.scale(at);
    let root = newton(&mut again, u0)?;
    report(&mut again, &root)
}

fn from_start(p: &DamperParams, req: &Request, cancel: Option<&AtomicBool>) -> Result<PeriodicOrbit, ThudError> {
    if !req.symmetric {
        return attractor(p, req.periods, cancel);
    }
    // The symmetric orbit nearest the motion: from the attractor's state, or from the
    // design's run itself where no attractor is found.
    match attractor(p, None, cancel) {
        Ok(near) => {
            let g = Guess { x_m: near.x_m, v_m_s: near.v_m_s, z_m: near.z_m, zdot_m_s: near.zdot_m_s };
            let mut o = from_guess(p, req, g, cancel)?;
            o.periods_simulated += near.periods_simulated;
            Ok(o)
        }
        Err(ThudError::Cancelled) => Err(ThudError::Cancelled),
        Err(_) => attractor(p, Some(1), cancel).and_then(|near| {
            let g = Guess { x_m: near.x_m, v_m_s: near.v_m_s, z_m: near.z_m, zdot_m_s: near.zdot_m_s };
            from_guess(p, req, g, cancel)
        }),
    }
}

/// The periodic orbit the design's motion settles to: its run simulated
/// [`FIRST_TRANSIENT_PERIODS`] forcing periods, then twice as long each time (at most
/// [`MAX_TRANSIENT_PERIODS`] in all), with a shooting attempt at each stop for the period the
/// motion seems to repeat with (`periods` if given, else the smallest `n` with the last two
/// samples within 5 % of the scale of those `n` periods before, else 1). Without `periods`
/// a stable orbit is taken; an unstable one of period `n` is passed over for a stable one of
/// period `2n` where there is one, else kept as the answer if nothing stable turns up.
fn attractor(p: &DamperParams, periods: Option<u32>, cancel: Option<&AtomicBool>) -> Result<PeriodicOrbit, ThudError> {
    attractor_from(p, [0.0, p.v0_m_s, p.ball_position_m, p.ball_velocity_m_s], periods, usize::MAX, cancel)
}

/// Impacts a settling motion may take while its orbit is looked for (`settle_to`): a motion
/// that rattles more than this before it repeats is left to the simulation (whose own work
/// caps, `thud limits`, then apply), which judges it over its windows.
pub const SETTLE_IMPACTS_MAX: usize = 5000;

/// A stable periodic orbit found by the attractor search ([`attractor`]) from `start`: the
/// state `(x, x', y, y')` (m, m/s) with the force at phase `phase` (rad), the motion first run
/// on to the force's next phase 0. An unstable orbit (nothing stable turned up) or none is an
/// error. Where attractors coexist it is not always the one the motion from `start` reaches
/// (docs/model.md §6.7): the seeds of a family's continuation, not a steady state to report.
pub(crate) fn settle_to(
    p: &DamperParams,
    start: [f64; 4],
    phase: f64,
    cancel: Option<&AtomicBool>,
) -> Result<PeriodicOrbit, ThudError> {
    settle_from(p, start, phase, MAX_TRANSIENT_PERIODS, cancel).0
}

/// Where an attractor search left the motion it followed: the state `(x, x', y, y')` (m, m/s)
/// at the force's phase 0, `time_s` (s) after the search's start (the motion's own time:
/// Newton's trial runs are not counted).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Reached {
    pub state: [f64; 4],
    pub time_s: f64,
}

/// [`settle_to`] over at most `periods_max` forcing periods of the motion, with where the
/// motion got to while it was looked for (None where a work cap or cancellation stopped its
/// run): a steady state that is no orbit is simulated on from there.
pub(crate) fn settle_from(
    p: &DamperParams,
    start: [f64; 4],
    phase: f64,
    periods_max: u32,
    cancel: Option<&AtomicBool>,
) -> (Result<PeriodicOrbit, ThudError>, Option<Reached>) {
    if let Err(e) = p.validate() {
        return (Err(e), None);
    }
    if !p.forced() {
        return (Err(ThudError::invalid("force", "0 N: a periodic orbit needs a harmonic force")), None);
    }
    let tau = std::f64::consts::TAU;
    let to_zero = ((tau - phase.rem_euclid(tau)) / tau).rem_euclid(1.0) / p.freq_hz;
    let (state, spent) = if to_zero > 0.0 {
        let f = damper::flow(p, start, phase, &[to_zero], cancel);
        match f.states.first().copied().filter(|_| !f.halted) {
            Some(s) => (s, to_zero * p.freq_hz),
            None => return (Err(not_found("the run stopped")), None),
        }
    } else {
        (start, 0.0)
    };
    let (found, motion) = search(p, state, (None, SETTLE_IMPACTS_MAX, periods_max), cancel);
    let reached = motion.map(|(state, periods)| Reached { state, time_s: to_zero + f64::from(periods) / p.freq_hz });
    let found = found.and_then(|o| {
        if o.stable {
            Ok(PeriodicOrbit { periods_simulated: o.periods_simulated + spent, ..o })
        } else {
            Err(not_found("the motion's orbit is unstable"))
        }
    });
    (found, reached)
}

/// [`attractor`] from the state `start` at the force's phase 0, given up (an error) once the
/// transient has taken more than `impacts_max` impacts.
fn attractor_from(
    p: &DamperParams,
    start: [f64; 4],
    periods: Option<u32>,
    impacts_max: usize,
    cancel: Option<&AtomicBool>,
) -> Result<PeriodicOrbit, ThudError> {
    search(p, start, (periods, impacts_max, MAX_TRANSIENT_PERIODS), cancel).0
}

/// Where a followed motion is: its state at the force's phase 0 and the forcing periods it took
/// to get there; None once a work cap has stopped its run.
type Followed = Option<([f64; 4], u32)>;

/// [`attractor_from`] over at most `periods_max` forcing periods of the motion, with the
/// motion's last state at the force's phase 0 and the forcing periods it took to get there
/// (None where a work cap or cancellation stopped its run).
fn search(
    p: &DamperParams,
    start: [f64; 4],
    limits: (Option<u32>, usize, u32),
    cancel: Option<&AtomicBool>,
) -> (Result<PeriodicOrbit, ThudError>, Followed) {
    let mut at = Some((start, 0));
    let found = follow(p, start, limits, cancel, &mut at);
    (found, at)
}

/// The loop of [`search`]; `at` follows the motion (its state at phase 0 and its periods), None
/// once a work cap has stopped its run.
fn follow(
    p: &DamperParams,
    start: [f64; 4],
    (periods, impacts_max, periods_max): (Option<u32>, usize, u32),
    cancel: Option<&AtomicBool>,
    at: &mut Followed,
) -> Result<PeriodicOrbit, ThudError> {
    // Over 80 lines: one loop over the transient's stops, each with its three outcomes
    // (speculate, shoot the detected period, or its double) and their bookkeeping.
    let period = 1.0 / p.freq_hz;
    let probe_sec = Section::new(*p, 0.0, 1, false, cancel);
    let mut state = start;
    let mut samples: Vec<Vector4<f64>> = vec![probe_sec.scale(state)];
    let mut spent = 0.0;
    let mut chunk = FIRST_TRANSIENT_PERIODS;
    let mut total = 0;
    let mut last_err =
        not_found("the motion did not settle to a periodic orbit (chaotic, quasi-periodic, or a longer period)");
    let mut unstable: Option<PeriodicOrbit> = None;
    let mut candidate: Option<(PeriodicOrbit, f64)> = None;
    let mut impacts_seen = 0;
    while total < periods_max {
        let stops: Vec<f64> = (1..=chunk).map(|k| f64::from(k) * period).collect();
        let f = damper::flow(p, state, 0.0, &stops, cancel);
        if cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
            return Err(ThudError::Cancelled);
        }
        if f.halted || f.states.len() != stops.len() {
            *at = None;
            return Err(not_found("a solver work cap stopped the design's run"));
        }
        spent += f64::from(chunk);
        total += chunk;
        state = *f.states.last().unwrap_or(&state);
        *at = Some((state, total));
        impacts_seen += f.impacts.len();
        if impacts_seen > impacts_max {
            return Err(not_found("the motion rattles on: more impacts than the search allows"));
        }
        samples.extend(f.states.iter().map(|s| probe_sec.scale(*s)));
        let span = f64::from(chunk) * period;
        let recent: Vec<damper::ImpactEvent> = f.impacts.into_iter().filter(|i| i.t_s >= span - 2.0 * period).collect();
        let detected = periods.or_else(|| detect_period(&samples, 0.05));
        let last_chance = total + chunk.max(8) > periods_max;
        let Some(n) = detected.or(last_chance.then_some(1)) else {
            // Nothing repeats yet: Newton's method for the simplest orbit from here, kept if
            // the motion is seen to approach it.
            if let Some((o, d)) = candidate.take() {
                // A stable orbit found before: kept once the motion has come closer to it.
                let now = distance(p, &o, state);
                if now < d {
                    return Ok(PeriodicOrbit { periods_simulated: spent, ..o });
                }
                candidate = Some((o, now));
            } else {
                match speculate(p, state, &recent, spent, cancel) {
                    Ok(Speculation::Found(o)) => return Ok(o),
                    Ok(Speculation::Moved { to, states, spent: s, stable }) => {
                        samples.extend(states.iter().map(|x| probe_sec.scale(*x)));
                        total += APPROACH_PERIODS;
                        state = to;
                        *at = Some((state, total));
                        spent = s;
                        candidate = stable.map(|o| {
                            let d = distance(p, &o, to);
                            (o, d)
                        });
                    }
                    Err(ThudError::Cancelled) => return Err(ThudError::Cancelled),
                    Err(_) => {}
                }
            }
            chunk = (total / 2).max(FIRST_TRANSIENT_PERIODS);
            continue;
        };
        match attempt(p, n, state, &recent, spent, MAX_NEWTON, cancel) {
            Ok(orbit) if orbit.stable || periods.is_some() => return Ok(orbit),
            Ok(orbit) => {
                spent = orbit.periods_simulated;
                // An unstable orbit beside a stable one of twice the period: the attractor.
                if 2 * n <= MAX_ORBIT_PERIODS {
                    match attempt(p, 2 * n, state, &recent, spent, MAX_NEWTON, cancel) {
                        Ok(o2) if o2.stable => return Ok(o2),
                        Ok(o2) => spent = o2.periods_simulated,
                        Err(ThudError::Cancelled) => return Err(ThudError::Cancelled),
                        Err(_) => {}
                    }
                }
                unstable = Some(orbit);
            }
            Err(ThudError::Cancelled) => return Err(ThudError::Cancelled),
            Err(e) => last_err = e,
        }
        chunk = (total / 2).max(FIRST_TRANSIENT_PERIODS);
    }
    unstable
        .map(|mut o| {
            o.periods_simulated = spent;
            o
        })
        .ok_or(last_err)
}

/// What a speculative attempt gave.
enum Speculation {
    /// A stable orbit the motion approaches.
    Found(PeriodicOrbit),
    /// None yet: the motion simulated on to `to` (its states at each period on the way),
    /// `spent` forcing periods in all; the stable orbit found, if any, that it did not yet
    /// approach.
    Moved { to: [f64; 4], states: Vec<[f64; 4]>, spent: f64, stable: Option<PeriodicOrbit> },
}

/// The distance (scaled, largest component) of `state` at the force's phase 0 from the
/// one-period orbit `o`'s state there.
fn distance(p: &DamperParams, o: &PeriodicOrbit, state: [f64; 4]) -> f64 {
    let sec = Section::new(*p, 0.0, 1, false, None);
    let at = sec.scale([o.x_m, o.v_m_s, o.x_m + o.z_m, o.v_m_s + o.zdot_m_s]);
    (sec.scale(state) - at).amax()
}

/// Shooting for a stable orbit of one forcing period from `state` (at the force's phase 0,
/// `spent` periods simulated so far), with a few Newton steps; the orbit is kept if the motion
/// from `state`, simulated [`APPROACH_PERIODS`] more periods, comes closer to it (it lies in the
/// orbit's basin, not another attractor's).
fn speculate(
    p: &DamperParams,
    state: [f64; 4],
    recent: &[damper::ImpactEvent],
    spent: f64,
    cancel: Option<&AtomicBool>,
) -> Result<Speculation, ThudError> {
    let period = 1.0 / p.freq_hz;
    let stops: Vec<f64> = (1..=APPROACH_PERIODS).map(|k| f64::from(k) * period).collect();
    let orbit = attempt(p, 1, state, recent, spent, SPECULATIVE_NEWTON, cancel);
    let spent = orbit.as_ref().map_or(spent, |o| o.periods_simulated) + f64::from(APPROACH_PERIODS);
    let f = damper::flow(p, state, 0.0, &stops, cancel);
    if f.halted || f.states.len() != stops.len() {
        return Err(not_found("a solver work cap stopped the design's run"));
    }
    let to = *f.states.last().unwrap_or(&state);
    let stable = orbit.ok().filter(|o| o.stable && o.periods == 1);
    if let Some(o) = &stable {
        let (d0, d1) = (distance(p, o, state), distance(p, o, to));
        if d1 < d0 || d0 <= 1e-9 {
            return Ok(Speculation::Found(PeriodicOrbit { periods_simulated: spent, ..o.clone() }));
        }
    }
    Ok(Speculation::Moved { to, states: f.states, spent, stable })
}

/// Shooting for an orbit of period `n` from `state` at the force's phase 0, the section put in
/// flight by `impacts` (times from a run that ended at `state` after whole periods), at most
/// `budget` Newton steps.
fn attempt(
    p: &DamperParams,
    n: u32,
    state: [f64; 4],
    impacts: &[damper::ImpactEvent],
    spent: f64,
    budget: u32,
    cancel: Option<&AtomicBool>,
) -> Result<PeriodicOrbit, ThudError> {
    let tau = std::f64::consts::TAU;
    let omega = tau * p.freq_hz;
    let phase = flight_phase(impacts, 0.0, omega);
    let s0 = if phase > 0.0 {
        let f = damper::flow(p, state, 0.0, &[phase / omega], cancel);
        f.states.first().copied().ok_or_else(|| not_found("the run to the section stopped"))?
    } else {
        state
    };
    shoot(p, false, n, phase, s0, (spent + phase / tau, budget), cancel)
}

/// The orbit through the root `root` of the section's map, reported from the force's phase 0.
pub(crate) fn report(sec: &mut Section, root: &Root) -> Result<PeriodicOrbit, ThudError> {
    // Over 80 lines: one run of the orbit read for every field of the report, in order.
    let p = sec.p;
    let tau = std::f64::consts::TAU;
    let period = 1.0 / p.freq_hz;
    let n = if sec.symmetric { 1 } else { sec.periods };
    let s = sec.unscale(&root.u);
    let t0 = ((tau - sec.phase) / tau).rem_euclid(1.0) * period;
    let span = f64::from(n) * period;
    // From the section (in flight) for n periods: every impact of the orbit once. Also the
    // state at phase 0, at each whole period after it, and half a period after it.
    let mut stops: Vec<f64> = vec![t0, t0 + 0.5 * period, span];
    stops.extend((1..n).map(|k| t0 + f64::from(k) * period));
    stops.sort_by(f64::total_cmp);
    stops.dedup();
    let f: Flowed = damper::flow(&p, s, sec.phase, &stops, None);
    sec.spent += stops.last().copied().unwrap_or(span) / period;
    if f.halted || f.states.len() != stops.len() {
        return Err(not_found("a solver work cap stopped the orbit's run"));
    }
    let at = |t: f64| stops.iter().position(|&x| x == t).map(|i| f.states[i]);
    let s0 = at(t0).unwrap_or(s);
    let u0 = sec.scale(s0);
    // The smallest period the orbit repeats with.
    let close = |a: [f64; 4]| (sec.scale(a) - u0).amax() <= 1e-6;
    let periods = (1..n).find(|&k| n % k == 0 && at(t0 + f64::from(k) * period).is_some_and(close)).unwrap_or(n);
    let half = at(t0 + 0.5 * period).map(|h| sec.scale(h));
    let symmetric = sec.symmetric || (periods == 1 && half.is_some_and(|h| (h + u0).amax() <= 1e-6));
    let whole = f64::from(periods) * period;
    let strobe_m = (0..periods).filter_map(|k| at(t0 + f64::from(k) * period)).map(|s| s[0]).collect();
    let mut impacts: Vec<OrbitImpact> = f
        .impacts
        .iter()
        .filter(|i| i.t_s < whole)
        .map(|i| {
            let k = ((i.t_s - t0) / period).rem_euclid(f64::from(periods));
            let period_index = k.floor();
            OrbitImpact {
                period: period_index as u32,
                phase: k - period_index,
                wall: i.wall,
                u_in_m_s: i.u_in_m_s,
                u_out_m_s: i.u_out_m_s,
            }
        })
        .collect();
    impacts.sort_by(|a, b| (f64::from(a.period) + a.phase).total_cmp(&(f64::from(b.period) + b.phase)));
    // The monodromy of the full orbit: the symmetric map's squared, the n-fold map's as is
    // (if the orbit's true period is a divisor of n, its multipliers are the n/k-th roots'
    // powers; they are reported for n as found).
    let jac = if sec.symmetric { root.jac * root.jac } else { root.jac };
    let multipliers = if impacts.is_empty() {
        // The ball floats: its block is [[1, nT], [0, 1]], a neutral pair; the structure's two.
        let block = jac.fixed_view::<2, 2>(0, 0).into_owned();
        let mut m: Vec<Multiplier> =
            block.complex_eigenvalues().iter().map(|c| Multiplier { re: c.re, im: c.im, abs: c.norm() }).collect();
        m.sort_by(|a, b| b.abs.total_cmp(&a.abs).then(b.im.total_cmp(&a.im)));
        m
    } else {
        multipliers(&jac)
    };
    let lead = multipliers.first().copied().unwrap_or(Multiplier { re: 0.0, im: 0.0, abs: 0.0 });
    let stable = multipliers.iter().all(|m| m.abs < 1.0);
    let scale_r = root.residual * sec.l.max(sec.v);
    Ok(PeriodicOrbit {
        periods: if sec.symmetric { 1 } else { periods },
        impacts_per_orbit: impacts.len() as u32,
        symmetric,
        x_m: s0[0],
        v_m_s: s0[1],
        z_m: s0[2] - s0[0],
        zdot_m_s: s0[3] - s0[1],
        strobe_m,
        amplitude_m: f.amplitude_m,
        amplitude_linear_m: linear_amplitude_m(&p),
        impacts,
        multipliers,
        stable,
        critical: loss(&lead),
        residual: scale_r,
        iterations: root.iterations,
        periods_simulated: sec.spent,
        section: Some((sec.phase, s)),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The `forced-rattle` preset's damper at forcing frequency `freq_hz` (Hz), from rest.
    fn forced_rattle(freq_hz: f64) -> DamperParams {
        DamperParams {
            impact_mass_kg: 0.0405,
            gap_m: 0.01,
            main_mass_kg: 0.5,
            stiffness_n_m: 500.0,
            damping_n_s_m: 1.5,
            force_n: 3.0,
            freq_hz,
            v0_m_s: 0.0,
            ..DamperParams::table2()
        }
    }

    #[test]
    fn the_section_is_in_the_middle_of_the_longest_flight() {
        let omega = std::f64::consts::TAU;
        let hit = |t: f64, len: f64| damper::ImpactEvent {
            t_s: t,
            wall: Wall::Upper,
            u_in_m_s: 1.0,
            u_out_m_s: 0.9,
            t_end_s: t + len,
            penetration_max_m: 0.0,
        };
        // Contacts at phases 0.1–0.2 and 0.5–0.55 of the cycle: the longest gap is 0.55 → 1.1.
        let phi = flight_phase(&[hit(3.1, 0.1), hit(3.5, 0.05)], 0.0, omega) / omega;
        assert!((phi - 0.825).abs() < 1e-12, "{phi}");
        assert_eq!(flight_phase(&[], 0.0, omega), 0.0);
    }

    /// The chained Jacobian (exact flights, differenced contact windows) is the whole map's
    /// forward-difference Jacobian, at a 3/1 orbit of forced-rattle and off it.
    #[test]
    fn the_chained_jacobian_is_the_whole_maps() {
        let p = forced_rattle(7.0);
        let o = find_damper(&p, &Request::default(), None).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!((o.impacts_per_orbit, o.periods), (3, 1), "{}", o.label());
        let s = [o.x_m, o.v_m_s, o.x_m + o.z_m, o.v_m_s + o.zdot_m_s];
        for off in [0.0, 0.02] {
            let mut sec = Section::new(p, 0.0, 1, false, None);
            let u = sec.scale(s) * (1.0 + off);
            let pu = sec.map(&u).unwrap();
            let chained = sec.jacobian(&u, &pu).unwrap();
            let whole = sec.full_jacobian(&u, &pu).unwrap();
            let err = (chained - whole).amax() / whole.amax();
            assert!(err < 1e-5, "off {off}: {err:e}\n{chained}\n{whole}");
        }
    }

    /// The stroboscopic samples of a period-2 orbit (forced-rattle's 12/2 at 5.3116 Hz) are x at
    /// the force's phase 0 at each of its two periods: a run from the orbit's state over eight
    /// periods passes through them in turn, to 1e-9 m.
    #[test]
    fn the_strobe_samples_are_x_at_each_period_of_the_orbit() {
        let p = forced_rattle(5.3116);
        let o = find_damper(&p, &Request { periods: Some(2), ..Request::default() }, None)
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!((o.periods, o.strobe_m.len()), (2, 2), "{}", o.label());
        assert_eq!(o.strobe_m[0], o.x_m);
        assert!(
            (o.strobe_m[1] - o.strobe_m[0]).abs() > 1e-6,
            "a period-2 orbit's two samples differ: {:?}",
            o.strobe_m
        );
        let period = 1.0 / p.freq_hz;
        let stops: Vec<f64> = (1..=8).map(|k| f64::from(k) * period).collect();
        let s = [o.x_m, o.v_m_s, o.x_m + o.z_m, o.v_m_s + o.zdot_m_s];
        let f = damper::flow(&p, s, 0.0, &stops, None);
        assert_eq!(f.states.len(), stops.len());
        for (k, state) in f.states.iter().enumerate() {
            let want = o.strobe_m[(k + 1) % 2];
            assert!((state[0] - want).abs() < 1e-9, "period {}: x {} vs {}", k + 1, state[0], want);
        }
    }

    #[test]
    fn multipliers_say_how_stability_is_lost() {
        let m = |re: f64, im: f64| Multiplier { re, im, abs: re.hypot(im) };
        assert_eq!(loss(&m(1.2, 0.0)), Loss::Fold);
        assert_eq!(loss(&m(-1.2, 0.0)), Loss::PeriodDoubling);
        assert_eq!(loss(&m(0.3, 0.9)), Loss::NeimarkSacker);
        let j = Matrix4::from_diagonal(&Vector4::new(0.5, -2.0, 0.1, 0.2));
        let ms = multipliers(&j);
        assert_eq!(ms[0].re, -2.0);
        assert!(ms.windows(2).all(|w| w[0].abs >= w[1].abs));
    }
}
