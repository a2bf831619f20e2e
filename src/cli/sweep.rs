//! `thud sweep`: the design chart over impact mass × gap.

use clap::Args;
use serde::Serialize;

use super::budget;
use super::design_args::{parse_range, DesignArgs};
use super::format::num;
use super::simulate::describe;
use super::{quantity, CliError, Ctx, Out, OutputArgs, OutputFormat};
use crate::design::{self, Band, Chart, Design, ZoneBy};
use crate::error::ThudError;
use crate::limits::{self, short};
use crate::units::Kind;

#[derive(Debug, Clone, Args)]
pub struct SweepArgs {
    #[command(flatten)]
    design: DesignArgs,
    /// Impact masses FROM:TO:N (e.g. 30g:100g:20).
    #[arg(long, value_name = "FROM:TO:N", allow_hyphen_values = true, default_value = "30g:100g:20")]
    masses: String,
    /// Gaps FROM:TO:N (e.g. 2cm:5cm:20).
    #[arg(long, value_name = "FROM:TO:N", allow_hyphen_values = true, default_value = "2cm:5cm:20")]
    gaps: String,
    /// Width of the inclination bands of the Table 5 summary (cm/s).
    #[arg(long, value_name = "CM_S", default_value = "0.2", allow_hyphen_values = true)]
    band: String,
    #[command(flatten)]
    output: OutputArgs,
}

#[derive(Serialize)]
struct SweepJson<'a> {
    design: &'a Design,
    chart: &'a Chart,
    table5: &'a [Band],
}

/// The smallest and largest inclination (cm/s) among the cells Table 5 bands: the engine's
/// [`design::inclination_span`].
fn inclination_span(chart: &Chart, zone_by: ZoneBy) -> Option<(f64, f64)> {
    design::inclination_span(chart, zone_by)
}

pub fn run(a: &SweepArgs, ctx: &Ctx, out: &mut Out) -> Result<(), CliError> {
    let d = a.design.design()?;
    let masses = parse_range("masses", &a.masses, Kind::Mass, &limits::MASS)?;
    let gaps = parse_range("gaps", &a.gaps, Kind::Length, &limits::GAP)?;
    let band = quantity("band", &Some(a.band.clone()), Kind::Inclination, &limits::BAND)?.unwrap_or(0.2);
    a.design.check_sweep(ctx, &d, masses.len(), gaps.len())?;
    let bar = budget::bar((masses.len() * gaps.len()) as u64, "sweep");
    let chart = design::sweep(&d, &masses, &gaps, None, &|_, _| bar.inc(1))?;
    bar.finish_and_clear();
    if let Some((lo, hi)) = inclination_span(&chart, d.thresholds.zone_by) {
        let bands = limits::band_count(lo, hi, band);
        ctx.enforce(bands, "--band", &a.band, &format!("use --band ≥ {} cm/s", short((hi - lo) / bands.cap.max)))?;
    }
    let bands = design::spl_range_by_inclination(&chart, band, d.thresholds.zone_by);
    match a.output.format() {
        OutputFormat::Json => out.json(&SweepJson { design: &d, chart: &chart, table5: &bands })?,
        OutputFormat::Csv => out.text(
            &crate::export::csv::sweep(&chart).map_err(|e| ThudError::invalid("csv", format!("cannot write: {e}")))?,
        )?,
        OutputFormat::Text => {
            let mut s = format!("base      {}\n", describe(&d));
            s += &format!(
                "zones     L* {} dB, e* {} cm/s by {}: 1 noisy & weak, 2 noisy & strong, 3 quiet & strong, 4 quiet & weak\n\n",
                num(d.thresholds.spl_db),
                num(d.thresholds.inclination_cm_s),
                match d.thresholds.zone_by {
                    ZoneBy::Paper => "e (Eq 27)",
                    ZoneBy::Fit => "e_fit",
                }
            );
            s += &zone_map(&chart);
            s += "\nTable 5 — SPLmax spread per band of e:\n   e (cm/s)        designs  SPLmax (dB)      range (dB)\n";
            for b in &bands {
                s += &format!(
                    "  {:>5.2} – {:<5.2}  {:>7}  {:>6.2} – {:<6.2}  {:>6.2}\n",
                    b.e_lo_cm_s,
                    b.e_hi_cm_s,
                    b.count,
                    b.spl_min_db,
                    b.spl_max_db,
                    b.spl_max_db - b.spl_min_db
                );
            }
            s += "\n(--csv for every cell: e, e_fit, U0max, SPLmax, impacts, zone)\n";
            super::output::check_finite(&(&chart, &bands))?;
            out.text(&s)?;
        }
    }
    Ok(())
}

/// A text map of the zones: gaps down, masses across.
fn zone_map(chart: &Chart) -> String {
    let mut s = String::from("zone map  (rows: gap in cm; columns: mass in g; · = no impact)\n");
    s += "          ";
    for (i, m) in chart.masses_kg.iter().enumerate() {
        s += &if i % 4 == 0 { format!("{:<4}", format!("{:.0}", m * 1e3)) } else { String::new() };
    }
    s += "\n";
    for (gi, g) in chart.gaps_m.iter().enumerate().rev() {
        s += &format!("  {:>6.2}  ", g * 1e2);
        for mi in 0..chart.masses_kg.len() {
            let z = chart.cell(mi, gi).and_then(|c| c.metrics.zone);
            s += &z.map_or("·".into(), |z| z.number().to_string());
        }
        s += "\n";
    }
    s
}
