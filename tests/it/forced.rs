#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test or benchmark fails
//! Forced vibration: harmonic forcing of the main mass in both solvers, the ball's
//! start, the steady state, its settling, its level and the frequency response.
//! docs/model.md §6.1–6.4.

use thud::damper::*;
use thud::design::{self, Design};
use thud::response::{self, Direction, ResponseOptions};
use thud::verdict::{Source, Verdict};

fn forced(force_n: f64, freq_hz: f64, duration_s: f64) -> DamperParams {
    DamperParams { force_n, freq_hz, duration_s, v0_m_s: 0.0, ..DamperParams::table2() }
}

fn opts() -> RunOptions<'static> {
    RunOptions::default()
}

fn close(x: f64, y: f64, rel: f64) -> bool {
    (x - y).abs() <= rel * x.abs().max(y.abs())
}

/// The first `n` impacts of both solvers (Newmark at 1e-7 s) agree to 1e-5 relative: onset and
/// exit times, wall, speeds in and out.
fn compare_first_impacts(p: DamperParams, n: usize) {
    let ev = simulate(&p, Solver::Event, &opts()).unwrap();
    let nm = simulate(&p, Solver::newmark_default(), &opts()).unwrap();
    assert!(ev.impacts.len() >= n && nm.impacts.len() >= n, "{} {}", ev.impacts.len(), nm.impacts.len());
    for (k, (a, b)) in ev.impacts.iter().zip(&nm.impacts).take(n).enumerate() {
        assert_eq!(a.wall, b.wall, "impact {k}");
        assert!(close(a.t_s, b.t_s, 1e-5), "impact {k} onset: {} vs {}", a.t_s, b.t_s);
        assert!(close(a.t_end_s, b.t_end_s, 1e-5), "impact {k} exit: {} vs {}", a.t_end_s, b.t_end_s);
        assert!(close(a.u_in_m_s, b.u_in_m_s, 1e-5), "impact {k} u_in: {} vs {}", a.u_in_m_s, b.u_in_m_s);
        assert!(close(a.u_out_m_s, b.u_out_m_s, 1e-5), "impact {k} u_out: {} vs {}", a.u_out_m_s, b.u_out_m_s);
    }
}

#[test]
fn solvers_agree_on_forced_designs_from_rest() {
    // Table 2 near resonance, above it, an off-centre ball driven harder below it, and a free
    // main mass (K = C = 0) shaken with the no-tension clamp.
    compare_first_impacts(forced(1.0, 5.0, 1.2), 6);
    compare_first_impacts(forced(1.0, 5.5, 2.0), 5);
    compare_first_impacts(DamperParams { ball_position_m: -0.012, ..forced(1.5, 4.6, 1.2) }, 6);
    compare_first_impacts(
        DamperParams {
            stiffness_n_m: 0.0,
            damping_n_s_m: 0.0,
            no_tension: true,
            ball_velocity_m_s: 0.05,
            ..forced(0.5, 2.0, 2.0)
        },
        5,
    );
}

/// Reference for a flight without impacts: classical RK4 on `M·x'' + C·x' + K·x = F0·cos(2πft)`
/// with a fine step, Richardson-extrapolated from two step sizes.
fn rk4_history(p: &DamperParams, times: &[f64]) -> Vec<f64> {
    let om = 2.0 * std::f64::consts::PI * p.freq_hz;
    let acc = |t: f64, x: f64, v: f64| {
        (p.force_n * (om * t).cos() - p.damping_n_s_m * v - p.stiffness_n_m * x) / p.main_mass_kg
    };
    let run = |per_sample: usize| {
        let (mut t, mut x, mut v) = (0.0, 0.0, p.v0_m_s);
        let mut out = Vec::new();
        for &ts in times {
            let h = (ts - t) / per_sample as f64;
            for _ in 0..per_sample {
                let (k1x, k1v) = (v, acc(t, x, v));
                let (k2x, k2v) = (v + 0.5 * h * k1v, acc(t + 0.5 * h, x + 0.5 * h * k1x, v + 0.5 * h * k1v));
                let (k3x, k3v) = (v + 0.5 * h * k2v, acc(t + 0.5 * h, x + 0.5 * h * k2x, v + 0.5 * h * k2v));
                let (k4x, k4v) = (v + h * k3v, acc(t + h, x + h * k3x, v + h * k3v));
                x += h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
                v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
                t += h;
            }
            t = ts;
            out.push(x);
        }
        out
    };
    let (a, b) = (run(200), run(400));
    a.iter().zip(&b).map(|(a, b)| b + (b - a) / 15.0).collect()
}

