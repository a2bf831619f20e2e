//! An experimental in-contact integrator of the event solver: paper Eq 26 in the square root of the
//! penetration `σ = √δ` against a Sundman time `θ` with `dt/dθ = σ`, integrated by Taylor
//! series of high order (docs/model.md §11).
//!
//! The Hertz force `K_HZ·δ^{3/2}` is not smooth where a contact starts and ends: near the onset
//! `δ ≈ u0·t`, so `δ(t)` carries a `t^{7/2}` term, and the same holds at the release. A method
//! of high order in `t` loses its order there. With `δ = σ²` and `dt = σ·dθ`,
//!
//! ```text
//! dx/dθ = σ·x'               dx'/dθ = σ·(a_M + s·F/M)
//! dσ/dθ = δ'/2               dδ'/dθ = σ·(−K*·F − s·a_M)
//! dE_c/dθ = σ·(F − K_HZ·σ³)·δ'    dE_v/dθ = σ·C·x'²        dt/dθ = σ
//! ```
//!
//! with `F = K_HZ·σ³ + c1·δ'` (`0` while the clamp holds under "no tension") and `a_M = (F(t) −
//! C·x' − K·x)/M`, the symbols of [`super::contact`]. Every right-hand side is a polynomial in
//! the state (the harmonic force `f·cos φ` with `dφ/dθ = Ω·σ` adds two more), so the solution is
//! analytic in θ across the onset (a regular point, `dσ/dθ = u0/2 > 0`) and the release (a
//! simple root of σ), and its Taylor coefficients follow from the state by the recurrences of
//! automatic differentiation (Cauchy products; Jorba & Zou 2005). A step of order [`ORDER`]
//! spans about a fifth of a contact; its polynomials are the solution all along the step, so
//! the release, the peak penetration, the clamp's switches, the time limit, the maxima of `x`
//! and the extrema of `|z'|` are roots of polynomials, found without further steps.
//!
//! The contract is [`super::contact::integrate`]'s: one contact to separation, to the time
//! limit (cut exactly there, resumable by [`resume`]), or to the step budget.

use nalgebra::SVector;

use crate::contact::{contact_duration, peak_approach};

use super::contact::{ContactEnd, ContactOutcome, Load, State, Sys};
#[cfg(feature = "research")]
use super::contact::{ContactStart, Stretch};
use super::roots::{self, NewtonEnd};

/// The integrated state `[x, x', σ, δ', E_contact, E_viscous, t − t_onset]` (m, m/s, √m, m/s,
/// J, J, s).
pub(crate) type Y = SVector<f64, 7>;

/// Order of the Taylor polynomials.
pub(crate) const ORDER: usize = 16;

/// Coefficients per series.
pub(crate) const NC: usize = ORDER + 1;

/// `TOL^(1/ORDER)`: a series' step as a fraction of its radius of convergence (see
/// [`Series::step_size`]), worked out once.
pub(crate) fn step_fraction() -> f64 {
    static LAM: std::sync::LazyLock<f64> = std::sync::LazyLock::new(|| TOL.powf(1.0 / ORDER as f64));
    *LAM
}

/// The last coefficients that size a step.
const TAIL: usize = 6;

/// Relative tolerance of a step, on the contact's own scales (see [`Series::step_size`]).
/// Chosen so that the release speeds agree with the reference integrator's to its own accuracy
/// (tests/contact_scheme.rs, docs/model.md §11).
pub(crate) const TOL: f64 = 1e-11;

/// What one Taylor step is charged against the run's in-contact step budget
/// ([`super::CONTACT_STEP_CAP`], counted in the reference's Dormand–Prince steps): about the
/// steps of the reference it replaces, so the cap keeps its meaning.
pub(crate) const STEP_COST: usize = 12;

/// The Taylor coefficients of one step, `c_k` of `(θ − θ0)^k`, of the state's seven series.
#[derive(Clone)]
pub(crate) struct Series {
    /// `[x, x', σ, δ', E_c, E_v, t − t_onset]`, each `NC` coefficients.
    pub c: [[f64; NC]; 7],
    /// The unclamped bracket `K_HZ·σ³ + c1·δ'` (N): where the Taylor scheme's clamp switches.
    #[cfg_attr(not(feature = "research"), allow(dead_code))]
    pub raw: [f64; NC],
}

