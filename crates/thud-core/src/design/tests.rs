use std::ops::Range;
use std::sync::atomic::{AtomicBool, Ordering};

use super::*;
use crate::contact;
use crate::damper::Maximum;
use crate::error::ThudError;

fn maxima(xs: &[(f64, f64)]) -> Vec<Maximum> {
    xs.iter().map(|&(t_s, x_m)| Maximum { t_s, x_m }).collect()
}

#[test]
fn eq27_from_first_two_maxima() {
    let m = maxima(&[(0.05, 0.06), (0.25, 0.058), (0.45, 0.05)]);
    assert!((inclination_cm_s(&m).unwrap() - 1.0).abs() < 1e-12);
}

#[test]
fn fit_of_a_straight_decay_is_its_slope() {
    let m = maxima(&(0..10).map(|k| (0.2 * f64::from(k), 0.06 - 0.004 * f64::from(k))).collect::<Vec<_>>());
    // Slope −0.02 m/s = 2 cm/s; stops below X1/2 = 0.03 (k > 7).
    assert!((inclination_fit_cm_s(&m).unwrap() - 2.0).abs() < 1e-9);
    assert!(inclination_fit_cm_s(&m[..1]).is_none());
}

#[test]
fn zones_by_thresholds() {
    let t = Thresholds { spl_db: 100.0, inclination_cm_s: 1.0, zone_by: ZoneBy::Paper };
    assert_eq!(Zone::classify(101.0, 0.5, &t), Zone::NoisyWeak);
    assert_eq!(Zone::classify(101.0, 1.5, &t), Zone::NoisyStrong);
    assert_eq!(Zone::classify(99.0, 1.5, &t), Zone::QuietStrong);
    assert_eq!(Zone::classify(99.0, 0.5, &t), Zone::QuietWeak);
}

fn metrics_with(e: Option<f64>, e_fit: Option<f64>, spl: Option<f64>) -> Metrics {
    Metrics {
        n_impacts: 3,
        inclination_cm_s: e,
        inclination_fit_cm_s: e_fit,
        u0_max_m_s: 1.0,
        zdot_abs_max_m_s: 1.0,
        spl_max_db: spl,
        contact_duration_s: None,
        restitution_mean: None,
        zone: None,
    }
}

#[test]
fn zone_uses_the_inclination_the_thresholds_name() {
    let m = metrics_with(Some(0.5), Some(1.5), Some(101.0));
    assert_eq!(m.inclination_by(ZoneBy::Paper), Some(0.5));
    assert_eq!(m.inclination_by(ZoneBy::Fit), Some(1.5));
    let paper = Thresholds { spl_db: 100.0, inclination_cm_s: 1.0, zone_by: ZoneBy::Paper };
    let fit = Thresholds { zone_by: ZoneBy::Fit, ..paper };
    assert_eq!(m.zone(&paper), Some(Zone::NoisyWeak), "e 0.5 < e* 1");
    assert_eq!(m.zone(&fit), Some(Zone::NoisyStrong), "e_fit 1.5 ≥ e* 1");
    assert_eq!(metrics_with(Some(0.5), None, Some(101.0)).zone(&fit), None, "no e_fit: no zone by it");
    assert_eq!(metrics_with(Some(0.5), None, Some(101.0)).zone(&paper), Some(Zone::NoisyWeak));
    assert_eq!(metrics_with(Some(0.5), Some(1.5), None).zone(&paper), None, "no sound: no zone");
}

#[test]
fn evaluated_zone_is_the_zone_under_the_design_thresholds() {
    for zone_by in [ZoneBy::Paper, ZoneBy::Fit] {
        let mut d = Design::default();
        d.thresholds.zone_by = zone_by;
        let m = evaluate(&d.clone().check().unwrap(), 0, None).unwrap().metrics;
        assert!(m.zone.is_some(), "the default design sounds and decays");
        assert_eq!(m.zone, m.zone(&d.thresholds));
        let e = m.inclination_by(zone_by).unwrap();
        // e* moved to the other side of e: strong becomes weak or weak strong.
        let e_star = if e >= d.thresholds.inclination_cm_s { e + 1.0 } else { e - 1.0 };
        let flipped = Thresholds { inclination_cm_s: e_star, ..d.thresholds };
        assert_ne!(m.zone(&flipped), m.zone, "e* across e changes the zone");
    }
}

#[test]
fn paper_density_is_the_acrylic_of_the_materials_table() {
    assert_eq!(contact::material("acrylic").unwrap().density_kg_m3, PAPER_BALL_DENSITY);
}

