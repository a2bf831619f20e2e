//! `thud sweep`: the design chart over impact mass × gap; with `--ensemble N` a chart of
//! ensembles, with `--shard K/N` one part of it for `thud merge`.

use std::path::{Path, PathBuf};

use clap::Args;
use serde::Serialize;

use super::budget;
use super::design_args::{parse_range, DesignArgs, ForceAmplitude};
use super::figure_out::FigureOutputs;
use super::simulate::describe;
use super::{count, quantity, CliError, Ctx, Out, OutputArgs, OutputFormat};
use crate::design::{self, Band, Chart, Design, ZoneBy};
use crate::ensemble::{self, EnsembleChart};
use crate::error::ThudError;
use crate::export::studies::short_base;
use crate::export::svg::Look;
use crate::fsio::{self, Overwrite};
use crate::limits::{self, short};
use crate::shard::{self, Header, PartCell, Study};
use crate::units::Kind;

#[derive(Debug, Clone, Args)]
pub struct SweepArgs {
    #[command(flatten)]
    design: DesignArgs<ForceAmplitude>,
    /// Impact masses FROM:TO:N (e.g. 30g:100g:20).
    #[arg(long, value_name = "FROM:TO:N", allow_hyphen_values = true, default_value = "30g:100g:20")]
    masses: String,
    /// Gaps FROM:TO:N (e.g. 2cm:5cm:20).
    #[arg(long, value_name = "FROM:TO:N", allow_hyphen_values = true, default_value = "2cm:5cm:20")]
    gaps: String,
    /// Vary any numeric parameter instead of mass × gap, NAME=FROM:TO:N in its units (e.g.
    /// v0=1:3:5, c1=10:60:6, freq=3Hz:8Hz:50); repeatable: the grid is the product of them.
    #[arg(long, value_name = "NAME=FROM:TO:N", allow_hyphen_values = true, conflicts_with_all = ["masses", "gaps", "band"])]
    vary: Vec<String>,
    /// Width of the inclination bands of the Table 5 summary (cm/s) [default: 0.2].
    #[arg(long, value_name = "CM_S", allow_hyphen_values = true)]
    band: Option<String>,
    /// Runs per cell, from ball offsets spread evenly over the clearance: each cell's zone is
    /// that of its medians, with its zone-3 probability (1: the single trajectory).
    #[arg(long, value_name = "N", default_value = "1", allow_hyphen_values = true)]
    ensemble: String,
    /// Compute only part K of N equal parts of the grid (K from 0, like SLURM_ARRAY_TASK_ID) and
    /// write it as JSON lines (or --csv) for `thud merge`.
    #[arg(long, value_name = "K/N", allow_hyphen_values = true)]
    shard: Option<String>,
    /// Write to this file instead of standard output (`-`: standard output); an existing file is
    /// kept unless --force. Written whole or not at all.
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// Also write the figure as SVG to this file.
    #[arg(long, value_name = "FILE", conflicts_with = "shard")]
    svg: Option<PathBuf>,
    /// Also write the figure as PDF to this file.
    #[arg(long, value_name = "FILE", conflicts_with = "shard")]
    pdf: Option<PathBuf>,
    /// Replace the --out, --svg or --pdf file if it exists.
    #[arg(long)]
    force: bool,
    #[command(flatten)]
    ascii: super::AsciiArgs,
    #[command(flatten)]
    output: OutputArgs,
}

impl SweepArgs {
    /// Where the table and its figure go.
    fn outputs(&self) -> FigureOutputs<'_> {
        FigureOutputs::new(&self.out, &self.svg, &self.pdf, self.force, self.ascii)
    }
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

/// The width of Table 5's bands when `--band` is not given (cm/s): the paper's.
const DEFAULT_BAND_CM_S: f64 = 0.2;

