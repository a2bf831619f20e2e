//! The fast in-contact integrator of the event solver: paper Eq 26 in the Sundman form of
//! [`super::sundman`] (`σ = √δ` against `θ`, `dt = σ·dθ`), integrated by the explicit
//! Runge–Kutta pair DOP853 of order 8 with its dense output of order 7 (docs/model.md §11).
//!
//! The Sundman form makes the motion analytic across the onset and the release (every
//! right-hand side is a polynomial in the state), which is what a method of high order needs
//! to take long steps: about 21 steps a contact on the Fig 9 design, against the reference's
//! 60 steps of order 5 in `t` (where the Hertz law's `δ^{3/2}` costs the order at both ends).
//! A Runge–Kutta stage of this form is a handful of products, much cheaper than the Taylor
//! scheme's Cauchy products, so the fewer steps pay.
//!
//! The state is `[x, x', σ, δ', (cos φ, sin φ)]` (m, m/s, √m, m/s; the force's phase `φ` only
//! under a [`Load`], as two more polynomial equations `d cos φ/dθ = −Ω·σ·sin φ`, `d sin φ/dθ =
//! Ω·σ·cos φ`), with three quadratures riding along `[E_contact, E_viscous, t − t_onset]`
//! (J, J, s) whose rates do not feed back. Each accepted step's dense output is built only when
//! the step holds something to locate (the release, the time limit, the peak penetration, a
//! maximum of `x`, an extremum of `|z'|`, a history sample): three more stages, turned into the
//! same polynomials in θ the Taylor scheme's steps are ([`Span`]), so the recorder and the event
//! search are shared. The dense output is of order 7 with a local error below the tolerance,
//! and every rate but `dσ/dθ` carries a factor σ, so the state at the release (a simple root of
//! σ) does not depend on where inside the step that root is placed to first order.
//!
//! Written by hand rather than taken from an ODE crate for the reasons of [`super::contact`]:
//! the events, the shared step budget and the quadratures kept out of the stages.

use std::cell::OnceCell;

#[cfg(feature = "research")]
use super::contact::ContactStart;
use super::contact::{ContactOutcome, Load, Stretch, Sys};
use super::dop853_tableau as tab;
use super::sundman::{self, root_in, step_end, Dense, Observer, Paused, Rhs, Series, Span, NC, Y};

/// Relative tolerance of a step on the contact's own scales (positions, speeds, √ of the peak
/// penetration, the relative kinetic energy, the Hertz duration). Chosen so that the release
/// speeds agree with the reference's to its own accuracy (`damper::dop853` unit tests,
/// tests/it/contact_sundman.rs, docs/model.md §11).
pub(crate) const RTOL: f64 = 3e-10;

/// What one step (accepted or not) is charged against the run's in-contact step budget
/// ([`super::CONTACT_STEP_CAP`], counted in the reference's Dormand–Prince steps): about the
/// steps of the reference it replaces, so the cap keeps its meaning.
pub(crate) const STEP_COST: usize = 4;

/// Steps a Hertz contact is cut into at most (θ units: the contact's length over this), while
/// the error estimate allows: the estimate of DOP853 swings by a factor of ten from one step to
/// the next on this motion, so a controller that chases it rejects one step in four; the
/// motion in θ is smooth and nearly uniform, so even steps cost less.
pub(crate) const STEPS_NOMINAL: f64 = 20.0;

/// The step-size controller's safety factor and bounds on the change of step (Hairer's
/// `dop853.f`: 0.9, 1/3 and 6).
const SAFETY: f64 = 0.9;
const FAC_MIN: f64 = 1.0 / 3.0;
const FAC_MAX: f64 = 6.0;

/// `x^{1/8}` by three square roots (the step-size controller's exponent for order 8).
#[inline(always)]
fn eighth_root(x: f64) -> f64 {
    x.sqrt().sqrt().sqrt()
}

/// The rates of the motion and of the quadratures at the motion `m` (into `r`, `q`).
#[inline(always)]
fn rate<L: Load, const N: usize>(rhs: &Rhs<'_>, m: &[f64; N], r: &mut [f64; N], q: &mut [f64; 3]) {
    rhs.motion::<L, N, N>(m, r);
    *q = rhs.quad(m);
}

/// Where and how a contact integration ended (the peak penetration located on the step's
/// dense output).
pub(crate) type End = super::contact::ContactEnd<Resume>;