#[test]
fn c1_for_restitution_inverts_the_curve() {
    let d = Design::default().check().unwrap();
    let c1 = c1_for_restitution(&d, 1.4, 0.8).unwrap();
    let mut d2 = d.clone().into_design();
    d2.damper.c1_n_s_m = c1;
    let r = restitution_curve(&d2.check().unwrap(), &[d.damper.impact_mass_kg], 1.4).unwrap()[0].1;
    assert!((r - 0.8).abs() < 1e-6, "{r}");
    assert!(c1_for_restitution(&d, 1.4, 1.5).is_err());
}

/// A small chart: four cells of short runs.
fn small_sweep(on_cell: &(dyn Fn(usize, &Cell) + Sync), cancel: Option<&AtomicBool>) -> Result<Chart, ThudError> {
    let mut d = Design::default();
    d.damper.duration_s = 0.1;
    sweep(&d.check().unwrap(), &[0.03, 0.06], &[0.02, 0.04], cancel, on_cell)
}

#[test]
fn sweep_is_the_cells_evaluated_one_by_one() {
    let seen = std::sync::atomic::AtomicUsize::new(0);
    let chart = small_sweep(
        &|_, _| {
            seen.fetch_add(1, Ordering::Relaxed);
        },
        None,
    )
    .unwrap();
    assert_eq!(seen.into_inner(), 4);
    assert_eq!(chart.done(), 4);
    let mut d = Design::default();
    d.damper.duration_s = 0.1;
    for (g, &gap) in chart.gaps_m.iter().enumerate() {
        for (m, &mass) in chart.masses_kg.iter().enumerate() {
            let alone = evaluate(&variant(&d, mass, gap).check().unwrap(), 0, None).unwrap().metrics;
            assert_eq!(chart.cell(m, g).unwrap().metrics, alone, "mass {mass}, gap {gap}");
        }
    }
}

#[test]
fn a_cancelled_sweep_starts_no_cell() {
    let stop = AtomicBool::new(true);
    let chart = small_sweep(&|_, _| panic!("no cell may finish"), Some(&stop)).unwrap();
    assert_eq!(chart.done(), 0);
}

/// A panic inside one cell (here in its progress callback, which runs in the cell's task)
/// reaches the caller instead of leaving a hole in an `Ok` chart.
#[test]
fn a_panicking_cell_propagates() {
    let caught = std::panic::catch_unwind(|| {
        small_sweep(
            &|i, _| {
                assert!(i != 2, "cell 2 failed");
            },
            None,
        )
    });
    let payload = caught.expect_err("the panic must propagate out of the sweep");
    assert_eq!(payload.downcast_ref::<&str>(), Some(&"cell 2 failed"));
}

#[test]
fn shards_cover_every_cell_once_in_order() {
    for cells in [1usize, 2, 7, 400, 401] {
        for n in 1..=cells.min(70) {
            let parts: Vec<Range<usize>> = (0..n).map(|k| shard_range(cells, k, n)).collect();
            assert_eq!(parts[0].start, 0);
            assert_eq!(parts[n - 1].end, cells);
            for w in parts.windows(2) {
                assert_eq!(w[0].end, w[1].start, "{cells} cells, {n} parts: contiguous");
            }
            let (lo, hi) = (
                parts.iter().map(std::iter::ExactSizeIterator::len).min(),
                parts.iter().map(std::iter::ExactSizeIterator::len).max(),
            );
            assert!(lo.unwrap() >= 1 && hi.unwrap() - lo.unwrap() <= 1, "{cells}/{n}: {lo:?}..{hi:?}");
        }
    }
    assert_eq!(shard_range(10, 3, 3), 0..0, "k ≥ n is no part");
    assert_eq!(shard_range(10, 0, 0), 0..0);
}

#[test]
fn a_sweep_split_into_parts_is_the_whole_sweep() {
    let mut d = Design::default();
    d.damper.duration_s = 0.1;
    let d = d.check().unwrap();
    let (masses, gaps) = ([0.03, 0.05, 0.07], [0.02, 0.04]);
    let whole = sweep(&d, &masses, &gaps, None, &|_, _| {}).unwrap();
    let mut joined = Chart::empty(masses.to_vec(), gaps.to_vec(), d.thresholds);
    for k in 0..4 {
        for (i, c) in sweep_cells(&d, &masses, &gaps, shard_range(6, k, 4), None, &|_, _| {}).unwrap() {
            assert!(joined.cells[i].replace(c).is_none(), "cell {i} twice");
        }
    }
    assert_eq!(joined, whole);
}

