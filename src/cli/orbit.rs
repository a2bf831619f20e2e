//! `thud orbit`: the periodic orbit of a forced design found by shooting (docs/model.md §6.7):
//! from the design's own motion, or from `--guess`, of a given `--period` or the one the motion
//! repeats with, optionally `--symmetric`; its amplitude, impacts, Floquet multipliers and
//! stability as text, `--json` or `--csv` (one row per impact).

use std::path::PathBuf;

use clap::Args;

use super::design_args::{DesignArgs, ForceAmplitude};
use super::format::num;
use super::simulate::describe;
use super::sweep::Target;
use super::{CliError, Ctx, Out, OutputArgs, OutputFormat};
use crate::design::Design;
use crate::error::ThudError;
use crate::orbit::{self, Guess, PeriodicOrbit, Request};
use crate::units::{self, Kind};

#[derive(Debug, Clone, Args)]
pub struct OrbitArgs {
    #[command(flatten)]
    design: DesignArgs<ForceAmplitude>,
    /// The orbit's period in forcing periods, 1 to 16 [default: the one the design's motion
    /// repeats with].
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    period: Option<String>,
    /// Look for the symmetric orbit, x(t + T/2) = −x(t) (period one forcing period), stable
    /// or not.
    #[arg(long)]
    symmetric: bool,
    /// Start Newton's method from this state at the force's phase 0 instead of the design's
    /// motion: X,V,Z,ZDOT (main mass x in m and x' in m/s, the ball's z = y − x in m and z' in
    /// m/s; units allowed: 3mm,0.1,-12mm,40cm/s).
    #[arg(long, value_name = "X,V,Z,ZDOT", allow_hyphen_values = true)]
    guess: Option<String>,
    /// Write the result (text, --json or --csv) to this file instead of standard output.
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// Replace the --out file if it exists.
    #[arg(long)]
    force: bool,
    #[command(flatten)]
    output: OutputArgs,
}

#[derive(serde::Serialize)]
struct OrbitJson<'a> {
    design: &'a Design,
    #[serde(flatten)]
    orbit: &'a PeriodicOrbit,
}

pub fn run(a: &OrbitArgs, _ctx: &Ctx, out: &mut Out) -> Result<(), CliError> {
    let d = a.design.design()?;
    let target = Target::new(a.out.as_deref(), a.force)?;
    let periods = parse_period(a.period.as_deref())?;
    let guess = a.guess.as_deref().map(parse_guess).transpose()?;
    let req = Request { periods, symmetric: a.symmetric, guess };
    let o = orbit::find(&d, &req, None).map_err(|e| match e.param() {
        // No orbit from the start the user gave: the refusal names that start.
        "orbit" if a.guess.is_some() => e.renamed("--guess"),
        _ => named(e),
    })?;
    super::output::check_finite(&o)?;
    let text = match a.output.format() {
        OutputFormat::Json => {
            let mut t =
                serde_json::to_string_pretty(&OrbitJson { design: &d, orbit: &o }).map_err(std::io::Error::from)?;
            t.push('\n');
            t
        }
        OutputFormat::Csv => csv(&o),
        OutputFormat::Text => text(&d, &o),
    };
    target.write(&text, out)
}

/// `--period N` (1 to 16 forcing periods), if given.
pub(super) fn parse_period(text: Option<&str>) -> Result<Option<u32>, ThudError> {
    text.map(|t| {
        let n = crate::limits::ORBIT_PERIODS.parse_count("--period", t)?;
        Ok(u32::try_from(n).unwrap_or(u32::MAX))
    })
    .transpose()
}

/// The impacts of an orbit, one line each: period, phase (T), wall, u_in and u_out (m/s).
pub(super) fn impact_table<'a>(rows: impl Iterator<Item = (u32, f64, &'a crate::damper::Wall, f64, f64)>) -> String {
    let mut t = String::from("  period   phase (T)   wall   u_in (m/s)   u_out (m/s)\n");
    for (period, phase, wall, u_in, u_out) in rows {
        t += &format!(
            "  {:>6}   {:>9}   {:>+4}   {:>10}   {:>11}\n",
            period,
            format!("{phase:.4}"),
            wall,
            num(u_in),
            num(u_out)
        );
    }
    t
}

/// The engine's parameter names as this command's flags.
fn named(e: ThudError) -> ThudError {
    match e.param() {
        "solver" => e.renamed("--solver"),
        "force" => e.renamed("--force-amplitude"),
        "period" => e.renamed("--period"),
        "guess" => e.renamed("--guess"),
        _ => e,
    }
}

