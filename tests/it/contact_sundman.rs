#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! The fast Sundman contact schemes, DOP853 and Adams (`ContactScheme::SundmanDop853`,
//! `ContactScheme::SundmanAdams`, docs/model.md §11), each against the reference Dormand–Prince
//! scheme (`ContactScheme::DormandPrince`) and the Sundman–Taylor scheme, with the acceptance for a
//! new contact scheme:
//!
//! - impact speeds within 5e-8 m/s of the reference on the Fig 9 design (its first 8 impacts,
//!   before the rattle amplifies the reference's own ~1e-9 error a contact past that; see
//!   tests/it/contact_scheme.rs) and on 30 random designs (seeded; their first 2 impacts, a
//!   third of them forced);
//! - each run's energy ledger closed to 1e-9;
//! - where the Hertz law has a closed form (two free bodies, elastic) the speed comes back to
//!   better than the reference's own error;
//! - the cycle maxima and `|z'|max` inside contacts located on the steps' polynomials, not taken
//!   at a step's end.

use thud::damper::{simulate_with, ContactScheme, DamperParams, Run, RunOptions, Solver};

use crate::contact_scheme::{ledger_residual, random_designs, run, speed_gap};

/// The schemes checked.
const SCHEMES: [ContactScheme; 2] = [ContactScheme::SundmanDop853, ContactScheme::SundmanAdams];

#[test]
fn the_fig9_design_agrees_with_the_reference_and_closes_its_ledger() {
    let p = DamperParams::table2();
    let old = run(&p, ContactScheme::DormandPrince);
    let taylor = run(&p, ContactScheme::SundmanTaylor);
    for scheme in SCHEMES {
        let new = run(&p, scheme);
        let first = speed_gap(&old, &new, 8);
        let to_taylor = speed_gap(&taylor, &new, 8);
        eprintln!("fig9 {scheme:?}: reference {first:e}, Taylor {to_taylor:e} m/s; ledger {:e}", ledger_residual(&new));
        assert!(first <= 5e-8, "{scheme:?}, first 8 impacts: {first:e} m/s");
        // Against the more accurate Taylor scheme the gap is far smaller than against the
        // reference.
        assert!(
            to_taylor < 0.5 * first.max(1e-12) || to_taylor < 1e-9,
            "{scheme:?}: Taylor {to_taylor:e}, reference {first:e}"
        );
        assert!(ledger_residual(&new) <= 1e-9, "{scheme:?}: {:e}", ledger_residual(&new));
    }
}

#[test]
fn thirty_random_designs_agree_on_their_first_two_impacts() {
    let mut worst = [(0.0_f64, 0.0_f64, 0.0_f64); SCHEMES.len()];
    for (i, p) in random_designs() {
        let (old, taylor) = (run(&p, ContactScheme::DormandPrince), run(&p, ContactScheme::SundmanTaylor));
        for (scheme, w) in SCHEMES.into_iter().zip(&mut worst) {
            let new = run(&p, scheme);
            assert!(!new.impacts.is_empty(), "{scheme:?}, design {i}");
            let du = speed_gap(&old, &new, 2);
            *w = (w.0.max(du), w.1.max(speed_gap(&taylor, &new, 2)), w.2.max(ledger_residual(&new)));
            assert!(du <= 5e-8, "{scheme:?}, design {i}: {du:e} m/s; {p:?}");
            assert!(ledger_residual(&new) <= 1e-9, "{scheme:?}, design {i}: {:e}", ledger_residual(&new));
        }
    }
    for (scheme, (du, dt, le)) in SCHEMES.iter().zip(worst) {
        eprintln!(
            "30 designs {scheme:?}: worst {du:e} m/s against the reference, {dt:e} against Taylor; ledger {le:e}"
        );
    }
}

#[test]
fn an_elastic_contact_of_free_bodies_gives_back_its_speed() {
    // K = C = c1 = 0: each contact conserves momentum and energy, so u_out = u_in.
    let p = DamperParams {
        stiffness_n_m: 0.0,
        damping_n_s_m: 0.0,
        c1_n_s_m: 0.0,
        duration_s: 0.3,
        ..DamperParams::table2()
    };
    let worst = |r: &Run| r.impacts.iter().map(|i| (i.u_out_m_s / i.u_in_m_s - 1.0).abs()).fold(0.0, f64::max);
    let old = run(&p, ContactScheme::DormandPrince);
    for scheme in SCHEMES {
        let new = run(&p, scheme);
        assert!(new.impacts.len() >= 5 && new.impacts.len() == old.impacts.len());
        let (e_old, e_new) = (worst(&old), worst(&new));
        eprintln!("elastic: reference {e_old:e}, {scheme:?} {e_new:e}");
        assert!(e_new < e_old, "{scheme:?} {e_new:e} against the reference's {e_old:e}");
    }
}