/// A design with `f` applied, checked: the name of the parameter the check refuses.
fn refused(f: impl FnOnce(&mut Design)) -> String {
    let mut d = Design::default();
    f(&mut d);
    d.check().unwrap_err().param().to_string()
}

#[test]
fn check_refuses_a_ball_outside_the_clearance_a_nan_and_an_out_of_range_value() {
    assert_eq!(refused(|d| d.damper.ball_position_m = 0.5 * d.damper.gap_m), "ball-position", "|y0| = d/2");
    assert_eq!(refused(|d| d.damper.ball_position_m = -0.03), "ball-position", "|y0| > d/2 (d 4 cm)");
    assert_eq!(refused(|d| d.damper.v0_m_s = f64::NAN), "v0");
    assert_eq!(refused(|d| d.thresholds.spl_db = f64::NAN), "thresholds");
    // Positive and finite, so the physics' own checks pass it; the range table does not.
    assert_eq!(refused(|d| d.damper.main_mass_kg = 1e7), "main-mass");
    assert_eq!(refused(|d| d.damper.freq_hz = 1e6), "freq");
    assert_eq!(refused(|d| d.observer.theta_rad = 120f64.to_radians()), "theta", "behind the corner's wall");
    let inside = Design::default().check().unwrap();
    assert!(inside.damper.ball_position_m.abs() < 0.5 * inside.damper.gap_m);
}

#[test]
fn check_resolves_k_hz_from_the_materials_for_the_balls_radius() {
    let rho = contact::material("nylon").unwrap().density_kg_m3;
    let mut d = Design {
        materials: Some(Materials { sphere: "nylon".into(), plate: "steel".into(), sphere_nu: None }),
        ball: BallSize::Density(rho),
        ..Design::default()
    };
    d.damper.k_hz = 1.0; // stale: the materials decide
    let v = d.clone().check().unwrap();
    let (nylon, steel) = (contact::material("nylon").unwrap(), contact::material("steel").unwrap());
    let radius = (3.0 * d.damper.impact_mass_kg / (4.0 * std::f64::consts::PI * rho)).cbrt();
    let want = contact::hertz_stiffness(radius, &nylon, &steel);
    assert!((v.damper.k_hz - want).abs() <= 1e-12 * want, "{} vs {want}", v.damper.k_hz);
    // A chart cell of another mass has another radius and so another K_HZ.
    let heavy = v.variant(4.0 * d.damper.impact_mass_kg, d.damper.gap_m).unwrap();
    let want_heavy = contact::hertz_stiffness(radius * 4f64.cbrt(), &nylon, &steel);
    assert!((heavy.damper.k_hz - want_heavy).abs() <= 1e-12 * want_heavy);
    assert!(heavy.damper.k_hz > v.damper.k_hz, "a bigger ball is stiffer (Eq 2)");
    // Without materials K_HZ is the design's own.
    assert_eq!(Design::default().check().unwrap().damper.k_hz, Design::default().damper.k_hz);
    // And a changed design is a Design again, to check again.
    let mut back = v.into_design();
    back.damper.ball_position_m = 1.0;
    assert_eq!(back.check().unwrap_err().param(), "ball-position");
}

#[test]
fn the_balls_poisson_ratio_overrides_its_materials_in_eq_2() {
    let radius: f64 = 0.01905 / 2.0;
    let with = |sphere_nu| Materials { sphere: "steel".into(), plate: "steel".into(), sphere_nu };
    // Eq 2 from the handbook numbers: steel E 210 GPa, ν 0.30; the ball's ν 0.28.
    let (e_s, e_p, nu_s, nu_p) = (210e9, 210e9, 0.28, 0.30);
    let want = 4.0 / 3.0 * radius.sqrt() / ((1.0 - nu_s * nu_s) / e_s + (1.0 - nu_p * nu_p) / e_p);
    let k = with(Some(nu_s)).hertz_stiffness(radius).unwrap();
    assert!((k - want).abs() <= 1e-12 * want, "{k} vs {want}");
    let own = with(None).hertz_stiffness(radius).unwrap();
    assert!(k < own, "a smaller ν is a more compliant contact: {k} vs {own}");
    // The material's own ν as the override is the material: the same K_HZ to the bit.
    for m in contact::MATERIALS {
        let pair = |sphere_nu| Materials { sphere: m.name.into(), plate: "brass".into(), sphere_nu };
        let (given, plain) = (pair(Some(m.nu)).hertz_stiffness(radius), pair(None).hertz_stiffness(radius));
        assert_eq!(given.unwrap().to_bits(), plain.unwrap().to_bits(), "{}", m.name);
    }
    // A design checks and resolves it, and refuses it out of its range by name.
    let mut d = Design { materials: Some(with(Some(nu_s))), ..Design::default() };
    let v = d.clone().check().unwrap();
    let want = with(Some(nu_s)).hertz_stiffness(d.ball_radius_m()).unwrap();
    assert_eq!(v.damper.k_hz.to_bits(), want.to_bits());
    d.materials = Some(with(Some(0.7)));
    assert_eq!(d.check().unwrap_err().param(), "sphere-poisson");
}