pub fn run(a: &SweepArgs, ctx: &Ctx, out: &mut Out) -> Result<(), CliError> {
    if !a.vary.is_empty() {
        return vary(a, ctx, out);
    }
    let d = a.design.design()?;
    let masses = parse_range("masses", &a.masses, Kind::Mass, &limits::MASS)?;
    let gaps = parse_range("gaps", &a.gaps, Kind::Length, &limits::GAP)?;
    let band = quantity("band", &a.band, Kind::Inclination, &limits::BAND)?.unwrap_or(DEFAULT_BAND_CM_S);
    let runs = count("ensemble", &a.ensemble, &limits::ENSEMBLE)?;
    a.design.check_ensemble(runs)?;
    let files = a.outputs();
    files.check()?;
    let target = Target::new(a.out.as_deref(), a.force)?;
    if let Some(text) = &a.shard {
        let (k, n) = parse_shard(text, masses.len() * gaps.len())?;
        let study = Study { design: d.into_design(), masses_kg: masses, gaps_m: gaps, band_cm_s: band, ensemble: runs };
        return write_shard(a, ctx, study, k, n, &target, out);
    }
    a.design.check_sweep(ctx, &d, masses.len(), gaps.len())?;
    let chart = if runs == 1 {
        let bar = budget::bar((masses.len() * gaps.len()) as u64, "sweep");
        let chart = design::sweep(&d, &masses, &gaps, None, &|_, _| bar.inc(1))?;
        bar.finish_and_clear();
        Charted::Plain(chart)
    } else {
        let cells = masses.len() * gaps.len();
        a.design.check_runs(ctx, &d, cells, runs, "--ensemble", &a.ensemble)?;
        let bar = budget::bar(cells as u64, "sweep");
        let chart = ensemble::sweep(&d, &masses, &gaps, runs, None, &|_, _| bar.inc(1))?;
        bar.finish_and_clear();
        Charted::Ensemble(chart)
    };
    let band_text = a.band.clone().unwrap_or_else(|| format!("{DEFAULT_BAND_CM_S} (the default)"));
    let text = render(ctx, &d, &chart, band, &band_text, a.output.format())?;
    let figure = files.wants_figure().then(|| match &chart {
        Charted::Plain(c) => crate::export::figures::design_chart(
            c,
            &format!("Design chart: zone of each impact mass × gap — {}", short_base(&d)),
            &Look::default(),
        ),
        Charted::Ensemble(e) => {
            crate::export::studies::ensemble_chart(e, &crate::export::studies::ensemble_title(e, &d), &Look::default())
        }
    });
    files.write(&text, figure, out)
}

/// `thud sweep --vary …` ([`super::study`]): one run a cell (no ensemble, no shards yet).
fn vary(a: &SweepArgs, ctx: &Ctx, out: &mut Out) -> Result<(), CliError> {
    if count("ensemble", &a.ensemble, &limits::ENSEMBLE)? > 1 {
        return Err(ThudError::invalid(
            "--ensemble",
            format!("{}: a study with --vary runs one trajectory a cell; leave out --ensemble", a.ensemble),
        )
        .into());
    }
    let files = a.outputs();
    files.check()?;
    let target = Target::new(a.out.as_deref(), a.force)?;
    if let Some(text) = &a.shard {
        let d = super::study::design_for(&a.design, &a.vary)?;
        let grid = super::study::grid(d, &a.vary)?;
        let part = parse_shard(text, grid.cells())?;
        let s = super::study::write_shard(&a.design, ctx, &grid, part, a.output.csv)?;
        return target.write(&s, out);
    }
    if files.wants_figure() && !(1..=2).contains(&a.vary.len()) {
        let flag = if a.svg.is_some() { "--svg" } else { "--pdf" };
        return Err(ThudError::invalid(
            flag,
            format!(
                "a figure draws a study over one or two parameters, not {}; leave out {flag} or give at most two --vary",
                a.vary.len()
            ),
        )
        .into());
    }
    let (text, study) = super::study::sweep_vary(&a.design, &a.vary, ctx, a.output.format())?;
    let figure = files.wants_figure().then(|| super::study::figure(&study)).flatten();
    files.write(&text, figure, out)
}

/// A computed chart: the ordinary one, or one of ensembles.
pub(super) enum Charted {
    Plain(Chart),
    Ensemble(EnsembleChart),
}

impl Charted {
    /// The chart the zone map and Table 5 are drawn from (of the medians for ensembles).
    fn zones(&self) -> std::borrow::Cow<'_, Chart> {
        match self {
            Charted::Plain(c) => std::borrow::Cow::Borrowed(c),
            Charted::Ensemble(e) => std::borrow::Cow::Owned(e.medians()),
        }
    }
}

#[derive(Serialize)]
struct EnsembleSweepJson<'a> {
    design: &'a Design,
    chart: &'a EnsembleChart,
    table5: &'a [Band],
}