/// Sets the constant terms of the state's seven series `c` (`[x, x', σ, δ', E_c, E_v, t −
/// t_onset]`) to the state `y`.
#[inline(always)]
pub(crate) fn seed(c: &mut [[f64; NC]; 7], y: &Y) {
    for (row, &yi) in c.iter_mut().zip(y.iter()) {
        row[0] = yi;
    }
}

/// `Σ_{j=0..=k} a_j·b_{k−j}`: coefficient `k` of the product of two series.
#[cfg(feature = "research")]
#[inline(always)]
#[allow(clippy::range_plus_one, reason = "a half-open range: `0..=k`'s iterator checks its end twice a turn")]
fn cauchy(a: &[f64; NC], b: &[f64; NC], k: usize) -> f64 {
    let mut acc = 0.0;
    for j in 0..k + 1 {
        acc += a[j] * b[k - j];
    }
    acc
}

impl Series {
    /// The series of the motion from state `y` (contact onset at `t_onset`, wall `s`), with the
    /// clamp holding (`clamped`, F = 0) or not.
    #[cfg(feature = "research")]
    #[inline(always)]
    pub(crate) fn expand<L: Load>(sys: &Sys, load: &L, s: f64, t_onset: f64, y: &Y, clamped: bool) -> Self {
        if clamped {
            Self::expand_in::<L, true>(sys, load, s, t_onset, y)
        } else {
            Self::expand_in::<L, false>(sys, load, s, t_onset, y)
        }
    }