/// A contact cut by its time limit, as it stood: the part every Sundman scheme carries on, the
/// nominal step (θ units) and whether a step ending with σ > 0 has been accepted.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Resume {
    at: Paused,
    h_nom: f64,
    had_pos: bool,
}

impl Resume {
    /// A contact taken over mid-way from another Sundman scheme (the Adams scheme's hand-over,
    /// [`super::adams`]), its step `at.h` the nominal one.
    pub(crate) fn taken_over(at: Paused) -> Self {
        Resume { at, h_nom: at.h, had_pos: true }
    }
}

/// One contact being integrated. `N` is 4 without a force, 6 with one (the phase's cosine
/// and sine).
struct Integration<'a, L, O, const N: usize> {
    rhs: Rhs<'a>,
    load: std::marker::PhantomData<L>,
    /// Error scales in the order of [`Y`]; the phase's are 1.
    sc: [f64; 7],
    t_onset: f64,
    t_limit: f64,
    /// The motion and the quadratures, and their rates.
    m: [f64; N],
    q: [f64; 3],
    k0: [f64; N],
    kq0: [f64; 3],
    pen: f64,
    /// The next trial step and the nominal step (θ units).
    h: f64,
    h_nom: f64,
    /// A step ending with σ > 0 has been accepted (the contact is real).
    had_pos: bool,
    obs: O,
}

/// Integrates one contact at wall `s` from `y0 = [x, x', 0, u0, 0, 0]` (u0 > 0) at time `t0`
/// until the exit, the time limit `t_limit` or the step budget.
#[cfg(feature = "research")]
pub(crate) fn integrate<L: Load>(start: ContactStart<'_, L>, budget: &mut usize, obs: impl Observer) -> End {
    use super::sundman::{onset, Onset};
    let ContactStart { sys, load, s, t0, y0, t_limit, .. } = start;
    let start = onset(sys, &y0);
    let h = start.theta_length() / STEPS_NOMINAL;
    let Onset { sc, y, .. } = start;
    let r = Resume { at: Paused { s, sc, t_onset: t0, y, pen: 0.0, h }, h_nom: h, had_pos: false };
    go(sys, load, &r, t_limit, budget, obs)
}

/// Carries on a contact cut by its time limit over the stretch `at`.
pub(crate) fn resume<L: Load>(at: Stretch<'_, L>, r: &Resume, budget: &mut usize, obs: impl Observer) -> End {
    go(at.sys, at.load, r, at.t_limit, budget, obs)
}

/// The integration from `r`, with the state's size chosen by the load.
fn go<L: Load, O: Observer>(sys: &Sys, load: L, r: &Resume, t_limit: f64, budget: &mut usize, obs: O) -> End {
    if L::ON {
        Integration::<L, O, 6>::new(sys, load, r, t_limit, obs).run(budget)
    } else {
        Integration::<L, O, 4>::new(sys, load, r, t_limit, obs).run(budget)
    }
}

impl<'a, L: Load, O: Observer, const N: usize> Integration<'a, L, O, N> {
    fn new(sys: &'a Sys, load: L, r: &Resume, t_limit: f64, obs: O) -> Self {
        let Paused { s, sc, t_onset, y, pen, h } = r.at;
        let (f, omega, phi) = load.harmonic(t_onset + y[6]);
        let rhs = Rhs { sys, s, f, omega };
        let mut m = [0.0; N];
        m[..4].copy_from_slice(&[y[0], y[1], y[2], y[3]]);
        if L::ON {
            let (sp, cp) = phi.sin_cos();
            m[4] = cp;
            m[5] = sp;
        }
        let q = [y[4], y[5], y[6]];
        let (mut k0, mut kq0) = ([0.0; N], [0.0; 3]);
        rate::<L, N>(&rhs, &m, &mut k0, &mut kq0);
        Integration {
            rhs,
            load: std::marker::PhantomData,
            sc,
            t_onset,
            t_limit,
            m,
            q,
            k0,
            kq0,
            pen,
            h,
            h_nom: r.h_nom,
            had_pos: r.had_pos,
            obs,
        }
    }

    /// The state in the order of [`Y`].
    #[inline(always)]
    fn y_of(m: &[f64; N], q: &[f64; 3]) -> Y {
        Y::from([m[0], m[1], m[2], m[3], q[0], q[1], q[2]])
    }

