//! `thud basins --grid N`: the basins of attraction of a forced design over the ball's start:
//! N offsets y0 across the clearance × N velocities w0 over `--w0 FROM:TO`, each
//! start's attractor (its orbit's type and amplitude), drawn as a map with the share of each.

use clap::Args;

use super::bifurcation::{check_work, look, short_design, OrbitArgs};
use super::design_args::{DesignArgs, ForceAmplitude};
use super::format::num;
use super::simulate::describe;
use super::{count, CliError, Ctx, Out, OutputFormat};
use crate::design::{linspace, Design};
use crate::dynamics::{self, Basins};
use crate::error::ThudError;
use crate::export::dynamics::letter;
use crate::limits;
use crate::units::{self, Kind};

#[derive(Debug, Clone, Args)]
pub struct BasinsArgs {
    #[command(flatten)]
    design: DesignArgs<ForceAmplitude>,
    /// Starts per side: N offsets y0 across the clearance (the centres of N equal cells) × N
    /// velocities w0.
    #[arg(long, value_name = "N", default_value = "20", allow_hyphen_values = true)]
    grid: String,
    /// The range of the ball's starting velocity w0, FROM:TO (m/s, e.g. -1:1).
    #[arg(long, value_name = "FROM:TO", default_value = "-1:1", allow_hyphen_values = true)]
    w0: String,
    #[command(flatten)]
    orbit: OrbitArgs,
}

#[derive(serde::Serialize)]
struct BasinsJson<'a> {
    design: &'a Design,
    #[serde(flatten)]
    basins: &'a Basins,
}

/// `--w0 FROM:TO` in m/s, each end inside the ball's velocity range.
fn parse_w0(text: &str) -> Result<(f64, f64), ThudError> {
    let Some((a, b)) = text.split_once(':') else {
        return Err(ThudError::invalid("--w0", format!("'{text}'; expected FROM:TO (m/s), e.g. -1:1")));
    };
    let r = &limits::BALL_VELOCITY;
    let a = r.check_as("--w0", units::parse("--w0", a, Kind::Speed)?)?;
    let b = r.check_as("--w0", units::parse("--w0", b, Kind::Speed)?)?;
    Ok((a, b))
}

pub fn run(a: &BasinsArgs, ctx: &Ctx, out: &mut Out) -> Result<(), CliError> {
    super::bifurcation::refuse_run_flags(&a.design, "a basin map")?;
    let d = a.design.design()?;
    let n = count("grid", &a.grid, &limits::GRID_N)?;
    let (w_lo, w_hi) = parse_w0(&a.w0)?;
    if a.design.has("ball-position") || a.design.has("ball-velocity") {
        return Err(ThudError::invalid(
            "--grid",
            "the basins set the ball's start; leave out --ball-position and --ball-velocity",
        )
        .into());
    }
    let s = a.orbit.settings(&a.design, &d)?;
    a.orbit.check_targets()?;
    check_work(ctx, n * n, s, false, ("--grid", &a.grid))?;
    let w0 = linspace(w_lo, w_hi, n);
    let bar = super::budget::bar((n * n) as u64, "basins");
    let b = dynamics::basins(&d, n, &w0, s, "--force-amplitude", None, &|_| bar.inc(1))
        .map_err(super::bifurcation::flagged)?;
    bar.finish_and_clear();
    super::output::check_finite(&b)?;
    let title = format!("Basins of attraction over the ball's start — {}", short_design(&d, ""));
    a.orbit.write(
        |format| {
            Ok(match format {
                OutputFormat::Json => {
                    let mut t = serde_json::to_string_pretty(&BasinsJson { design: &d, basins: &b })
                        .map_err(std::io::Error::from)?;
                    t.push('\n');
                    t
                }
                OutputFormat::Csv => crate::export::dynamics::basins_csv(&b)
                    .map_err(|e| ThudError::invalid("csv", format!("cannot write: {e}")))?,
                OutputFormat::Text => text(&d, &b),
            })
        },
        || crate::export::dynamics::basins_svg(&b, &title, &look()),
        out,
    )
}

/// The map (w0 up, y0 across, a letter per attractor) and the attractors with their shares.
fn text(d: &Design, b: &Basins) -> String {
    let ny = b.y0_m.len();
    let mut t = format!("design    {}\n", describe(d));
    t += &format!(
        "basins    {} × {} starts: y0 {} to {} mm across, w0 {} to {} m/s up; {} transient periods, {} sampled\n\n",
        ny,
        b.w0_m_s.len(),
        num(b.y0_m[0] * 1e3),
        num(b.y0_m[ny - 1] * 1e3),
        num(b.w0_m_s[0]),
        num(b.w0_m_s[b.w0_m_s.len() - 1]),
        b.settings.transient_periods,
        b.settings.periods
    );
    for (iw, w) in b.w0_m_s.iter().enumerate().rev() {
        t += &format!("  {:>8}  ", num(*w));
        for iy in 0..ny {
            t += &letter(b.cells[iw * ny + iy]);
        }
        t += "\n";
    }
    t += "\nattractors (m/n = m impacts per n periods; sym = x(t+T/2) = −x(t)):\n";
    for a in &b.attractors {
        let mirror = a.mirror.map_or(String::new(), |m| format!("  the mirror image of {}", letter(m)));
        t += &format!(
            "  {}  {:<12} amplitude {:>8} mm  {:>5.1} % of starts ({}){mirror}\n",
            letter(a.id),
            a.label,
            num(a.amplitude_m * 1e3),
            a.share * 100.0,
            a.starts
        );
    }
    t
}
