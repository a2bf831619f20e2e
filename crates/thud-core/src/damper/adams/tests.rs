use super::super::contact::ContactStart;
use super::super::contact::NoLoad;
use super::super::contact::{State, Unobserved};
use super::super::scheme_checks::{self, sys};
use super::*;

/// The start's series (fewer products) is the Taylor scheme's series, free and forced.
#[test]
fn the_start_series_is_the_taylor_schemes() {
    use super::super::forced::Harmonic;
    let s = sys(20.0, 500.0);
    let y = Y::from([0.01, -0.2, 3e-3, 0.7, 1e-4, 2e-6, 1e-4]);
    let r = Start { s: -1.0, sc: [1.0; 7], t_onset: 0.3, y, length: 0.064 };
    let check = |a: &Series, b: &Series| {
        for i in 0..7 {
            for k in 0..NC {
                let sc = a.c[i].iter().map(|c| c.abs()).fold(0.0, f64::max);
                assert!((a.c[i][k] - b.c[i][k]).abs() <= 1e-13 * sc, "{i} {k}: {} vs {}", a.c[i][k], b.c[i][k]);
            }
        }
    };
    let it = Integration::<NoLoad, Unobserved, 4, 8>::new(&s, NoLoad, &r, 1.0, Unobserved);
    check(&Series::expand(&s, &NoLoad, -1.0, 0.3, &y, false), &it.series());
    let load = Harmonic { f: 4.0, omega: 31.4, phase: 0.7 };
    let it = Integration::<Harmonic, Unobserved, 6, 10>::new(&s, load, &r, 1.0, Unobserved);
    check(&Series::expand(&s, &load, -1.0, 0.3, &y, false), &it.series());
}

/// A contact cut by its time limit ends exactly there and carries on (by DOP853) as if never
/// cut.
#[test]
fn a_cut_contact_resumes_where_it_stopped() {
    scheme_checks::cut_contacts(
        &[0.05, 0.1, 0.3, 0.5, 0.7, 0.93, 0.99],
        [1e-9, 1e-9, 1e-8],
        |s, y0, t_limit, left| integrate(ContactStart::free(s, y0, t_limit), left, Unobserved),
        |s, r, left| dop853::resume(Stretch::free(s, 1.0), r, left, Unobserved),
    );
}

/// Isolated contacts against the reference and the Taylor scheme, within the start and 64
/// steps a contact.
#[test]
fn isolated_contacts_match_the_reference_and_the_taylor_scheme() {
    scheme_checks::isolated_contacts(START_COST + 64 * STEP_COST, |s, y0, t_limit, left| {
        integrate(ContactStart::free(s, y0, t_limit), left, Unobserved)
    });
}

/// The release located on σ's polynomial with the state from the corrector's weights
/// ([`release`]) is the dense output's release, to round-off: the same polynomial,
/// evaluated two ways (rates at the nodes from smooth functions of θ; the step from θ = 0
/// to h, node j at θ = (1 − j)·h).
#[test]
fn the_release_is_the_dense_outputs() {
    let rate_at = |th: f64| {
        [
            (1.3 * th).cos(),
            -0.7 + 0.2 * th * th,
            -1.0 - 3.0 * th + th * th,
            0.4 * (2.0 * th).sin() - 0.9,
            0.3 + th,
            0.1 - th * th,
            1.0 + 0.5 * th,
            0.0,
        ]
    };
    for (h, s0) in [(0.02, 0.012), (0.02, 0.0199), (0.05, 1e-4), (0.01, 0.004)] {
        let rp = rate_at(h);
        let wm: Vec<[f64; 8]> = (0..K).map(|j| rate_at(-(j as f64) * h)).collect();
        let y = Y::from([0.01, -0.2, s0, 0.3, 1e-4, 2e-6, 1e-3]);
        let ser = dense::<4, 8>(&wm, &y, h, &rp);
        let y1 = ser.state(h);
        assert!(y1[2] < 0.0, "{h} {s0}");
        let (q, ye, du) = release::<4, 8>(&wm, &y, &y1, h, &rp);
        let qd = root_in(h, y[2], y1[2], |q| ser.eval(2, q));
        let want = ser.state(qd);
        assert!((q - qd).abs() <= 1e-13 * h, "{h} {s0}: q {q} vs {qd}");
        assert_eq!(ye[2], 0.0);
        for i in [0, 1, 3, 4, 5, 6] {
            let sc = want[i].abs().max(h);
            assert!((ye[i] - want[i]).abs() <= 1e-14 * sc, "{h} {s0} {i}: {} vs {}", ye[i], want[i]);
        }
        let dd = ser.eval(3, qd).1;
        assert!((du - dd).abs() <= 1e-13 * dd.abs().max(1.0), "{h} {s0}: {du} vs {dd}");
    }
}

/// The peak of σ by two Newton steps from the linear guess ([`peak_sigma`]) is the
/// maximum of the quintic Hermite interpolant to round-off, and that is the true peak of a
/// Hertz-like hump (σ = sin θ, peak 1 at π/2) to the tolerance, wherever the peak falls in
/// the step.
#[test]
fn the_peak_is_the_hermite_maximum() {
    // The same interpolant's maximum located by bisection on its slope's sign to
    // round-off (the reference).
    let by_bisection = |h: f64, a: (f64, f64, f64), b: (f64, f64, f64)| {
        let p = SigmaHermite::new(h, a, b);
        let (mut lo, mut hi) = (0.0, 1.0);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if p.slope(mid) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        p.value(0.5 * (lo + hi))
    };
    let h = std::f64::consts::PI / 64.0;
    for k in 0..=40 {
        // The peak at a fraction k/40 of the step (both ends included).
        let th0 = std::f64::consts::FRAC_PI_2 - h * f64::from(k) / 40.0;
        let end = |th: f64| (th.sin(), 2.0 * th.cos(), -2.0 * th.sin());
        let (a, b) = (end(th0), end(th0 + h));
        if !(a.1 > 0.0 && b.1 <= 0.0) {
            continue;
        }
        let got = peak_sigma(h, a, b);
        let want = by_bisection(h, a, b);
        assert!((got - want).abs() <= 4.0 * f64::EPSILON, "k {k}: {got} vs {want}");
        assert!((got - 1.0).abs() <= 1e-10, "k {k}: {got}");
    }
}

#[test]
fn the_step_budget_stops_a_contact() {
    let s = sys(20.0, 0.0);
    let y0 = State::new(0.0, 0.0, 0.0, 1.4, 0.0, 0.0);
    let mut left = START_COST + 3 * STEP_COST;
    let end = integrate(ContactStart::free(&s, y0, 1.0), &mut left, Unobserved);
    assert_eq!(end.outcome, ContactOutcome::WorkCap);
    assert_eq!(left, 0);
    assert!(end.y[2] > 0.0);
}