    /// The error norm of a step of length `h` from `m` to `mn`: DOP853's blended estimate
    /// `h·E5/√(E5 + 0.01·E3)` (Hairer's `dop853.f`), with `E5`, `E3` the mean squares of the
    /// two estimates over the motion's components, each over `RTOL·(scale + |value|)`. The
    /// quadratures (the energies and the time) are left out: their rates are smooth functions
    /// of the motion alone, so their errors follow the motion's.
    #[inline(always)]
    fn error(&self, h: f64, k: &[[f64; N]; 13], mn: &[f64; N]) -> f64 {
        let (e5, e3) = (tab::weights_e5(k), tab::weights_e3(k));
        let (mut s5, mut s3) = (0.0, 0.0);
        for i in 0..N {
            let sc = if i < 4 { self.sc[i] } else { 1.0 };
            let w = 1.0 / (RTOL * (sc + self.m[i].abs().max(mn[i].abs())));
            s5 += (e5[i] * w) * (e5[i] * w);
            s3 += (e3[i] * w) * (e3[i] * w);
        }
        let den = s5 + 0.01 * s3;
        let err = if den > 0.0 { h.abs() * s5 / (den * N as f64).sqrt() } else { 0.0 };
        // An estimate that is not a number makes the step fail.
        if err.is_finite() && mn.iter().all(|v| v.is_finite()) {
            err
        } else {
            f64::INFINITY
        }
    }

    /// One trial step of length `h` from the state where the contact stands: the stages'
    /// rates into `k`, `kq` (`k[0]`, `kq[0]` the rates at the start), the state and the
    /// quadratures at its end and its error norm. Kept out of line: the stages' straight-line
    /// code is compiled on its own, apart from the events' and the observer's.
    #[inline(never)]
    fn trial(&self, h: f64, k: &mut [[f64; N]; 13], kq: &mut [[f64; 3]; 13]) -> ([f64; N], [f64; 3], f64) {
        let rhs = self.rhs;
        k[0] = self.k0;
        kq[0] = self.kq0;
        tab::stages(&self.m, h, k, kq, |i, st, r, qq| {
            rhs.motion::<L, N, N>(st, r);
            if i >= 5 {
                *qq = rhs.quad(st);
            }
        });
        let (db, dbq) = (tab::weights_b(k), tab::weights_b(kq));
        let mut mn = self.m;
        for (a, d) in mn.iter_mut().zip(db) {
            *a += h * d;
        }
        let mut qn = self.q;
        for (a, d) in qn.iter_mut().zip(dbq) {
            *a += h * d;
        }
        let err = self.error(h, k, &mn);
        (mn, qn, err)
    }

    fn run(mut self, budget: &mut usize) -> End {
        let tau_lim = self.t_limit - self.t_onset;
        if self.q[2] >= tau_lim {
            return self.end(ContactOutcome::EndOfRun);
        }
        let rhs = self.rhs;
        let h_floor = 1e-14 * self.sc[6] / self.sc[2].max(1e-300);
        let mut k = [[0.0; N]; 13];
        let mut kq = [[0.0; 3]; 13];
        loop {
            if *budget < STEP_COST {
                *budget = 0;
                return self.end(ContactOutcome::WorkCap);
            }
            *budget -= STEP_COST;
            let h = self.h;
            let (mn, qn, err) = self.trial(h, &mut k, &mut kq);
            // (`err` is a number or +∞: an estimate that was not a number was made +∞.)
            if err > 1.0 {
                let fac = if err.is_finite() { (SAFETY * eighth_root(1.0 / err)).max(FAC_MIN) } else { 0.25 };
                self.h *= fac;
                continue;
            }
            if !self.had_pos && mn[2] <= 0.0 {
                // The first step spanned the whole (tiny) contact: shorten it, or call it a graze.
                if h <= h_floor {
                    return self.end(ContactOutcome::Grazed);
                }
                self.h *= 0.25;
                continue;
            }
            self.had_pos = true;
            {
                let (kk, qq) = (&mut k[12], &mut kq[12]);
                rate::<L, N>(&rhs, &mn, kk, qq);
            }
            let fac = (SAFETY * eighth_root(1.0 / err.max(1e-30))).clamp(FAC_MIN, FAC_MAX);
            if let Some(outcome) = self.accept(h, &k, &kq, mn, qn, tau_lim) {
                return self.end(outcome);
            }
            // Up to the nominal step unless the estimate is far below the tolerance.
            self.h = if err > 1e-3 { (h * fac).min(self.h_nom.max(h)) } else { h * fac };
        }
    }

