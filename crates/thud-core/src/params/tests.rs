use super::*;
use crate::contact;
use crate::damper::Solver;
use crate::design::{BallSize, Materials};
use crate::error::ThudError;
use crate::limits;

fn text(pairs: &[(&str, &str)]) -> Vec<(String, Input)> {
    pairs.iter().map(|(n, v)| (n.to_string(), Input::Text(v.to_string()))).collect()
}

fn err<T: std::fmt::Debug>(r: Result<T, ThudError>) -> String {
    r.unwrap_err().to_string()
}

#[test]
fn the_default_design_and_presets_like_it_are_in_range() {
    check_design(&Design::default()).unwrap();
    check_design(&Design::paper_table3()).unwrap();
}

#[test]
fn check_design_refuses_an_out_of_range_field_by_name() {
    let mut d = Design::default();
    d.damper.stiffness_n_m = 1e308;
    assert!(check_design(&d).unwrap_err().to_string().starts_with("invalid k: "));
    let d = Design { ball: BallSize::Density(1e308), ..Design::default() };
    assert!(check_design(&d).unwrap_err().to_string().starts_with("invalid density: "));
    let mut d = Design::default();
    d.thresholds.inclination_cm_s = -5.0;
    assert!(check_design(&d).unwrap_err().to_string().starts_with("invalid e-star: "));
}

/// The check is the table's: for every row of [`DESIGN`] with a range, a design with that
/// one value below its range, above it or NaN (on a design the row applies to) is refused
/// by [`Design::check`], and [`check_design`] names the row.
#[test]
fn a_design_with_any_single_row_out_of_range_is_refused() {
    let materials = Materials { sphere: "steel".into(), plate: "steel".into(), sphere_nu: Some(0.3) };
    // Designs between them every row applies to: the default (a density ball, the event
    // solver, no materials, no force), a ball of a given radius, the Newmark solver, materials.
    let bases = [
        Design::default(),
        Design { ball: BallSize::Radius(0.01), ..Design::default() },
        Design { solver: Solver::Newmark { dt_s: NEWMARK_DT_S }, ..Design::default() },
        Design { materials: Some(materials), ..Design::default() },
    ];
    for p in DESIGN {
        let Some(range) = p.range() else { continue };
        assert_eq!(range.param, p.name, "the range of a row names the row");
        let get = p.get.unwrap_or_else(|| panic!("{}: a row with a range reads its value", p.name));
        let mut refused = 0;
        let wide = |b: f64| b.abs().max(1.0);
        for v in [range.min - wide(range.min), range.max + wide(range.max), f64::NAN] {
            // The row's value set to v: the Newmark step is the solver's, not a design value.
            let with = |base: &Design| match p.name {
                "dt" => Design { solver: Solver::Newmark { dt_s: v }, ..base.clone() },
                _ => set_number(base, p, v),
            };
            let Some(d) = bases.iter().map(with).find(|d| p.applies.is_none_or(|applies| applies(d))) else {
                panic!("{}: no design the row applies to", p.name)
            };
            if range.contains(get(&d)) {
                continue; // a count cannot hold v (NaN, or below 0)
            }
            assert!(d.clone().check().is_err(), "{} = {v} passed Design::check", p.name);
            let e = check_design(&d).unwrap_err();
            assert_eq!(e.param(), p.name, "{} = {v}: {e}", p.name);
            refused += 1;
        }
        assert!(refused >= 2, "{}: only {refused} of its out-of-range values could be set", p.name);
    }
}

/// A row is checked only where it applies: K_HZ that materials set, a frequency without a
/// force, a Newmark step of the event solver, a density of a ball of given radius.
#[test]
fn a_row_that_does_not_apply_is_not_checked() {
    let materials = Materials { sphere: "steel".into(), plate: "steel".into(), sphere_nu: None };
    let mut d = Design { materials: Some(materials), ..Design::default() };
    d.damper.k_hz = 0.0;
    check_design(&d).unwrap();
    let mut d = Design { ball: BallSize::Radius(0.01), ..Design::default() };
    d.damper.freq_hz = 0.0;
    d.damper.force_n = 0.0;
    check_design(&d).unwrap();
    d.damper.force_n = 1.0;
    assert_eq!(check_design(&d).unwrap_err().param(), "freq", "a force needs a frequency");
}

