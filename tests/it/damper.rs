#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test or benchmark fails
//! Integration tests of the impact-damper solvers against docs/model.md §6, §7, §9.

use std::sync::atomic::AtomicBool;

use proptest::prelude::*;
use thud::contact::{contact_duration, inverse_effective_mass, peak_approach, Target};
use thud::damper::*;

fn opts() -> RunOptions<'static> {
    RunOptions::default()
}

fn fig9(duration: f64) -> DamperParams {
    DamperParams { duration_s: duration, ..DamperParams::table2() }
}

fn check_fig9(run: &Run, who: &str) {
    let i1 = run.impacts[0];
    let i2 = run.impacts[1];
    assert!((i1.t_s - 0.0101800).abs() < 1e-6, "{who}: t1 {}", i1.t_s);
    assert!((i1.u_in_m_s - 1.89529).abs() < 5e-5, "{who}: u_in {}", i1.u_in_m_s);
    assert!((i1.u_out_m_s - 1.76371).abs() < 5e-5, "{who}: u_out {}", i1.u_out_m_s);
    assert!((i2.u_in_m_s - 2.43469).abs() < 5e-5, "{who}: u_in2 {}", i2.u_in_m_s);
    assert_eq!(i1.wall, Wall::Lower, "{who}: the main mass moves up first, so the ball meets the lower wall");
    assert_eq!(i2.wall, Wall::Upper);
}

#[test]
fn fig9_first_impacts_event() {
    let run = simulate(&fig9(2.0), Solver::Event, &opts()).unwrap();
    check_fig9(&run, "event");
    assert!(!run.cancelled && run.final_time_s == 2.0);
    assert!(run.maxima.len() >= 5, "{:?}", run.maxima);
}

#[test]
fn fig9_first_impacts_newmark() {
    let run = simulate(&fig9(0.035), Solver::Newmark { dt_s: 1e-7 }, &opts()).unwrap();
    check_fig9(&run, "newmark");
}

fn k_star(m: f64, big_m: f64) -> f64 {
    inverse_effective_mass(m, Target::MovableMass(big_m))
}

#[test]
fn undamped_single_contact_matches_closed_form() {
    let (m, big_m, k) = (0.0405, 0.5, 5.6e8);
    for &u0 in &[1.3, 1.4, 2.2] {
        let tau = contact_duration(peak_approach(u0, k_star(m, big_m), k), u0);
        let acc = single_contact(m, big_m, k, 0.0, false, u0);
        assert!((acc.duration_s / tau - 1.0).abs() < 1e-6, "accurate τ {} vs {tau}", acc.duration_s);
        assert!((acc.u_out_m_s / u0 - 1.0).abs() < 1e-6, "elastic rebound {}", acc.u_out_m_s);
        let amax = peak_approach(u0, k_star(m, big_m), k);
        assert!((acc.penetration_max_m / amax - 1.0).abs() < 1e-6);
        let nm = IsolatedContact { m, big_m, k_hz: k, c1: 0.0, no_tension: false }.newmark(u0, 1e-7);
        assert!((nm.duration_s / tau - 1.0).abs() < 5e-5, "newmark τ {} vs {tau}", nm.duration_s);
    }
}

#[test]
fn contact_damping_lengthens_the_contact() {
    // docs/model.md §7, Table 4 (m = 40 g, M = 0.5 kg): c1 = 20 lasts ~0.7–0.8 % longer.
    for &u0 in &[1.3, 1.7, 2.2] {
        let d0 = single_contact(0.04, 0.5, 5.6e8, 0.0, false, u0).duration_s;
        let d20 = single_contact(0.04, 0.5, 5.6e8, 20.0, false, u0).duration_s;
        let r = d20 / d0 - 1.0;
        assert!((0.006..0.009).contains(&r), "u0 {u0}: +{:.3} %", 100.0 * r);
        let nm = IsolatedContact { m: 0.04, big_m: 0.5, k_hz: 5.6e8, c1: 20.0, no_tension: false }
            .newmark(u0, 1e-7)
            .duration_s;
        assert!((nm / d20 - 1.0).abs() < 5e-5, "newmark {nm} vs {d20}");
    }
}