#[test]
fn no_poisson_ratio_is_written_unless_one_is_given() {
    let d = Design {
        materials: Some(Materials { sphere: "glass".into(), plate: "steel".into(), sphere_nu: None }),
        ..Design::default()
    };
    let text = serde_json::to_string(&d).unwrap();
    assert!(text.contains(r#""materials":{"sphere":"glass","plate":"steel"}"#), "{text}");
    let mut m = d.materials.clone().unwrap();
    m.sphere_nu = Some(0.25);
    let back: Materials = serde_json::from_str(&serde_json::to_string(&m).unwrap()).unwrap();
    assert_eq!(back, m);
    let old: Materials = serde_json::from_str(r#"{"sphere":"glass","plate":"steel"}"#).unwrap();
    assert_eq!(old.sphere_nu, None, "a file from before the parameter reads as the material's own ν");
}

#[test]
fn a_variant_outside_the_clearance_is_refused() {
    let mut d = Design::default();
    d.damper.ball_position_m = 0.015;
    let v = d.check().unwrap();
    assert!(v.variant(0.05, 0.04).is_ok());
    assert_eq!(v.variant(0.05, 0.02).unwrap_err().param(), "ball-position", "|y0| 1.5 cm ≥ 1 cm");
    let e = sweep(&v, &[0.05], &[0.04, 0.02], None, &|_, _| {}).unwrap_err();
    assert_eq!(e.param(), "ball-position", "the sweep's cell at d 2 cm");
}

#[test]
fn a_checked_design_is_read_back_only_if_it_checks() {
    let v = Design::default().check().unwrap();
    let text = serde_json::to_string(&v).unwrap();
    assert_eq!(text, serde_json::to_string(v.design()).unwrap(), "written as the design it holds");
    let back: ValidDesign = serde_json::from_str(&text).unwrap();
    assert_eq!(back, v);
    let mut json: serde_json::Value = serde_json::from_str(&text).unwrap();
    json["damper"]["main_mass_kg"] = serde_json::json!(1e7);
    let raw: Design = serde_json::from_value(json.clone()).unwrap();
    assert_eq!(raw.damper.main_mass_kg, 1e7, "a plain Design reads it");
    let e = serde_json::from_value::<ValidDesign>(json).unwrap_err().to_string();
    assert!(e.contains("invalid main-mass: ") && e.contains("out of range"), "{e}");
}

#[test]
fn design_round_trips_through_json() {
    let d = Design::default();
    let back: Design = serde_json::from_str(&serde_json::to_string(&d).unwrap()).unwrap();
    assert_eq!(back, d);
}

/// One spelling written (units in the keys, enums as the flags spell them); thud 0.1's
/// spelling still read, so saved designs and presets load.
#[test]
fn design_is_written_in_the_one_spelling_and_read_in_the_old_one_too() {
    let mut d = Design::default();
    d.radiation.pulse = crate::acoustics::PulseShape::HalfSine;
    let text = serde_json::to_string(&d).unwrap();
    for new in ["\"k_hz_n_m1_5\":", "\"density_kg_m3\":", "\"solver\":\"event\"", "\"pulse\":\"half-sine\""] {
        assert!(text.contains(new), "{new} not in {text}");
    }
    let old = text
        .replace("\"k_hz_n_m1_5\":", "\"k_hz\":")
        .replace("\"density_kg_m3\":", "\"density\":")
        .replace("\"solver\":\"event\"", "\"solver\":\"Event\"")
        .replace("\"pulse\":\"half-sine\"", "\"pulse\":\"half_sine\"");
    assert_ne!(old, text);
    assert_eq!(serde_json::from_str::<Design>(&old).unwrap(), d);
    d.solver = crate::damper::Solver::newmark_default();
    d.ball = BallSize::Radius(0.01);
    let text = serde_json::to_string(&d).unwrap();
    assert!(text.contains("{\"newmark\":{\"dt_s\":") && text.contains("{\"radius_m\":0.01}"), "{text}");
    let old = text.replace("\"newmark\"", "\"Newmark\"").replace("\"radius_m\"", "\"radius\"");
    assert_eq!(serde_json::from_str::<Design>(&old).unwrap(), d);
}
