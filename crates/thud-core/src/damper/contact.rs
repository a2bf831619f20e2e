// Over 800 lines: one integrator, its step, its event location and its energy ledger.
//! The in-contact integrator of the event solver: adaptive Dormand–Prince 5(4) on the coupled
//! equations of paper Eq 26 while the ball presses a wall.
//!
//! State `[x, x', δ, δ', E_contact, E_viscous]`: main-mass position (m) and velocity (m/s), the
//! penetration `δ = s·z − d/2` (m) and its rate (m/s) at wall `s = ±1`, and the energies (J)
//! dissipated so far by the contact damping and by the viscous damper. With the bracket
//! `F = K_HZ·δ₊^{3/2} + c1·δ'` (clamped at ≥ 0 under "no tension"), the force on the ball is
//! `−s·F`, on the main mass `+s·F`, so
//! `M·x'' = −C·x' − K·x + F(t) + s·F` and `δ'' = −K*·F − s·(F(t) − C·x' − K·x)/M`, `K* = (m+M)/(m·M)`,
//! where `F(t)` is the harmonic force on the main mass of a forced run ([`Load`]; none in the
//! paper's free decay, where that code path is exactly the unforced one).
//! The law is extended smoothly past the exit (`δ₊ = max(δ, 0)`) so the exit root is well posed.
//!
//! [`integrate`] runs one contact to one of its [`ContactOutcome`]s: separated (δ back to 0),
//! grazed, cut by the end of the run, or stopped by the run's step budget (a work cap). A
//! contact cut by the end of a stretch of a run ([`ContactEnd::resume`]) can be carried on by
//! [`resume`] exactly where it stopped.
//!
//! Hand-written rather than taken from an ODE crate because the work is in the events, not in
//! the Runge–Kutta stages: the exit and the clamp's switches are located inside a step (a root
//! of the step's quintic Hermite interpolant, refined by real steps whose error is judged again),
//! the peak penetration comes from the same interpolant, the step budget is shared across a run,
//! and the stages carry only the motion (the dissipated energies enter the final combination
//! alone). The state and the stage sums are nalgebra vectors.

use nalgebra::{Vector2, Vector4, Vector6};

use crate::contact::{contact_duration, peak_approach};

use super::forced::Harmonic;
use super::roots::{illinois, IllinoisStop};
use super::DamperParams;

/// A force on the main mass as a function of time, per unit main mass (m/s²): none (the
/// paper's free decay; `ON` is false and every use of it compiles away), or [`Harmonic`].
pub(crate) trait Load: Copy {
    /// Whether there is a force at all.
    const ON: bool;
    /// The force per unit main mass at time `t` (s).
    fn accel(&self, t: f64) -> f64;
    /// `(f, Ω, θ(t))`: the amplitude per unit main mass (m/s²), the angular frequency (rad/s)
    /// and the phase at `t` of the force `f·cos θ(t)` (zeros without a force).
    fn harmonic(&self, t: f64) -> (f64, f64, f64);
    /// The force at the Dormand–Prince stage times `t + c_i·h`, `i = 2 … 7`.
    #[inline(always)]
    fn stages(&self, t: f64, h: f64) -> [f64; 6] {
        [C2, C3, C4, C5, 1.0, 1.0].map(|c| self.accel(t + c * h))
    }
}

/// No force: the paper's free decay.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct NoLoad;

impl Load for NoLoad {
    const ON: bool = false;
    #[inline(always)]
    fn accel(&self, _: f64) -> f64 {
        0.0
    }
    #[inline(always)]
    fn harmonic(&self, _: f64) -> (f64, f64, f64) {
        (0.0, 0.0, 0.0)
    }
}

impl Load for Harmonic {
    const ON: bool = true;
    #[inline(always)]
    fn accel(&self, t: f64) -> f64 {
        Harmonic::accel(self, t)
    }
    #[inline(always)]
    fn harmonic(&self, t: f64) -> (f64, f64, f64) {
        (self.f, self.omega, self.theta(t))
    }

    /// One `sin_cos` a step: `cos(θ + a) = cos θ·cos a − sin θ·sin a` with `a = Ω·c_i·h`, whose
    /// sine and cosine are short series while `|Ω·h| ≤ 0.05` (truncation below 1e-19).
    #[inline(always)]
    fn stages(&self, t: f64, h: f64) -> [f64; 6] {
        let u = self.omega * h;
        if u.abs() > 0.05 {
            return [C2, C3, C4, C5, 1.0, 1.0].map(|c| self.accel(t + c * h));
        }
        let (s0, c0) = self.theta(t).sin_cos();
        let at = |c: f64| {
            let a = u * c;
            let a2 = a * a;
            let sa = a * (1.0 - a2 / 6.0 * (1.0 - a2 / 20.0 * (1.0 - a2 / 42.0 * (1.0 - a2 / 72.0))));
            let ca = 1.0 - a2 / 2.0 * (1.0 - a2 / 12.0 * (1.0 - a2 / 30.0 * (1.0 - a2 / 56.0)));
            self.f * (c0 * ca - s0 * sa)
        };
        let end = at(1.0);
        [at(C2), at(C3), at(C4), at(C5), end, end]
    }
}

