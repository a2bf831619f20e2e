//! `thud pulse`: one Hertzian impact heard at one observer.

use clap::Args;
use serde::Serialize;

use super::format::num;
use super::{count, quantity, CliError, Ctx, Out, OutputArgs, OutputFormat, PulseArg, QuadSignsArg, SourceArg};
use crate::acoustics::{Air, Extremum, Field, Levels, Observer, QuadSigns, Radiation, Source};
use crate::contact::{self, Contact, Impact, Target};
use crate::error::ThudError;
use crate::limits::{self, short};
use crate::units::Kind;

/// Defaults are the paper's Fig 2 impact: an acrylic sphere, a 19.05 mm, m 40.5 g, U0 1.4 m/s,
/// K_HZ 5.6e8 N/m^1.5, on a fixed plate, heard as a dipole at r 0.7 m, θ 45°.
#[derive(Debug, Clone, Args)]
pub struct PulseArgs {
    /// Take the defaults from a preset (`thud presets`): its ball, K_HZ, observer, source and
    /// air, and U0 = its v0 (e.g. paper-fig2, paper-table1); the target stays a fixed plate.
    #[arg(long, value_name = "P")]
    preset: Option<String>,
    /// Sphere radius (m, or e.g. 19.05mm). Default: from --mass and --sphere's density, else 19.05 mm.
    #[arg(long, value_name = "A", allow_hyphen_values = true)]
    radius: Option<String>,
    /// Sphere mass (kg, or e.g. 40.5g). Default: from --radius and --sphere's density, else 40.5 g.
    #[arg(long, value_name = "M", allow_hyphen_values = true)]
    mass: Option<String>,
    /// Impact speed U0 (m/s) [default: 1.4].
    #[arg(long, value_name = "U", allow_hyphen_values = true)]
    u0: Option<String>,
    /// Hertz stiffness K_HZ (N/m^1.5) [default: 5.6e8, or from --sphere/--plate].
    #[arg(long, value_name = "K", allow_hyphen_values = true, conflicts_with_all = ["sphere", "plate"])]
    k_hz: Option<String>,
    /// Sphere material (steel, stainless-steel, acrylic, brass, aluminium, glass, rubber, nylon, tungsten-carbide).
    #[arg(long, value_name = "MATERIAL", allow_hyphen_values = true)]
    sphere: Option<String>,
    /// Plate material [default: steel when --sphere is given].
    #[arg(long, value_name = "MATERIAL", allow_hyphen_values = true)]
    plate: Option<String>,
    /// Mass of a movable target (kg): K* = (m+M)/(mM) (Eq 8). Default: a fixed plate.
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    main_mass: Option<String>,
    /// Observer distance from the contact point (m) [default: 0.7].
    #[arg(long, value_name = "R", allow_hyphen_values = true)]
    r: Option<String>,
    /// Observer angle from the plate's normal (degrees) [default: 45].
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    theta: Option<String>,
    /// Reflecting surfaces: a free sphere, a plate, or a wall–floor corner [default: dipole].
    #[arg(long, value_enum)]
    source: Option<SourceArg>,
    /// Quadrupole wall-image signs: the paper's (pressure-release wall) or a rigid wall [default: rigid].
    #[arg(long, value_enum)]
    quad_signs: Option<QuadSignsArg>,
    /// Acceleration pulse: the paper's half-sine (Eq 7) or the exact Hertz pulse [default: half-sine].
    #[arg(long, value_enum)]
    pulse: Option<PulseArg>,
    /// Air impedance ρ0·c (Pa·s/m) [default: 400, the paper's].
    #[arg(long, value_name = "Z", allow_hyphen_values = true)]
    rho_c: Option<String>,
    /// Speed of sound (m/s) [default: 343].
    #[arg(long, value_name = "C", allow_hyphen_values = true)]
    c: Option<String>,
    /// Waveform points.
    #[arg(long, value_name = "N", default_value = "2000", allow_hyphen_values = true)]
    points: String,
    #[command(flatten)]
    output: OutputArgs,
}

/// Everything a pulse computation needs, in SI units.
struct PulseInput {
    radius_m: f64,
    impact: Impact,
    observer: Observer,
    radiation: Radiation,
}

