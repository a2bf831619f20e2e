#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test or benchmark fails
//! Part 2 of the paper reproduced: Tables 3–5, Figs 9 and 13, and the design metrics
//! (docs/model.md §6, §7, §9).

use thud::contact::{kappa, ln_gamma};
use thud::design::{self, Design, U0MaxRule, Zone};
use thud::paper;
use thud::presets;

#[test]
fn table3_u0max_every_cell_within_0_012() {
    let model = paper::table3_model().unwrap();
    let mut sq = 0.0;
    for (mi, row) in paper::TABLE3.iter().enumerate() {
        for (gi, &(u_paper, _)) in row.iter().enumerate() {
            let u = model[mi][gi].0;
            assert!(
                (u - u_paper).abs() < 0.012,
                "m {} d {}: {u:.4} vs {u_paper}",
                paper::TABLE3_MASSES_KG[mi],
                paper::TABLE3_GAPS_M[gi]
            );
            sq += (u - u_paper).powi(2);
        }
    }
    // docs/model.md §7: rms ≈ 0.005 m/s.
    assert!((sq / 44.0).sqrt() < 0.006);
}

#[test]
fn table3_splmax_residual_is_reported_not_tuned() {
    // The paper's SPLmax column follows no clear convention; with the acrylic ball and the
    // paper's signs the model is within about 1 dB everywhere (rms ≈ 0.6 dB). This guards
    // against a regression, it does not tune to the paper.
    let model = paper::table3_model().unwrap();
    let mut sq = 0.0;
    for (mi, row) in paper::TABLE3.iter().enumerate() {
        for (gi, &(_, l_paper)) in row.iter().enumerate() {
            let l = model[mi][gi].1;
            assert!(
                (l - l_paper).abs() < 1.2,
                "m {} d {}: {l:.2} vs {l_paper}",
                paper::TABLE3_MASSES_KG[mi],
                paper::TABLE3_GAPS_M[gi]
            );
            sq += (l - l_paper).powi(2);
        }
    }
    assert!((sq / 44.0).sqrt() < 0.7);
}

#[test]
fn table3_splmax_rises_with_mass_and_gap() {
    let model = paper::table3_model().unwrap();
    for gi in 0..4 {
        for mi in 1..model.len() {
            assert!(model[mi][gi].1 > model[mi - 1][gi].1 - 0.05, "mass trend at gap {gi}");
        }
    }
    for row in &model {
        for gi in 1..4 {
            assert!(row[gi].1 > row[gi - 1].1, "gap trend");
        }
    }
}

/// τ by quadrature of the Hertz energy integral, τ = (2α_max/U0)·∫₀¹ dx/√(1 − x^(5/2)), with
/// x = 1 − s² to remove the endpoint singularity.
fn duration_by_quadrature(alpha_max: f64, u0: f64) -> f64 {
    let integral = thud::acoustics::gauss_legendre(0.0, 1.0, 400, |s| {
        let x: f64 = 1.0 - s * s;
        2.0 * s / (1.0 - x.powf(2.5)).sqrt()
    });
    2.0 * alpha_max / u0 * integral
}

#[test]
fn kappa_and_table4_closed_form() {
    let b = (ln_gamma(0.4) + ln_gamma(0.5) - ln_gamma(0.9)).exp();
    assert!((kappa() - 0.8 * b).abs() < 1e-15);
    assert!((kappa() - 2.943_275_184_3).abs() < 1e-9);
    for (u0, ..) in paper::TABLE4 {
        let closed = paper::closed_form_duration(0.040, 0.5, 5.6e8, u0);
        let k_star = (0.040 + 0.5) / (0.040 * 0.5);
        let alpha = thud::contact::peak_approach(u0, k_star, 5.6e8);
        let quad = duration_by_quadrature(alpha, u0);
        assert!(((closed - quad) / quad).abs() < 1e-9, "U0 {u0}: {closed} vs {quad}");
    }
}

#[test]
fn table4_model_notes_values() {
    // docs/model.md §7 lists the 40 g closed form to 0.01 µs; those numbers were made with the
    // paper's rounded κ = 2.9432 (e.g. 251.50 where the exact κ gives 251.51). Check both:
    // the list with the rounded κ to its rounding, and the exact κ within the κ rounding.
    let listed = [258.81, 255.00, 251.50, 248.28, 245.29, 242.50, 239.89, 237.44, 235.14, 232.96];
    for ((u0, ..), l) in paper::TABLE4.iter().zip(listed) {
        let exact = paper::closed_form_duration(0.040, 0.5, 5.6e8, *u0) * 1e6;
        let rounded = exact * 2.9432 / kappa();
        assert!((rounded - l).abs() <= 0.005 + 1e-9, "U0 {u0}: {rounded:.4} vs {l}");
        assert!(((exact - l) / l).abs() < 2.3e-5 + 0.005 / l, "U0 {u0}: {exact:.4} vs {l}");
    }
}

