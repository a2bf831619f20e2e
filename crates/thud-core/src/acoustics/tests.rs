use super::*;
use crate::contact::{Impact, Target};

#[test]
fn the_peak_level_alone_is_the_levels_peak_to_the_bit() {
    let contact = Impact { mass_kg: 0.0405, u0_m_s: 1.4, k_hz: 5.6e8, target: Target::FixedPlate }.contact();
    for source in Source::ALL {
        for pulse in [PulseShape::HalfSine, PulseShape::Hertz] {
            for (r, th) in [(0.7, 45.0), (0.2828, 45.0), (0.05, 80.0), (3.0, 10.0)] {
                let rad = Radiation { source, pulse, air: Air::from_state(20.0, 101_325.0), ..Default::default() };
                let f = Field::new(0.01905, &contact, &Observer::new(r, th), &rad).unwrap();
                assert_eq!(f.peak_db(), f.levels().spl_peak_db, "{source:?} {pulse:?} r {r} θ {th}");
            }
        }
    }
}

#[test]
fn room_air_from_temperature_and_pressure() {
    // ρ0 = 101325/(287.05287·293.15) = 1.204 11 kg/m³; c = √(1.4·287.05287·293.15)
    // = √117 809.3 = 343.234 m/s; ρ0c = 413.29 Pa·s/m (Kinsler et al. list 1.21 kg/m³,
    // 343 m/s and 415 rayl for 20 °C).
    let air = Air::from_state(20.0, 101_325.0);
    assert!((air.c_m_s - 343.234).abs() < 1e-3, "{air:?}");
    assert!((air.rho_c_pa_s_m / air.c_m_s - 1.204_11).abs() < 1e-5, "{air:?}");
    assert!((air.rho_c_pa_s_m - 413.29).abs() < 0.01, "{air:?}");
    // The speed of sound does not depend on the pressure; the impedance is proportional to it.
    let thin = Air::from_state(20.0, 50_662.5);
    assert!((thin.c_m_s - air.c_m_s).abs() < 1e-12 && (2.0 * thin.rho_c_pa_s_m - air.rho_c_pa_s_m).abs() < 1e-9);
}

#[test]
fn theta_range_is_the_open_side_of_each_source() {
    let a = 0.01905;
    for source in Source::ALL {
        let (lo, hi) = source.theta_range_deg();
        let valid = |deg: f64| validate_observer(a, &Observer::new(0.7, deg), source).is_ok();
        assert!(valid(lo) && valid(hi) && valid(0.5 * (lo + hi)), "{source:?}: {lo}..{hi} valid");
        if lo > -180.0 {
            assert!(!valid(lo - 1.0), "{source:?}: below {lo} is behind a wall");
        }
        if hi < 180.0 {
            assert!(!valid(hi + 1.0), "{source:?}: above {hi} is behind a wall");
        }
    }
    // Each added reflecting surface closes off space: quadrupole ⊂ dipole ⊂ single.
    let width = |s: Source| s.theta_range_deg().1 - s.theta_range_deg().0;
    assert!(width(Source::Quadrupole) < width(Source::Dipole) && width(Source::Dipole) < width(Source::Single));
}

fn fig2_contact() -> Contact {
    Impact { mass_kg: 0.0405, u0_m_s: 1.4, k_hz: 5.6e8, target: Target::FixedPlate }.contact()
}

#[test]
fn closed_form_matches_quadrature() {
    let air = Air::default();
    let mut worst: f64 = 0.0;
    for (a, u0, r, th) in
        [(0.01905, 1.4, 0.7, 45.0), (0.009525, 0.99, 0.2828, 10.0), (0.03, 2.8, 0.05, 80.0), (0.005, 0.3, 3.0, 0.0)]
    {
        let m = 0.0405 * (a / 0.01905_f64).powi(3);
        let c = Impact { mass_kg: m, u0_m_s: u0, k_hz: 5.6e8, target: Target::FixedPlate }.contact();
        let obs = Observer::new(r, th);
        let field = Field::new(a, &c, &obs, &Radiation { source: Source::Single, ..Default::default() }).unwrap();
        let s = field.sources().next().copied().unwrap();
        let scale = field.extrema().iter().fold(0.0_f64, |m, e| m.max(e.p_pa.abs()));
        for i in 0..200 {
            let t_ret = (f64::from(i) / 199.0) * 3.0 * c.tau_s;
            let closed = field.pressure(t_ret + s.delay_s);
            let quad = pressure_by_quadrature(t_ret, s.r_m, s.cos_theta, a, &c, &air);
            worst = worst.max((closed - quad).abs() / scale);
        }
    }
    assert!(worst < 1e-9, "worst relative difference {worst:e}");
}