fn compare_first_impacts(p: DamperParams, n: usize) {
    let ev = simulate(&p, Solver::Event, &opts()).unwrap();
    let nm = simulate(&p, Solver::Newmark { dt_s: 1e-7 }, &opts()).unwrap();
    assert!(ev.impacts.len() >= n && nm.impacts.len() >= n, "{} {}", ev.impacts.len(), nm.impacts.len());
    for (a, b) in ev.impacts.iter().zip(&nm.impacts).take(n) {
        assert_eq!(a.wall, b.wall);
        assert!((a.t_s - b.t_s).abs() < 1e-6, "{a:?} {b:?}");
        assert!((a.t_end_s - b.t_end_s).abs() < 1e-6, "{a:?} {b:?}");
        assert!((a.u_in_m_s - b.u_in_m_s).abs() < 5e-5, "{a:?} {b:?}");
        assert!((a.u_out_m_s - b.u_out_m_s).abs() < 5e-5, "{a:?} {b:?}");
        assert!((a.penetration_max_m / b.penetration_max_m - 1.0).abs() < 1e-4, "{a:?} {b:?}");
    }
}

#[test]
fn solvers_agree_on_other_designs() {
    let base = DamperParams::table2();
    compare_first_impacts(DamperParams { impact_mass_kg: 0.03, gap_m: 0.02, v0_m_s: 1.4, duration_s: 0.15, ..base }, 5);
    compare_first_impacts(DamperParams { impact_mass_kg: 0.08, gap_m: 0.03, v0_m_s: 2.5, duration_s: 0.15, ..base }, 5);
    compare_first_impacts(
        DamperParams {
            impact_mass_kg: 0.05,
            gap_m: 0.05,
            v0_m_s: -2.2,
            no_tension: true,
            c1_n_s_m: 83.68,
            duration_s: 0.35,
            ..base
        },
        5,
    );
}

#[test]
fn no_impact_is_pure_viscous_decay() {
    let p = DamperParams { v0_m_s: 0.5, gap_m: 0.04, ..DamperParams::table2() };
    let w = (p.stiffness_n_m / p.main_mass_kg).sqrt();
    assert!(p.gap_m > 2.0 * p.v0_m_s / w);
    let run = simulate(&p, Solver::Event, &RunOptions { history_samples: 501, cancel: None }).unwrap();
    assert!(run.impacts.is_empty());
    assert_eq!(run.history.len(), 501);
    for h in &run.history {
        // Exact viscous decay, written out independently of the crate.
        let g = p.damping_n_s_m / (2.0 * p.main_mass_kg);
        let wd = (w * w - g * g).sqrt();
        let x = p.v0_m_s / wd * (-g * h.t_s).exp() * (wd * h.t_s).sin();
        assert!((h.x_m - x).abs() < 1e-13, "{h:?} vs {x}");
        assert!((h.x_m - free_response(&p, h.t_s)).abs() < 1e-15);
        assert_eq!(h.y_m, 0.0);
    }
    assert!((run.zdot_abs_max_m_s - 0.5).abs() < 1e-15);
    // Cycle maxima of the free decay: one per period.
    assert!(run.maxima.len() >= 9, "{}", run.maxima.len());
    let e = &run.energy;
    assert!((e.final_mechanical_j + e.dissipated_viscous_j - e.initial_j).abs() < 1e-12 * e.initial_j);
    assert_eq!(e.dissipated_contact_j, 0.0);
}

#[test]
fn energy_is_conserved_without_damping() {
    let p = DamperParams { damping_n_s_m: 0.0, c1_n_s_m: 0.0, duration_s: 1.0, ..DamperParams::table2() };
    let run = simulate(&p, Solver::Event, &opts()).unwrap();
    assert!(run.impacts.len() > 10);
    let e = run.energy;
    assert!((e.final_mechanical_j / e.initial_j - 1.0).abs() < 1e-6, "{e:?}");
    for i in &run.impacts {
        assert!((i.u_out_m_s / i.u_in_m_s - 1.0).abs() < 1e-3, "{i:?}");
    }
}