/// The chart as `thud sweep` prints it in `format` (checked finite): the one printout of
/// `sweep` and `merge`. `band_text` is the band width as the user gave it (for a refusal).
pub(super) fn render(
    ctx: &Ctx,
    d: &Design,
    charted: &Charted,
    band: f64,
    band_text: &str,
    format: OutputFormat,
) -> Result<String, CliError> {
    let chart = charted.zones();
    if let Some((lo, hi)) = inclination_span(&chart, d.thresholds.zone_by) {
        let bands = limits::band_count(lo, hi, band);
        ctx.enforce(bands, "--band", band_text, &format!("use --band ≥ {} cm/s", short((hi - lo) / bands.cap.max)))?;
    }
    let bands = design::spl_range_by_inclination(&chart, band, d.thresholds.zone_by);
    let csv_error = |e: csv::Error| ThudError::invalid("csv", format!("cannot write: {e}"));
    Ok(match (format, charted) {
        (OutputFormat::Json, Charted::Plain(c)) => pretty(&SweepJson { design: d, chart: c, table5: &bands })?,
        (OutputFormat::Json, Charted::Ensemble(e)) => {
            pretty(&EnsembleSweepJson { design: d, chart: e, table5: &bands })?
        }
        (OutputFormat::Csv, Charted::Plain(c)) => crate::export::csv::sweep(c).map_err(csv_error)?,
        (OutputFormat::Csv, Charted::Ensemble(e)) => {
            super::output::check_finite(e)?;
            crate::export::csv::sweep_ensemble(e).map_err(csv_error)?
        }
        (OutputFormat::Text, _) => {
            let mut s = format!("base      {}\n", describe(d));
            s += &format!(
                "zones     L* {} dB, e* {} cm/s by {}: 1 noisy & weak, 2 noisy & strong, 3 quiet & strong, 4 quiet & weak\n\n",
                crate::units::short(d.thresholds.spl_db),
                crate::units::short(d.thresholds.inclination_cm_s),
                match d.thresholds.zone_by {
                    ZoneBy::Paper => "e (Eq 27)",
                    ZoneBy::Fit => "e_fit",
                }
            );
            s += &zone_map(&chart);
            if let Charted::Ensemble(e) = charted {
                super::output::check_finite(e)?;
                s += &ensemble_maps(e);
            }
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
            super::output::check_finite(&(&*chart, &bands))?;
            s
        }
    })
}

/// `v` as `--json` prints it (pretty, with a final newline), after the finite check.
fn pretty<T: Serialize>(v: &T) -> Result<String, CliError> {
    super::output::check_finite(v)?;
    let mut s = serde_json::to_string_pretty(v).map_err(std::io::Error::from)?;
    s.push('\n');
    Ok(s)
}

/// Where the output goes: standard output, or a file written whole through [`fsio`].
pub(super) struct Target<'a> {
    path: Option<&'a Path>,
    overwrite: Overwrite,
}

impl<'a> Target<'a> {
    /// The target `--out` names (checked now, before any work), or standard output.
    pub(super) fn new(path: Option<&'a Path>, force: bool) -> Result<Self, ThudError> {
        let overwrite = Overwrite::from_force(force);
        let path = path.filter(|p| !fsio::is_stdout(p));
        if let Some(p) = path {
            fsio::check_target(p, overwrite).map_err(|e| super::export::out_error(p, &e))?;
        }
        Ok(Target { path, overwrite })
    }

    /// The file it names, if not standard output.
    pub(super) fn file(&self) -> Option<&'a Path> {
        self.path
    }

    /// Writes `text` (already checked) there; says on stderr which file was written.
    pub(super) fn write(&self, text: &str, out: &mut Out) -> Result<(), CliError> {
        match self.path {
            None => out.text(text),
            Some(p) => {
                super::output::check_text(text)?;
                fsio::write(p, text.as_bytes(), self.overwrite).map_err(|e| super::export::write_error(p, &e))?;
                super::warn(&format!("wrote {}", fsio::shown(p)));
                Ok(())
            }
        }
    }
}

