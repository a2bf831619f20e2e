#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! The isolated contact behind `thud restitution` (`damper::single_contact`) by the default
//! contact scheme (Sundman–Adams, docs/model.md §11) against the reference Dormand–Prince
//! scheme, with the acceptance for a new contact scheme: release speeds within 5e-8 m/s;
//! with `no_tension` the reference itself.

use thud::damper::{single_contact, ContactScheme, IsolatedContact};

#[test]
fn the_restitution_contact_agrees_with_the_reference() {
    let mut worst = (0.0_f64, 0.0_f64);
    for &m in &[0.01, 0.0405, 0.1] {
        for &c1 in &[0.0, 20.0, 100.0, 500.0] {
            for &u0 in &[0.3, 1.4, 3.0] {
                let new = single_contact(m, 0.5, 5.6e8, c1, false, u0);
                let old = IsolatedContact { m, big_m: 0.5, k_hz: 5.6e8, c1, no_tension: false }
                    .by(ContactScheme::DormandPrince, u0);
                assert_eq!(
                    new,
                    IsolatedContact { m, big_m: 0.5, k_hz: 5.6e8, c1, no_tension: false }
                        .by(ContactScheme::SundmanAdams, u0)
                );
                let du = (new.u_out_m_s - old.u_out_m_s).abs();
                // (A contact so damped that it does not end within 1e4 of its elastic duration
                // gives 0 by both.) Duration and peak penetration go as powers of the speed ≤ 4/5 (Hertz), so within
                // the same relative bound as the speed, 5e-8 m/s over 0.3 m/s.
                let rel = (new.duration_s / old.duration_s - 1.0)
                    .abs()
                    .max((new.penetration_max_m / old.penetration_max_m - 1.0).abs());
                worst = (worst.0.max(du), worst.1.max(rel));
                assert!(
                    (new.u_out_m_s > 0.0) == (old.u_out_m_s > 0.0) && du <= 5e-8,
                    "m {m}, c1 {c1}, u0 {u0}: {new:?} vs {old:?}"
                );
                assert!(rel <= 5e-8 / 0.3, "m {m}, c1 {c1}, u0 {u0}: {new:?} vs {old:?}");
            }
        }
    }
    eprintln!("restitution contact: worst {:e} m/s, {:e} relative", worst.0, worst.1);
    // No tension: the reference, as in a run.
    let clamped = single_contact(0.0405, 0.5, 5.6e8, 100.0, true, 1.4);
    assert_eq!(
        clamped,
        IsolatedContact { m: 0.0405, big_m: 0.5, k_hz: 5.6e8, c1: 100.0, no_tension: true }
            .by(ContactScheme::DormandPrince, 1.4)
    );
    assert_eq!(
        clamped,
        IsolatedContact { m: 0.0405, big_m: 0.5, k_hz: 5.6e8, c1: 100.0, no_tension: true }
            .by(ContactScheme::SundmanAdams, 1.4)
    );
}