/// The physical constants of one design, in SI units.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Sys {
    pub big_m: f64,
    pub m: f64,
    pub k: f64,
    pub c: f64,
    /// d/2 (m).
    pub half_gap: f64,
    pub k_hz: f64,
    pub c1: f64,
    pub no_tension: bool,
    /// K* = (m+M)/(m·M) (1/kg).
    pub kstar: f64,
    /// 1/M (1/kg).
    pub inv_big_m: f64,
}

impl Sys {
    /// Total mechanical energy (J): kinetic of both masses, the spring, and the Hertz contact
    /// at penetration `delta` (m, ≥ 0): ½Mx'² + ½Kx² + ½my'² + (2/5)·K_HZ·δ^(5/2).
    pub fn mechanical_energy(&self, x: f64, v: f64, w: f64, delta: f64) -> f64 {
        0.5 * self.big_m * v * v
            + 0.5 * self.k * x * x
            + 0.5 * self.m * w * w
            + 0.4 * self.k_hz * delta * delta * delta.sqrt()
    }

    pub fn new(p: &DamperParams) -> Self {
        Sys {
            big_m: p.main_mass_kg,
            m: p.impact_mass_kg,
            k: p.stiffness_n_m,
            c: p.damping_n_s_m,
            half_gap: 0.5 * p.gap_m,
            k_hz: p.k_hz,
            c1: p.c1_n_s_m,
            no_tension: p.no_tension,
            kstar: (p.impact_mass_kg + p.main_mass_kg) / (p.impact_mass_kg * p.main_mass_kg),
            inv_big_m: 1.0 / p.main_mass_kg,
        }
    }

    /// The unclamped bracket `K_HZ·δ₊^{3/2} + c1·δ'` (N) at state `y` and its rate (N/s), given
    /// the state's derivative `d`.
    #[inline]
    pub fn raw_bracket(&self, y: &State, d: &State) -> (f64, f64) {
        let dp = y[2].max(0.0);
        let r = dp.sqrt();
        (self.k_hz * dp * r + self.c1 * y[3], 1.5 * self.k_hz * r * y[3] + self.c1 * d[3])
    }

    /// `(F, K_HZ·δ₊^{3/2}, clamped)`: the contact bracket (N) and its elastic part.
    #[inline]
    pub fn bracket(&self, del: f64, dd: f64) -> (f64, f64, bool) {
        let dp = del.max(0.0);
        let hz = self.k_hz * dp * dp.sqrt();
        let f = hz + self.c1 * dd;
        if self.no_tension && f < 0.0 {
            (0.0, hz, true)
        } else {
            (f, hz, false)
        }
    }
}

/// The integrated state `[x, x', δ, δ', E_contact, E_viscous]` (m, m/s, m, m/s, J, J), and
/// also its rate.
pub(crate) type State = Vector6<f64>;

/// The mechanical part `[x, x', δ, δ']` of a state (or of its rate); the only part the stages
/// of a step need.
type Motion = Vector4<f64>;

/// The rate of the whole state at `y`, with the force per unit main mass `g` (m/s²) at its time.
#[inline]
fn rhs<L: Load>(sys: &Sys, s: f64, y: &State, g: f64) -> State {
    let (x, v, del, dd) = (y[0], y[1], y[2], y[3]);
    let (f, hz, _) = sys.bracket(del, dd);
    let mut spring = (-sys.c * v - sys.k * x) * sys.inv_big_m;
    if L::ON {
        spring += g;
    }
    State::new(v, spring + s * f * sys.inv_big_m, dd, -sys.kstar * f - s * spring, (f - hz) * dd, sys.c * v * v)
}

// Dormand–Prince 5(4) coefficients: the stage times c_i, then the a_ij, b_i and error weights.
const C2: f64 = 1.0 / 5.0;
const C3: f64 = 3.0 / 10.0;
const C4: f64 = 4.0 / 5.0;
const C5: f64 = 8.0 / 9.0;
const A21: f64 = 1.0 / 5.0;
const A31: f64 = 3.0 / 40.0;
const A32: f64 = 9.0 / 40.0;
const A41: f64 = 44.0 / 45.0;
const A42: f64 = -56.0 / 15.0;
const A43: f64 = 32.0 / 9.0;
const A51: f64 = 19372.0 / 6561.0;
const A52: f64 = -25360.0 / 2187.0;
const A53: f64 = 64448.0 / 6561.0;
const A54: f64 = -212.0 / 729.0;
const A61: f64 = 9017.0 / 3168.0;
const A62: f64 = -355.0 / 33.0;
const A63: f64 = 46732.0 / 5247.0;
const A64: f64 = 49.0 / 176.0;
const A65: f64 = -5103.0 / 18656.0;
const B1: f64 = 35.0 / 384.0;
const B3: f64 = 500.0 / 1113.0;
const B4: f64 = 125.0 / 192.0;
const B5: f64 = -2187.0 / 6784.0;
const B6: f64 = 11.0 / 84.0;
const E1: f64 = 71.0 / 57600.0;
const E3: f64 = -71.0 / 16695.0;
const E4: f64 = 71.0 / 1920.0;
const E5: f64 = -17253.0 / 339200.0;
const E6: f64 = 22.0 / 525.0;
const E7: f64 = -1.0 / 40.0;

