use super::*;
use crate::design::Design;

fn sample(k: usize, x: f64, v: f64) -> Sample {
    Sample { period: k as u32, x_m: x, v_m_s: v, z_m: 0.0, zdot_m_s: 0.0 }
}

#[test]
fn periods_and_symmetry_are_read_from_the_samples() {
    let one: Vec<Sample> = (0..60).map(|k| sample(k, 0.01, 0.2)).collect();
    let halves = vec![[-0.01, -0.2]; 60];
    assert_eq!(classify(&one, &halves, 120), Orbit::periodic(2, 1, true));
    let asym = vec![[-0.005, -0.2]; 60];
    assert_eq!(classify(&one, &asym, 60), Orbit::periodic(1, 1, false));
    let two: Vec<Sample> = (0..60).map(|k| sample(k, if k % 2 == 0 { 0.01 } else { 0.012 }, 0.2)).collect();
    assert_eq!(classify(&two, &halves, 60), Orbit::periodic(2, 2, false));
}

#[test]
fn the_zero_one_test_tells_the_logistic_map_from_a_cycle() {
    // The logistic map at r = 3.97 is chaotic, at r = 3.5 a 4-cycle (Gottwald & Melbourne's
    // own example, 2009 §3).
    let orbit = |r: f64| {
        let mut x = 0.3;
        (0..3000)
            .map(|_| {
                x = r * x * (1.0 - x);
                x
            })
            .skip(1000)
            .collect::<Vec<f64>>()
    };
    let chaotic = zero_one_test(&orbit(3.97));
    let regular = zero_one_test(&orbit(3.5));
    assert!(chaotic > 0.9, "K = {chaotic}");
    assert!(regular.abs() < 0.2, "K = {regular}");
}

#[test]
fn an_unsettled_drift_is_not_periodic() {
    let drift: Vec<Sample> = (0..60).map(|k| sample(k, 0.01 * (1.0 + 0.01 * k as f64), 0.2)).collect();
    assert!(!matches!(classify(&drift, &[], 0), Orbit::Periodic { .. }));
}

/// The design of the `forced-rattle` preset (assets/presets/forced-rattle.toml).
fn forced_rattle() -> Design {
    let mut d = Design::default();
    d.damper.damping_n_s_m = 1.5;
    d.damper.gap_m = 0.01;
    d.damper.v0_m_s = 0.0;
    d.damper.force_n = 3.0;
    d.damper.freq_hz = 7.5;
    d
}

#[test]
fn the_forced_rattle_doubles_its_period_below_7_6_hz() {
    // Found with `thud bifurcation --preset forced-rattle --vary f=3Hz:8Hz:200` and checked
    // here on the samples themselves: at 7.7 Hz two impacts a period, every x(kT) the
    // same; at 7.55 Hz four impacts per two periods, x(kT) alternating between two values
    // far apart (a period doubling, not a slow transient); lower still, chaos.
    let vary = Vary::of_values("freq", &[7.55, 7.7], Spelling::Keyword).unwrap();
    let d = forced_rattle().check().unwrap();
    let b = bifurcation(&d, &vary, Settings::default(), false, "force", None, &|_| {}).unwrap();
    let (doubled, single) = (&b.points[0].run, &b.points[1].run);
    assert_eq!(single.orbit, Orbit::periodic(2, 1, false));
    assert_eq!(doubled.orbit, Orbit::periodic(4, 2, false));
    // x(kT) alternates between two values (10 tolerances apart or more), every other
    // sample the same to far below that.
    let tol = PERIODIC_TOLERANCE * doubled.amplitude_m;
    let split = (doubled.samples[0].x_m - doubled.samples[1].x_m).abs();
    assert!(split > 5.0 * tol, "x(kT) alternates by {split} m");
    let even = doubled.samples.iter().step_by(2).map(|s| (s.x_m - doubled.samples[0].x_m).abs()).fold(0.0, f64::max);
    assert!(even < 0.05 * split, "x(2kT) repeats to {even} m");
    let spread = single.samples.iter().map(|s| (s.x_m - single.samples[0].x_m).abs()).fold(0.0, f64::max);
    assert!(spread < 1e-4 * single.amplitude_m, "x(kT) repeats to {spread} m");
    assert_eq!(single.impacts.len(), 2 * single.samples.len());
    assert!(single.impacts.iter().all(|i| (0.0..1.0).contains(&i.phase) && i.u_in_m_s > 0.0));
    // Both walls, once a period each.
    assert_eq!(single.impacts.iter().filter(|i| i.wall.sign() > 0.0).count(), single.samples.len());
    let chaos = Vary::of_values("freq", &[7.42], Spelling::Keyword).unwrap();
    let c = bifurcation(&d, &chaos, Settings::default(), false, "force", None, &|_| {}).unwrap();
    assert!(matches!(c.points[0].run.orbit, Orbit::Chaotic { .. }), "{:?}", c.points[0].run.orbit);
}

#[test]
fn sampling_does_not_change_the_motion() {
    // The stroboscopic run stops at every half period and resumes; the ordinary run does
    // not. Their impacts must be the same ones, to the bit: a stretch that ends in flight
    // leaves the flight's launch behind and the next carries that flight on (event.rs), so
    // no round-off enters where the run stopped (this chaotic rattle would amplify it,
    // ~10× every few impacts, to ~1e-9 m/s within 15 periods).
    let mut d = forced_rattle();
    d.damper.freq_hz = 7.7;
    let s = Settings { transient_periods: 0, periods: 15 };
    let d = d.check().unwrap();
    let strobed = impact_map(&d, s, "force", None).unwrap();
    // The sampled window is periods 1 to 16 (the first sample is at the first whole turn
    // after t = 0); the plain run covers it.
    let t = 1.0 / 7.7;
    let mut plain = d.design().clone();
    plain.damper.duration_s = 16.5 * t;
    let run = crate::design::evaluate(&plain.check().unwrap(), 0, None).unwrap().run;
    let window: Vec<_> = run.impacts.iter().filter(|i| i.t_s >= t && i.t_s < 16.0 * t).collect();
    assert_eq!(window.len(), strobed.impacts.len());
    assert!(window.len() >= 20);
    for (a, b) in window.iter().zip(&strobed.impacts) {
        assert_eq!(a.u_in_m_s, b.u_in_m_s);
        assert!(((a.t_s / t).fract() - b.phase).abs() < 1e-9);
    }
}