/// Parses `--shard K/N` for a chart of `cells` cells: whole numbers, 0 ≤ K < N ≤ cells.
pub(super) fn parse_shard(text: &str, cells: usize) -> Result<(usize, usize), ThudError> {
    let invalid = |why: String| ThudError::invalid("--shard", format!("'{text}': {why}"));
    let Some((k, n)) = text.split_once('/') else {
        return Err(invalid("expected K/N, e.g. 3/64: part K (from 0, like SLURM_ARRAY_TASK_ID) of N".into()));
    };
    let whole = |t: &str, what: &str| {
        t.trim().parse::<usize>().map_err(|_| invalid(format!("{what} '{}' is not a whole number ≥ 0", t.trim())))
    };
    let (k, n) = (whole(k, "K")?, whole(n, "N")?);
    if n == 0 {
        return Err(invalid("N must be at least 1".into()));
    }
    if k >= n {
        return Err(invalid(format!("K must be below N: 0 to {} (K counts from 0, like SLURM_ARRAY_TASK_ID)", n - 1)));
    }
    if n > cells {
        return Err(invalid(format!("{n} parts of a chart of {cells} cells; N must be at most the number of cells")));
    }
    Ok((k, n))
}

/// `thud sweep --shard K/N`: computes part K of N of `study` and writes it with its header.
fn write_shard(
    a: &SweepArgs,
    ctx: &Ctx,
    study: Study,
    k: usize,
    n: usize,
    target: &Target,
    out: &mut Out,
) -> Result<(), CliError> {
    let header = Header::new(study, k, n);
    let s = &header.study;
    let part_cells = header.end_cell - header.first_cell;
    let (flag, value) = if s.ensemble > 1 {
        ("--ensemble", a.ensemble.as_str())
    } else {
        ("--shard", a.shard.as_deref().unwrap_or_default())
    };
    // Refused up front: a study whose parts `thud merge` could never join.
    let merged = limits::merged_runs(s.cells(), s.ensemble);
    ctx.enforce(
        merged,
        flag,
        value,
        &format!(
            "`thud merge` joins a chart of at most {} runs ({} cells × {} runs here): use fewer --masses or --gaps values or a smaller --ensemble",
            short(merged.cap.max),
            s.cells(),
            s.ensemble
        ),
    )?;
    // The study's design is the checked design of the flags; checked again as the engine's type.
    let d = s.design.clone().check()?;
    a.design.check_runs(ctx, &d, part_cells, s.ensemble, flag, value)?;
    let bar = budget::bar(part_cells as u64, "shard");
    let range = header.first_cell..header.end_cell;
    let cells = ensemble::sweep_cells(&d, &s.masses_kg, &s.gaps_m, s.ensemble, range, None, &|_, _| bar.inc(1))?;
    bar.finish_and_clear();
    let cells: Vec<PartCell> = cells.iter().map(|(i, c)| PartCell::new(*i, c)).collect();
    super::output::check_finite(&cells)?;
    let format = if a.output.csv { shard::Format::Csv } else { shard::Format::JsonLines };
    let text =
        shard::write(format, &header, &cells).map_err(|e| ThudError::invalid("csv", format!("cannot write: {e}")))?;
    target.write(&text, out)
}

/// Maps of how sure each cell of an ensemble chart is: the fraction of its runs in zone 3, and
/// the fraction that agree with its zone, in tenths (`*`: all of them).
fn ensemble_maps(chart: &EnsembleChart) -> String {
    let tenths = |f: f64| if f >= 1.0 { '*' } else { char::from(b'0' + (f * 10.0).floor().clamp(0.0, 9.0) as u8) };
    let map = |title: &str, value: &dyn Fn(&ensemble::EnsembleCell) -> f64| {
        let mut s = format!("\n{title}\n");
        for (gi, g) in chart.gaps_m.iter().enumerate().rev() {
            s += &format!("  {:>6.2}  ", g * 1e2);
            for mi in 0..chart.masses_kg.len() {
                s.push(chart.cell(mi, gi).map_or('·', |c| tenths(value(c))));
            }
            s += "\n";
        }
        s
    };
    let runs = chart.runs;
    let mut s = format!(
        "\nensemble  {runs} runs a cell, the ball starting at rest at y0 = −d/2 + (k + ½)·d/{runs}; zones above are of the medians\n"
    );
    s += &map("zone-3 probability (tenths of the runs in zone 3; * = all)", &|c| c.ensemble.zone3_probability);
    s += &map("agreement (tenths of the runs in the cell's zone; * = all)", &|c| c.ensemble.agreement);
    s
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