#[test]
fn energy_ledger_balances_with_damping() {
    for nt in [false, true] {
        let p = DamperParams { no_tension: nt, ..DamperParams::table2() };
        let e = simulate(&p, Solver::Event, &opts()).unwrap().energy;
        let total = e.final_mechanical_j + e.dissipated_viscous_j + e.dissipated_contact_j;
        assert!((total / e.initial_j - 1.0).abs() < 1e-6, "{e:?}");
        assert!(e.dissipated_contact_j > 0.0 && e.dissipated_viscous_j > 0.0);
    }
}

#[test]
fn momentum_is_conserved_through_contacts() {
    // K = C = 0: M·x' + m·y' is exactly conserved, so the centre of mass moves uniformly.
    let p = DamperParams { stiffness_n_m: 0.0, damping_n_s_m: 0.0, duration_s: 0.5, ..DamperParams::table2() };
    let run = simulate(&p, Solver::Event, &RunOptions { history_samples: 2001, cancel: None }).unwrap();
    assert!(run.impacts.len() >= 10, "{}", run.impacts.len());
    let (big_m, m) = (p.main_mass_kg, p.impact_mass_kg);
    // Isolated contacts with c1 > 0 always lose relative speed.
    for i in &run.impacts {
        assert!(i.u_out_m_s <= i.u_in_m_s * (1.0 + 1e-9), "{i:?}");
    }
    let v_cm = big_m * p.v0_m_s / (big_m + m);
    for h in &run.history {
        let x_cm = (big_m * h.x_m + m * h.y_m) / (big_m + m);
        let want = v_cm * h.t_s;
        assert!((x_cm - want).abs() <= 1e-9 * (want.abs() + p.gap_m), "{h:?}: {x_cm} vs {want}");
    }
}

#[test]
fn restitution_against_impact_mass() {
    // docs/model.md §6, §9 (Fig 13): ≈ 0.84, 0.91, 0.93, 0.95 at 10, 30, 50, 100 g, 1.4 m/s, c1 = 20.
    for &(m, want) in &[(0.01, 0.84), (0.03, 0.91), (0.05, 0.93), (0.1, 0.95)] {
        let r = single_contact(m, 0.5, 5.6e8, 20.0, false, 1.4).u_out_m_s / 1.4;
        assert!((r - want).abs() < 0.01, "m {m}: R {r}");
    }
}

#[test]
fn c1_for_restitution_inverts_single_contact() {
    for &(m, nt, r) in &[(0.0405, false, 0.9), (0.01, true, 0.6), (0.1, false, 0.97)] {
        let c1 = c1_for_restitution(m, 0.5, 5.6e8, nt, 1.4, r).unwrap();
        let got = single_contact(m, 0.5, 5.6e8, c1, nt, 1.4).u_out_m_s / 1.4;
        assert!((got - r).abs() < 1e-6, "m {m}: c1 {c1} gives {got}");
    }
    // Round trip from the Table 2 value.
    let r20 = single_contact(0.0405, 0.5, 5.6e8, 20.0, false, 1.4).u_out_m_s / 1.4;
    let c1 = c1_for_restitution(0.0405, 0.5, 5.6e8, false, 1.4, r20).unwrap();
    assert!((c1 - 20.0).abs() < 1e-4, "{c1}");
    assert_eq!(c1_for_restitution(0.0405, 0.5, 5.6e8, false, 1.4, 1.0).unwrap(), 0.0);
    for bad in [0.0, -0.1, 1.2, f64::NAN] {
        assert!(c1_for_restitution(0.0405, 0.5, 5.6e8, false, 1.4, bad).is_err());
    }
}

