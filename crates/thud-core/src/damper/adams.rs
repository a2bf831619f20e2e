//! The multistep in-contact integrator of the event solver: paper Eq 26 in the Sundman form of
//! [`super::sundman`] (`σ = √δ` against `θ`, `dt = σ·dθ`), integrated by an Adams–Bashforth–
//! Moulton pair of order 12/13 on a fixed step in θ (docs/model.md §11).
//!
//! In the Sundman form every right-hand side is a polynomial in the state, so the motion is
//! analytic across the onset and the release, and in θ a Hertz contact is a smooth, nearly
//! uniform hump: the case a multistep method of high order is made for. A step is two
//! evaluations of the right-hand side (predict, evaluate, correct, evaluate) against twelve for
//! DOP853 and six for the reference's Dormand–Prince; about 58 even steps (the estimated length
//! over [`STEPS_NOMINAL`]) span a Fig 9 contact to ~1e-10 of its speed.
//!
//! A multistep method needs the rates at the twelve nodes before its first step. They come from
//! the Taylor series of the motion at the contact's onset (the recurrences of
//! [`super::sundman`], with fewer products): that series carries the first [`START`] steps of
//! the contact itself (its events located on it as in the Taylor scheme), and gives the rates at
//! the nodes `START − j` steps from the onset, `j = 0 … 11`, all within the series' reach (the
//! nodes before the onset lie on the analytic continuation of the motion, which is all the
//! interpolation behind the method asks). The step is `1/64` of the contact's length in θ
//! estimated from the Hertz law, shortened when the series' own tail asks for it.
//!
//! Each step is watched by the difference of corrector and predictor (Milne's device), which
//! bounds the corrector's error. Where the motion is not the hump the even steps are sized for —
//! a difference above [`RTOL`] of the contact's scales, or far below it for [`CALM_STEPS`]
//! steps (a ball pressed against the wall by the main mass, whose contact lasts long and moves
//! slowly), or a series that reaches less than half a step — DOP853 ([`super::dop853`]), whose
//! steps adapt, carries the contact on from the last accepted state. So does it a contact cut
//! by its time limit (the end of a stretch of a run): it needs no history to carry on.
//!
//! Each accepted step's dense output, the corrector's polynomial (degree 13 in θ), is built only
//! when the step holds something to locate (the time limit, a maximum of `x`, an extremum of
//! `|z'|`, a history sample), as the same polynomials in θ the other Sundman schemes give
//! ([`Span`]), so the recorder and the event search are shared. The release, nearly every
//! contact's last step, needs only σ's polynomial and the state at one point ([`release`]). The
//! peak penetration needs none: σ is flat there, and the quintic Hermite interpolant of σ from
//! the step's ends gives it.
//!
//! Written by hand rather than taken from an ODE crate for the reasons of [`super::contact`]:
//! the events, the shared step budget, the start from a series and the quadratures kept out of
//! the predictor.

use std::cell::OnceCell;

use super::adams_tableau::{AB, AM, BASIS, K};
use super::contact::{ContactOutcome, ContactStart, Load, Stretch, Sys};
use super::dop853;
use super::sundman::{self, onset, root_in, step_end, Dense, Observer, Onset, Paused, Rhs, Series, Span, NC, ORDER, Y};

/// Even steps a Hertz contact is cut into (θ units: the contact's estimated length over this).
/// Chosen so that the release speeds agree with the Taylor scheme's to ~1e-10 of the speed
/// (`damper::adams` unit tests, tests/it/contact_sundman.rs, docs/model.md §11).
pub(crate) const STEPS_NOMINAL: f64 = 64.0;

/// Steps of the contact's start carried by the Taylor series (the history's nodes then lie
/// within `START` steps either side of the series' centre).
const START: usize = 6;

/// Largest difference of corrector and predictor a step may show, relative to the contact's
/// scales (the components' scale plus their size): it bounds the corrector's local error, which
/// is many times smaller.
pub(crate) const RTOL: f64 = 1e-7;

/// How far below the tolerance the corrector–predictor difference must stay, for
/// [`CALM_STEPS`] steps, for the motion to count as slowed down: a step twice as long would
/// still keep it below a quarter of the tolerance (the difference grows like the step's 13th
/// power, `2^13·CALM = 1/4`).
const CALM: f64 = 1.0 / (4.0 * 8192.0);
const CALM_STEPS: usize = 2 * K;