/// Relative tolerance of the contact integrator (on a state scaled by the contact's own sizes).
pub(crate) const RTOL: f64 = 3e-9;

/// The four non-trivial rates `(x'', δ'', P_contact, P_viscous)` at `(x, x', δ, δ')`, with the
/// force per unit main mass `g` (m/s²) there. `NT` is [`Sys::no_tension`], fixed at compile time
/// so that a contact without the clamp does not carry its select in every stage.
#[inline(always)]
fn acc<L: Load, const NT: bool>(sys: &Sys, s: f64, x: f64, v: f64, del: f64, dd: f64, g: f64) -> (f64, f64, f64, f64) {
    let dp = del.max(0.0);
    let hz = sys.k_hz * dp * dp.sqrt();
    let mut f = hz + sys.c1 * dd;
    if NT && f < 0.0 {
        f = 0.0;
    }
    let mut spring = (-sys.c * v - sys.k * x) * sys.inv_big_m;
    if L::ON {
        spring += g;
    }
    (spring + (s * sys.inv_big_m) * f, -sys.kstar * f - s * spring, (f - hz) * dd, sys.c * v * v)
}

/// The rate of the motion `[x', x'', δ', δ'']` at a stage state and the two dissipated powers
/// `[P_contact, P_viscous]` (W) there.
#[inline(always)]
fn stage_rate<L: Load, const NT: bool>(sys: &Sys, s: f64, m: &Motion, g: f64) -> (Motion, Vector2<f64>) {
    let (a, b, pc, pv) = acc::<L, NT>(sys, s, m[0], m[1], m[2], m[3], g);
    (Motion::new(m[1], a, m[3], b), Vector2::new(pc, pv))
}

/// One DOPRI5 step of length `h` from `y` at time `t` (with `k1 = f(y)`): the new state, `f(new)`
/// and the scaled error norm (max norm over the state with scales `sc`). The stages carry only
/// the motion `[x, x', δ, δ']`: no stage rate depends on the dissipated energies, whose powers
/// enter the final combination alone.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn step<L: Load, const NT: bool>(
    sys: &Sys,
    load: &L,
    s: f64,
    t: f64,
    y: &State,
    k1: &State,
    h: f64,
    sc: &[f64; 6],
) -> (State, State, f64) {
    let g = if L::ON { load.stages(t, h) } else { [0.0; 6] };
    let (y0, e0): (Motion, Vector2<f64>) = (y.fixed_rows::<4>(0).into_owned(), y.fixed_rows::<2>(4).into_owned());
    let (r1, p1): (Motion, Vector2<f64>) = (k1.fixed_rows::<4>(0).into_owned(), k1.fixed_rows::<2>(4).into_owned());
    // Stage state = (y + h·Σ older terms) + (h·a_last)·k_last: the newest rate enters last, so the
    // sums over older stages overlap with the evaluation of the newest one.
    let stage = |older: Motion, a_last: f64, r_last: &Motion| (y0 + older * h) + r_last * (h * a_last);

    let (r2, _) = stage_rate::<L, NT>(sys, s, &stage(Motion::zeros(), A21, &r1), g[0]);
    let (r3, p3) = stage_rate::<L, NT>(sys, s, &stage(r1 * A31, A32, &r2), g[1]);
    let (r4, p4) = stage_rate::<L, NT>(sys, s, &stage(r1 * A41 + r2 * A42, A43, &r3), g[2]);
    let (r5, p5) = stage_rate::<L, NT>(sys, s, &stage(r1 * A51 + r2 * A52 + r3 * A53, A54, &r4), g[3]);
    let (r6, p6) = stage_rate::<L, NT>(sys, s, &stage(r1 * A61 + r2 * A62 + r3 * A63 + r4 * A64, A65, &r5), g[4]);

    // The fifth-order solution (B2 = 0), its rate (first-same-as-last) and the error estimate.
    let m7 = y0 + (r1 * B1 + r3 * B3 + r4 * B4 + r5 * B5 + r6 * B6) * h;
    let e7 = e0 + (p1 * B1 + p3 * B3 + p4 * B4 + p5 * B5 + p6 * B6) * h;
    let yn = State::new(m7[0], m7[1], m7[2], m7[3], e7[0], e7[1]);
    let (r7, p7) = stage_rate::<L, NT>(sys, s, &m7, g[5]);
    let k7 = State::new(r7[0], r7[1], r7[2], r7[3], p7[0], p7[1]);
    let em = (r1 * E1 + r3 * E3 + r4 * E4 + r5 * E5 + r6 * E6 + r7 * E7) * h;
    let ep = (p1 * E1 + p3 * E3 + p4 * E4 + p5 * E5 + p6 * E6 + p7 * E7) * h;
    let errs = [em[0], em[1], em[2], em[3], ep[0], ep[1]];
    let q = |i: usize| errs[i].abs() / (RTOL * (sc[i] + y[i].abs().max(yn[i].abs())));
    // The max norm from 0 over the six quotients, two chains of three joined at the end: a max
    // is exact, so the grouping cannot change it (and `worse` skips a quotient that is not a
    // number, as `f64::max` does), but the step-size controller waits on it one max sooner.
    let err = worse(worse(worse(worse(0.0, q(0)), q(1)), q(2)), worse(worse(worse(0.0, q(3)), q(4)), q(5)));
    (yn, k7, err)
}