#[test]
fn invalid_parameters_are_named() {
    let base = DamperParams::table2();
    let cases: Vec<(DamperParams, &str)> = vec![
        (DamperParams { impact_mass_kg: 0.0, ..base }, "mass"),
        (DamperParams { impact_mass_kg: -1.0, ..base }, "mass"),
        (DamperParams { gap_m: 0.0, ..base }, "gap"),
        (DamperParams { gap_m: -0.01, ..base }, "gap"),
        (DamperParams { v0_m_s: f64::NAN, ..base }, "v0"),
        (DamperParams { v0_m_s: f64::INFINITY, ..base }, "v0"),
        (DamperParams { duration_s: 0.0, ..base }, "duration"),
        (DamperParams { duration_s: -1.0, ..base }, "duration"),
        (DamperParams { main_mass_kg: 0.0, ..base }, "main-mass"),
        (DamperParams { stiffness_n_m: -1.0, ..base }, "k"),
        (DamperParams { damping_n_s_m: f64::NAN, ..base }, "c"),
        (DamperParams { c1_n_s_m: -1.0, ..base }, "c1"),
        (DamperParams { k_hz: 0.0, ..base }, "k-hz"),
    ];
    for (p, name) in cases {
        let e = simulate(&p, Solver::Event, &opts()).unwrap_err();
        assert_eq!(e.param(), name, "{e}");
        assert!(p.validate().is_err());
    }
    for dt in [0.0, -1e-7, f64::NAN, f64::INFINITY] {
        let e = simulate(&base, Solver::Newmark { dt_s: dt }, &opts()).unwrap_err();
        assert_eq!(e.param(), "dt");
    }
    assert!(base.validate().is_ok());
    // v0 = 0 is valid: nothing moves.
    let still = simulate(&DamperParams { v0_m_s: 0.0, ..base }, Solver::Event, &opts()).unwrap();
    assert!(still.impacts.is_empty() && still.maxima.is_empty());
}

#[test]
fn cancellation_returns_partial_run() {
    let flag = AtomicBool::new(true);
    let o = RunOptions { history_samples: 10, cancel: Some(&flag) };
    for solver in [Solver::Event, Solver::Newmark { dt_s: 1e-6 }] {
        let run = simulate(&DamperParams::table2(), solver, &o).unwrap();
        assert!(run.cancelled);
        assert!(run.final_time_s < 2.0);
    }
}

#[test]
fn history_is_uniform_and_continuous() {
    let n = 4001;
    let run = simulate(&fig9(0.5), Solver::Event, &RunOptions { history_samples: n, cancel: None }).unwrap();
    assert_eq!(run.history.len(), n);
    assert_eq!(run.history[0], HistoryPoint { t_s: 0.0, x_m: 0.0, y_m: 0.0 });
    assert_eq!(run.history[n - 1].t_s, 0.5);
    for w in run.history.windows(2) {
        assert!((w[1].t_s - w[0].t_s - 0.5 / (n - 1) as f64).abs() < 1e-12);
        assert!((w[1].x_m - w[0].x_m).abs() < 3.0 * 0.5 / (n - 1) as f64, "{w:?}");
        // The ball stays inside the enclosure up to the (tiny) penetration.
        assert!((w[1].y_m - w[1].x_m).abs() < 0.02 + 3e-4);
    }
    // Newmark history agrees with the event history before the motion becomes chaotic.
    let nm = simulate(&fig9(0.05), Solver::Newmark { dt_s: 1e-7 }, &RunOptions { history_samples: 101, cancel: None })
        .unwrap();
    let ev = simulate(&fig9(0.05), Solver::Event, &RunOptions { history_samples: 101, cancel: None }).unwrap();
    for (a, b) in ev.history.iter().zip(&nm.history) {
        assert!((a.x_m - b.x_m).abs() < 1e-6 && (a.y_m - b.y_m).abs() < 1e-6, "{a:?} {b:?}");
    }
}