/// What a start (a Taylor series and the history) is charged against the run's in-contact step
/// budget ([`super::CONTACT_STEP_CAP`], counted in the reference's Dormand–Prince steps).
pub(crate) const START_COST: usize = sundman::STEP_COST;

/// What one step is charged: two evaluations against the reference's six, rounded up.
pub(crate) const STEP_COST: usize = 1;

/// The rates in θ of the state row `m` (the motion in `0..N`, the quadratures in `N..N + 3`)
/// into `r`, in the same places.
#[inline(always)]
fn rate<L: Load, const N: usize, const W: usize>(rhs: &Rhs<'_>, m: &[f64; W], r: &mut [f64; W]) {
    rhs.motion::<L, N, W>(m, r);
    let [c, v, t] = rhs.quad(m);
    (r[N], r[N + 1], r[N + 2]) = (c, v, t);
}

/// Where and how a contact integration ended: a contact cut by its time limit is carried on
/// by DOP853 ([`dop853::resume`]).
pub(crate) type End = super::contact::ContactEnd<dop853::Resume>;

/// Where an integration by this scheme starts (always at a contact's onset): wall `s`, error
/// scales, onset time (s), state and the contact's estimated length in θ
/// ([`Onset::theta_length`]), which sizes the steps.
#[derive(Debug, Clone, Copy)]
struct Start {
    s: f64,
    sc: [f64; 7],
    t_onset: f64,
    y: Y,
    length: f64,
}

/// How a run of Adams steps ended.
enum Next {
    /// The contact is over.
    Done(ContactOutcome),
    /// The motion is no longer the Hertz hump the even steps are sized for: a step's error was
    /// too large, or it has been far below the tolerance for a while (a contact whose motion
    /// has slowed down: a ball pressed against the wall by the main mass). DOP853, whose steps
    /// adapt, carries the contact on from the last accepted state.
    HandOver,
}

/// Integrates one contact at wall `s` from `y0 = [x, x', 0, u0, 0, 0]` (u0 > 0) at time `t0`
/// until the exit, the time limit `t_limit` or the step budget.
pub(crate) fn integrate<L: Load>(start: ContactStart<'_, L>, budget: &mut usize, obs: impl Observer) -> End {
    let ContactStart { sys, load, s, t0, y0, t_limit, .. } = start;
    let start = onset(sys, &y0);
    let length = start.theta_length();
    let Onset { sc, y, .. } = start;
    go(sys, load, &Start { s, sc, t_onset: t0, y, length }, t_limit, budget, obs)
}

/// The integration from `r`, with the motion's size chosen by the load.
fn go<L: Load, O: Observer>(sys: &Sys, load: L, r: &Start, t_limit: f64, budget: &mut usize, obs: O) -> End {
    if L::ON {
        Integration::<L, O, 6, 10>::new(sys, load, r, t_limit, obs).run(budget)
    } else {
        Integration::<L, O, 4, 8>::new(sys, load, r, t_limit, obs).run(budget)
    }
}

/// One contact being integrated. `N` is 4 without a force, 6 with one (the phase's cosine and
/// sine); a state row holds the motion in `0..N`, the quadratures `[E_contact, E_viscous, t −
/// t_onset]` in `N..N + 3` and zeros up to its width `W` (a whole number of vector registers).
struct Integration<'a, L, O, const N: usize, const W: usize> {
    sys: &'a Sys,
    load: L,
    rhs: Rhs<'a>,
    /// Error scales in the order of [`Y`].
    sc: [f64; 7],
    t_onset: f64,
    t_limit: f64,
    /// The accepted state in the order of [`Y`], and as a row (with the force's phase).
    y: Y,
    m: [f64; W],
    pen: f64,
    /// The step (θ units), and the contact's estimated length in θ.
    h: f64,
    length: f64,
    /// The rates (rows) at the last `K` nodes, twice over so that the window `[p, p + K)`
    /// holds them newest first without moving them.
    fm: [[f64; W]; 2 * K],
    p: usize,
    obs: O,
}

impl<'a, L: Load, O: Observer, const N: usize, const W: usize> Integration<'a, L, O, N, W> {
    fn new(sys: &'a Sys, load: L, r: &Start, t_limit: f64, obs: O) -> Self {
        let (f, omega, _) = load.harmonic(r.t_onset + r.y[6]);
        Integration {
            sys,
            load,
            rhs: Rhs { sys, s: r.s, f, omega },
            sc: r.sc,
            t_onset: r.t_onset,
            t_limit,
            y: r.y,
            m: [0.0; W],
            pen: 0.0,
            h: r.length / STEPS_NOMINAL,
            length: r.length,
            fm: [[0.0; W]; 2 * K],
            p: 0,
            obs,
        }
    }

