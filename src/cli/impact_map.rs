//! `thud impact-map`: the Poincaré section on impacts of one forced design: after
//! `--transient` periods, every impact over `--periods` N as the force's phase against the
//! relative impact speed, with the orbit's type.

use clap::Args;

use super::bifurcation::{check_work, look, short_design, OrbitArgs};
use super::design_args::{DesignArgs, ForceAmplitude};
use super::format::num;
use super::simulate::describe;
use super::{CliError, Ctx, Out, OutputFormat};
use crate::design::Design;
use crate::dynamics::{self, OrbitRun};
use crate::error::ThudError;

#[derive(Debug, Clone, Args)]
pub struct ImpactMapArgs {
    #[command(flatten)]
    design: DesignArgs<ForceAmplitude>,
    #[command(flatten)]
    orbit: OrbitArgs,
}

#[derive(serde::Serialize)]
struct ImpactMapJson<'a> {
    design: &'a Design,
    settings: dynamics::Settings,
    #[serde(flatten)]
    run: &'a OrbitRun,
}

pub fn run(a: &ImpactMapArgs, ctx: &Ctx, out: &mut Out) -> Result<(), CliError> {
    super::bifurcation::refuse_run_flags(&a.design, "an impact map")?;
    let d = a.design.design()?;
    let s = a.orbit.settings(&a.design, &d)?;
    a.orbit.check_targets()?;
    check_work(ctx, 1, s, false, ("--transient", &s.transient_periods.to_string()))?;
    let run = dynamics::impact_map(&d, s, "--force-amplitude", None).map_err(super::bifurcation::flagged)?;
    super::output::check_finite(&run)?;
    let title = format!("Impact map — {}", short_design(&d, ""));
    a.orbit.write(
        |format| {
            Ok(match format {
                OutputFormat::Json => {
                    let mut t = serde_json::to_string_pretty(&ImpactMapJson { design: &d, settings: s, run: &run })
                        .map_err(std::io::Error::from)?;
                    t.push('\n');
                    t
                }
                OutputFormat::Csv => crate::export::dynamics::impact_map_csv(&run)
                    .map_err(|e| ThudError::invalid("csv", format!("cannot write: {e}")))?,
                OutputFormat::Text => text(&d, s, &run),
            })
        },
        || crate::export::dynamics::impact_map_svg(&run, &title, &look()),
        out,
    )
}

/// The orbit and its impacts, one line each.
fn text(d: &Design, s: dynamics::Settings, run: &OrbitRun) -> String {
    let mut t = format!("design    {}\n", describe(d));
    t += &format!(
        "orbit     {} (after {} transient periods, over {} sampled); amplitude {} mm\n\n",
        run.orbit.label(),
        s.transient_periods,
        s.periods,
        num(run.amplitude_m * 1e3)
    );
    t += &super::orbit::impact_table(run.impacts.iter().map(|i| (i.period, i.phase, &i.wall, i.u_in_m_s, i.u_out_m_s)));
    if run.impacts.is_empty() {
        t += "  (no impact after the transient)\n";
    }
    t
}
