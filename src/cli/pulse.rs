//! `thud pulse`: one Hertzian impact heard at one observer.

use clap::{ArgMatches, Args, Command, FromArgMatches};

use super::design_args::{table_flag, table_value};
use super::format::num;
use super::{count, CliError, Ctx, Out, OutputArgs, OutputFormat};
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
    #[command(flatten)]
    source: PulseSource,
    /// Points of the waveform.
    #[arg(long, value_name = "N", default_value = "2000", allow_hyphen_values = true)]
    points: String,
    #[command(flatten)]
    output: OutputArgs,
}

/// The impact of `thud pulse` (and of `thud export svg|pdf|wav pulse`): a preset or design
/// for the defaults, then the impact's flags.
#[derive(Debug, Clone, Args)]
pub struct PulseSource {
    /// Take the defaults from a preset (`thud presets`): its ball, K_HZ, observer, source and
    /// air, and U0 = its v0 (e.g. paper-fig2, paper-table1); the target stays a fixed plate.
    #[arg(long, value_name = "P")]
    preset: Option<String>,
    #[arg(long, value_name = "FILE", conflicts_with = "preset", help = super::design_args::DESIGN_HELP)]
    design: Option<String>,
    #[command(flatten)]
    impact: ImpactArgs,
}

/// The impact's flags: the rows of the engine's table [`params::PULSE`] (name, placeholder,
/// help, choices, conflicts), built from it by [`Args::augment_args`] and read back by
/// [`FromArgMatches`], as the design commands' are ([`super::design_args`]): no hand-kept list.
#[derive(Debug, Clone, Default)]
pub struct ImpactArgs {
    /// The flags given, as (row name, value) in table order.
    given: Vec<(String, Input)>,
}

impl Args for ImpactArgs {
    fn augment_args(cmd: Command) -> Command {
        params::PULSE.iter().fold(cmd, |cmd, p| cmd.arg(table_flag(p, p.name, p.alias, true)))
    }

    fn augment_args_for_update(cmd: Command) -> Command {
        Self::augment_args(cmd)
    }
}

impl FromArgMatches for ImpactArgs {
    fn from_arg_matches(m: &ArgMatches) -> Result<Self, clap::Error> {
        let given =
            params::PULSE.iter().filter_map(|p| table_value(p, m, p.name).map(|v| (p.name.to_string(), v))).collect();
        Ok(ImpactArgs { given })
    }

    fn update_from_arg_matches(&mut self, m: &ArgMatches) -> Result<(), clap::Error> {
        *self = Self::from_arg_matches(m)?;
        Ok(())
    }
}

/// The impact these flags describe: the engine's [`params::pulse`] on the flags given, with the
/// preset's design (if any) for the defaults.
pub(super) fn resolve(a: &PulseSource) -> Result<PulseInput, ThudError> {
    let base = match &a.design {
        Some(text) => Some(super::design_args::load_design(text)?),
        None => a.preset.as_deref().map(crate::presets::preset).transpose()?,
    };
    params::pulse(base.as_ref(), &a.impact.given, Spelling::Flag)
}

/// The waveform's points `--points` asks for, within its range and cap.
pub(super) fn points(ctx: &Ctx, typed: &str) -> Result<usize, CliError> {
    let points = count("points", typed, &limits::POINTS)?;
    ctx.enforce(
        limits::waveform_points(points),
        "--points",
        typed,
        &format!("use --points ≤ {}", short(limits::WAVEFORM_POINTS.max)),
    )?;
    Ok(points)
}

pub fn run(a: &PulseArgs, ctx: &Ctx, out: &mut Out) -> Result<(), CliError> {
    let points = points(ctx, &a.points)?;
    let input = resolve(&a.source)?;
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
        Target::MovableMass(m) => format!("a movable mass of {} kg", short(m)),
    };
    // The design's numbers as given (`short`, as `describe`); what the contact makes of them to
    // four decimals.
    let mut s = format!(
        "impact    sphere a {} mm, m {} g at U0 {} m/s on {target}, K_HZ {} N/m^1.5\n",
        short(input.radius_m * 1e3),
        short(input.impact.mass_kg * 1e3),
        short(input.impact.u0_m_s),
        short(input.impact.k_hz)
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
        short(input.observer.r_m),
        short(input.observer.theta_rad.to_degrees()),
        input.radiation.source.name(),
        if input.radiation.source == crate::acoustics::Source::Quadrupole {
            format!(" ({} signs)", input.radiation.quad_signs.name())
        } else {
            String::new()
        },
        short(input.radiation.air.rho_c_pa_s_m),
        short(input.radiation.air.c_m_s),
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