    // Over 80 lines: one pass of the Taylor recursion, every order's terms built in one loop.
    /// [`Series::expand`] with the clamp's state `CL` fixed at compile time.
    #[cfg(feature = "research")]
    #[inline(always)]
    fn expand_in<L: Load, const CL: bool>(sys: &Sys, load: &L, s: f64, t_onset: f64, y: &Y) -> Self {
        let clamped = CL;
        let z = [0.0; NC];
        let mut c = [z; 7];
        seed(&mut c, y);
        let [mut x, mut v, mut sg, mut u, mut ec, mut ev, mut tt] = c;
        let (mut s2, mut s3, mut a, mut b, mut sv, mut raw) = (z, z, z, z, z, z);
        let (mut q2, mut cs, mut sn) = (z, z, z);
        let (f, omega, phi) = load.harmonic(t_onset + y[6]);
        if L::ON {
            let (sp, cp) = phi.sin_cos();
            cs[0] = cp;
            sn[0] = sp;
        }
        let (khz, c1, kstar, im) = (sys.k_hz, sys.c1, sys.kstar, sys.inv_big_m);
        let mut sa = z;
        let mut sb = z;
        let mut qq = z;
        for k in 0..ORDER {
            // Coefficient k of every product, in one pass over the terms j < k (independent
            // sums, so they run side by side), then the terms j = k in dependency order.
            let (mut p_s2, mut p_s3, mut p_sv, mut p_sa, mut p_sb) = (0.0, 0.0, 0.0, 0.0, 0.0);
            let (mut p_svv, mut p_q2, mut p_qq, mut p_sn, mut p_cs) = (0.0, 0.0, 0.0, 0.0, 0.0);
            for j in 0..k {
                let (gj, gk) = (sg[j], sg[k - j]);
                p_s2 += gj * gk;
                p_s3 += s2[j] * gk;
                p_sv += gj * v[k - j];
                p_sa += gj * a[k - j];
                p_sb += gj * b[k - j];
                p_svv += sv[j] * v[k - j];
                if clamped {
                    p_q2 += s2[j] * s2[k - j];
                } else {
                    p_q2 += u[j] * u[k - j];
                }
                p_qq += if clamped { q2[j] * u[k - j] } else { gj * q2[k - j] };
                if L::ON {
                    p_sn += gj * sn[k - j];
                    p_cs += gj * cs[k - j];
                }
            }
            let g0 = sg[0];
            s2[k] = p_s2 + sg[k] * g0;
            s3[k] = p_s3 + s2[k] * g0;
            raw[k] = khz * s3[k] + c1 * u[k];
            let fk = if clamped { 0.0 } else { raw[k] };
            let mut spr = (-sys.c * v[k] - sys.k * x[k]) * im;
            if L::ON {
                spr += f * cs[k];
            }
            a[k] = spr + s * im * fk;
            b[k] = -kstar * fk - s * spr;
            sv[k] = p_sv + sg[k] * v[0];
            // (the j = 0 terms hold a[k] and b[k], zero in the pass above)
            // (the j = 0 terms hold a[k] and b[k], zero in the pass above; at k = 0 the two
            // end terms are one)
            let ends = if k == 0 { 1.0 } else { 2.0 };
            sa[k] = if k == 0 { g0 * a[0] } else { p_sa + g0 * a[k] + sg[k] * a[0] };
            sb[k] = if k == 0 { g0 * b[0] } else { p_sb + g0 * b[k] + sg[k] * b[0] };
            let inv = 1.0 / (k + 1) as f64;
            x[k + 1] = sv[k] * inv;
            v[k + 1] = sa[k] * inv;
            sg[k + 1] = 0.5 * u[k] * inv;
            u[k + 1] = sb[k] * inv;
            tt[k + 1] = sg[k] * inv;
            ev[k + 1] = sys.c * (p_svv + sv[k] * v[0]) * inv;
            // E_c' = σ·(F − K_HZ·σ³)·δ': c1·σ·δ'² while pressed, −K_HZ·σ⁴·δ' while clamped.
            if clamped {
                q2[k] = p_q2 + ends * s2[k] * s2[0];
                qq[k] = p_qq + q2[k] * u[0];
                ec[k + 1] = -khz * qq[k] * inv;
            } else {
                q2[k] = p_q2 + u[k] * u[0];
                qq[k] = if k == 0 { g0 * q2[0] } else { p_qq + g0 * q2[k] + sg[k] * q2[0] };
                ec[k + 1] = c1 * qq[k] * inv;
            }
            if L::ON {
                let w = omega * inv;
                cs[k + 1] = -w * (p_sn + sg[k] * sn[0]);
                sn[k + 1] = w * (p_cs + sg[k] * cs[0]);
            }
        }
        s2[ORDER] = cauchy(&sg, &sg, ORDER);
        s3[ORDER] = cauchy(&s2, &sg, ORDER);
        raw[ORDER] = khz * s3[ORDER] + c1 * u[ORDER];
        Series { c: [x, v, sg, u, ec, ev, tt], raw }
    }

    /// The step (θ units) over which every series' last terms stay below `TOL` of its scale
    /// `sc[i] + |c_0|`: the radius of convergence estimated from the last [`TAIL`] coefficients
    /// (more than two: at the onset of a free contact the series of σ holds only every fifth
    /// power), scaled down to the tolerance.
    pub(crate) fn step_size(&self, sc: &[f64; 7], guess: f64, lam: f64) -> f64 {
        let ratio = |h: f64| self.tail_ratio(sc, h, lam);
        let mut h = guess;
        for _ in 0..3 {
            let r = ratio(h);
            if !(r > 0.0 && r.is_finite()) {
                return if r == 0.0 { 4.0 * h } else { 0.25 * h };
            }
            // The tail terms go as h^(ORDER−TAIL+1) … h^ORDER: shrink by the lowest power,
            // grow by the highest, so that each guess errs on the safe side.
            let e = if r > 1.0 { (ORDER + 1 - TAIL) as f64 } else { ORDER as f64 };
            let next = h * r.powf(-1.0 / e);
            if r <= 1.0 && r > 0.5 {
                return h.max(next.min(h * 1.02));
            }
            h = next;
        }
        h
    }