#[test]
fn regimes_without_spring_or_damper_run() {
    // K = 0 and C = 0 (free masses), K = 0 < C (overdamped), heavy damping (overdamped).
    let base = DamperParams { duration_s: 0.3, gap_m: 0.004, ..DamperParams::table2() };
    for p in [
        DamperParams { stiffness_n_m: 0.0, damping_n_s_m: 0.0, ..base },
        DamperParams { stiffness_n_m: 0.0, damping_n_s_m: 1.0, ..base },
        DamperParams { damping_n_s_m: 100.0, ..base },
        DamperParams { damping_n_s_m: 2.0 * (500.0f64 * 0.5).sqrt(), ..base },
    ] {
        let run = simulate(&p, Solver::Event, &opts()).unwrap();
        let e = run.energy;
        let total = e.final_mechanical_j + e.dissipated_viscous_j + e.dissipated_contact_j;
        assert!((total / e.initial_j - 1.0).abs() < 1e-6, "{p:?} {e:?}");
        assert!(!run.impacts.is_empty());
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, .. ProptestConfig::default() })]
    #[test]
    fn random_designs_are_sane(
        m in 0.005f64..0.2,
        big_m in 0.1f64..2.0,
        k in 0.0f64..2000.0,
        c in 0.0f64..5.0,
        d in 0.002f64..0.08,
        c1 in 0.0f64..200.0,
        nt in any::<bool>(),
        v0 in -3.0f64..3.0,
        khz_exp in 7.0f64..10.0,
        dur in 0.01f64..0.3,
    ) {
        let p = DamperParams {
            main_mass_kg: big_m, stiffness_n_m: k, damping_n_s_m: c, impact_mass_kg: m, gap_m: d,
            k_hz: 10f64.powf(khz_exp), c1_n_s_m: c1, no_tension: nt, v0_m_s: v0, duration_s: dur,
            ..DamperParams::table2()
        };
        let run = simulate(&p, Solver::Event, &RunOptions { history_samples: 50, cancel: None }).unwrap();
        prop_assert!(run.zdot_abs_max_m_s.is_finite());
        prop_assert!(run.zdot_abs_max_m_s >= v0.abs() * (1.0 - 1e-12));
        let mut last = 0.0;
        for i in &run.impacts {
            prop_assert!(i.t_s.is_finite() && i.u_in_m_s.is_finite() && i.u_out_m_s.is_finite());
            prop_assert!(i.t_s >= last && i.t_end_s >= i.t_s, "{:?}", i);
            prop_assert!(i.penetration_max_m >= 0.0);
            if c1 > 0.0 {
                // A damped contact cannot speed the ball up by itself, but the spring and the
                // damper of the main mass act during the contact too (a slow, long contact can
                // leave faster than it came: found by this test, confirmed by Newmark). Their
                // relative acceleration is at most |v0|·(ω0 + C/M), as the energy never grows.
                let a_ext = v0.abs() * ((k / big_m).sqrt() + c / big_m);
                let slack = a_ext * (i.t_end_s - i.t_s);
                prop_assert!(i.u_out_m_s <= i.u_in_m_s * (1.0 + 1e-9) + slack, "{:?}", i);
            }
            last = i.t_end_s;
        }
        for h in &run.history {
            prop_assert!(h.x_m.is_finite() && h.y_m.is_finite());
        }
        // The Newmark reference on a short stretch of the same design.
        let short = DamperParams { duration_s: dur.min(0.02), ..p };
        let nm = simulate(&short, Solver::Newmark { dt_s: 1e-6 }, &RunOptions::default()).unwrap();
        let mut last = 0.0;
        for i in &nm.impacts {
            prop_assert!(i.u_in_m_s.is_finite() && i.u_out_m_s.is_finite() && i.penetration_max_m >= 0.0);
            prop_assert!(i.t_s >= last && i.t_end_s >= i.t_s, "{:?}", i);
            last = i.t_end_s;
        }
        prop_assert!(nm.energy.final_mechanical_j.is_finite());
        let e = run.energy;
        prop_assert!(e.final_mechanical_j.is_finite() && e.dissipated_contact_j.is_finite());
        if run.final_time_s == dur {
            let total = e.final_mechanical_j + e.dissipated_viscous_j + e.dissipated_contact_j;
            prop_assert!((total - e.initial_j).abs() <= 1e-5 * e.initial_j.max(1e-12), "{:?}", e);
        }
    }
}