#[test]
fn numbers_and_texts_with_units_give_the_same_design() {
    let a = design(Design::default(), &text(&[("mass", "0.05"), ("gap", "3cm")]), Spelling::Flag).unwrap();
    let b = design(
        Design::default(),
        &[("gap".into(), Input::Num(0.03)), ("mass".into(), Input::Num(0.05))],
        Spelling::Keyword,
    )
    .unwrap();
    assert_eq!(a, b);
    assert_eq!(a.damper.impact_mass_kg, 0.05);
    assert_eq!(a.damper.gap_m, 0.03);
}

#[test]
fn no_parameters_leave_the_base_as_it_is() {
    assert_eq!(design(Design::paper_fig9(), &[], Spelling::Flag).unwrap(), Design::paper_fig9());
}

#[test]
fn errors_name_the_parameter_as_the_front_end_spells_it() {
    let e = err(design(Design::default(), &text(&[("main-mass", "1e308")]), Spelling::Flag));
    assert!(e.starts_with("invalid --main-mass: 1e308 kg is out of range; the main mass M must be"), "{e}");
    let e = err(design(Design::default(), &[("main_mass".into(), Input::Num(1e308))], Spelling::Keyword));
    assert!(e.starts_with("invalid main_mass: 1e308 kg is out of range; the main mass M must be"), "{e}");
    let e = err(design(Design::default(), &[("gap".into(), Input::Num(f64::NAN))], Spelling::Keyword));
    assert!(e.starts_with("invalid gap: NaN is not a finite number"), "{e}");
    let e = err(design(Design::default(), &[("gap".into(), Input::Num(f64::INFINITY))], Spelling::Keyword));
    assert!(e.starts_with("invalid gap: inf is not a finite number"), "{e}");
}

#[test]
fn unknown_names_and_wrong_kinds_are_refused() {
    let e = err(design(Design::default(), &[("mas".into(), Input::Num(1.0))], Spelling::Keyword));
    assert!(e.starts_with("invalid mas: unknown parameter; did you mean mass?"), "{e}");
    assert!(e.contains("main_mass") && e.contains("e_star"), "{e}");
    let e = err(design(Design::default(), &[("mass".into(), Input::Switch(true))], Spelling::Keyword));
    assert_eq!(e, "invalid mass: expected a number in kg or a text with a unit, not a switch (True or False)");
    let e = err(design(Design::default(), &[("mass".into(), Input::Other("a list".into()))], Spelling::Keyword));
    assert_eq!(e, "invalid mass: expected a number in kg or a text with a unit, not a list");
    let e = err(design(Design::default(), &[("main-mass".into(), Input::Num(1.0))], Spelling::Keyword));
    assert!(e.starts_with("invalid main-mass: unknown parameter; did you mean main_mass?"), "{e}");
    let e = err(design(Design::default(), &text(&[("source", "monopole")]), Spelling::Keyword));
    assert_eq!(e, "invalid source: unknown value 'monopole'; one of: single, dipole, quadrupole");
    let e = err(design(Design::default(), &[("no_tension".into(), Input::Num(1.0))], Spelling::Keyword));
    assert!(e.starts_with("invalid no_tension: expected on or off"), "{e}");
}

#[test]
fn the_first_problem_in_table_order_is_reported_whatever_the_order_given() {
    let pairs = text(&[("theta", "1e9"), ("mass", "-1")]);
    assert!(err(design(Design::default(), &pairs, Spelling::Flag)).starts_with("invalid --mass: "));
}

#[test]
fn combinations_the_command_line_refuses_in_clap_are_refused_here() {
    // A radius and a density fix the ball's mass (not a conflict); a mass as
    // well over-determines it, refused when the three disagree.
    let d = design(Design::default(), &text(&[("density", "1000"), ("radius", "1cm")]), Spelling::Keyword).unwrap();
    assert!((d.damper.impact_mass_kg - contact::sphere_mass(0.01, 1000.0)).abs() < 1e-15);
    let e = err(design(
        Design::default(),
        &text(&[("density", "1000"), ("radius", "1cm"), ("mass", "40.5g")]),
        Spelling::Flag,
    ));
    assert!(
        e.starts_with("invalid --density: --mass 0.0405 kg, --radius 0.01 m and --density 1000 kg/m^3 disagree"),
        "{e}"
    );
    let e = err(design(Design::default(), &text(&[("plate", "steel")]), Spelling::Keyword));
    assert_eq!(e, "invalid plate: needs sphere as well");
    let e = err(design(Design::default(), &text(&[("dt", "1e-7")]), Spelling::Keyword));
    assert!(e.contains("add solver=\"newmark\""), "{e}");
}