/// `max(acc, q)` for an `acc` that is a number: `q` if it is larger, else `acc` (so a `q` that
/// is not a number is skipped). One `maxsd`, where `f64::max` also tests `acc` for NaN.
#[inline(always)]
fn worse(acc: f64, q: f64) -> f64 {
    if q > acc {
        q
    } else {
        acc
    }
}

/// Where one contact starts: the system, the force on the main mass `load`, the wall `s = ±1`,
/// the onset time `t0` (s) and state `y0 = [x, x', 0, u0, 0, 0]` (u0 > 0), the end of the
/// stretch `t_limit` (s), and `a_bound` (m/s²), a bound on the non-contact relative
/// acceleration that sizes the reference's first step of a slow contact (the other schemes do
/// not use it).
#[derive(Clone, Copy)]
pub(crate) struct ContactStart<'a, L> {
    pub sys: &'a Sys,
    pub load: L,
    pub s: f64,
    pub t0: f64,
    pub y0: State,
    pub t_limit: f64,
    pub a_bound: f64,
}

impl<'a> ContactStart<'a, NoLoad> {
    /// An isolated contact without a force: at wall +1 from time 0, up to `t_limit` (s).
    pub(crate) fn free(sys: &'a Sys, y0: State, t_limit: f64) -> Self {
        ContactStart { sys, load: NoLoad, s: 1.0, t0: 0.0, y0, t_limit, a_bound: 0.0 }
    }
}

/// The stretch a contact cut by the end of the one before carries on over: the system, the
/// force on the main mass `load` and the new end of the stretch `t_limit` (s).
#[derive(Clone, Copy)]
pub(crate) struct Stretch<'a, L> {
    pub sys: &'a Sys,
    pub load: L,
    pub t_limit: f64,
}

#[cfg(test)]
impl<'a> Stretch<'a, NoLoad> {
    /// A stretch without a force, up to `t_limit` (s).
    pub(crate) fn free(sys: &'a Sys, t_limit: f64) -> Self {
        Stretch { sys, load: NoLoad, t_limit }
    }
}

/// Sees every accepted step of a contact integration: `step(t0, y0, k0, t1, y1, k1)` with the
/// states at both ends and their derivatives. A closure is one; the event solver's recording is
/// another, whose `step` is inlined into the step loop (a closure's call is not, and then the
/// states must be written out to memory for it at every step).
pub(crate) trait Observer {
    fn step(&mut self, t0: f64, y0: &State, k0: &State, t1: f64, y1: &State, k1: &State);
}

impl<F: FnMut(f64, &State, &State, f64, &State, &State)> Observer for F {
    #[inline(always)]
    fn step(&mut self, t0: f64, y0: &State, k0: &State, t1: f64, y1: &State, k1: &State) {
        self(t0, y0, k0, t1, y1, k1);
    }
}

/// The observer that sees nothing (an isolated contact).
pub(crate) struct Unobserved;

impl Observer for Unobserved {
    #[inline(always)]
    fn step(&mut self, _: f64, _: &State, _: &State, _: f64, _: &State, _: &State) {}
}

/// How a contact integration ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum ContactOutcome {
    /// The ball left the wall: δ is back to 0 (set exactly in the end state).
    Separated,
    /// The "contact" never produced a positive penetration (a numerical graze): carry on in flight.
    Grazed,
    /// The time limit (the end of the run) came first: the contact is cut there.
    EndOfRun,
    /// The step budget ran out first (a work cap).
    WorkCap,
}