    /// An accepted step of length `h` to `(mn, qn)` with stage rates `k`, `kq` (`k[12]` the
    /// rate at its end): the release or the time limit inside it cut it short; the peak
    /// penetration is noted and the observer shown the step. `Some` when the contact is over.
    #[allow(clippy::too_many_arguments)]
    fn accept(
        &mut self,
        h: f64,
        k: &[[f64; N]; 13],
        kq: &[[f64; 3]; 13],
        mn: [f64; N],
        qn: [f64; 3],
        tau_lim: f64,
    ) -> Option<ContactOutcome> {
        let y0 = Self::y_of(&self.m, &self.q);
        let y1 = Self::y_of(&mn, &qn);
        let (rhs, m0, q0) = (self.rhs, self.m, self.q);
        let cell = OnceCell::new();
        let build = || Self::dense(rhs, (&m0, &q0), h, k, kq, (&mn, &qn));
        let ser = || cell.get_or_init(build);
        let cut = step_end(h, &y0, &y1, tau_lim, ser);
        let (he, ye, du1) = cut.map_or((h, y1, k[12][3]), |(q, ye, du, _)| (q, ye, du));
        if y0[3] > 0.0 && ye[3] <= 0.0 {
            let s = ser();
            let q = root_in(he, y0[3], ye[3], |q| s.eval(3, q));
            let sg = s.eval(2, q).0.max(y0[2]).max(ye[2]);
            self.pen = self.pen.max(sg * sg);
        }
        self.pen = self.pen.max(ye[2] * ye[2]);
        let span = Span::new(self.t_onset, he, Dense::Lazy(&cell, &build), &y0, &ye, (self.k0[3], du1));
        self.obs.step(&span);
        if let Some((_, _, _, outcome)) = cut {
            self.m[..4].copy_from_slice(&[ye[0], ye[1], ye[2], ye[3]]);
            self.q = [ye[4], ye[5], ye[6]];
            Some(outcome)
        } else {
            self.m = mn;
            self.q = qn;
            self.k0 = k[12];
            self.kq0 = kq[12];
            None
        }
    }

    /// The dense output of the step of length `h` (order 7; Hairer's `dop853.f`) as polynomials
    /// in `θ − θ_0` in the order of [`Y`]: three more stages, then the interpolant
    /// `y0 + x·(F0 + (1−x)·(F1 + x·(F2 + (1−x)·(F3 + x·(F4 + (1−x)·(F5 + x·F6))))))`, `x = θ/h`,
    /// multiplied out.
    fn dense(
        rhs: Rhs<'_>,
        (m0, q0): (&[f64; N], &[f64; 3]),
        h: f64,
        k: &[[f64; N]; 13],
        kq: &[[f64; 3]; 13],
        (mn, qn): (&[f64; N], &[f64; 3]),
    ) -> Series {
        // The three more stages' rates, apart from the step's (which are only read).
        let (mut kx, mut kqx) = ([[0.0; N]; 3], [[0.0; 3]; 3]);
        tab::dense_stages(m0, h, k, &mut kx, &mut kqx, |_, st, r, qq| rate::<L, N>(&rhs, st, r, qq));
        let d = [tab::weights_d0(k, &kx), tab::weights_d1(k, &kx), tab::weights_d2(k, &kx), tab::weights_d3(k, &kx)];
        let dq = [
            tab::weights_d0(kq, &kqx),
            tab::weights_d1(kq, &kqx),
            tab::weights_d2(kq, &kqx),
            tab::weights_d3(kq, &kqx),
        ];
        // (y0, y1, f0, f1, D·K) of component i of Y.
        let part = |i: usize| -> (f64, f64, f64, f64, [f64; 4]) {
            if i < 4 {
                (m0[i], mn[i], k[0][i], k[12][i], [d[0][i], d[1][i], d[2][i], d[3][i]])
            } else {
                let j = i - 4;
                (q0[j], qn[j], kq[0][j], kq[12][j], [dq[0][j], dq[1][j], dq[2][j], dq[3][j]])
            }
        };
        let mut c = [[0.0; NC]; 7];
        for (i, ci) in c.iter_mut().enumerate() {
            let (a, b, f0, f1, dk) = part(i);
            let dy = b - a;
            let f = [dy, h * f0 - dy, 2.0 * dy - h * (f0 + f1), h * dk[0], h * dk[1], h * dk[2], h * dk[3]];
            // Horner in the nested form, alternating factors x and (1 − x).
            let mut p = [0.0; 8];
            for (n, fi) in f.iter().rev().enumerate() {
                p[0] += fi;
                if n % 2 == 0 {
                    for j in (1..8).rev() {
                        p[j] = p[j - 1];
                    }
                    p[0] = 0.0;
                } else {
                    for j in (1..8).rev() {
                        p[j] -= p[j - 1];
                    }
                }
            }
            p[0] += a;
            // From x = θ/h to θ.
            let mut scale = 1.0;
            for (cj, pj) in ci.iter_mut().zip(p) {
                *cj = pj * scale;
                scale /= h;
            }
        }
        Series { c, raw: [0.0; NC] }
    }