    /// The largest tail term at step `h` (θ units) relative to its tolerance (scales `sc`,
    /// `lam` = `TOL^(1/ORDER)`): `TOL^(k/ORDER)` of the scale for term k, i.e. a step of
    /// `TOL^(1/ORDER)` times the radius of convergence the tail shows (Jorba & Zou 2005). At
    /// most 1 where the step is within the tolerance.
    pub(crate) fn tail_ratio(&self, sc: &[f64; 7], h: f64, lam: f64) -> f64 {
        let mut pw = [0.0; TAIL];
        let mut p = (h / lam).powi((ORDER + 1 - TAIL) as i32);
        for w in &mut pw {
            *w = p;
            p *= h / lam;
        }
        let mut r: f64 = 0.0;
        for (i, c) in self.c.iter().enumerate() {
            let inv_e = 1.0 / (sc[i] + c[0].abs());
            let mut m: f64 = 0.0;
            for (t, w) in pw.iter().enumerate() {
                m = m.max(c[ORDER + 1 - TAIL + t].abs() * w);
            }
            r = r.max(m * inv_e);
        }
        r
    }

    /// Series `i` at `q`: `(value, derivative)` by Horner.
    #[inline]
    pub fn eval(&self, i: usize, q: f64) -> (f64, f64) {
        horner(&self.c[i], q)
    }

    /// The state at `q`.
    #[inline]
    pub fn state(&self, q: f64) -> Y {
        Y::from(std::array::from_fn::<f64, 7, _>(|i| horner(&self.c[i], q).0))
    }
}

/// A polynomial `Σ c_k·q^k` and its derivative at `q`.
#[inline]
fn horner(c: &[f64; NC], q: f64) -> (f64, f64) {
    let mut p = c[ORDER];
    let mut d = 0.0;
    for k in (0..ORDER).rev() {
        d = d * q + p;
        p = p * q + c[k];
    }
    (p, d)
}

/// A root in `(0, h]` of `f` (value and derivative) with `f(0) = f0`, `f(h) = f1` of opposite
/// signs or `f1 = 0`: Newton safeguarded by bisection.
pub(crate) fn root_in(h: f64, f0: f64, f1: f64, f: impl Fn(f64) -> (f64, f64)) -> f64 {
    if f1 == 0.0 {
        return h;
    }
    roots::newton((0.0, h), f1 > f0, h * f0 / (f0 - f1), NewtonEnd::Span(h), f)
}

/// The system's constants the Sundman form's rates need, for the schemes that evaluate them
/// stage by stage (DOP853 and Adams): the design, the wall's sign and the force's amplitude per
/// unit main mass (m/s²) and angular frequency (rad/s).
#[derive(Clone, Copy)]
pub(crate) struct Rhs<'a> {
    pub sys: &'a Sys,
    pub s: f64,
    pub f: f64,
    pub omega: f64,
}

impl Rhs<'_> {
    /// The rates in θ of the motion (`m[..N]`: `[x, x', σ, δ']`, and the force's `cos φ`,
    /// `sin φ` under a [`Load`]) into `r[..N]`: the Sundman form of Eq 26 (module doc).
    #[inline(always)]
    pub fn motion<L: Load, const N: usize, const W: usize>(&self, m: &[f64; W], r: &mut [f64; W]) {
        let sys = self.sys;
        let (x, v, sg, u) = (m[0], m[1], m[2], m[3]);
        let force = sys.k_hz * (sg * sg * sg) + sys.c1 * u;
        let mut spring = (-sys.c * v - sys.k * x) * sys.inv_big_m;
        if L::ON {
            spring += self.f * m[4];
        }
        r[0] = sg * v;
        r[1] = sg * (spring + (self.s * sys.inv_big_m) * force);
        r[2] = 0.5 * u;
        r[3] = sg * (-sys.kstar * force - self.s * spring);
        if L::ON && N >= 6 {
            let w = self.omega * sg;
            r[4] = -w * m[5];
            r[5] = w * m[4];
        }
    }

    /// The rates in θ of the quadratures `[E_contact, E_viscous, t − t_onset]` (W per θ unit,
    /// W, s per θ unit) at the motion `m`.
    #[inline(always)]
    pub fn quad<const W: usize>(&self, m: &[f64; W]) -> [f64; 3] {
        let sys = self.sys;
        let (v, sg, u) = (m[1], m[2], m[3]);
        [sg * sys.c1 * (u * u), sg * sys.c * (v * v), sg]
    }
}