/// Where and how a contact integration ended, by any scheme; `R` is the scheme's state of a
/// contact cut by its time limit (this module's [`Resume`] for the reference).
#[derive(Debug, Clone, Copy)]
pub(crate) struct ContactEnd<R = Resume> {
    /// Time (s) and state `[x, x', δ, δ', E_contact, E_viscous]` at the end.
    pub t: f64,
    pub y: State,
    /// Peak penetration (m), refined where δ' = 0.
    pub pen_max: f64,
    pub outcome: ContactOutcome,
    /// With [`ContactOutcome::EndOfRun`]: everything needed to carry the contact on.
    pub resume: Option<R>,
}

impl<R> ContactEnd<R> {
    /// The same end with its resume state mapped by `f` (the event solver tags it by scheme).
    pub(crate) fn map_resume<S>(self, f: impl FnOnce(R) -> S) -> ContactEnd<S> {
        ContactEnd { t: self.t, y: self.y, pen_max: self.pen_max, outcome: self.outcome, resume: self.resume.map(f) }
    }
}

/// A contact integration cut by its time limit, as it stood: the step-size controller, the
/// state and what has been seen so far. [`resume`] carries it on.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Resume {
    s: f64,
    sc: [f64; 6],
    tau: f64,
    t: f64,
    y: State,
    k1: State,
    h: f64,
    had_pos: bool,
    switches: usize,
    pen: f64,
    err_old: f64,
}

/// Clamp switches located exactly per contact. A ball pressed by the wall under "no tension"
/// can slide along the switching surface (the clamp chatters); past this many switches the
/// integrator steps through them under plain error control instead of stopping at each.
const MAX_SWITCHES: usize = 16;

/// First step as a fraction of the Hertz duration estimate τ (the onset force grows like
/// t^{3/2}, so the first step is limited by that, not by smoothness).
const H0_FRACTION: f64 = 1.0 / 1000.0;

/// What one trial step led to.
enum Flow {
    /// Go on with the next trial step (this one accepted, cut short, or rejected).
    Continue,
    /// The contact integration is over.
    Done(ContactOutcome),
}

/// One contact being integrated: the accepted state, the step-size controller and what has
/// been seen so far. Units: s, m, m/s, J. `NT` is [`Sys::no_tension`] (see [`acc`]).
struct Integration<'a, L, O, const NT: bool> {
    sys: &'a Sys,
    load: L,
    /// The wall's sign (±1).
    s: f64,
    /// Error scales of the six state components.
    sc: [f64; 6],
    /// The Hertz duration estimate τ (s) at the onset speed.
    tau: f64,
    t_limit: f64,
    t: f64,
    y: State,
    /// The state's derivative f(y).
    k1: State,
    /// The next trial step (s).
    h: f64,
    /// A step ending with δ > 0 has been accepted (the contact is real).
    had_pos: bool,
    /// Clamp switches located so far.
    switches: usize,
    /// Peak penetration so far (m).
    pen: f64,
    /// log2 of the previous step's error norm (floored at 1e-4).
    err_old: f64,
    /// The trial step before it was shortened to end at the time limit (s).
    h_full: f64,
    /// Sees every accepted step.
    obs: O,
}

/// Integrates one contact at wall `s` from `y0` (δ = 0, δ' > 0) at time `t0` until the exit
/// (δ returns to 0), the time limit `t_limit`, or `budget` steps run out, under the force `load`.
/// `a_bound` (m/s²) bounds the non-contact relative acceleration (used to size the first step of
/// slow contacts). `obs` sees every accepted step ([`Observer::step`]: states and their
/// derivatives).
pub(crate) fn integrate<L: Load>(start: ContactStart<'_, L>, budget: &mut usize, obs: impl Observer) -> ContactEnd {
    let ContactStart { sys, load, s, t0, y0, t_limit, a_bound } = start;
    if sys.no_tension {
        run(Integration::<L, _, true>::start(sys, load, s, t0, y0, t_limit, a_bound, obs), budget)
    } else {
        run(Integration::<L, _, false>::start(sys, load, s, t0, y0, t_limit, a_bound, obs), budget)
    }
}

/// Carries on a contact cut by its time limit (`r`, from [`ContactEnd::resume`]) over the
/// stretch `at`, as [`integrate`] would have had it not been cut.
pub(crate) fn resume<L: Load>(at: Stretch<'_, L>, r: &Resume, budget: &mut usize, obs: impl Observer) -> ContactEnd {
    let Stretch { sys, load, t_limit } = at;
    if sys.no_tension {
        run(Integration::<L, _, true>::resumed(sys, load, r, t_limit, obs), budget)
    } else {
        run(Integration::<L, _, false>::resumed(sys, load, r, t_limit, obs), budget)
    }
}