#[test]
fn solver_materials_and_choices_apply() {
    let d = design(
        Design::default(),
        &text(&[("solver", "newmark"), ("dt", "1e-6"), ("sphere", "steel"), ("source", "dipole")]),
        Spelling::Flag,
    )
    .unwrap();
    assert_eq!(d.solver, Solver::Newmark { dt_s: 1e-6 });
    assert_eq!(d.materials.as_ref().map(|m| m.plate.as_str()), Some("steel"));
    assert_eq!(d.radiation.source, Source::Dipole);
    let steel = contact::material("steel").unwrap();
    assert_eq!(d.damper.k_hz, contact::hertz_stiffness(d.ball_radius_m(), &steel, &steel));
}

#[test]
fn one_ball_whatever_the_command() {
    // A steel ball of 40.5 g: a = (3m/4πρ)^(1/3) = 10.7 mm, for a design and an impact alike.
    let steel = contact::material("steel").unwrap();
    let a = contact::sphere_radius(0.0405, steel.density_kg_m3);
    assert!((a - 0.010_7).abs() < 1e-4, "{a}");
    let given = text(&[("sphere", "steel"), ("mass", "40.5g")]);
    let d = design(Design::default(), &given, Spelling::Flag).unwrap();
    let p = pulse(None, &given, Spelling::Flag).unwrap();
    assert!(
        (d.ball_radius_m() - a).abs() < 1e-15 && (p.radius_m - a).abs() < 1e-15,
        "{} {}",
        d.ball_radius_m(),
        p.radius_m
    );
    assert_eq!((d.damper.impact_mass_kg, p.impact.mass_kg), (0.0405, 0.0405));
    assert_eq!(d.damper.k_hz, p.impact.k_hz, "one ball, one K_HZ");
    // Only a material: the design keeps its mass, the density follows the material.
    let d = design(Design::default(), &text(&[("sphere", "steel")]), Spelling::Flag).unwrap();
    assert!((d.ball_radius_m() - a).abs() < 1e-15);
    // Mass, radius and density that agree are taken.
    let r = format!("{}m", contact::sphere_radius(0.0405, 2000.0));
    let given = text(&[("mass", "40.5g"), ("radius", &r), ("density", "2000")]);
    assert!(design(Design::default(), &given, Spelling::Flag).is_ok());
    let e = err(pulse(None, &text(&[("mass", "40.5g"), ("radius", "1cm"), ("density", "2000")]), Spelling::Keyword));
    assert!(e.starts_with("invalid density: mass 0.0405 kg, radius 0.01 m and density 2000 kg/m^3 disagree"), "{e}");
}

#[test]
fn the_physical_model_derives_air_pulse_and_stiffness_and_refuses_them_given() {
    let d = design(Design::default(), &text(&[("model", "physical")]), Spelling::Flag).unwrap();
    let sound = d.sound();
    assert_eq!(sound.pulse, PulseShape::Hertz);
    assert!((sound.air.rho_c_pa_s_m - 413.29).abs() < 0.01, "{sound:?}");
    let acrylic_on_steel = Materials::new("acrylic", "steel").hertz_stiffness(d.ball_radius_m()).unwrap();
    assert_eq!(d.damper.k_hz, acrylic_on_steel);
    let paper = design(Design::default(), &[], Spelling::Flag).unwrap();
    assert_eq!(paper.sound(), paper.radiation, "the paper's model takes the radiation as given");
    let hot = design(Design::default(), &text(&[("model", "physical"), ("air-temperature", "40")]), Spelling::Flag);
    assert!(hot.unwrap().sound().air.c_m_s > sound.air.c_m_s);
    let e = err(design(Design::default(), &text(&[("model", "physical"), ("k-hz", "5e8")]), Spelling::Flag));
    assert!(e.starts_with("invalid --k-hz: cannot be combined with --model physical"), "{e}");
    let e = err(design(Design::default(), &text(&[("air-temperature", "100")]), Spelling::Flag));
    assert!(e.starts_with("invalid --air-temperature: 100 degC is out of range"), "{e}");
    // A pulse of the physical model: its ball's mass from acrylic's density at Fig 2's radius.
    let p = pulse(None, &text(&[("model", "physical")]), Spelling::Flag).unwrap();
    assert!((p.impact.mass_kg - contact::sphere_mass(0.01905, 1190.0)).abs() < 1e-15);
    assert_eq!(p.radiation.pulse, PulseShape::Hertz);
}