/// How a Sundman integration ended, in the event solver's terms: at the time limit `t_limit`
/// (s) or at the state's own time after the onset `t_onset` (s), the state `y` back in `δ = σ²`,
/// the peak penetration `pen_max` (m), and the scheme's resume state of a cut contact.
pub(crate) fn ended<R>(
    y: &Y,
    (t_onset, t_limit): (f64, f64),
    pen_max: f64,
    outcome: ContactOutcome,
    resume: Option<R>,
) -> ContactEnd<R> {
    let t = if outcome == ContactOutcome::EndOfRun { t_limit } else { t_onset + y[6] };
    ContactEnd { t, y: State::new(y[0], y[1], y[2] * y[2], y[3], y[4], y[5]), pen_max, outcome, resume }
}

/// The earliest end of a step of length `h` (θ units) from `y0` to `y1` before its end: the
/// release (σ back to 0) or the time limit (`t − t_onset` reaching `tau_lim`, s), located on the
/// step's polynomials (`ser`, built only when one lies in the step): `(q, the state there with σ
/// or t set exactly, dδ'/dθ there, the outcome it means)`. Shared by the schemes whose steps
/// end at their own length (DOP853 and Adams; the Taylor scheme also locates the clamp's
/// switches).
pub(crate) fn step_end<'s>(
    h: f64,
    y0: &Y,
    y1: &Y,
    tau_lim: f64,
    ser: impl Fn() -> &'s Series,
) -> Option<(f64, Y, f64, ContactOutcome)> {
    let mut cut: Option<(f64, ContactOutcome)> = None;
    if y1[2] <= 0.0 {
        let s = ser();
        cut = Some((root_in(h, y0[2], y1[2], |q| s.eval(2, q)), ContactOutcome::Separated));
    }
    if y1[6] >= tau_lim {
        let s = ser();
        let q = root_in(h, y0[6] - tau_lim, y1[6] - tau_lim, |q| {
            let (v, d) = s.eval(6, q);
            (v - tau_lim, d)
        });
        if cut.is_none_or(|(b, _)| q < b) {
            cut = Some((q, ContactOutcome::EndOfRun));
        }
    }
    let (q, outcome) = cut?;
    let s = ser();
    let mut ye = s.state(q);
    if outcome == ContactOutcome::Separated {
        ye[2] = 0.0;
    } else {
        ye[6] = tau_lim;
    }
    Some((q, ye, s.eval(3, q).1, outcome))
}

/// The polynomials of one step: ready (a Taylor step's series), or built on first use (the
/// dense output of a Runge–Kutta step, [`super::dop853`], which costs three more stages and is
/// wanted only in the steps that hold an event).
pub(crate) enum Dense<'a> {
    Ready(&'a Series),
    Lazy(&'a std::cell::OnceCell<Series>, &'a dyn Fn() -> Series),
}

/// One accepted step of a contact: its series, over `[0, h]` in θ, the contact having started
/// at `t_onset` (s).
pub(crate) struct Span<'a> {
    pub t_onset: f64,
    pub h: f64,
    dense: Dense<'a>,
    pub y0: &'a Y,
    pub y1: &'a Y,
    /// `dδ'/dθ` at both ends (m/s per θ unit).
    du: (f64, f64),
}

impl<'a> Span<'a> {
    /// A step with its polynomials `dense` and `dδ'/dθ` at both ends `du`.
    pub fn new(t_onset: f64, h: f64, dense: Dense<'a>, y0: &'a Y, y1: &'a Y, du: (f64, f64)) -> Self {
        Span { t_onset, h, dense, y0, y1, du }
    }

    /// The step's polynomials.
    #[inline]
    pub fn ser(&self) -> &Series {
        match self.dense {
            Dense::Ready(s) => s,
            Dense::Lazy(cell, build) => cell.get_or_init(build),
        }
    }

    /// Time (s) at each end.
    #[inline]
    pub fn t0(&self) -> f64 {
        self.t_onset + self.y0[6]
    }

    #[inline]
    pub fn t1(&self) -> f64 {
        self.t_onset + self.y1[6]
    }