    fn end(&self, outcome: ContactOutcome) -> End {
        let y = Self::y_of(&self.m, &self.q);
        let resume = (outcome == ContactOutcome::EndOfRun).then_some(Resume {
            at: Paused { s: self.rhs.s, sc: self.sc, t_onset: self.t_onset, y, pen: self.pen, h: self.h },
            h_nom: self.h_nom,
            had_pos: self.had_pos,
        });
        sundman::ended(&y, (self.t_onset, self.t_limit), self.pen, outcome, resume)
    }
}

#[cfg(test)]
mod tests {
    use super::super::contact::ContactStart;
    use super::super::contact::{State, Unobserved};
    use super::super::scheme_checks::{self, sys};
    use super::*;

    /// Isolated contacts against the reference and the Taylor scheme, at most 25 steps a
    /// contact (rejected ones included).
    #[test]
    fn isolated_contacts_match_the_reference_and_the_taylor_scheme() {
        scheme_checks::isolated_contacts(25 * STEP_COST, |s, y0, t_limit, left| {
            integrate(ContactStart::free(s, y0, t_limit), left, Unobserved)
        });
    }

    /// A contact cut by its time limit ends exactly there and carries on as if never cut (the
    /// cut state comes from the dense output, of order 7, then new steps).
    #[test]
    fn a_cut_contact_resumes_where_it_stopped() {
        scheme_checks::cut_contacts(
            &[0.1, 0.5, 0.93],
            [1e-9, 1e-9, 1e-8],
            |s, y0, t_limit, left| integrate(ContactStart::free(s, y0, t_limit), left, Unobserved),
            |s, r, left| resume(Stretch::free(s, 1.0), r, left, Unobserved),
        );
    }

    /// The bound that spares building a step's polynomials for an extremum of `|δ'|` that cannot
    /// raise the run's largest `|z'|` (`Span::speed_extremum`) holds: every extremum located is
    /// still located with the floor just below it. Strongly damped contacts (the tension near
    /// the release makes `|δ'|` peak inside them), with and without the main spring.
    #[test]
    fn the_speed_extremum_bound_never_hides_an_extremum() {
        let mut found = 0;
        for (c1, k, u0) in [(20.0, 0.0, 1.4), (60.0, 500.0, 0.3), (60.0, 500.0, 3.0), (200.0, 0.0, 0.5)] {
            let s = sys(c1, k);
            let y0 = State::new(0.0, 0.1, 0.0, u0, 0.0, 0.0);
            let mut left = 100_000;
            let obs = |sp: &Span<'_>| {
                if let Some(e) = sp.speed_extremum(0.0) {
                    found += 1;
                    assert_eq!(sp.speed_extremum(e * (1.0 - 1e-12)), Some(e), "c1 {c1}, u0 {u0}");
                }
            };
            let end = integrate(ContactStart::free(&s, y0, 1.0), &mut left, obs);
            assert_eq!(end.outcome, ContactOutcome::Separated);
        }
        assert!(found >= 4, "{found} extrema");
    }

    #[test]
    fn the_step_budget_stops_a_contact() {
        let s = sys(20.0, 0.0);
        let y0 = State::new(0.0, 0.0, 0.0, 1.4, 0.0, 0.0);
        let mut left = 3 * STEP_COST + 1;
        let end = integrate(ContactStart::free(&s, y0, 1.0), &mut left, Unobserved);
        assert_eq!(end.outcome, ContactOutcome::WorkCap);
        assert_eq!(left, 0);
        assert!(end.y[2] > 0.0);
    }
}