#[test]
fn a_window_counts_the_contact_that_straddles_its_end() {
    // At 7 Hz the forced rattle is a 3/1 orbit whose third contact begins just before the
    // force's phase 0 and ends after it: the window must count it at its end (its onset is
    // inside), as it does not count the one cut by its start. Every length of window then
    // holds exactly three impacts a period.
    let mut d = forced_rattle();
    d.damper.freq_hz = 7.0;
    let v = d.clone().check().unwrap();
    for periods in [50, 99, 100, 101] {
        let s = Settings { transient_periods: DEFAULT_TRANSIENT_PERIODS, periods };
        let run = impact_map(&v, s, "force", None).unwrap();
        assert_eq!(run.impacts.len(), 3 * periods as usize, "{periods} periods");
        assert_eq!(run.orbit, Orbit::periodic(3, 1, false), "{periods} periods");
        let last = run.impacts.last().unwrap();
        assert_eq!(last.period, periods - 1);
    }
    // The steady windows of an ordinary run (ending at the force's phase 0) count the same.
    d.damper.settle = true;
    let run = crate::design::evaluate(&d.check().unwrap(), 0, None).unwrap().run;
    let st = run.steady.unwrap();
    assert!(st.settled, "{st:?}");
    assert_eq!(st.impacts, 3 * st.periods as usize, "{st:?}");
}

#[test]
fn basins_tell_an_asymmetric_orbit_from_its_mirror_image() {
    // At 7 Hz the forced rattle's orbit is 3/1 and not symmetric: its mirror image
    // (x → −x, z → −z half a period later) is an orbit too, of the same type and amplitude.
    // Starts of the ball across the clearance reach both; they are two attractors, each
    // the other's mirror, and the samples x(kT) of one are −x(kT + T/2) of the other.
    let mut d = forced_rattle();
    d.damper.freq_hz = 7.0;
    let d = d.check().unwrap();
    let s = Settings { transient_periods: 200, periods: 30 };
    let w0 = [-2.0, -1.0, -0.3, 0.3, 1.0, 2.0];
    let b = basins(&d, 8, &w0, s, "force", None, &|_| {}).unwrap();
    let two: Vec<&Attractor> = b.attractors.iter().filter(|a| a.orbit == Orbit::periodic(3, 1, false)).collect();
    assert_eq!(two.len(), 2, "{:?}", b.attractors);
    assert_eq!(two[0].mirror, Some(two[1].id));
    assert_eq!(two[1].mirror, Some(two[0].id));
    assert!((two[0].amplitude_m - two[1].amplitude_m).abs() < 1e-3 * two[0].amplitude_m);
    // The mirror relation on the runs themselves: a start of each attractor.
    let start_of = |id: usize| {
        let i = b.cells.iter().position(|&c| c == id).unwrap();
        let mut st = Start::of(&d.damper);
        st.y = b.y0_m[i % b.y0_m.len()];
        st.w = b.w0_m_s[i / b.y0_m.len()];
        run_orbit_halves(&d, &st, s, None)
    };
    let (a, _, _) = start_of(two[0].id);
    let (_, _, b_halves) = start_of(two[1].id);
    let tol = 1e-3 * a.amplitude_m;
    let last = a.samples.last().unwrap().x_m;
    assert!((last + b_halves.last().unwrap()[0]).abs() < tol, "x(kT) {last} vs −x(kT + T/2)");
    // The mirror is another orbit: its x(kT) is not the first one's.
    let (b_run, _, _) = start_of(two[1].id);
    assert!((last - b_run.samples.last().unwrap().x_m).abs() > 10.0 * tol);
}

#[test]
fn continuation_sweeps_up_then_down_and_basins_share_everything() {
    let d = forced_rattle().check().unwrap();
    let vary = Vary::of_values("freq", &[7.7, 7.8], Spelling::Keyword).unwrap();
    let s = Settings { transient_periods: 100, periods: 30 };
    let b = bifurcation(&d, &vary, s, true, "force", None, &|_| {}).unwrap();
    let dirs: Vec<(f64, Direction)> = b.points.iter().map(|p| (p.value, p.direction)).collect();
    assert_eq!(dirs, [(7.7, Direction::Up), (7.8, Direction::Up), (7.8, Direction::Down), (7.7, Direction::Down)]);
    let mut free = Design::default();
    free.damper.v0_m_s = 0.0;
    let e = bifurcation(&free.check().unwrap(), &vary, s, false, "force", None, &|_| {}).unwrap_err();
    assert_eq!(e.param(), "force");
    let basins = basins(&d, 3, &[-0.5, 0.5], s, "force", None, &|_| {}).unwrap();
    assert_eq!(basins.cells.len(), 6);
    let total: usize = basins.attractors.iter().map(|a| a.starts).sum();
    assert_eq!(total, 6);
    assert!((basins.attractors.iter().map(|a| a.share).sum::<f64>() - 1.0).abs() < 1e-12);
}