    /// The row of a state `y` (with the force's phase at its time).
    #[inline(always)]
    fn motion(&self, y: &Y) -> [f64; W] {
        let mut m = [0.0; W];
        m[..4].copy_from_slice(&[y[0], y[1], y[2], y[3]]);
        m[N..N + 3].copy_from_slice(&[y[4], y[5], y[6]]);
        if L::ON {
            let (sp, cp) = self.load.harmonic(self.t_onset + y[6]).2.sin_cos();
            m[4] = cp;
            m[5] = sp;
        }
        m
    }

    fn run(mut self, budget: &mut usize) -> End {
        let tau_lim = self.t_limit - self.t_onset;
        if self.y[6] >= tau_lim {
            return self.end(ContactOutcome::EndOfRun);
        }
        if *budget < START_COST {
            *budget = 0;
            return self.end(ContactOutcome::WorkCap);
        }
        *budget -= START_COST;
        // TOL^(1/ORDER): the series' step as a fraction of its radius of convergence.
        let lam = sundman::step_fraction();
        let ser = self.series();
        // Every node of the history within the series' reach; where the series reaches less
        // than half the nominal step (not a Hertz hump there), DOP853 takes the contact. Most
        // contacts' series reach the start's steps at the nominal step already (its tail
        // within the tolerance there): then the step stays, without sizing the reach.
        let r = ser.tail_ratio(&self.sc, START as f64 * self.h, lam);
        if !(r > 0.0 && r <= 1.0) {
            let reach = ser.step_size(&self.sc, START as f64 * self.h, lam) / START as f64;
            if reach.is_nan() || reach < 0.5 * self.h {
                return self.hand_over(budget);
            }
            self.h = self.h.min(reach);
        }
        if let Some(outcome) = self.taylor_start(&ser, tau_lim) {
            return self.end(outcome);
        }
        match self.steps(budget, tau_lim) {
            Next::Done(outcome) => self.end(outcome),
            Next::HandOver => self.hand_over(budget),
        }
    }