#[test]
fn a_ball_that_reaches_the_observer_blames_what_was_typed() {
    let e = err(design(Design::default(), &text(&[("mass", "100"), ("density", "10")]), Spelling::Keyword));
    assert!(e.starts_with("invalid mass: the ball's radius"), "{e}");
    assert!(e.ends_with("move the observer with r"), "{e}");
}

#[test]
fn ranges_parse_like_the_command_line() {
    let m = parse_range("--masses", "30g:100g:3", Kind::Mass, &limits::MASS).unwrap();
    assert_eq!(m, crate::design::linspace(0.03, 0.1, 3));
    let e = parse_range("masses", "30g:100g", Kind::Mass, &limits::MASS).unwrap_err().to_string();
    assert!(e.starts_with("invalid masses: '30g:100g'; expected FROM:TO:N"), "{e}");
    let e = parse_range("--masses", "30g:30g:3", Kind::Mass, &limits::MASS).unwrap_err().to_string();
    assert!(e.starts_with("invalid --masses: '30g:30g:3': FROM and TO are one value"), "{e}");
    assert_eq!(parse_range("--masses", "30g:30g:1", Kind::Mass, &limits::MASS).unwrap(), vec![0.03]);
}

#[test]
fn a_pulse_defaults_to_the_paper_s_fig2_impact() {
    let p = pulse(None, &[], Spelling::Flag).unwrap();
    assert_eq!((p.radius_m, p.impact.mass_kg, p.impact.u0_m_s, p.impact.k_hz), (0.01905, 0.0405, 1.4, 5.6e8));
    assert_eq!(p.radiation.source, Source::Dipole);
    let e = pulse(None, &[("u0".into(), Input::Num(-1.0))], Spelling::Keyword).unwrap_err().to_string();
    assert!(e.starts_with("invalid u0: -1 m/s is out of range"), "{e}");
    let p = pulse(None, &text(&[("r", "1cm")]), Spelling::Keyword).unwrap();
    let e = p.field(&p.contact()).unwrap_err().to_string();
    assert!(e.starts_with("invalid r: "), "{e}");
}

#[test]
fn forcing_rows_apply_and_the_alias_names_itself() {
    let d = design(
        Design::default(),
        &text(&[
            ("force", "2N"),
            ("freq", "5Hz"),
            ("ball-position", "-1cm"),
            ("periods", "1e1"),
            ("ball-velocity", "0.5"),
        ]),
        Spelling::Flag,
    )
    .unwrap();
    let p = &d.damper;
    assert_eq!(
        (p.force_n, p.freq_hz, p.ball_position_m, p.ball_velocity_m_s, p.steady_periods),
        (2.0, 5.0, -0.01, 0.5, 10)
    );
    let on = design(Design::default(), &[("settle".into(), Input::Switch(true))], Spelling::Keyword).unwrap();
    assert!(on.damper.settle);
    let e = err(design(Design::default(), &text(&[("force-amplitude", "-1"), ("freq", "5")]), Spelling::Flag));
    assert!(e.starts_with("invalid --force-amplitude: -1 N is out of range"), "{e}");
    let e = err(design(Design::default(), &text(&[("force", "1")]), Spelling::Flag));
    assert_eq!(e, "invalid --freq: a force needs a frequency; give --freq (Hz)");
    let e = err(design(Design::default(), &[("periods".into(), Input::Num(2.5))], Spelling::Keyword));
    assert!(e.starts_with("invalid periods: '2.5' is not a whole number"), "{e}");
    let e = err(design(Design::default(), &text(&[("ball-position", "2.5cm")]), Spelling::Flag));
    assert!(e.starts_with("invalid --ball-position: ") && e.contains("d/2"), "{e}");
    let both = [("force".into(), Input::Num(1.0)), ("force_amplitude".into(), Input::Num(2.0))];
    assert_eq!(err(design(Design::default(), &both, Spelling::Keyword)), "invalid force_amplitude: is given twice");
}