    /// Where `x'` changes sign inside the step (its sign at the ends says it does): `(t, x)` at
    /// the extremum of x.
    pub fn x_extremum(&self) -> (f64, f64) {
        let ser = self.ser();
        let q = root_in(self.h, self.y0[1], self.y1[1], |q| ser.eval(1, q));
        (self.t_onset + ser.eval(6, q).0, ser.eval(0, q).0)
    }

    /// The largest `|δ'|` inside the step where `dδ'/dθ` changes sign; `None` without a sign
    /// change, or when it cannot exceed `floor` (m/s): it exceeds the larger of the ends' `|δ'|`
    /// by at most `h·max|dδ'/dθ|` over the step, bounded here (with a factor 2 to spare) by
    /// `2·h·(|dδ'/dθ|₀ + |dδ'/dθ|₁)`, the rate at both ends (it is smooth, and its sign changes
    /// once in a step that is a small part of the contact), so the step's polynomials are not
    /// built for an extremum that cannot raise the run's largest `|z'|`.
    #[inline(always)]
    pub fn speed_extremum(&self, floor: f64) -> Option<f64> {
        let (d0, d1) = self.du;
        if d0 == 0.0 || (d0 > 0.0) == (d1 > 0.0) {
            return None;
        }
        let bound = self.y0[3].abs().max(self.y1[3].abs()) + 2.0 * self.h * (d0.abs() + d1.abs());
        if bound <= floor {
            return None;
        }
        Some(self.speed_extremum_inside())
    }

    /// The largest `|δ'|` inside the step, located on its polynomials ([`Span::speed_extremum`]
    /// has checked that `dδ'/dθ` changes sign and that it may raise the run's largest `|z'|`).
    #[inline(never)]
    fn speed_extremum_inside(&self) -> f64 {
        let (d0, d1) = self.du;
        let ser = self.ser();
        let c = &ser.c[3];
        let q = root_in(self.h, d0, d1, |q| {
            // The derivative of δ' and its own derivative.
            let mut p = 0.0;
            let mut dp = 0.0;
            for k in (1..NC).rev() {
                dp = dp * q + p;
                p = p * q + k as f64 * c[k];
            }
            (p, dp)
        });
        ser.eval(3, q).0.abs()
    }

    /// `(x, penetration δ)` (m) at time `t` (s) in the step.
    pub fn sample(&self, t: f64) -> (f64, f64) {
        let target = t - self.t_onset;
        let (a, b) = (self.y0[6] - target, self.y1[6] - target);
        let ser = self.ser();
        let q = if a >= 0.0 {
            0.0
        } else if b <= 0.0 {
            self.h
        } else {
            root_in(self.h, a, b, |q| {
                let (v, d) = ser.eval(6, q);
                (v - target, d)
            })
        };
        let sg = ser.eval(2, q).0;
        (ser.eval(0, q).0, sg * sg)
    }
}

/// Sees every accepted step of a contact integration.
pub(crate) trait Observer {
    fn step(&mut self, span: &Span<'_>);
}

impl<F: FnMut(&Span<'_>)> Observer for F {
    #[inline(always)]
    fn step(&mut self, span: &Span<'_>) {
        self(span);
    }
}

/// The observer that sees nothing ([`super::contact::Unobserved`]) sees no Sundman step
/// either.
impl Observer for super::contact::Unobserved {
    #[inline(always)]
    fn step(&mut self, _: &Span<'_>) {}
}

/// Where and how a contact integration ended (the peak penetration located on the step's
/// series).
#[cfg(feature = "research")]
pub(crate) type End = super::contact::ContactEnd<Resume>;

/// A contact in the Sundman form cut by its time limit, as it stood, in what the Taylor and
/// DOP853 schemes both carry on: wall `s`, error scales `sc`, onset time `t_onset` (s), state
/// `y`, peak penetration so far `pen` (m) and the next step `h` (θ units).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Paused {
    pub s: f64,
    pub sc: [f64; 7],
    pub t_onset: f64,
    pub y: Y,
    pub pen: f64,
    pub h: f64,
}

/// A contact cut by its time limit, as it stood: the shared part and the clamp's state.
#[cfg(feature = "research")]
#[derive(Debug, Clone, Copy)]
pub(crate) struct Resume {
    at: Paused,
    clamped: bool,
    switches: usize,
}

/// Clamp switches located exactly per contact (see `contact.rs`); past them the clamp's state
/// is taken at each step's start.
#[cfg(feature = "research")]
const MAX_SWITCHES: usize = 16;

#[cfg(feature = "research")]
struct Integration<'a, L, O> {
    sys: &'a Sys,
    load: L,
    s: f64,
    sc: [f64; 7],
    t_onset: f64,
    t_limit: f64,
    y: Y,
    clamped: bool,
    switches: usize,
    pen: f64,
    /// The last step (θ units), the next one's first guess.
    h: f64,
    obs: O,
}