    /// The Taylor series of the motion at the current state (θ from there), order
    /// [`ORDER`], by the recurrences of automatic differentiation with the fewest products this
    /// form allows (the same series as [`Series::expand`], which uses more): with `F = K_HZ·σ³ +
    /// c1·δ'`, `σ·F = K_HZ·(σ²)² + c1·σδ'` and `σδ' = (σ²)'`, so the rates need the products
    /// `σ²`, `(σ²)²`, `σ·a_M`, `σ·x'`, `(σδ')·δ'` and `(σx')·x'` only (and `σ·cos φ`, `σ·sin φ`
    /// under a force).
    #[allow(
        clippy::range_plus_one,
        reason = "a half-open range: `0..=n`'s iterator checks its end twice a turn and does not unroll (−4 % on the chart)"
    )]
    fn series(&self) -> Series {
        let (sys, s) = (self.sys, self.rhs.s);
        let y = &self.y;
        let z = [0.0; NC];
        // (Built in place: the series is returned without copying its seven rows.)
        let mut out = Series { c: [z; 7], raw: z };
        sundman::seed(&mut out.c, y);
        let [x, v, sg, u, ec, ev, tt] = &mut out.c;
        let (mut s2, mut sv, mut am, mut cs, mut sn) = (z, z, z, z, z);
        let mut su = z;
        if L::ON {
            let (sp, cp) = self.load.harmonic(self.t_onset + y[6]).2.sin_cos();
            cs[0] = cp;
            sn[0] = sp;
        }
        let (f, omega) = (self.rhs.f, self.rhs.omega);
        let (im, ks, khz, c1) = (sys.inv_big_m, sys.kstar, sys.k_hz, sys.c1);
        s2[0] = sg[0] * sg[0];
        for n in 0..ORDER {
            let inv = 1.0 / (n + 1) as f64;
            // σ_{n+1} from δ'_n, so that (σ²)_{n+1}, and with it (σδ')_n, are known.
            sg[n + 1] = 0.5 * u[n] * inv;
            let mut acc = 0.0;
            for j in 0..n + 2 {
                acc += sg[j] * sg[n + 1 - j];
            }
            s2[n + 1] = acc;
            su[n] = (n + 1) as f64 * s2[n + 1];
            am[n] = (-sys.c * v[n] - sys.k * x[n]) * im + if L::ON { f * cs[n] } else { 0.0 };
            let (mut s4, mut q, mut svn, mut pc, mut pv, mut pcs, mut psn) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
            for j in 0..n + 1 {
                let k = n - j;
                s4 += s2[j] * s2[k];
                q += sg[j] * am[k];
                svn += sg[j] * v[k];
                if L::ON {
                    pcs += sg[j] * cs[k];
                    psn += sg[j] * sn[k];
                }
            }
            sv[n] = svn;
            for j in 0..n + 1 {
                let k = n - j;
                pc += su[j] * u[k];
                pv += sv[j] * v[k];
            }
            // σ·F and σ·a_M.
            let p = khz * s4 + c1 * su[n];
            x[n + 1] = svn * inv;
            v[n + 1] = (q + s * im * p) * inv;
            u[n + 1] = (-ks * p - s * q) * inv;
            tt[n + 1] = sg[n] * inv;
            ec[n + 1] = c1 * pc * inv;
            ev[n + 1] = sys.c * pv * inv;
            if L::ON {
                cs[n + 1] = -omega * psn * inv;
                sn[n + 1] = omega * pcs * inv;
            }
        }
        out
    }

    /// The first [`START`] steps on the series `ser` (centred on the current state), with the
    /// release and the time limit located on it, then the history: the rates at the nodes
    /// `START − j` steps from the centre. `Some` when the contact is over.
    fn taylor_start(&mut self, ser: &Series, tau_lim: f64) -> Option<ContactOutcome> {
        let hs = START as f64 * self.h;
        let y1 = ser.state(hs);
        let cut = step_end(hs, &self.y, &y1, tau_lim, || ser);
        let (q, yn) = cut.map_or((hs, y1), |(q, ye, _, _)| (q, ye));
        let y0 = self.y;
        self.note_peak(&y0, &yn, q, |q| ser.eval(3, q), |q| ser.eval(2, q).0);
        let du = (ser.c[3][1], ser.eval(3, q).1);
        self.obs.step(&Span::new(self.t_onset, q, Dense::Ready(ser), &y0, &yn, du));
        self.y = yn;
        if let Some((_, _, _, outcome)) = cut {
            return Some(outcome);
        }
        self.m = self.motion(&yn);
        for j in 0..K {
            // The motion at the node (and its time, for the force's phase).
            let q = hs - j as f64 * self.h;
            let mj = if j == 0 {
                self.m
            } else {
                let mut node = Y::zeros();
                for i in 0..4 {
                    node[i] = ser.eval(i, q).0;
                }
                if L::ON {
                    node[6] = ser.eval(6, q).0;
                }
                self.motion(&node)
            };
            let mut r = [0.0; W];
            rate::<L, N, W>(&self.rhs, &mj, &mut r);
            self.fm[j] = r;
            self.fm[j + K] = r;
        }
        self.p = 0;
        None
    }

    /// The peak penetration inside a step from `y0` to `yn` of length `h` when δ' turns there,
    /// located on the step's polynomials (`u(q)` for δ' and its rate, `sg(q)` for σ).
    #[inline(always)]
    fn note_peak(&mut self, y0: &Y, yn: &Y, h: f64, u: impl Fn(f64) -> (f64, f64), sg: impl Fn(f64) -> f64) {
        if y0[3] > 0.0 && yn[3] <= 0.0 {
            let q = root_in(h, y0[3], yn[3], u);
            let s = sg(q).max(y0[2]).max(yn[2]);
            self.pen = self.pen.max(s * s);
        }
        self.pen = self.pen.max(yn[2] * yn[2]);
    }

    /// Adams steps from the current state and history until the contact is over or the motion
    /// is no longer the hump the steps are sized for ([`Next::HandOver`]: a step's difference
    /// above [`RTOL`], or below [`CALM`] of it for [`CALM_STEPS`] steps).
    fn steps(&mut self, budget: &mut usize, tau_lim: f64) -> Next {
        let h = self.h;
        let rhs = self.rhs;
        let mut calm = 0;
        // The history's parts of the predictor (Adams–Bashforth) and of the corrector (Adams–
        // Moulton) over all but the newest rate, oldest first. Each step adds the newest rate's
        // term to them, and works out the next step's while its own rates are evaluated: they
        // need only rates known already, so they run beside the step's chain of dependent
        // operations instead of after it. (The predictor only needs the motion: no rate
        // depends on the quadratures.) The sums are the one-pass sums over the window, term
        // for term in the same order.
        let Some(wm) = self.fm[self.p..].first_chunk::<K>() else {
            return Next::HandOver;
        };
        let (mut pm_old, mut cm_old) = older_sums::<N, W>(wm, 0);
        // The accepted row, kept here (the history holds its rates).
        let mut m = self.m;
        loop {
            if *budget < STEP_COST {
                *budget = 0;
                return Next::Done(ContactOutcome::WorkCap);
            }
            *budget -= STEP_COST;
            let p = self.p;
            // (A window of known length, so the sums unroll; `p < K` always.)
            let Some(wm) = self.fm[p..].first_chunk::<K>() else {
                return Next::HandOver;
            };
            let newest = &wm[0];
            let (mut pm, mut cm) = (pm_old, cm_old);
            for i in 0..N {
                pm[i] += AB[0] * newest[i];
            }
            for i in 0..W {
                cm[i] += AM[1] * newest[i];
            }
            let mut mp = m;
            for i in 0..N {
                mp[i] += h * pm[i];
            }
            // The next step's window is this one shifted by the rates this step adds.
            (pm_old, cm_old) = older_sums::<N, W>(wm, 1);
            // Evaluate, correct.
            let mut rp = [0.0; W];
            rate::<L, N, W>(&rhs, &mp, &mut rp);
            let mut mc = m;
            for i in 0..W {
                mc[i] += h * (cm[i] + AM[0] * rp[i]);
            }
            // Milne's device: the corrector–predictor difference bounds the step's error (a
            // difference that is not a number fails the test too).
            let (mut within, mut quiet) = (true, true);
            for i in 0..4 {
                let (d, tol) = ((mc[i] - mp[i]).abs(), RTOL * (self.sc[i] + mc[i].abs()));
                within &= d <= tol;
                quiet &= d <= CALM * tol;
            }
            if !within {
                return Next::HandOver;
            }
            calm = if quiet { calm + 1 } else { 0 };
            let mut rc = [0.0; W];
            rate::<L, N, W>(&rhs, &mc, &mut rc);
            if let Some(outcome) = self.accept(h, &rp, &mc, rc[3], tau_lim) {
                return Next::Done(outcome);
            }
            m = mc;
            // The new rates enter the history, newest first.
            let np = (p + K - 1) % K;
            self.fm[np] = rc;
            self.fm[np + K] = rc;
            self.p = np;
            if calm >= CALM_STEPS {
                return Next::HandOver;
            }
        }
    }

    /// An accepted step of length `h` to the row `mc` whose corrector used the predicted rates
    /// `rp` (`du1` the corrected state's `dδ'/dθ`): the release or the time limit inside it cut
    /// it short; the peak penetration is noted and the observer shown the step. `Some` when the
    /// contact is over.
    fn accept(&mut self, h: f64, rp: &[f64; W], mc: &[f64; W], du1: f64, tau_lim: f64) -> Option<ContactOutcome> {
        // (The step's start is read in place and its end by reference: a step copies the
        // state once, into `self.y`.)
        let y1 = Y::from([mc[0], mc[1], mc[2], mc[3], mc[N], mc[N + 1], mc[N + 2]]);
        let y0 = &self.y;
        let wm = &self.fm[self.p..self.p + K];
        let cell = OnceCell::new();
        let build = || dense::<N, W>(wm, y0, h, rp);
        let ser = || cell.get_or_init(build);
        // The release alone (nearly every contact's last step) is located on σ's polynomial and
        // the state there taken from the corrector's weights ([`release`]); the time limit
        // (once a stretch of a run) on the whole dense output.
        let cut = if y1[2] <= 0.0 && y1[6] < tau_lim {
            let (q, ye, du) = release::<N, W>(wm, y0, &y1, h, rp);
            Some((q, ye, du, ContactOutcome::Separated))
        } else {
            step_end(h, y0, &y1, tau_lim, ser)
        };
        let (he, ye, du_end) = match &cut {
            Some((q, ye, du, _)) => (*q, ye, *du),
            None => (h, &y1, du1),
        };
        let du0 = wm[0][3];
        let mut pen = self.pen;
        if y0[3] > 0.0 && ye[3] <= 0.0 {
            // σ is flat at the peak (σ' = δ'/2 = 0), so its value there is insensitive to where
            // the peak is placed: the quintic Hermite of σ from (σ, σ', σ'') at the step's ends
            // (σ'' = (dδ'/dθ)/2) gives it to the tolerance without the dense output.
            let sg = peak_sigma(he, (y0[2], y0[3], du0), (ye[2], ye[3], du_end)).max(y0[2]).max(ye[2]);
            pen = pen.max(sg * sg);
        }
        self.pen = pen.max(ye[2] * ye[2]);
        let span = Span::new(self.t_onset, he, Dense::Lazy(&cell, &build), y0, ye, (du0, du_end));
        self.obs.step(&span);
        self.y = *ye;
        cut.map(|(_, _, _, outcome)| outcome)
    }

    /// DOP853 carries the contact on from the last accepted state ([`Next::HandOver`]), with
    /// its own nominal step for this contact.
    fn hand_over(self, budget: &mut usize) -> End {
        let r = self.taken_over(self.y);
        dop853::resume(Stretch { sys: self.sys, load: self.load, t_limit: self.t_limit }, &r, budget, self.obs)
    }

    /// This contact at state `y` as DOP853 carries it on, with its own nominal step.
    fn taken_over(&self, y: Y) -> dop853::Resume {
        let h_nom = self.length / dop853::STEPS_NOMINAL;
        let at = Paused { s: self.rhs.s, sc: self.sc, t_onset: self.t_onset, y, pen: self.pen, h: h_nom };
        dop853::Resume::taken_over(at)
    }

    fn end(&self, outcome: ContactOutcome) -> End {
        let y = self.y;
        // A contact cut by the time limit is carried on by DOP853 from the cut state: it needs
        // no history, so the contact goes on as the uncut one does, to both schemes' accuracy
        // (a new start of this scheme there would do worse: its history would come from a
        // series centred mid-contact, where the series reaches less far).
        let resume = (outcome == ContactOutcome::EndOfRun).then(|| self.taken_over(y));
        sundman::ended(&y, (self.t_onset, self.t_limit), self.pen, outcome, resume)
    }
}