fn resolve(a: &PulseArgs) -> Result<PulseInput, ThudError> {
    let base = a.preset.as_deref().map(crate::presets::preset).transpose()?.map(|d| d.resolved()).transpose()?;
    let sphere = a.sphere.as_deref().map(contact::material).transpose()?;
    let plate = match (&a.plate, &sphere) {
        (Some(p), _) => Some(contact::material(p)?),
        (None, Some(_)) => Some(contact::material("steel")?),
        (None, None) => None,
    };
    let radius = quantity("radius", &a.radius, Kind::Length, &limits::RADIUS)?;
    let mass = quantity("mass", &a.mass, Kind::Mass, &limits::MASS)?;
    let (radius_m, mass_kg) = match (radius, mass, sphere) {
        (Some(r), Some(m), _) => (r, m),
        (Some(r), None, Some(s)) => {
            (r, derived(&limits::MASS, contact::sphere_mass(r, s.density_kg_m3), "radius", r, &s)?)
        }
        (None, Some(m), Some(s)) => {
            (derived(&limits::RADIUS, contact::sphere_radius(m, s.density_kg_m3), "mass", m, &s)?, m)
        }
        (r, m, _) => (
            r.or(base.as_ref().map(|d| d.ball_radius_m())).unwrap_or(0.01905),
            m.or(base.as_ref().map(|d| d.damper.impact_mass_kg)).unwrap_or(0.0405),
        ),
    };
    limits::RADIUS.check_as("--radius", radius_m)?;
    limits::MASS.check_as("--mass", mass_kg)?;
    let k_hz = match (quantity("k-hz", &a.k_hz, Kind::HertzStiffness, &limits::K_HZ)?, sphere, plate) {
        (Some(k), _, _) => k,
        (None, Some(s), Some(p)) => contact::hertz_stiffness(radius_m, &s, &p),
        (None, None, Some(p)) => contact::hertz_stiffness(radius_m, &contact::material("acrylic")?, &p),
        _ => match base.as_ref().map(|d| (&d.materials, d.damper.k_hz)) {
            Some((Some(m), _)) => {
                contact::hertz_stiffness(radius_m, &contact::material(&m.sphere)?, &contact::material(&m.plate)?)
            }
            Some((None, k)) => k,
            None => 5.6e8,
        },
    };
    let ball_flag = if a.radius.is_some() || a.mass.is_none() { "--radius" } else { "--mass" };
    limits::K_HZ.check_as(ball_flag, k_hz)?;
    let target = match quantity("main-mass", &a.main_mass, Kind::Mass, &limits::MAIN_MASS)? {
        Some(mm) => Target::MovableMass(mm),
        None => Target::FixedPlate,
    };
    let u0 = quantity("u0", &a.u0, Kind::Speed, &limits::U0)?.or(base.as_ref().map(|d| d.damper.v0_m_s)).unwrap_or(1.4);
    limits::U0.check_as("--u0", u0)?;
    let impact = Impact { mass_kg, u0_m_s: u0, k_hz, target };
    impact.validate()?;
    let base_air = base.as_ref().map_or(Air::default(), |d| d.radiation.air);
    let air = Air {
        rho_c_pa_s_m: quantity("rho-c", &a.rho_c, Kind::Impedance, &limits::RHO_C)?.unwrap_or(base_air.rho_c_pa_s_m),
        c_m_s: quantity("c", &a.c, Kind::Speed, &limits::C_SOUND)?.unwrap_or(base_air.c_m_s),
    };
    let base_observer = base.as_ref().map_or(Observer::new(0.7, 45.0), |d| d.observer);
    let observer = Observer::new(
        quantity("r", &a.r, Kind::Length, &limits::R)?.unwrap_or(base_observer.r_m),
        quantity("theta", &a.theta, Kind::Angle, &limits::THETA)?.unwrap_or(base_observer.theta_rad.to_degrees()),
    );
    let source = a.source.map(Into::into).or(base.as_ref().map(|d| d.radiation.source)).unwrap_or(Source::Dipole);
    let quad_signs =
        a.quad_signs.map(Into::into).or(base.as_ref().map(|d| d.radiation.quad_signs)).unwrap_or(QuadSigns::Rigid);
    let pulse = a.pulse.map(Into::into).or(base.as_ref().map(|d| d.radiation.pulse)).unwrap_or_default();
    Ok(PulseInput { radius_m, impact, observer, radiation: Radiation { source, quad_signs, air, pulse } })
}

/// An observer inside the ball is the ball's fault when the user sized the ball and left the
/// observer alone: name the flag they typed, not `r`.
fn blame_ball(a: &PulseArgs, e: ThudError) -> ThudError {
    let msg = e.to_string();
    let Some(rest) = msg.strip_prefix("invalid r: ") else { return e };
    match [("radius", &a.radius), ("mass", &a.mass)].into_iter().find(|(_, t)| t.is_some()) {
        Some((name, _)) if a.r.is_none() => {
            ThudError::invalid(format!("--{name}"), format!("the ball reaches the observer: {rest}"))
        }
        _ => e,
    }
}

/// A ball size derived from the typed `--{from}` and the sphere's density, checked against
/// `range`; the error names the flag typed.
fn derived(range: &limits::Range, value: f64, from: &str, typed: f64, s: &contact::Material) -> Result<f64, ThudError> {
    if range.contains(value) {
        return Ok(value);
    }
    Err(ThudError::invalid(
        format!("--{from}"),
        format!(
            "{} {} of {} ({} kg/m^3) makes a {} of {} {}; it must be {}",
            short(typed),
            if from == "radius" { "m" } else { "kg" },
            s.name,
            short(s.density_kg_m3),
            range.what,
            short(value),
            range.unit,
            range.describe()
        ),
    ))
}

#[derive(Serialize)]
struct Waveform {
    t_s: Vec<f64>,
    p_pa: Vec<f64>,
}