/// A contact's start in the Sundman form, shared by the Taylor and DOP853 schemes: the peak
/// approach α_max (m, Eq 5) and the Hertz duration τ (s) at the incoming speed u0 = |δ'|, the
/// error scales in the order of [`Y`], and the state `[x, x', σ = 0, δ', 0, 0, 0]`.
pub(crate) struct Onset {
    pub amax: f64,
    pub tau: f64,
    pub sc: [f64; 7],
    pub y: Y,
}

impl Onset {
    /// The contact's length in θ (√m·s/m units, σ·θ being time), about `1.9·τ/√α_max`: the
    /// integral of `dt/√δ` over the Hertz contact's half sine. The fast schemes size their steps
    /// from it.
    pub fn theta_length(&self) -> f64 {
        1.9 * self.tau / self.amax.sqrt()
    }
}

/// The [`Onset`] of a contact from `y0 = [x, x', 0, u0, 0, 0]`.
pub(crate) fn onset(sys: &Sys, y0: &State) -> Onset {
    let u0 = y0[3].abs().max(1e-12);
    let amax = peak_approach(u0, sys.kstar, sys.k_hz);
    let tau = contact_duration(amax, u0);
    let e_sc = 0.5 * u0 * u0 / sys.kstar;
    let sc = [2.0 * sys.half_gap + y0[0].abs(), y0[1].abs() + u0, amax.sqrt(), u0, e_sc, e_sc, tau];
    let y = Y::from([y0[0], y0[1], 0.0, y0[3], 0.0, 0.0, 0.0]);
    Onset { amax, tau, sc, y }
}

/// Integrates one contact at wall `s` from `y0 = [x, x', 0, u0, 0, 0]` (u0 > 0) at time `t0`
/// until the exit, the time limit `t_limit` or the step budget.
#[cfg(feature = "research")]
pub(crate) fn integrate<L: Load>(start: ContactStart<'_, L>, budget: &mut usize, obs: impl Observer) -> End {
    let ContactStart { sys, load, s, t0, y0, t_limit, .. } = start;
    let Onset { amax, tau, sc, y } = onset(sys, &y0);
    // The contact's length in θ: about 1.9·τ/√α_max (the integral of dt/√δ over a half sine).
    let h = 0.3 * tau / amax.sqrt();
    let it = Integration { sys, load, s, sc, t_onset: t0, t_limit, y, clamped: false, switches: 0, pen: 0.0, h, obs };
    it.run(budget)
}

/// Carries on a contact cut by its time limit over the stretch `at`.
#[cfg(feature = "research")]
pub(crate) fn resume<L: Load>(at: Stretch<'_, L>, r: &Resume, budget: &mut usize, obs: impl Observer) -> End {
    let Stretch { sys, load, t_limit } = at;
    let Paused { s, sc, t_onset, y, pen, h } = r.at;
    let (clamped, switches) = (r.clamped, r.switches);
    let it = Integration { sys, load, s, sc, t_onset, t_limit, y, clamped, switches, pen, h, obs };
    it.run(budget)
}

/// What ends a step early.
#[cfg(feature = "research")]
#[derive(Clone, Copy, PartialEq)]
enum Cut {
    Exit,
    Limit,
    Switch,
}