/// The predictor's and the corrector's sums over the window `wm` (rates newest first) but its
/// newest rate, oldest first: `Σ_{j = K−1 … 1} AB[j]·wm[j − shift]` over the motion and
/// `Σ_{j = K−1 … 1} AM[j + 1]·wm[j − shift]` over the whole row. `shift = 0` for the window's
/// own step, `1` for the next step's (whose window is this one after a new newest rate).
#[inline(always)]
fn older_sums<const N: usize, const W: usize>(wm: &[[f64; W]; K], shift: usize) -> ([f64; N], [f64; W]) {
    let (mut pm, mut cm) = ([0.0; N], [0.0; W]);
    for j in (1..K).rev() {
        let (b, a, row) = (AB[j], AM[j + 1], &wm[j - shift]);
        for i in 0..N {
            pm[i] += b * row[i];
        }
        for i in 0..W {
            cm[i] += a * row[i];
        }
    }
    (pm, cm)
}

/// The dense output of the step of length `h` from `y` (history rows `wm`, newest first): the
/// corrector's polynomial `y(θ_n + q) = y_n + ∫_0^q P`, `P` the interpolant of the rates at the
/// nodes `θ_{n+1}` (the predicted state's `rp`, as the corrector used them), `θ_n`, …,
/// `θ_{n−11}`, as polynomials in `q` in the order of [`Y`].
fn dense<const N: usize, const W: usize>(wm: &[[f64; W]], y: &Y, h: f64, rp: &[f64; W]) -> Series {
    let f = node_rates::<N, W>(wm, rp);
    // d_k = Σ_j BASIS[j][k]·f_j, each row summed over j in order in registers.
    let mut d = [[0.0; 8]; K + 1];
    for (k, dk) in d.iter_mut().enumerate() {
        for (fj, bj) in f.iter().zip(&BASIS) {
            let b = bj[k];
            for (a, v) in dk.iter_mut().zip(fj) {
                *a += b * v;
            }
        }
    }
    let mut c = [[0.0; NC]; 7];
    let mut scale = 1.0;
    for (k, dk) in d.iter().enumerate() {
        let w = scale / (k + 1) as f64;
        for (ci, a) in c.iter_mut().zip(dk) {
            ci[k + 1] = a * w;
        }
        scale /= h;
    }
    for (ci, yi) in c.iter_mut().zip(y.iter()) {
        ci[0] = *yi;
    }
    Series { c, raw: [0.0; NC] }
}