#[derive(Serialize)]
struct PulseJson<'a> {
    radius_m: f64,
    mass_kg: f64,
    u0_m_s: f64,
    k_hz: f64,
    r_m: f64,
    theta_deg: f64,
    source: &'static str,
    quad_signs: &'static str,
    pulse: &'static str,
    rho_c_pa_s_m: f64,
    c_m_s: f64,
    alpha_max_m: f64,
    accel_max_m_s2: f64,
    tau_s: f64,
    force_max_n: f64,
    arrival_s: f64,
    spl_db: f64,
    spl_definition: &'static str,
    spl_peak_db: f64,
    sel_db: f64,
    p_rms_pa: f64,
    p_max_pa: f64,
    p_min_pa: f64,
    extrema: &'a [Extremum],
    waveform: Waveform,
}

pub fn run(a: &PulseArgs, ctx: &Ctx, out: &mut Out) -> Result<(), CliError> {
    let points = count("points", &a.points, &limits::POINTS)?;
    ctx.enforce(
        limits::waveform_points(points),
        "--points",
        &a.points,
        &format!("use --points ≤ {}", short(limits::WAVEFORM_POINTS.max)),
    )?;
    let input = resolve(a)?;
    let contact = input.impact.contact();
    let field =
        Field::new(input.radius_m, &contact, &input.observer, &input.radiation).map_err(|e| blame_ball(a, e))?;
    let (t, p) = field.waveform(points);
    match a.output.format() {
        OutputFormat::Csv => {
            out.text("t_s,p_pa\n")?;
            for (ti, pi) in t.iter().zip(&p) {
                out.csv_row(&[*ti, *pi])?;
            }
        }
        OutputFormat::Json => {
            let lv = field.levels();
            let ext = field.extrema();
            let j = PulseJson {
                radius_m: input.radius_m,
                mass_kg: input.impact.mass_kg,
                u0_m_s: input.impact.u0_m_s,
                k_hz: input.impact.k_hz,
                r_m: input.observer.r_m,
                theta_deg: input.observer.theta_rad.to_degrees(),
                source: input.radiation.source.name(),
                quad_signs: input.radiation.quad_signs.name(),
                pulse: input.radiation.pulse.name(),
                rho_c_pa_s_m: input.radiation.air.rho_c_pa_s_m,
                c_m_s: input.radiation.air.c_m_s,
                alpha_max_m: contact.alpha_max_m,
                accel_max_m_s2: contact.accel_max_m_s2,
                tau_s: contact.tau_s,
                force_max_n: contact.force_max_n,
                arrival_s: field.arrival_s(),
                spl_db: lv.spl_db,
                spl_definition: "rms over one contact duration from the direct arrival",
                spl_peak_db: lv.spl_peak_db,
                sel_db: lv.sel_db,
                p_rms_pa: lv.p_rms_pa,
                p_max_pa: lv.p_max_pa,
                p_min_pa: lv.p_min_pa,
                extrema: &ext,
                waveform: Waveform { t_s: t, p_pa: p },
            };
            out.json(&j)?;
        }
        OutputFormat::Text => out.text(&summary(&input, &contact, &field, &field.levels()))?,
    }
    Ok(())
}

fn summary(input: &PulseInput, c: &Contact, field: &Field, lv: &Levels) -> String {
    let target = match input.impact.target {
        Target::FixedPlate => "a fixed plate".to_string(),
        Target::MovableMass(m) => format!("a movable mass of {} kg", num(m)),
    };
    let mut s = format!(
        "impact    sphere a {} mm, m {} g at U0 {} m/s on {target}, K_HZ {:.4e} N/m^1.5\n",
        num(input.radius_m * 1e3),
        num(input.impact.mass_kg * 1e3),
        num(input.impact.u0_m_s),
        input.impact.k_hz
    );
    s += &format!(
        "contact   α_max {} µm   A_max {} m/s²   τ {} µs   F_max {} N\n",
        num(c.alpha_max_m * 1e6),
        num(c.accel_max_m_s2),
        num(c.tau_s * 1e6),
        num(c.force_max_n)
    );
    s += &format!(
        "observer  r {} m, θ {}°, {} source{}, ρ0c {} Pa·s/m, c {} m/s; direct arrival {} ms\n",
        num(input.observer.r_m),
        num(input.observer.theta_rad.to_degrees()),
        input.radiation.source.name(),
        if input.radiation.source == crate::acoustics::Source::Quadrupole {
            format!(" ({} signs)", input.radiation.quad_signs.name())
        } else {
            String::new()
        },
        num(input.radiation.air.rho_c_pa_s_m),
        num(input.radiation.air.c_m_s),
        num(field.arrival_s() * 1e3)
    );
    s += &format!(
        "levels    SPL {:.2} dB (rms over τ from the direct arrival)   peak {:.2} dB   SEL {:.2} dB\n",
        lv.spl_db, lv.spl_peak_db, lv.sel_db
    );
    s += &format!("pressure  max {:+.4} Pa   min {:+.4} Pa   rms {:.4} Pa\n", lv.p_max_pa, lv.p_min_pa, lv.p_rms_pa);
    s += &format!("extrema   {} (after the direct arrival)\n", field.describe_peaks());
    s
}