/// The step loop of one contact integration.
#[inline(always)]
fn run<L: Load, O: Observer, const NT: bool>(mut it: Integration<'_, L, O, NT>, budget: &mut usize) -> ContactEnd {
    let (sys, s, t_limit) = (it.sys, it.s, it.t_limit);
    loop {
        if *budget == 0 {
            return it.end(ContactOutcome::WorkCap);
        }
        let last = it.t + it.h >= t_limit;
        if last {
            it.h_full = it.h;
            it.h = t_limit - it.t;
        }
        let (yn, k7, err) = step::<L, NT>(sys, &it.load, s, it.t, &it.y, &it.k1, it.h, &it.sc);
        *budget -= 1;
        let flow = match it.clamp_switch(&yn, &k7, budget) {
            Some(flow) => flow,
            None if it.had_pos && yn[2] <= 0.0 => it.exit_in_step(&yn, &k7, budget),
            None if err.is_nan() || err > 1.0 => it.reject(err),
            None if !it.had_pos && yn[2] <= 0.0 => it.first_step_overshoot(last, yn, k7),
            None => it.accept(last, yn, k7, err),
        };
        if let Flow::Done(outcome) = flow {
            return it.end(outcome);
        }
    }
}

impl<'a, L: Load, O: Observer, const NT: bool> Integration<'a, L, O, NT> {
    /// The integration at the onset: error scales from the contact's own sizes and a first step
    /// that resolves the t^{3/2} growth of the force.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn start(sys: &'a Sys, load: L, s: f64, t0: f64, y0: State, t_limit: f64, a_bound: f64, obs: O) -> Self {
        let u0 = y0[3].abs().max(1e-12);
        let amax = peak_approach(u0, sys.kstar, sys.k_hz);
        let tau = contact_duration(amax, u0);
        // Error scales: positions, velocities, penetration, its rate, and the relative kinetic
        // energy ½·u0²/K* for the dissipated energies (their integrands are non-smooth where the
        // clamp holds and at the exit, so they must be error-controlled too).
        let e_sc = 0.5 * u0 * u0 / sys.kstar;
        let sc = [2.0 * sys.half_gap + y0[0].abs(), y0[1].abs() + u0, amax, u0, e_sc, e_sc];
        let mut h = tau * H0_FRACTION;
        if a_bound > 0.0 {
            h = h.min(0.1 * u0 / a_bound);
        }
        let g0 = if L::ON { load.accel(t0) } else { 0.0 };
        Integration {
            sys,
            load,
            s,
            sc,
            tau,
            t_limit,
            t: t0,
            y: y0,
            k1: rhs::<L>(sys, s, &y0, g0),
            h,
            had_pos: false,
            switches: 0,
            pen: 0.0,
            err_old: -13.3,
            h_full: h,
            obs,
        }
    }

    /// The integration of a cut contact `r`, to be carried on up to `t_limit`.
    #[inline(always)]
    fn resumed(sys: &'a Sys, load: L, r: &Resume, t_limit: f64, obs: O) -> Self {
        Integration {
            sys,
            load,
            s: r.s,
            sc: r.sc,
            tau: r.tau,
            t_limit,
            t: r.t,
            y: r.y,
            k1: r.k1,
            h: r.h,
            had_pos: r.had_pos,
            switches: r.switches,
            pen: r.pen,
            err_old: r.err_old,
            h_full: r.h,
            obs,
        }
    }

    #[inline(always)]
    fn end(&self, outcome: ContactOutcome) -> ContactEnd {
        let resume = (outcome == ContactOutcome::EndOfRun).then(|| Resume {
            s: self.s,
            sc: self.sc,
            tau: self.tau,
            t: self.t,
            y: self.y,
            k1: self.k1,
            h: self.h_full.max(self.h),
            had_pos: self.had_pos,
            switches: self.switches,
            pen: self.pen,
            err_old: self.err_old,
        });
        ContactEnd { t: self.t, y: self.y, pen_max: self.pen, outcome, resume }
    }

    /// The peak penetration inside a step of length `h` to `(yn, kn)` when δ' turns there.
    #[inline(always)]
    fn note_peak(&mut self, h: f64, yn: &State, kn: &State) {
        if self.y[3] > 0.0 && yn[3] <= 0.0 {
            self.pen = self.pen.max(refine_peak(&self.y, &self.k1, h, yn, kn));
        }
    }

    /// Under "no tension", a trial step across which the unclamped bracket changes sign (the
    /// clamp switches): the step is cut at the switch so that no step straddles the kink of the
    /// force law. `None` when the trial step has no switch (or the switches are used up).
    #[inline(always)]
    fn clamp_switch(&mut self, yn: &State, k7: &State, budget: &mut usize) -> Option<Flow> {
        let sys = self.sys;
        if !(NT && sys.c1 > 0.0 && self.had_pos && self.switches < MAX_SWITCHES) {
            return None;
        }
        let b0 = sys.raw_bracket(&self.y, &self.k1).0;
        let b1 = sys.raw_bracket(yn, k7).0;
        if b0 == 0.0 || (b0 > 0.0) == (b1 > 0.0) {
            return None;
        }
        let sg = b0.signum();
        let guess = self.h * b0 / (b0 - b1);
        let tol = 1e-14 * sys.c1.max(1e-300) * self.sc[3];
        let bracket = |st: &State, d: &State| {
            let (v, r) = sys.raw_bracket(st, d);
            (sg * v, sg * r)
        };
        let (hc, yc, kc, err_c) = refine_root::<L, NT>(
            sys, &self.load, self.s, self.t, &self.y, &self.k1, self.h, guess, &self.sc, budget, bracket, tol,
        );
        self.switches += 1;
        if err_c <= 1.0 || hc <= 1e-14 * self.tau {
            self.note_peak(hc, &yc, &kc);
            self.pen = self.pen.max(yc[2]);
            self.obs.step(self.t, &self.y, &self.k1, self.t + hc, &yc, &kc);
            self.t += hc;
            self.y = yc;
            self.k1 = kc;
            if yc[2] <= 0.0 {
                self.y[2] = 0.0;
                return Some(Flow::Done(ContactOutcome::Separated));
            }
        } else {
            self.h = hc * (0.9 * err_c.powf(-0.2)).clamp(0.2, 0.9);
        }
        Some(Flow::Continue)
    }

    /// The exit (δ back to 0) lies in the trial step: locate it with real steps, then judge the
    /// error of the step that ends there (the extended force law is non-smooth only beyond it).
    #[inline(always)]
    fn exit_in_step(&mut self, yn: &State, k7: &State, budget: &mut usize) -> Flow {
        let guess = quintic_root::<0>(&self.y, &self.k1, yn, k7, self.h);
        let pen_tol = 1e-14 * self.sc[2];
        let (he, mut ye, ke, err_e) = refine_root::<L, NT>(
            self.sys,
            &self.load,
            self.s,
            self.t,
            &self.y,
            &self.k1,
            self.h,
            guess,
            &self.sc,
            budget,
            |st, _| (st[2], st[3]),
            pen_tol,
        );
        if err_e <= 1.0 || he <= 1e-14 * self.tau {
            self.note_peak(he, &ye, &ke);
            ye[2] = 0.0;
            self.obs.step(self.t, &self.y, &self.k1, self.t + he, &ye, &ke);
            self.t += he;
            self.y = ye;
            self.k1 = ke;
            return Flow::Done(ContactOutcome::Separated);
        }
        self.h = he * (0.9 * err_e.powf(-0.2)).clamp(0.2, 0.9);
        Flow::Continue
    }

    /// A trial step whose error is too large (or not a number): retry shorter.
    #[inline(always)]
    fn reject(&mut self, err: f64) -> Flow {
        let f = if err.is_finite() { (0.9 * err.powf(-0.2)).max(0.2) } else { 0.2 };
        self.h *= f;
        Flow::Continue
    }

    /// The first step jumped over a (tiny) contact, ending with δ ≤ 0 before any δ > 0 was
    /// accepted: shorten it, or call the contact a graze.
    #[inline(always)]
    fn first_step_overshoot(&mut self, last: bool, yn: State, k7: State) -> Flow {
        if self.h <= 1e-14 * self.tau.max(1e-12) || last {
            self.obs.step(self.t, &self.y, &self.k1, self.t + self.h, &yn, &k7);
            self.t = if last { self.t_limit } else { self.t + self.h };
            self.y = yn;
            self.k1 = k7;
            return Flow::Done(ContactOutcome::Grazed);
        }
        self.h *= 0.25;
        Flow::Continue
    }

    /// An accepted step inside the contact; the next step from the PI controller.
    #[inline(always)]
    fn accept(&mut self, last: bool, yn: State, k7: State, err: f64) -> Flow {
        // PI step-size control (Hairer's dopri5: α = 0.17, β = 0.04). The next step waits on
        // it, so it comes first; the bookkeeping below runs beside it.
        let le = err.max(1e-10).log2();
        let fac = (0.9 * (-0.17 * le + 0.04 * self.err_old).exp2()).clamp(0.2, 5.0);
        self.had_pos = true;
        self.note_peak(self.h, &yn, &k7);
        self.pen = self.pen.max(yn[2]);
        let t1 = if last { self.t_limit } else { self.t + self.h };
        self.obs.step(self.t, &self.y, &self.k1, t1, &yn, &k7);
        self.t = t1;
        self.y = yn;
        self.k1 = k7;
        if last {
            return Flow::Done(ContactOutcome::EndOfRun);
        }
        self.err_old = le.max(-13.3);
        self.h *= fac;
        Flow::Continue
    }
}