/// The rates at the nodes of the step from `θ_n`, newest first (the predicted state's `rp`,
/// then the history `wm`), in the order of [`Y`]'s components (and a zero).
#[inline(always)]
fn node_rates<const N: usize, const W: usize>(wm: &[[f64; W]], rp: &[f64; W]) -> [[f64; 8]; K + 1] {
    let mut f = [[0.0; 8]; K + 1];
    for (fj, row) in f.iter_mut().zip(std::iter::once(rp).chain(wm)) {
        fj[..4].copy_from_slice(&row[..4]);
        fj[4..7].copy_from_slice(&row[N..N + 3]);
    }
    f
}

/// The corrector's basis integrated, `∫_0^w ℓ_j = Σ_i BASIS[j][i]·w^{i+1}/(i+1)`, by the
/// coefficients `BASIS[j][i]/(i+1)` ([`release`]).
const BASIS_INT: [[f64; K + 1]; K + 1] = {
    let mut b = BASIS;
    let mut j = 0;
    while j <= K {
        let mut i = 0;
        while i <= K {
            b[j][i] /= (i + 1) as f64;
            i += 1;
        }
        j += 1;
    }
    b
};

/// `w^0 … w^K`, each a product of two earlier ones (a chain of four products at most;
/// written out, as a loop kept them in memory).
#[inline(always)]
fn powers(w: f64) -> [f64; K + 1] {
    const { assert!(K == 12) };
    let w2 = w * w;
    let (w3, w4) = (w2 * w, w2 * w2);
    let w8 = w4 * w4;
    [1.0, w, w2, w3, w4, w4 * w, w4 * w2, w4 * w3, w8, w8 * w, w8 * w2, w8 * w3, w8 * w4]
}