#[test]
fn hertz_approach_is_the_exact_impact() {
    let n = 20_000;
    let g = hertz_approach_shape(n);
    // Peak approach α_max at τ/2, back to zero at τ (the exact κ), symmetric.
    assert!((g[n / 2] - 1.0).abs() < 1e-9, "{}", g[n / 2]);
    assert!(g[n].abs() < 1e-6, "{}", g[n]);
    for i in (0..=n).step_by(500) {
        assert!((g[i] - g[n - i]).abs() < 1e-7);
    }
    // Its acceleration impulse is 2·U0: ∫g^1.5 ds = 8/(5κ) in units of A_max·τ.
    let impulse = gauss_legendre(0.0, 1.0, 200, |s| {
        let x = s * n as f64;
        let i = (x as usize).min(n - 1);
        let g = g[i] + (x - i as f64) * (g[i + 1] - g[i]);
        g.powf(1.5)
    });
    let want = 8.0 / (5.0 * crate::contact::kappa());
    assert!((impulse - want).abs() < 1e-6, "{impulse} vs {want}");
}

#[test]
fn hertz_sine_series_reconstructs_the_pulse() {
    let n = 2000;
    let g = hertz_approach_shape(n);
    let b = PulseShape::Hertz.sine_series();
    let mut worst: f64 = 0.0;
    for (i, gi) in g.iter().enumerate() {
        let s = i as f64 / n as f64;
        let series: f64 =
            b.iter().enumerate().map(|(j, bk)| bk * ((2 * j + 1) as f64 * std::f64::consts::PI * s).sin()).sum();
        worst = worst.max((series - gi.powf(1.5)).abs());
    }
    assert!(worst < 1e-3, "{worst}");
    // The half-sine is its own one-term series; the Hertz pulse carries 8/(5κ)/(2/π) of its impulse.
    assert_eq!(PulseShape::HalfSine.sine_series(), &[1.0]);
}

#[test]
fn hertz_pulse_closed_form_matches_quadrature() {
    let c = fig2_contact();
    let air = Air::default();
    let rad = Radiation { source: Source::Single, pulse: PulseShape::Hertz, ..Default::default() };
    let field = Field::new(0.01905, &c, &Observer::new(0.7, 30.0), &rad).unwrap();
    let src = field.sources().next().copied().unwrap();
    let n = 20_000;
    let g = hertz_approach_shape(n);
    let accel = |xi: f64| {
        let x = (xi / c.tau_s).clamp(0.0, 1.0) * n as f64;
        let i = (x as usize).min(n - 1);
        c.accel_max_m_s2 * (g[i] + (x - i as f64) * (g[i + 1] - g[i])).powf(1.5)
    };
    let peak = field.extrema().iter().fold(0.0_f64, |m, e| m.max(e.p_pa.abs()));
    for k in 0..120 {
        let t_ret = f64::from(k) / 119.0 * 2.5 * c.tau_s;
        let upper = t_ret.min(c.tau_s);
        let quad = gauss_legendre(0.0, upper.max(1e-30), 200, |xi| {
            impulse_response(t_ret - xi, src.r_m, src.cos_theta, 0.01905, &air) * accel(xi)
        });
        let closed = field.pressure(t_ret + src.delay_s);
        assert!((closed - quad).abs() < 2e-3 * peak, "t' {t_ret}: {closed} vs {quad}");
    }
}

#[test]
fn impulse_response_is_zero_before_arrival() {
    assert_eq!(impulse_response(-1e-9, 1.0, 1.0, 0.01, &Air::default()), 0.0);
}

#[test]
fn single_source_falls_off_as_one_over_r_far_away() {
    let c = fig2_contact();
    let rad = Radiation { source: Source::Single, ..Default::default() };
    let l1 = Field::new(0.01905, &c, &Observer::new(100.0, 0.0), &rad).unwrap().levels();
    let l2 = Field::new(0.01905, &c, &Observer::new(200.0, 0.0), &rad).unwrap().levels();
    assert!((l1.spl_db - l2.spl_db - 20.0 * 2f64.log10()).abs() < 0.01);
}

#[test]
fn observer_inside_sphere_is_rejected() {
    let c = fig2_contact();
    assert!(Field::new(0.01905, &c, &Observer::new(0.01, 45.0), &Radiation::default()).is_err());
    assert!(Field::new(0.01905, &c, &Observer::new(0.03, 0.0), &Radiation::default()).is_err());
    assert!(Field::new(0.01905, &c, &Observer::new(f64::NAN, 0.0), &Radiation::default()).is_err());
}

#[test]
fn quadrupole_signs_differ() {
    let c = fig2_contact();
    let obs = Observer::new(0.7, 45.0);
    let paper = Field::new(0.01905, &c, &obs, &Radiation { quad_signs: QuadSigns::Paper, ..Default::default() })
        .unwrap()
        .levels();
    let rigid = Field::new(0.01905, &c, &obs, &Radiation::default()).unwrap().levels();
    assert!((paper.spl_db - rigid.spl_db).abs() > 0.1);
}

#[test]
fn degrees_round_trip_through_serde() {
    let o = Observer::new(0.7, 45.0);
    let s = serde_json::to_string(&o).unwrap();
    assert!(s.contains("\"theta_deg\":45"), "{s}");
    let back: Observer = serde_json::from_str(&s).unwrap();
    assert!((back.theta_rad - o.theta_rad).abs() < 1e-15);
}