/// Quintic Hermite interpolant of δ on a step of length `h` built from δ, δ', δ'' at both ends
/// (all known from the step's states and derivatives, error O(h⁶)): `(δ, δ')` at `q ∈ [0, h]`.
#[inline]
fn quintic(y: &State, k1: &State, yn: &State, k7: &State, h: f64, q: f64) -> (f64, f64) {
    let u = q / h;
    let (p0, d0, a0) = (y[2], h * y[3], h * h * k1[3]);
    let (p1, d1, a1) = (yn[2], h * yn[3], h * h * k7[3]);
    let u2 = u * u;
    let u3 = u2 * u;
    let u4 = u3 * u;
    let u5 = u4 * u;
    let h00 = 1.0 - 10.0 * u3 + 15.0 * u4 - 6.0 * u5;
    let h10 = u - 6.0 * u3 + 8.0 * u4 - 3.0 * u5;
    let h20 = 0.5 * (u2 - 3.0 * u3 + 3.0 * u4 - u5);
    let h01 = 10.0 * u3 - 15.0 * u4 + 6.0 * u5;
    let h11 = -4.0 * u3 + 7.0 * u4 - 3.0 * u5;
    let h21 = 0.5 * (u3 - 2.0 * u4 + u5);
    let g00 = -30.0 * u2 + 60.0 * u3 - 30.0 * u4;
    let g10 = 1.0 - 18.0 * u2 + 32.0 * u3 - 15.0 * u4;
    let g20 = 0.5 * (2.0 * u - 9.0 * u2 + 12.0 * u3 - 5.0 * u4);
    let g11 = -12.0 * u2 + 28.0 * u3 - 15.0 * u4;
    let g21 = 0.5 * (3.0 * u2 - 8.0 * u3 + 5.0 * u4);
    let val = h00 * p0 + h10 * d0 + h20 * a0 + h01 * p1 + h11 * d1 + h21 * a1;
    let der = (g00 * (p0 - p1) + g10 * d0 + g20 * a0 + g11 * d1 + g21 * a1) / h;
    (val, der)
}

