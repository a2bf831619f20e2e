use super::*;

/// The Fig 9 ball against the free main mass (no spring), hitting the upper wall at 1.4 m/s.
fn sys(c1: f64) -> Sys {
    let p = DamperParams { stiffness_n_m: 0.0, damping_n_s_m: 0.0, c1_n_s_m: c1, ..DamperParams::table2() };
    Sys::new(&p)
}

fn contact(sys: &Sys, t_limit: f64, budget: usize) -> (ContactEnd, usize) {
    let mut left = budget;
    let y0 = State::new(0.0, 0.0, 0.0, 1.4, 0.0, 0.0);
    let end = integrate(ContactStart::free(sys, y0, t_limit), &mut left, Unobserved);
    (end, budget - left)
}

#[test]
fn each_way_a_contact_can_end() {
    let elastic = sys(0.0);
    let tau = contact_duration(peak_approach(1.4, elastic.kstar, elastic.k_hz), 1.4);
    let (end, used) = contact(&elastic, 1.0, 10_000);
    assert_eq!(end.outcome, ContactOutcome::Separated);
    assert_eq!(end.y[2], 0.0, "the exit is set exactly at δ = 0");
    assert!((end.t / tau - 1.0).abs() < 1e-6 && (-end.y[3] / 1.4 - 1.0).abs() < 1e-6, "{end:?}");
    assert!(used < 1000, "{used} steps");

    let (cut, _) = contact(&elastic, 0.5 * tau, 10_000);
    assert_eq!(cut.outcome, ContactOutcome::EndOfRun);
    assert_eq!(cut.t, 0.5 * tau);
    assert!(cut.y[2] > 0.0);

    let (capped, used) = contact(&elastic, 1.0, 5);
    assert_eq!(capped.outcome, ContactOutcome::WorkCap);
    assert_eq!(used, 5);
    assert!(capped.t < tau);
}

#[test]
fn stage_loads_by_rotation_are_the_cosines() {
    let load = Harmonic { f: 2.0, omega: 31.4, phase: 0.7 };
    for &(t, h) in &[(0.0, 1e-6), (123.456, 3e-5), (7.0, 1.5e-3)] {
        let fast = load.stages(t, h);
        for (g, c) in fast.iter().zip([C2, C3, C4, C5, 1.0, 1.0]) {
            // The direct cosine carries the rounding of θ = Ω·(t + c·h) + φ.
            let direct = load.accel(t + c * h);
            let theta_ulp = 4.0 * f64::EPSILON * (load.theta(t) + 1.0);
            assert!((g - direct).abs() < (theta_ulp + 1e-15) * load.f, "{g} vs {direct}");
        }
    }
}

#[test]
fn a_cut_contact_resumes_where_it_stopped() {
    let s = sys(20.0);
    let tau = contact_duration(peak_approach(1.4, s.kstar, s.k_hz), 1.4);
    let (whole, _) = contact(&s, 1.0, 10_000);
    for cut in [0.1, 0.5, 0.93] {
        let (first, _) = contact(&s, cut * tau, 10_000);
        assert_eq!(first.outcome, ContactOutcome::EndOfRun);
        let r = first.resume.expect("a cut contact can resume");
        let mut left = 10_000;
        let mut seen_from = f64::NAN;
        let end = resume(
            Stretch::free(&s, 1.0),
            &r,
            &mut left,
            |t0: f64, _: &State, _: &State, _: f64, _: &State, _: &State| {
                if seen_from.is_nan() {
                    seen_from = t0;
                }
            },
        );
        assert_eq!(seen_from, cut * tau, "the first step starts where the cut left it");
        assert_eq!(end.outcome, ContactOutcome::Separated);
        assert!((end.t / whole.t - 1.0).abs() < 1e-8, "{} vs {}", end.t, whole.t);
        // The same contact to the integrator's tolerance (RTOL 3e-9 a step).
        assert!(
            (end.y[3] / whole.y[3] - 1.0).abs() < 1e-7 && (end.y[4] / whole.y[4] - 1.0).abs() < 1e-7,
            "{cut}: {:?} vs {:?}",
            end.y,
            whole.y
        );
        assert!((end.pen_max / whole.pen_max - 1.0).abs() < 1e-9);
    }
}

#[test]
fn a_damped_contact_dissipates_what_the_ball_loses() {
    let s = sys(20.0);
    let (end, _) = contact(&s, 1.0, 10_000);
    assert_eq!(end.outcome, ContactOutcome::Separated);
    // Relative kinetic energy ½·u²/K* before and after; the loss is the contact's dissipation.
    let lost = 0.5 * (1.4f64.powi(2) - end.y[3].powi(2)) / s.kstar;
    assert!(lost > 0.0 && (end.y[4] / lost - 1.0).abs() < 1e-6, "{} vs {lost}", end.y[4]);
}