#[test]
fn forced_flight_matches_numerical_integration() {
    // No impact (a 10 m clearance): the main mass alone, lightly damped off resonance, undamped
    // near resonance, heavily damped; the exact flight against RK4 to 1e-10 of the amplitude.
    for p in [
        DamperParams { gap_m: 10.0, ..forced(1.0, 4.0, 3.0) },
        DamperParams { gap_m: 10.0, damping_n_s_m: 0.0, ..forced(1.0, 5.0, 3.0) },
        DamperParams { gap_m: 10.0, damping_n_s_m: 30.0, v0_m_s: 0.4, ..forced(2.0, 7.0, 3.0) },
    ] {
        let run = simulate(&p, Solver::Event, &RunOptions { history_samples: 301, cancel: None }).unwrap();
        assert!(run.impacts.is_empty());
        let times: Vec<f64> = run.history.iter().map(|h| h.t_s).collect();
        let want = rk4_history(&p, &times);
        let size = want.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for (h, w) in run.history.iter().zip(&want) {
            assert!((h.x_m - w).abs() < 1e-10 * size, "{p:?} at {}: {} vs {w}", h.t_s, h.x_m);
            assert!((h.x_m - free_response(&p, h.t_s)).abs() < 1e-15 * size.max(1.0));
        }
    }
}

#[test]
fn without_impacts_the_steady_amplitude_is_the_closed_form() {
    // A damped main mass (the transient has decayed by e^-60 within the first third of the run)
    // whose ball never reaches a wall: the largest |x| over the window is
    // F0/√((K − MΩ²)² + (CΩ)²) to 1e-9.
    for freq in [2.0, 4.9, 5.03, 9.0] {
        let p = DamperParams { gap_m: 10.0, damping_n_s_m: 5.0, ..forced(1.0, freq, 40.0) };
        let run = simulate(&p, Solver::Event, &opts()).unwrap();
        let s = run.steady.expect("a forced run has a steady state");
        let om = 2.0 * std::f64::consts::PI * freq;
        let closed = 1.0 / ((500.0 - 0.5 * om * om).powi(2) + (5.0 * om).powi(2)).sqrt();
        assert!(close(s.amplitude_linear_m.unwrap(), closed, 1e-14));
        assert!(close(s.amplitude_m, closed, 1e-9), "{freq} Hz: {} vs {closed}", s.amplitude_m);
        assert!(s.reduction_db.unwrap().abs() < 1e-7);
        assert!(s.periodic && s.settled && !s.truncated && s.impacts == 0, "{s:?}");
        assert_eq!(s.window_end_s, 40.0);
        assert!((s.window_start_s - (40.0 - 10.0 / freq)).abs() < 1e-12);
    }
    // The Newmark reference to its own accuracy.
    let p = DamperParams { gap_m: 10.0, damping_n_s_m: 5.0, ..forced(1.0, 5.0, 6.0) };
    let s = simulate(&p, Solver::Newmark { dt_s: 1e-5 }, &opts()).unwrap().steady.unwrap();
    assert!(close(s.amplitude_m, s.amplitude_linear_m.unwrap(), 1e-6), "{s:?}");
}

#[test]
fn undamped_resonance_has_no_steady_state() {
    let w0 = (500.0f64 / 0.5).sqrt();
    let p = DamperParams { gap_m: 10.0, damping_n_s_m: 0.0, ..forced(1.0, w0 / (2.0 * std::f64::consts::PI), 4.0) };
    let run = simulate(&p, Solver::Event, &RunOptions { history_samples: 41, cancel: None }).unwrap();
    let s = run.steady.unwrap();
    assert_eq!((s.amplitude_linear_m, s.reduction_db), (None, None));
    assert!(!s.settled && !s.periodic);
    // The secular growth x = F0/M·t·sin(ω0t)/(2ω0), written out here.
    for h in &run.history {
        let x = 2.0 * h.t_s * (w0 * h.t_s).sin() / (2.0 * w0);
        assert!((h.x_m - x).abs() < 1e-12, "{h:?} vs {x}");
    }
    // The largest |x| over the window [2, 4] s, found here on the formula: a fine scan, then
    // golden-section search around its best sample.
    let x = |t: f64| (2.0 * t * (w0 * t).sin() / (2.0 * w0)).abs();
    let n = 20_000;
    let dt = 2.0 / f64::from(n);
    let best = (0..=n).map(|i| 2.0 + f64::from(i) * dt).fold(2.0, |b, t| if x(t) > x(b) { t } else { b });
    let (mut lo, mut hi) = ((best - dt).max(2.0), (best + dt).min(4.0));
    for _ in 0..200 {
        let (m1, m2) = (lo + 0.382 * (hi - lo), hi - 0.382 * (hi - lo));
        if x(m1) < x(m2) {
            lo = m1;
        } else {
            hi = m2;
        }
    }
    assert!(close(s.amplitude_m, x(0.5 * (lo + hi)), 1e-9), "{} vs {}", s.amplitude_m, x(0.5 * (lo + hi)));
}

