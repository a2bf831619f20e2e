//! `thud sweep`: the design chart over impact mass × gap.

use std::io::IsTerminal;
use std::sync::atomic::{AtomicUsize, Ordering};

use clap::Args;

use super::design_args::{parse_range, DesignArgs};
use super::format::{num, print_str};
use super::simulate::describe;
use super::{OutputArgs, OutputFormat};
use crate::design::{self, Chart, ZoneBy};
use crate::error::ThudError;
use crate::units::Kind;

#[derive(Debug, Clone, Args)]
pub struct SweepArgs {
    #[command(flatten)]
    design: DesignArgs,
    /// Impact masses FROM:TO:N (e.g. 30g:100g:20).
    #[arg(long, value_name = "FROM:TO:N", default_value = "30g:100g:20")]
    masses: String,
    /// Gaps FROM:TO:N (e.g. 2cm:5cm:20).
    #[arg(long, value_name = "FROM:TO:N", default_value = "2cm:5cm:20")]
    gaps: String,
    /// Width of the inclination bands of the Table 5 summary (cm/s).
    #[arg(long, value_name = "CM_S", default_value = "0.2")]
    band: String,
    #[command(flatten)]
    output: OutputArgs,
}

pub fn run(a: &SweepArgs) -> Result<(), ThudError> {
    let d = a.design.design()?;
    let masses = parse_range("masses", &a.masses, Kind::Mass)?;
    let gaps = parse_range("gaps", &a.gaps, Kind::Length)?;
    let band = crate::units::parse("band", &a.band, Kind::Inclination)?;
    crate::error::check_positive("band", band, "cm/s")?;
    let total = masses.len() * gaps.len();
    let done = AtomicUsize::new(0);
    let progress = std::io::stderr().is_terminal();
    let chart = design::sweep(&d, &masses, &gaps, None, &|_, _| {
        let k = done.fetch_add(1, Ordering::Relaxed) + 1;
        if progress && (k.is_multiple_of(8) || k == total) {
            eprint!("\rsweep {k}/{total} designs");
            if k == total {
                eprintln!();
            }
        }
    })?;
    let bands = design::spl_range_by_inclination(&chart, band, d.thresholds.zone_by);
    match a.output.format() {
        OutputFormat::Json => {
            let j = serde_json::json!({ "design": d, "chart": chart, "table5": bands });
            print_str(&(serde_json::to_string_pretty(&j).unwrap_or_default() + "\n"));
        }
        OutputFormat::Csv => print_str(
            &crate::export::csv::sweep(&chart).map_err(|e| ThudError::invalid("csv", format!("cannot write: {e}")))?,
        ),
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
            print_str(&s);
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