/// Root in `(0, h)` of the quintic interpolant's δ (`WHICH = 0`) or δ' (`WHICH = 1`), by the
/// Illinois regula falsi on the sign change between the step ends.
fn quintic_root<const WHICH: usize>(y: &State, k1: &State, yn: &State, k7: &State, h: f64) -> f64 {
    let (glo, ghi) = if WHICH == 0 { (y[2], yn[2]) } else { (y[3], yn[3]) };
    let stop = IllinoisStop { width: 1e-14 * h, value: 1e-15 * glo.abs().max(ghi.abs()) };
    let g = |q: f64| {
        let (v, d) = quintic(y, k1, yn, k7, h, q);
        (if WHICH == 0 { v } else { d }, ())
    };
    illinois((0.0, glo), (h, ghi), stop, (0.5 * h, ()), g).0
}

/// The peak penetration inside a step where δ' goes from > 0 to ≤ 0, from the quintic Hermite
/// interpolant: no extra force evaluations.
fn refine_peak(y: &State, k1: &State, h: f64, yn: &State, k7: &State) -> f64 {
    let q = quintic_root::<1>(y, k1, yn, k7, h);
    quintic(y, k1, yn, k7, h, q).0.max(y[2]).max(yn[2])
}

/// A root of `g` inside a trial step: Newton on the real step length from `guess`, safeguarded by
/// bisection; `g(state, f(state))` returns the function (> 0 at the step start) and its rate.
/// Returns `(h*, state, f(state), error norm of that step)`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn refine_root<L: Load, const NT: bool>(
    sys: &Sys,
    load: &L,
    s: f64,
    t: f64,
    y: &State,
    k1: &State,
    h: f64,
    guess: f64,
    sc: &[f64; 6],
    budget: &mut usize,
    g: impl Fn(&State, &State) -> (f64, f64),
    g_tol: f64,
) -> (f64, State, State, f64) {
    let (mut lo, mut hi) = (0.0, h);
    let mut hh = guess;
    let mut out = (h, *y, *k1, f64::INFINITY);
    for _ in 0..16 {
        if !(hh > lo && hh < hi) {
            hh = 0.5 * (lo + hi);
        }
        let (ys, ks, err) = step::<L, NT>(sys, load, s, t, y, k1, hh, sc);
        *budget = budget.saturating_sub(1);
        out = (hh, ys, ks, err);
        let (gv, gd) = g(&ys, &ks);
        if gv > 0.0 {
            lo = hh;
        } else {
            hi = hh;
        }
        if gv.abs() <= g_tol || gd == 0.0 {
            break;
        }
        let next = hh - gv / gd;
        if (next - hh).abs() <= 1e-16 * h {
            break;
        }
        hh = next;
    }
    out
}

#[cfg(test)]
mod tests;