#[test]
fn settling_runs_on_until_the_windows_agree() {
    // Light damping, no impact: the free transient decays as e^(−γt), γ = 0.05 1/s.
    let p = DamperParams { gap_m: 10.0, ..forced(1.0, 3.0, 10.0) };
    let plain = simulate(&p, Solver::Event, &opts()).unwrap();
    assert_eq!(plain.final_time_s, 10.0);
    let s0 = plain.steady.unwrap();
    assert!(!s0.settled, "10 s is not enough: {s0:?}");
    let settled = simulate(&DamperParams { settle: true, ..p }, Solver::Event, &opts()).unwrap();
    let s = settled.steady.unwrap();
    assert!(s.settled && settled.final_time_s > 10.0, "{s:?}");
    assert_eq!(s.window_end_s, settled.final_time_s);
    let change = (s.amplitude_m / s.previous_amplitude_m.unwrap() - 1.0).abs();
    assert!(change <= 1e-3, "{change}");
    // Settled to the criterion, what is left of the transient is below 1e-3 of the amplitude.
    assert!(close(s.amplitude_m, s.amplitude_linear_m.unwrap(), 1e-3), "{s:?}");
    // A run that never settles stops at the cap and says so.
    let w0 = (500.0f64 / 0.5).sqrt();
    let never = DamperParams {
        gap_m: 10.0,
        damping_n_s_m: 0.0,
        settle: true,
        ..forced(1e-3, w0 / (2.0 * std::f64::consts::PI), 4.0)
    };
    let run = simulate(&never, Solver::Event, &opts()).unwrap();
    let s = run.steady.unwrap();
    assert!(!s.settled);
    let periods = (run.final_time_s - 4.0) * never.freq_hz;
    assert!((periods - f64::from(SETTLE_PERIODS_MAX)).abs() < 1e-6, "{periods}");
}

#[test]
fn the_energy_ledger_balances_with_the_work_of_the_force() {
    for solver in [Solver::Event, Solver::Newmark { dt_s: 1e-7 }] {
        for p in [
            forced(1.0, 5.0, 1.0),
            DamperParams { no_tension: true, ball_position_m: 0.01, ..forced(2.0, 4.0, 1.0) },
            DamperParams { damping_n_s_m: 0.0, ..forced(1.0, 5.5, 1.0) },
        ] {
            let run = simulate(&p, solver, &opts()).unwrap();
            let e = run.energy;
            assert!(e.forcing_work_j != 0.0 && !run.impacts.is_empty());
            let out = e.final_mechanical_j + e.dissipated_viscous_j + e.dissipated_contact_j;
            let scale = e.forcing_work_j.abs().max(e.final_mechanical_j);
            assert!((e.initial_j + e.forcing_work_j - out).abs() < 1e-6 * scale, "{solver:?} {p:?}: {e:?}");
        }
    }
}