/// `X,V,Z,ZDOT` with units.
fn parse_guess(text: &str) -> Result<Guess, ThudError> {
    let parts: Vec<&str> = text.split(',').collect();
    let [x, v, z, zd] = parts[..] else {
        return Err(ThudError::invalid(
            "--guess",
            format!("'{text}'; expected X,V,Z,ZDOT (m, m/s, m, m/s), e.g. 3mm,0.1,-12mm,0.4"),
        ));
    };
    let finite = |t: &str, kind: Kind| -> Result<f64, ThudError> {
        let v = units::parse("--guess", t, kind)?;
        if v.is_finite() {
            Ok(v)
        } else {
            Err(ThudError::invalid("--guess", format!("'{t}' in '{text}' is not a finite number")))
        }
    };
    Ok(Guess {
        x_m: finite(x, Kind::Length)?,
        v_m_s: finite(v, Kind::Speed)?,
        z_m: finite(z, Kind::Length)?,
        zdot_m_s: finite(zd, Kind::Speed)?,
    })
}

/// The orbit in words: its type, amplitude, stability, multipliers and impacts.
fn text(d: &Design, o: &PeriodicOrbit) -> String {
    let mut t = format!("design       {}\n", describe(d));
    t += &format!(
        "orbit        {} (periodic, found by shooting: residual {:.1e}, {} Newton steps, {} forcing periods simulated)\n",
        o.label(),
        o.residual,
        o.iterations,
        num(o.periods_simulated)
    );
    t += &format!("amplitude    {} mm", num(o.amplitude_m * 1e3));
    if let Some(lin) = o.amplitude_linear_m {
        t += &format!(" (without the ball {} mm)", num(lin * 1e3));
    }
    t += "\n";
    t += &format!(
        "at phase 0   x {} mm, x' {} m/s, z {} mm, z' {} m/s\n",
        num(o.x_m * 1e3),
        num(o.v_m_s),
        num(o.z_m * 1e3),
        num(o.zdot_m_s)
    );
    let lead = o.multipliers.first().map_or(0.0, |m| m.abs);
    t += &format!(
        "stability    {} (largest |λ| {}; {} {})\n",
        if o.stable { "stable" } else { "unstable" },
        num(lead),
        if o.stable { "would lose it at" } else { "lost at" },
        o.critical.describe()
    );
    t += "multipliers ";
    for m in &o.multipliers {
        t += &format!(" {}", multiplier(m));
    }
    if o.impacts.is_empty() {
        t += "  (the ball floats: a neutral pair at +1 not listed)";
    }
    t += "\n\n";
    t += &impact_table(o.impacts.iter().map(|i| (i.period, i.phase, &i.wall, i.u_in_m_s, i.u_out_m_s)));
    if o.impacts.is_empty() {
        t += "  (no impact: the ball never touches a wall)\n";
    }
    t
}

/// `0.918`, `-1.21`, `0.52±0.77i`.
fn multiplier(m: &orbit::Multiplier) -> String {
    if m.im == 0.0 {
        num(m.re)
    } else if m.im > 0.0 {
        format!("{}+{}i", num(m.re), num(m.im))
    } else {
        format!("{}-{}i", num(m.re), num(-m.im))
    }
}

/// One row per impact (an orbit without impacts: one row with the impact columns empty), the
/// orbit's own columns on every row.
fn csv(o: &PeriodicOrbit) -> String {
    let mut t = String::from(
        "orbit,periods,impacts_per_orbit,symmetric,amplitude_m,stable,critical,multiplier_abs_max,impact,period,phase,wall,u_in_m_s,u_out_m_s\n",
    );
    let lead = o.multipliers.first().map_or(0.0, |m| m.abs);
    let head = format!(
        "{},{},{},{},{:e},{},{},{:e}",
        o.label(),
        o.periods,
        o.impacts_per_orbit,
        o.symmetric,
        o.amplitude_m,
        o.stable,
        serde_json::to_value(o.critical).ok().and_then(|v| v.as_str().map(str::to_string)).unwrap_or_default(),
        lead
    );
    for (k, i) in o.impacts.iter().enumerate() {
        t += &format!("{head},{k},{},{:e},{},{:e},{:e}\n", i.period, i.phase, i.wall, i.u_in_m_s, i.u_out_m_s);
    }
    if o.impacts.is_empty() {
        t += &format!("{head},,,,,,\n");
    }
    t
}