/// `Σ_i c_i·p_i` over four running sums (a short chain of additions: the release's sums are
/// short, and each waits on the last otherwise).
#[inline(always)]
fn dot(c: &[f64; K + 1], p: &[f64; K + 1]) -> f64 {
    let mut a = [0.0; 4];
    for (i, (ci, pi)) in c.iter().zip(p).enumerate() {
        a[i % 4] += ci * pi;
    }
    (a[0] + a[1]) + (a[2] + a[3])
}

/// The release inside the step of length `h` from `y` to `y1` (σ from > 0 to ≤ 0; history
/// `wm`, predicted rates `rp`): `(q, the state there with σ = 0, dδ'/dθ there)`, on the same
/// polynomial as the step's dense output ([`dense`]), built for what the release needs only.
/// σ's polynomial locates it; the state there is `y + h·Σ_j f_j·∫_0^w ℓ_j` and `dδ'/dθ` is
/// `Σ_j f_j[δ']·ℓ_j(w)` (`w = q/h`, `f_j` the rates at the nodes), with the basis evaluated
/// once at `w` instead of every component's polynomial built and evaluated. The polynomials
/// are summed over the powers of `w` rather than by Horner's rule, whose chain of dependent
/// operations (each waiting on the last) made the release 7 % of the robust chart's time.
fn release<const N: usize, const W: usize>(wm: &[[f64; W]], y: &Y, y1: &Y, h: f64, rp: &[f64; W]) -> (f64, Y, f64) {
    let f = node_rates::<N, W>(wm, rp);
    // σ's rate interpolant in powers of w, and its integral's coefficients.
    let mut sr = [0.0; K + 1];
    for (fj, bj) in f.iter().zip(&BASIS) {
        for (a, b) in sr.iter_mut().zip(bj) {
            *a += b * fj[2];
        }
    }
    let si: [f64; K + 1] = std::array::from_fn(|i| sr[i] / (i + 1) as f64);
    let inv_h = 1.0 / h;
    let q = root_in(h, y[2], y1[2], |q| {
        let pw = powers(q * inv_h);
        (y[2] + q * dot(&si, &pw), dot(&sr, &pw))
    });
    let pw = powers(q * inv_h);
    let mut ye = *y;
    let mut du = 0.0;
    for ((fj, bj), ij) in f.iter().zip(&BASIS).zip(&BASIS_INT) {
        let a = q * dot(ij, &pw);
        for (yi, fi) in ye.iter_mut().zip(fj) {
            *yi += a * fi;
        }
        du += dot(bj, &pw) * fj[3];
    }
    ye[2] = 0.0;
    (q, ye, du)
}