#[test]
fn the_ball_starts_where_it_is_put() {
    // No force: the first contact of a ball started off centre and moving is where its straight
    // flight meets the free main mass's closed-form motion (found here by bisection).
    let p = DamperParams { ball_position_m: -0.011, ball_velocity_m_s: 0.3, duration_s: 0.2, ..DamperParams::table2() };
    let run = simulate(&p, Solver::Event, &opts()).unwrap();
    let (m, k, c) = (p.main_mass_kg, p.stiffness_n_m, p.damping_n_s_m);
    let g = c / (2.0 * m);
    let wd = (k / m - g * g).sqrt();
    let x = |t: f64| p.v0_m_s / wd * (-g * t).exp() * (wd * t).sin();
    // z = y − x reaches −d/2 first (the main mass moves up, towards the ball from below).
    let gap = |t: f64| p.ball_position_m + p.ball_velocity_m_s * t - x(t) + 0.5 * p.gap_m;
    let (mut lo, mut hi) = (0.0, 0.05);
    assert!(gap(lo) > 0.0 && gap(hi) < 0.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if gap(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let first = run.impacts[0];
    assert_eq!(first.wall, Wall::Lower);
    assert!((first.t_s - lo).abs() < 1e-12, "{} vs {lo}", first.t_s);
    // The centred ball at rest is the paper's start: the same run as before this option existed.
    let centred = DamperParams { ball_position_m: 0.0, ball_velocity_m_s: 0.0, ..p };
    assert_eq!(
        simulate(&centred, Solver::Event, &opts()).unwrap(),
        simulate(&DamperParams { duration_s: 0.2, ..DamperParams::table2() }, Solver::Event, &opts()).unwrap()
    );
    // A ball outside the clearance is refused by name.
    let outside = DamperParams { ball_position_m: 0.02, ..p };
    assert_eq!(simulate(&outside, Solver::Event, &opts()).unwrap_err().param(), "ball-position");
}

#[test]
fn a_frequency_without_a_force_changes_nothing() {
    let base = DamperParams::table2();
    let with_freq = DamperParams { freq_hz: 5.0, ..base };
    assert_eq!(simulate(&with_freq, Solver::Event, &opts()).unwrap(), simulate(&base, Solver::Event, &opts()).unwrap());
    assert!(simulate(&base, Solver::Event, &opts()).unwrap().steady.is_none());
    assert_eq!(simulate(&DamperParams { force_n: 1.0, ..base }, Solver::Event, &opts()).unwrap_err().param(), "freq");
}

#[test]
fn leq_is_the_energy_average_of_the_pulses() {
    // Impacts far apart: Leq over a window is the sum of the pulses' exposures (each pulse's own
    // SEL, integrated by the acoustics module) over the window's length.
    let d = Design::default().check().unwrap();
    let impacts: Vec<ImpactEvent> = [(0.1, 1.2), (0.35, 0.8), (0.61, 1.9)]
        .iter()
        .map(|&(t_s, u)| ImpactEvent {
            t_s,
            wall: Wall::Upper,
            u_in_m_s: u,
            u_out_m_s: u,
            t_end_s: t_s,
            penetration_max_m: 0.0,
        })
        .collect();
    let run = Run {
        impacts: impacts.clone(),
        maxima: vec![],
        zdot_abs_max_m_s: 0.0,
        energy: EnergyLedger::default(),
        history: vec![],
        final_time_s: 1.0,
        cancelled: false,
        truncated: None,
        steady: None,
    };
    let leq = response::leq_db(&run, &d, 0.0, 1.0).unwrap().unwrap();
    let sum: f64 = impacts.iter().map(|i| 10f64.powf(d.impact_field(i.u_in_m_s).unwrap().levels().sel_db / 10.0)).sum();
    let want = 10.0 * sum.log10();
    assert!((leq - want).abs() < 1e-6, "{leq} vs {want}");
    // A shorter window (0.6 s) holding the same pulses: 10·log10(1/0.6) dB more; none inside: no level.
    let short = response::leq_db(&run, &d, 0.09, 0.69).unwrap().unwrap();
    assert!((short - leq - 10.0 * (1.0f64 / 0.6).log10()).abs() < 1e-6, "{short}");
    assert_eq!(response::leq_db(&run, &d, 0.7, 1.0).unwrap(), None);
    // Two impacts at one instant are one pulse twice as loud in pressure: +6 dB on one.
    let twin = Run { impacts: vec![impacts[0], impacts[0]], ..run.clone() };
    let one = Run { impacts: vec![impacts[0]], ..run };
    let (l2, l1) = (
        response::leq_db(&twin, &d, 0.0, 1.0).unwrap().unwrap(),
        response::leq_db(&one, &d, 0.0, 1.0).unwrap().unwrap(),
    );
    assert!((l2 - l1 - 20.0 * 2f64.log10()).abs() < 1e-6);
}

#[test]
fn a_forced_design_reports_its_steady_state_in_its_evaluation() {
    let d = Design { damper: forced(1.0, 5.5, 4.0), ..Design::default() }.check().unwrap();
    let e = design::evaluate(&d, 0, None).unwrap();
    let s = e.steady.expect("forced");
    let m = e.run.steady.unwrap();
    assert_eq!((s.amplitude_m, s.impacts_per_period, s.periodic), (m.amplitude_m, m.impacts_per_period, m.periodic));
    assert!(s.leq_db.is_some() && s.impacts_per_period > 0.0);
    assert!(design::evaluate(&Design::default().check().unwrap(), 0, None).unwrap().steady.is_none());
}

/// A response from rest is its points run one by one: each point has the verdict of the
/// design at that frequency simulated until it settles, and its amplitude within that
/// simulation's settling tolerance (1e-3); where the motion settles to a periodic orbit with
/// impacts the point is that orbit, found by shooting.
#[test]
fn a_response_from_rest_is_its_points_run_one_by_one() {
    let d = Design { damper: forced(1.0, 5.0, 2.0), ..Design::default() }.check().unwrap();
    let freqs = [4.0, 5.2, 6.0];
    let r = response::response(&d, &freqs, &ResponseOptions::default(), None, &|| {}).unwrap();
    assert_eq!(r.sweeps.len(), 1);
    assert_eq!(r.sweeps[0].direction, Direction::FromRest);
    let mut shot = 0;
    for (pt, &f) in r.sweeps[0].points.iter().zip(&freqs) {
        let one = design::evaluate(&response::at_frequency(&d, f, true).check().unwrap(), 0, None).unwrap();
        let sim = one.steady.unwrap();
        if matches!(pt.steady.verdict, Verdict::Periodic { source: Source::Exact, .. }) {
            shot += 1;
        }
        assert_eq!(pt.steady.verdict.label(), sim.verdict.label(), "{f} Hz");
        let rel = (pt.steady.amplitude_m - sim.amplitude_m).abs() / sim.amplitude_m;
        assert!(rel <= 1e-3, "{f} Hz: {} vs {} simulated", pt.steady.amplitude_m, sim.amplitude_m);
        assert!(pt.final_time_s >= 2.0 * 10.0 / f);
    }
    assert!(shot >= 1, "the impacting orbit at 5.2 Hz is found by shooting");
}

#[test]
fn a_continued_response_sweeps_up_then_down() {
    let mut d = Design { damper: forced(1.0, 5.0, 2.0), ..Design::default() };
    d.damper.steady_periods = 4;
    let d = d.check().unwrap();
    let freqs = [4.8, 5.0, 5.2];
    let opts = ResponseOptions { continuation: true, settle: false };
    let r = response::response(&d, &freqs, &opts, None, &|| {}).unwrap();
    let dirs: Vec<Direction> = r.sweeps.iter().map(|s| s.direction).collect();
    assert_eq!(dirs, [Direction::Up, Direction::Down]);
    let up: Vec<f64> = r.sweeps[0].points.iter().map(|p| p.freq_hz).collect();
    let down: Vec<f64> = r.sweeps[1].points.iter().map(|p| p.freq_hz).collect();
    assert_eq!(up, freqs);
    assert_eq!(down, [5.2, 5.0, 4.8]);
    // The first point starts from rest, as a point of the response from rest does.
    let rest =
        response::response(&d, &freqs[..1], &ResponseOptions { continuation: false, settle: false }, None, &|| {})
            .unwrap();
    assert_eq!(r.sweeps[0].points[0], rest.sweeps[0].points[0]);
    // The next ones do not (they carry the state on).
    let rest2 =
        response::response(&d, &freqs[1..2], &ResponseOptions { continuation: false, settle: false }, None, &|| {})
            .unwrap();
    assert_ne!(r.sweeps[0].points[1].steady, rest2.sweeps[0].points[0].steady);
}

#[test]
fn a_forced_run_cut_by_a_work_cap_says_so_in_its_steady_state() {
    // A long, hard-driven run in a small clearance: the in-contact step cap stops it.
    let p = DamperParams { gap_m: 0.005, ..forced(5.0, 5.0, 5000.0) };
    let run = simulate(&p, Solver::Event, &opts()).unwrap();
    assert_eq!(run.truncated, Some(Truncation::ContactSteps));
    let s = run.steady.unwrap();
    assert!(s.truncated && !s.settled && !s.periodic, "{s:?}");
    assert_eq!(s.window_end_s, run.final_time_s.min(5000.0));
    // The window is the one the run stopped in, up to where it stopped.
    assert!(s.window_end_s < 5000.0 && s.window_start_s < s.window_end_s, "{s:?}");
    assert!(s.window_end_s - s.window_start_s <= 10.0 / 5.0 + 1e-9);
}