#[cfg(feature = "research")]
impl<L: Load, O: Observer> Integration<'_, L, O> {
    fn run(mut self, budget: &mut usize) -> End {
        let tau_lim = self.t_limit - self.t_onset;
        if self.y[6] >= tau_lim {
            return self.end(ContactOutcome::EndOfRun);
        }
        let nt = self.sys.no_tension && self.sys.c1 > 0.0;
        // TOL^(1/ORDER): the step as a fraction of the radius of convergence.
        let lam = step_fraction();
        loop {
            if *budget < STEP_COST {
                *budget = 0;
                return self.end(ContactOutcome::WorkCap);
            }
            *budget -= STEP_COST;
            if nt && self.switches >= MAX_SWITCHES {
                // Past the located switches the clamp follows the bracket at the step's start.
                let raw = self.sys.k_hz * self.y[2].powi(3) + self.sys.c1 * self.y[3];
                self.clamped = raw < 0.0;
            }
            let ser = Series::expand(self.sys, &self.load, self.s, self.t_onset, &self.y, self.clamped);
            let h = ser.step_size(&self.sc, self.h, lam);
            self.h = h;
            if !(h > 0.0 && h.is_finite()) {
                return self.end(ContactOutcome::WorkCap);
            }
            // The earliest of the events inside [0, h].
            let mut cut: Option<(f64, Cut)> = None;
            let mut consider = |q: f64, c: Cut| {
                if cut.is_none_or(|(b, _)| q < b) {
                    cut = Some((q, c));
                }
            };
            let sg1 = ser.eval(2, h).0;
            if sg1 <= 0.0 {
                consider(root_in(h, self.y[2], sg1, |q| ser.eval(2, q)), Cut::Exit);
            }
            let tt1 = ser.eval(6, h).0;
            if tt1 >= tau_lim {
                let a = self.y[6] - tau_lim;
                consider(
                    root_in(h, a, tt1 - tau_lim, |q| {
                        let (v, d) = ser.eval(6, q);
                        (v - tau_lim, d)
                    }),
                    Cut::Limit,
                );
            }
            if nt && self.switches < MAX_SWITCHES {
                let (r0, r1) = (ser.raw[0], horner(&ser.raw, h).0);
                if r0 != 0.0 && (r0 > 0.0) != (r1 > 0.0) {
                    consider(root_in(h, r0, r1, |q| horner(&ser.raw, q)), Cut::Switch);
                }
            }
            let q = cut.map_or(h, |(q, _)| q);
            let mut yn = ser.state(q);
            match cut.map(|(_, c)| c) {
                Some(Cut::Exit) => yn[2] = 0.0,
                Some(Cut::Limit) => yn[6] = tau_lim,
                _ => {}
            }
            self.advance(&ser, q, yn);
            match cut.map(|(_, c)| c) {
                Some(Cut::Exit) => return self.end(ContactOutcome::Separated),
                Some(Cut::Limit) => return self.end(ContactOutcome::EndOfRun),
                Some(Cut::Switch) => {
                    self.clamped = !self.clamped;
                    self.switches += 1;
                }
                None => {}
            }
        }
    }

    /// Moves to `yn`, the end of an accepted step of length `h` on `ser`, showing it to the
    /// observer, and notes the peak penetration inside it.
    #[inline(always)]
    fn advance(&mut self, ser: &Series, h: f64, yn: Y) {
        if self.y[3] > 0.0 && yn[3] <= 0.0 {
            let q = root_in(h, self.y[3], yn[3], |q| ser.eval(3, q));
            let sg = ser.eval(2, q).0.max(self.y[2]).max(yn[2]);
            self.pen = self.pen.max(sg * sg);
        }
        self.pen = self.pen.max(yn[2] * yn[2]);
        let du = (ser.c[3][1], ser.eval(3, h).1);
        let span = Span::new(self.t_onset, h, Dense::Ready(ser), &self.y, &yn, du);
        self.obs.step(&span);
        self.y = yn;
    }

    fn end(&self, outcome: ContactOutcome) -> End {
        let resume = (outcome == ContactOutcome::EndOfRun).then_some(Resume {
            at: Paused { s: self.s, sc: self.sc, t_onset: self.t_onset, y: self.y, pen: self.pen, h: self.h },
            clamped: self.clamped,
            switches: self.switches,
        });
        ended(&self.y, (self.t_onset, self.t_limit), self.pen, outcome, resume)
    }
}

#[cfg(test)]
mod tests;
