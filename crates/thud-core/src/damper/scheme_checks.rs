//! Checks shared by the unit tests of the Sundman contact schemes: the design of [`sys`] by all
//! three; the same isolated contacts against the reference and the Taylor scheme, and a contact
//! cut by its time limit carried on as if never cut, by each to its own tolerance
//! ([`super::sundman`], [`super::dop853`], [`super::adams`]).

use super::contact::ContactStart;
use super::contact::{self, ContactEnd, ContactOutcome, State, Sys};
use super::sundman;
use super::DamperParams;

/// The Fig 9 ball against the main mass with contact damping `c1` (N·s/m) and main spring `k`
/// (N/m; with a spring, the main damper 0.05 N·s/m).
pub(crate) fn sys(c1: f64, k: f64) -> Sys {
    let damping = if k > 0.0 { 0.05 } else { 0.0 };
    let p = DamperParams { stiffness_n_m: k, damping_n_s_m: damping, c1_n_s_m: c1, ..DamperParams::table2() };
    Sys::new(&p)
}

/// The isolated contacts every scheme is checked on (contact damping, main spring, approach
/// speed, main-mass offset), each shown to `check` with its design, its start and the
/// reference's integration of it.
pub(crate) fn with_reference(mut check: impl FnMut(&Sys, State, &ContactEnd)) {
    for (c1, k, u0, x0) in
        [(0.0, 0.0, 1.4, 0.0), (20.0, 0.0, 1.4, 0.0), (20.0, 500.0, 0.3, -0.02), (60.0, 500.0, 2.0, 0.02)]
    {
        let s = sys(c1, k);
        let y0 = State::new(x0, 0.1, 0.0, u0, 0.0, 0.0);
        let a = 10.0 * (k * x0.abs() / 0.5 + 1.0);
        let mut left = 100_000;
        let old = contact::integrate(
            ContactStart { a_bound: a, ..ContactStart::free(&s, y0, 1.0) },
            &mut left,
            contact::Unobserved,
        );
        check(&s, y0, &old);
    }
}

/// Isolated contacts from the same state, integrated by `new` (design, start, time limit (s),
/// budget): the release speed, time, peak penetration and dissipation of the reference
/// (Dormand–Prince in t, whose own error is ~1e-9 of the speed) within 2e-8, and of the
/// Sundman–Taylor scheme (error ~1e-12) within 1e-9; at most `max_budget` budget units a
/// contact; and for two free elastic bodies the relative speed back closer than the reference
/// brings it.
pub(crate) fn isolated_contacts<R>(max_budget: usize, new: impl Fn(&Sys, State, f64, &mut usize) -> ContactEnd<R>) {
    with_reference(|s, y0, old| {
        let (s, u0) = (*s, y0[3]);
        let mut left = 100_000;
        let taylor = sundman::integrate(ContactStart::free(&s, y0, 1.0), &mut left, contact::Unobserved);
        let mut left = 100_000;
        let new = new(&s, y0, 1.0, &mut left);
        let used = 100_000 - left;
        assert!(used <= max_budget, "{used} budget units");
        assert_eq!(new.outcome, ContactOutcome::Separated);
        let e_sc = 0.5 * u0 * u0 / s.kstar;
        for (r, tol) in [(&old.y, 2e-8), (&taylor.y, 1e-9)] {
            assert!((r[3] - new.y[3]).abs() < tol * u0, "{:?} vs {:?}", r, new.y);
            assert!((r[4] - new.y[4]).abs() < tol * e_sc, "{:?} vs {:?}", r, new.y);
            assert!((r[0] - new.y[0]).abs() < tol * 1e-3 && (r[1] - new.y[1]).abs() < tol * u0);
        }
        assert!((old.t / new.t - 1.0).abs() < 2e-8 && (taylor.t / new.t - 1.0).abs() < 1e-9);
        assert!((old.pen_max / new.pen_max - 1.0).abs() < 2e-8 && (taylor.pen_max / new.pen_max - 1.0).abs() < 1e-9);
        if s.c1 == 0.0 && s.k == 0.0 {
            // Two free bodies, elastic: the relative speed comes back exactly; closer than the
            // reference brings it back.
            assert!((new.y[3] + u0).abs() < (old.y[3] + u0).abs(), "{} vs {}", new.y[3], old.y[3]);
        }
    });
}

/// A contact cut by its time limit at each fraction `cuts` of its duration, by `integrate`
/// (design, start, time limit (s), budget), ends exactly there, and `resume` (design, resume
/// state, budget; to no limit) carries it on to the uncut contact's end time, release speed and
/// dissipation within the relative `tol` (in that order).
pub(crate) fn cut_contacts<R>(
    cuts: &[f64],
    tol: [f64; 3],
    integrate: impl Fn(&Sys, State, f64, &mut usize) -> ContactEnd<R>,
    resume: impl Fn(&Sys, &R, &mut usize) -> ContactEnd<R>,
) {
    let s = sys(20.0, 500.0);
    let y0 = State::new(0.01, 0.1, 0.0, 1.4, 0.0, 0.0);
    let mut left = 100_000;
    let whole = integrate(&s, y0, 1.0, &mut left);
    for &cut in cuts {
        let mut left = 100_000;
        let first = integrate(&s, y0, cut * whole.t, &mut left);
        assert_eq!(first.outcome, ContactOutcome::EndOfRun);
        assert_eq!(first.t, cut * whole.t);
        let Some(r) = first.resume else { panic!("a cut contact can resume") };
        let end = resume(&s, &r, &mut left);
        assert_eq!(end.outcome, ContactOutcome::Separated);
        assert!((end.t / whole.t - 1.0).abs() < tol[0], "{} vs {}", end.t, whole.t);
        assert!(
            (end.y[3] / whole.y[3] - 1.0).abs() < tol[1] && (end.y[4] / whole.y[4] - 1.0).abs() < tol[2],
            "{cut}: {:?} vs {:?}",
            end.y,
            whole.y
        );
    }
}