#[test]
fn table4_paper_exact_column_matches_40_5_g() {
    for (u0, _, exact, _) in paper::TABLE4 {
        let at_40 = paper::closed_form_duration(0.040, 0.5, 5.6e8, u0);
        let at_40_5 = paper::closed_form_duration(0.0405, 0.5, 5.6e8, u0);
        // The paper prints to 1 µs (its rounding is not always to nearest: 249.43 → 250).
        assert!((at_40_5 - exact).abs() < 1e-6, "U0 {u0}");
        assert!((at_40_5 - exact).abs() < (at_40 - exact).abs() + 1e-12);
    }
}

#[test]
fn fig9_first_impacts() {
    let d = presets::preset("paper-fig9").unwrap().check().unwrap();
    let e = design::evaluate(&d, 0, None).unwrap();
    let i = &e.run.impacts;
    assert!((i[0].t_s - 0.0101800).abs() < 1e-6);
    assert!((i[0].u_in_m_s - 1.89529).abs() < 5e-5);
    assert!((i[0].u_out_m_s - 1.76371).abs() < 5e-5);
    assert!((i[1].u_in_m_s - 2.43469).abs() < 5e-5);
    // The impact damper damps: the maxima decay faster than with the viscous damper alone.
    let m = &e.metrics;
    assert!(m.inclination_fit_cm_s.unwrap() > 0.3);
}

#[test]
fn splmax_rises_with_impact_speed() {
    // SPLmax is taken at U0max: SPL must rise monotonically with the impact speed.
    let d = Design::default();
    let mut last = f64::NEG_INFINITY;
    for k in 1..40 {
        let l = d.impact_spl_db(0.1 * f64::from(k)).unwrap();
        assert!(l > last, "U0 {}", 0.1 * f64::from(k));
        last = l;
    }
}

#[test]
fn no_impact_design_has_no_spl_and_no_zone() {
    let mut d = Design::default();
    d.damper.gap_m = 2.5 * 2.0 * d.damper.v0_m_s / (d.damper.stiffness_n_m / d.damper.main_mass_kg).sqrt();
    let e = design::evaluate(&d.clone().check().unwrap(), 0, None).unwrap();
    assert_eq!(e.metrics.n_impacts, 0);
    assert!(e.metrics.spl_max_db.is_none() && e.metrics.zone.is_none());
    d.u0max_rule = U0MaxRule::WholeRun;
    let e = design::evaluate(&d.clone().check().unwrap(), 0, None).unwrap();
    assert!((e.metrics.u0_max_m_s - d.damper.v0_m_s).abs() < 1e-12);
}

#[test]
fn sweep_matches_single_evaluations_and_fills_every_cell() {
    let base = presets::preset("paper-table3").unwrap().check().unwrap();
    let masses = design::linspace(0.03, 0.1, 4);
    let gaps = design::linspace(0.02, 0.05, 3);
    let chart = design::sweep(&base, &masses, &gaps, None, &|_, _| {}).unwrap();
    assert_eq!(chart.done(), 12);
    for (gi, &g) in gaps.iter().enumerate() {
        for (mi, &m) in masses.iter().enumerate() {
            let one = design::evaluate(&design::variant(&base, m, g).check().unwrap(), 0, None).unwrap();
            assert_eq!(chart.cell(mi, gi).unwrap().metrics, one.metrics);
        }
    }
}

#[test]
fn zone_three_is_at_small_gaps_in_the_paper_chart() {
    // The paper: zone 3 (quiet and strong) for d 2–3 cm and m 30–60 g.
    let base = presets::preset("paper-table3").unwrap().check().unwrap();
    let chart = design::sweep(&base, &[0.03, 0.045, 0.06], &[0.0225, 0.025], None, &|_, _| {}).unwrap();
    let threes = chart.cells.iter().flatten().filter(|c| c.metrics.zone == Some(Zone::QuietStrong)).count();
    assert!(threes >= 5, "{threes} of 6 in zone 3");
}

#[test]
fn restitution_rises_with_mass() {
    let d = Design::default().check().unwrap();
    let r = design::restitution_curve(&d, &[0.01, 0.03, 0.05, 0.1], 1.4).unwrap();
    for ((_, got), want) in r.iter().zip([0.84, 0.91, 0.93, 0.95]) {
        assert!((got - want).abs() < 0.01, "{got} vs {want}");
    }
}

#[test]
fn invalid_designs_are_refused() {
    type Spoil = fn(&mut Design);
    let cases: [(&str, Spoil); 8] = [
        ("mass", |d| d.damper.impact_mass_kg = 0.0),
        ("mass", |d| d.damper.impact_mass_kg = -0.01),
        ("gap", |d| d.damper.gap_m = 0.0),
        ("v0", |d| d.damper.v0_m_s = f64::NAN),
        ("duration", |d| d.damper.duration_s = 0.0),
        ("dt", |d| d.solver = thud::damper::Solver::Newmark { dt_s: 0.0 }),
        ("r", |d| d.observer.r_m = 0.001),
        ("density", |d| d.ball = design::BallSize::Density(-1.0)),
    ];
    for (param, f) in cases {
        let mut d = Design::default();
        f(&mut d);
        let err = d.check().unwrap_err();
        assert_eq!(err.param(), param, "{err}");
    }
}