/// The largest σ on a step of length `h` (θ units) where δ' turns from > 0 to ≤ 0, from
/// `(σ, δ', dδ'/dθ)` at both ends: σ' = δ'/2 and σ'' = (dδ'/dθ)/2 make the quintic Hermite
/// interpolant of σ ([`SigmaHermite`]), whose maximum is where its derivative vanishes. Two
/// Newton steps on that derivative from where δ' interpolated linearly vanishes place it: σ is
/// flat there, so a place off by `ε` (step units) changes σ by about `ε²·h²·σ''/2`, and the
/// linear guess is off by about a hundredth of the step in a Hertz hump (`h ≈ 1/64` of the
/// contact), which two steps take below 1e-8, far below σ's round-off (a step that would leave
/// the step is not taken).
fn peak_sigma(h: f64, end0: (f64, f64, f64), end1: (f64, f64, f64)) -> f64 {
    let p = SigmaHermite::new(h, end0, end1);
    let mut w = p.d0 / (p.d0 - p.d1);
    for _ in 0..2 {
        let next = w - p.slope(w) / p.curvature(w);
        if next > 0.0 && next < 1.0 {
            w = next;
        }
    }
    p.value(w)
}

/// The quintic Hermite interpolant of σ over a step of length `h` (θ units), in the step
/// fraction `w ∈ [0, 1]`, from `(σ, δ', dδ'/dθ)` at both ends (σ' = δ'/2, σ'' = (dδ'/dθ)/2):
/// the ends' σ, and their first and second derivatives in `w` (`d = h·σ'`, `e = h²·σ''`).
struct SigmaHermite {
    s0: f64,
    s1: f64,
    d0: f64,
    d1: f64,
    e0: f64,
    e1: f64,
}

impl SigmaHermite {
    fn new(h: f64, (s0, u0, a0): (f64, f64, f64), (s1, u1, a1): (f64, f64, f64)) -> Self {
        SigmaHermite { s0, s1, d0: 0.5 * h * u0, d1: 0.5 * h * u1, e0: 0.5 * h * h * a0, e1: 0.5 * h * h * a1 }
    }

    /// σ at `w`.
    fn value(&self, w: f64) -> f64 {
        let SigmaHermite { s0, s1, d0, d1, e0, e1 } = *self;
        let (w2, w3) = (w * w, w * w * w);
        let (w4, w5) = (w3 * w, w3 * w2);
        (1.0 - 10.0 * w3 + 15.0 * w4 - 6.0 * w5) * s0
            + (w - 6.0 * w3 + 8.0 * w4 - 3.0 * w5) * d0
            + 0.5 * (w2 - 3.0 * w3 + 3.0 * w4 - w5) * e0
            + (10.0 * w3 - 15.0 * w4 + 6.0 * w5) * s1
            + (-4.0 * w3 + 7.0 * w4 - 3.0 * w5) * d1
            + 0.5 * (w3 - 2.0 * w4 + w5) * e1
    }

    /// dσ/dw at `w`.
    fn slope(&self, w: f64) -> f64 {
        let SigmaHermite { s0, s1, d0, d1, e0, e1 } = *self;
        let (w2, w3, w4) = (w * w, w * w * w, w * w * w * w);
        (-30.0 * w2 + 60.0 * w3 - 30.0 * w4) * (s0 - s1)
            + (1.0 - 18.0 * w2 + 32.0 * w3 - 15.0 * w4) * d0
            + 0.5 * (2.0 * w - 9.0 * w2 + 12.0 * w3 - 5.0 * w4) * e0
            + (-12.0 * w2 + 28.0 * w3 - 15.0 * w4) * d1
            + 0.5 * (3.0 * w2 - 8.0 * w3 + 5.0 * w4) * e1
    }

    /// d²σ/dw² at `w`.
    fn curvature(&self, w: f64) -> f64 {
        let SigmaHermite { s0, s1, d0, d1, e0, e1 } = *self;
        let (w2, w3) = (w * w, w * w * w);
        (-60.0 * w + 180.0 * w2 - 120.0 * w3) * (s0 - s1)
            + (-36.0 * w + 96.0 * w2 - 60.0 * w3) * d0
            + 0.5 * (2.0 - 18.0 * w + 36.0 * w2 - 20.0 * w3) * e0
            + (-24.0 * w + 84.0 * w2 - 60.0 * w3) * d1
            + 0.5 * (6.0 * w - 24.0 * w2 + 20.0 * w3) * e1
    }
}

#[cfg(test)]
mod tests;