#[test]
fn maxima_and_the_largest_relative_speed_inside_contacts_are_located() {
    // The first 0.3 s of Fig 9 with history samples inside and between contacts: the located
    // maxima agree with the Taylor scheme's (which finds them on its series) to far better than
    // the reference's step-end maxima, and positions with the reference to its accuracy.
    let p = DamperParams { duration_s: 0.3, ..DamperParams::table2() };
    let o = RunOptions { history_samples: 30_001, cancel: None };
    let old = simulate_with(&p, Solver::Event, &o, ContactScheme::DormandPrince).unwrap();
    let taylor = simulate_with(&p, Solver::Event, &o, ContactScheme::SundmanTaylor).unwrap();
    for scheme in SCHEMES {
        let new = simulate_with(&p, Solver::Event, &o, scheme).unwrap();
        assert_eq!(old.history.len(), new.history.len());
        for (a, b) in old.history.iter().zip(&new.history) {
            assert_eq!(a.t_s, b.t_s);
            assert!((a.x_m - b.x_m).abs() < 1.5e-8 && (a.y_m - b.y_m).abs() < 1.5e-8, "{a:?} vs {b:?}");
        }
        assert_eq!(taylor.maxima.len(), new.maxima.len());
        let (mut dt, mut dx): (f64, f64) = (0.0, 0.0);
        for (a, b) in taylor.maxima.iter().zip(&new.maxima) {
            dt = dt.max((a.t_s - b.t_s).abs());
            dx = dx.max((a.x_m - b.x_m).abs());
        }
        eprintln!("maxima against Taylor: {dt:e} s, {dx:e} m");
        assert!(dt < 1e-7 && dx < 1e-10, "{dt:e} s, {dx:e} m");
        for (a, b) in old.maxima.iter().zip(&new.maxima) {
            assert!(b.x_m >= a.x_m - 1e-9, "{a:?} vs {b:?}");
        }
        assert!((taylor.zdot_abs_max_m_s - new.zdot_abs_max_m_s).abs() < 1e-9);
        assert!((old.zdot_abs_max_m_s - new.zdot_abs_max_m_s).abs() < 1e-7);
    }
}

#[test]
fn extreme_designs_run_to_their_end_and_agree_on_the_first_impact() {
    // Corners of the design space: a very soft and a very stiff contact, a light and a heavy
    // ball, a tight clearance, a hard strike, heavy contact damping, and a ball pressed against
    // a wall by a strong slow force (long contacts, which the Adams scheme hands to DOP853).
    let base = DamperParams { duration_s: 0.5, ..DamperParams::table2() };
    let designs = [
        DamperParams { k_hz: 1e6, ..base },
        DamperParams { k_hz: 1e12, ..base },
        DamperParams { impact_mass_kg: 1e-3, ..base },
        DamperParams { impact_mass_kg: 1.0, ..base },
        DamperParams { gap_m: 1e-4, ..base },
        DamperParams { v0_m_s: 10.0, ..base },
        DamperParams { c1_n_s_m: 1000.0, ..base },
        DamperParams { v0_m_s: 0.0, force_n: 20.0, freq_hz: 1.0, duration_s: 2.0, ..base },
    ];
    for p in designs {
        let old = run(&p, ContactScheme::DormandPrince);
        for scheme in SCHEMES {
            let new = run(&p, scheme);
            assert!(new.truncated.is_none(), "{scheme:?} {p:?}: {:?}", new.truncated);
            assert!(!new.impacts.is_empty(), "{scheme:?} {p:?}");
            assert!(new.impacts.iter().all(|i| i.u_in_m_s.is_finite() && i.u_out_m_s.is_finite()));
            let du = speed_gap(&old, &new, 1);
            assert!(du <= 5e-8 * p.v0_m_s.max(1.0), "{scheme:?} {p:?}: {du:e} m/s");
            // The ledger to 1e-9 of the initial energy, or (where the reference itself does
            // worse: the heavy ball) no worse than the reference.
            let (le, le_ref) = (ledger_residual(&new), ledger_residual(&old));
            assert!(le <= 1e-9_f64.max(le_ref), "{scheme:?} {p:?}: ledger {le:e}, reference {le_ref:e}");
        }
    }
}