#[test]
fn a_response_design_starts_at_rest_and_needs_a_force() {
    let d = response_design(Design::paper_fig9(), &text(&[("force", "1")]), Spelling::Flag, 4.0, "force").unwrap();
    assert_eq!((d.damper.freq_hz, d.damper.v0_m_s), (4.0, 0.0));
    let kept = response_design(
        Design::paper_fig9(),
        &text(&[("force", "1"), ("ball-velocity", "0")]),
        Spelling::Flag,
        4.0,
        "force",
    );
    assert_eq!(kept.unwrap().damper.v0_m_s, Design::paper_fig9().damper.v0_m_s, "a typed start keeps v0");
    let e = response_design(Design::default(), &[], Spelling::Flag, 4.0, "force-amplitude").unwrap_err().to_string();
    assert_eq!(e, "invalid --force-amplitude: 0 N: a response needs a force; give --force-amplitude F0 (N)");
    let e =
        response_design(Design::default(), &text(&[("force", "1"), ("freq", "5Hz")]), Spelling::Keyword, 4.0, "force");
    assert!(e.unwrap_err().to_string().starts_with("invalid freq: '5Hz': a response sweeps the frequency"));
    assert!(check_ensemble(1, true, Spelling::Flag).is_ok() && check_ensemble(4, false, Spelling::Flag).is_ok());
    let e = check_ensemble(4, true, Spelling::Keyword).unwrap_err().to_string();
    assert!(e.starts_with("invalid ball_position: cannot be combined with ensemble 4"), "{e}");
}

#[test]
fn a_response_without_frequencies_spans_the_default_band_of_the_design_given() {
    let given = text(&[("force", "1"), ("k", "2000"), ("main-mass", "2kg")]);
    let (d, freqs) = response_setup(Design::default(), &given, Spelling::Flag, None, "force").unwrap();
    // √(K/M − (C/2M)²)/2π with K 2000 N/m, M 2 kg, C 0.05 N·s/m (the default's).
    let f = (1000.0f64 - (0.05f64 / 4.0).powi(2)).sqrt() / (2.0 * std::f64::consts::PI);
    assert_eq!(freqs.len(), crate::response::DEFAULT_POINTS);
    assert!((freqs[0] - 0.6 * f).abs() < 1e-12 && (freqs[freqs.len() - 1] - 1.6 * f).abs() < 1e-12);
    assert_eq!(d.damper.freq_hz, freqs[0]);
    let (_, given_freqs) =
        response_setup(Design::default(), &given, Spelling::Flag, Some(vec![4.0, 5.0]), "force").unwrap();
    assert_eq!(given_freqs, [4.0, 5.0]);
    let e = response_setup(Design::default(), &text(&[("force", "1"), ("k", "-1")]), Spelling::Flag, None, "force");
    assert!(e.unwrap_err().to_string().starts_with("invalid --k: -1 N/m is out of range"));
}

#[test]
fn names_are_checked_one_by_one_and_the_nearest_is_found() {
    assert!(check_named(&text(&[("force", "1"), ("plate", "steel")]), Spelling::Flag).is_ok(), "no relations");
    let e = check_named(&text(&[("gap", "1000m")]), Spelling::Flag).unwrap_err().to_string();
    assert!(e.starts_with("invalid --gap: 1000 m is out of range"), "{e}");
    assert_eq!(nearest_design_param("main_mas"), Some("main-mass"));
    assert_eq!(nearest_design_param("force-amplitud"), Some("force-amplitude"));
}

#[test]
fn edit_distance_counts_edits() {
    assert_eq!(edit_distance("mas", "mass"), 1);
    assert_eq!(edit_distance("gap", "gap"), 0);
    assert_eq!(edit_distance("estar", "e-star"), 1);
}
