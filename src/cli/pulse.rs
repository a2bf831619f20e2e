//! `thud pulse`: one Hertzian impact heard at one observer.

use clap::{Args, ValueEnum};

use super::format::num;
use super::{count, CliError, Ctx, ModelArg, Out, OutputArgs, OutputFormat, PulseArg, QuadSignsArg, SourceArg};
use crate::acoustics::{Field, Levels};
use crate::contact::{Contact, Target};
use crate::error::ThudError;
use crate::limits::{self, short};
use crate::params::{self, Input, PulseInput, Spelling};
use crate::report::PulseReport;

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
    /// Sphere density (kg/m³) [default: --sphere's]: with --mass the radius follows, with --radius the mass.
    #[arg(long, value_name = "RHO", allow_hyphen_values = true)]
    density: Option<String>,
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
    sound_speed: Option<String>,
    /// The model of the world [default: paper]: physical is the measured level (peak, exact
    /// Hertz pulse, air from --air-temperature and --air-pressure, K_HZ and mass from the materials).
    #[arg(long, value_enum)]
    model: Option<ModelArg>,
    /// Air temperature (°C) of the physical model: ρ0 and c follow [default: 20].
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    air_temperature: Option<String>,
    /// Air pressure (Pa, or e.g. 101.325kPa) of the physical model: ρ0 follows [default: 101325].
    #[arg(long, value_name = "P", allow_hyphen_values = true)]
    air_pressure: Option<String>,
    /// Waveform points.
    #[arg(long, value_name = "N", default_value = "2000", allow_hyphen_values = true)]
    points: String,
    #[command(flatten)]
    output: OutputArgs,
}

/// The impact these flags describe: the engine's [`params::pulse`] on the flags given, with the
/// preset's design (if any) for the defaults.
fn resolve(a: &PulseArgs) -> Result<PulseInput, ThudError> {
    let base = a.preset.as_deref().map(crate::presets::preset).transpose()?;
    let texts = [
        ("sphere", &a.sphere),
        ("plate", &a.plate),
        ("radius", &a.radius),
        ("mass", &a.mass),
        ("density", &a.density),
        ("k-hz", &a.k_hz),
        ("main-mass", &a.main_mass),
        ("u0", &a.u0),
        ("rho-c", &a.rho_c),
        ("sound-speed", &a.sound_speed),
        ("air-temperature", &a.air_temperature),
        ("air-pressure", &a.air_pressure),
        ("r", &a.r),
        ("theta", &a.theta),
    ];
    let choices = [
        ("source", a.source.and_then(|v| v.to_possible_value())),
        ("quad-signs", a.quad_signs.and_then(|v| v.to_possible_value())),
        ("pulse", a.pulse.and_then(|v| v.to_possible_value())),
        ("model", a.model.and_then(|v| v.to_possible_value())),
    ];
    let given: Vec<(String, Input)> = texts
        .into_iter()
        .filter_map(|(n, t)| t.as_ref().map(|t| (n.to_string(), Input::Text(t.clone()))))
        .chain(choices.into_iter().filter_map(|(n, c)| c.map(|c| (n.to_string(), Input::Text(c.get_name().into())))))
        .collect();
    params::pulse(base.as_ref(), &given, Spelling::Flag)
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
    let contact = input.contact();
    let field = input.field(&contact)?;
    match a.output.format() {
        OutputFormat::Csv => {
            let (t, p) = field.waveform(points);
            out.text("t_s,p_pa\n")?;
            for (ti, pi) in t.iter().zip(&p) {
                out.csv_row(&[*ti, *pi])?;
            }
        }
        OutputFormat::Json => out.json(&PulseReport::new(&input, &contact, &field, points))?,
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
    if input.model == crate::design::Model::Physical {
        s += &format!(
            "levels    peak {:.2} dB (the physical model's level)   SPL {:.2} dB (rms over τ)   SEL {:.2} dB\n",
            lv.spl_peak_db, lv.spl_db, lv.sel_db
        );
    } else {
        s += &format!(
            "levels    SPL {:.2} dB (rms over τ from the direct arrival)   peak {:.2} dB   SEL {:.2} dB\n",
            lv.spl_db, lv.spl_peak_db, lv.sel_db
        );
    }
    s += &format!("pressure  max {:+.4} Pa   min {:+.4} Pa   rms {:.4} Pa\n", lv.p_max_pa, lv.p_min_pa, lv.p_rms_pa);
    s += &format!("extrema   {} (after the direct arrival)\n", field.describe_peaks());
    s
}
