//! `thud fit structure|damper`: calibration from a measured free decay (CSV), by the engine's
//! [`crate::fit`]. The file is read through [`crate::fsio`] and parsed with the csv crate; its
//! columns carry their units in their names (`t_s`, `x_mm`, `v_m_s`, `a_g`, …).

use std::ffi::OsString;
use std::path::Path;

use clap::{Args, Subcommand};

use super::design_args::DesignArgs;
use super::{quantity, CliError, Ctx, Out};
use crate::design::Design;
use crate::error::ThudError;
use crate::fit::{self, damper::DamperFit, structure::StructureFit, Quantity, Series};
use crate::fsio;
use crate::limits::{self, Estimate};
use crate::units::{self, sig, Kind};

/// Largest measurement file read (bytes): 256 MiB, about 10 million rows of two numbers.
pub const MAX_DATA_BYTES: u64 = 256 << 20;

#[derive(Debug, Args)]
pub struct FitArgs {
    #[command(subcommand)]
    what: FitCommand,
}

#[derive(Debug, Subcommand)]
enum FitCommand {
    /// The structure alone, struck once: f_n, ζ, K and C with standard errors.
    Structure(StructureArgs),
    /// The structure with its damper, struck once: c1 and its restitution with a 95 % interval.
    Damper(Box<DamperArgs>),
}

#[derive(Debug, Args)]
struct StructureArgs {
    /// The measured decay: CSV with a time column `t_s` (or t_ms, t_us) and one signal column
    /// `x_m`, `v_m_s` or `a_m_s2` (or x_mm, x_um, v_mm_s, a_g, …).
    #[arg(long, value_name = "FILE")]
    data: OsString,
    /// The main mass M (kg; 12kg, 500g): K = M·ω_n², C = 2·M·ζ·ω_n.
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    main_mass: String,
    /// Save the fitted structure (the default design with this M, K and C) as a design NAME
    /// for `thud tui --design NAME`.
    #[arg(long, value_name = "NAME")]
    save: Option<String>,
    /// Print one JSON object.
    #[arg(long)]
    json: bool,
}

#[derive(Debug, Args)]
struct DamperArgs {
    /// A measured decay of the structure with the damper, starting at the strike (see `fit
    /// structure --data`); give it again for each repeated strike: they fit together.
    #[arg(long, value_name = "FILE", required = true)]
    data: Vec<OsString>,
    #[command(flatten)]
    design: DesignArgs,
    /// Save the design with the fitted c1 as NAME for `thud tui --design NAME`.
    #[arg(long, value_name = "NAME")]
    save: Option<String>,
    /// Print one JSON object.
    #[arg(long)]
    json: bool,
}

pub fn run(a: &FitArgs, ctx: &Ctx, out: &mut Out) -> Result<(), CliError> {
    match &a.what {
        FitCommand::Structure(s) => structure(s, ctx, out),
        FitCommand::Damper(d) => damper(d, ctx, out),
    }
}

/// A `--data` error naming the file.
fn data_error(path: &Path, message: impl std::fmt::Display) -> ThudError {
    ThudError::invalid(fit::DATA_PARAM, format!("{}: {message}", fsio::shown(path)))
}

/// The SI factor of a time column's unit (`s`, `ms`, `us`).
fn time_factor(unit: &str) -> Option<f64> {
    units::parse("t", &format!("1{unit}"), Kind::Time).ok()
}

/// The quantity and SI factor of a signal column: `x_<length>`, `v_<length>_s`,
/// `a_<length>_s2` or `a_g` (standard gravity, 9.80665 m/s²).
fn signal_column(name: &str) -> Option<(Quantity, f64)> {
    let (q, unit) = name.split_once('_')?;
    match q {
        "x" => units::parse("x", &format!("1{unit}"), Kind::Length).ok().map(|f| (Quantity::Displacement, f)),
        "v" => {
            let len = unit.strip_suffix("_s")?;
            units::parse("v", &format!("1{len}"), Kind::Length).ok().map(|f| (Quantity::Velocity, f))
        }
        "a" if unit == "g" => Some((Quantity::Acceleration, 9.80665)),
        "a" => {
            let len = unit.strip_suffix("_s2")?;
            units::parse("a", &format!("1{len}"), Kind::Length).ok().map(|f| (Quantity::Acceleration, f))
        }
        _ => None,
    }
    .filter(|(_, f)| f.is_finite() && *f > 0.0)
}

/// Reads one measurement file: the header names a time column and one signal column, each
/// with its unit; every row two numbers. Errors name `--data` and the file, as one line.
fn read_series(path: &Path, ctx: &Ctx) -> Result<Series, CliError> {
    let text = fsio::read_to_string(path, MAX_DATA_BYTES).map_err(|e| data_error(path, e.reason()))?;
    let mut r = csv::ReaderBuilder::new().trim(csv::Trim::All).comment(Some(b'#')).from_reader(text.as_bytes());
    let header: Vec<String> = r
        .headers()
        .map_err(|e| data_error(path, format!("cannot read the header: {e}")))?
        .iter()
        .map(str::to_ascii_lowercase)
        .collect();
    let unitless = |h: &String| !h.contains('_');
    if let Some(h) = header.iter().find(|h| unitless(h)) {
        return Err(data_error(
            path,
            format!("column '{h}' has no unit; name the columns with their units, e.g. t_s and x_m, v_m_s or a_m_s2"),
        )
        .into());
    }
    let Some((ti, tf)) =
        header.iter().enumerate().find_map(|(i, h)| h.strip_prefix("t_").and_then(time_factor).map(|f| (i, f)))
    else {
        return Err(data_error(path, "no time column; the header needs t_s (or t_ms, t_us)").into());
    };
    let signals: Vec<(usize, Quantity, f64)> =
        header.iter().enumerate().filter_map(|(i, h)| signal_column(h).map(|(q, f)| (i, q, f))).collect();
    let (si, q, sf) = match signals.as_slice() {
        [one] => *one,
        [] => {
            let other = header.iter().enumerate().find(|&(i, _)| i != ti).map_or("", |(_, h)| h.as_str());
            return Err(data_error(
                path,
                format!("no signal column with a known unit (found '{other}'); use x_m, v_m_s or a_m_s2 (or x_mm, v_mm_s, a_g, …)"),
            )
            .into());
        }
        _ => return Err(data_error(path, "more than one signal column; give one of x, v or a").into()),
    };
    let (mut t, mut y) = (Vec::new(), Vec::new());
    for (i, rec) in r.records().enumerate() {
        let rec = rec.map_err(|e| data_error(path, format!("row {}: {e}", i + 2)))?;
        let cell = |k: usize| -> Result<f64, ThudError> {
            let s = rec.get(k).unwrap_or("");
            s.parse::<f64>().map_err(|_| data_error(path, format!("row {}: '{s}' is not a number", i + 2)))
        };
        t.push(cell(ti)? * tf);
        y.push(cell(si)? * sf);
    }
    ctx.enforce(
        Estimate { cap: limits::HISTORY_SAMPLES, value: t.len() as f64 },
        "--data",
        &fsio::shown(path),
        "use a shorter or decimated record",
    )?;
    Series::new(t, y, q).map_err(|e| data_error(path, e.detail()).into())
}

/// Saves `design` as `name` (refusing to replace one), with a one-line description.
fn save(name: &str, design: Design, description: String) -> Result<String, CliError> {
    let file = crate::store::DesignFile { description, ensemble: None, design };
    match crate::store::save_user_design(name, &file, false) {
        Ok(path) => Ok(fsio::shown(&path)),
        Err(crate::store::StoreError::Exists(p)) => Err(ThudError::invalid(
            "save",
            format!("a design named '{name}' exists ({}); choose another name", fsio::shown(&p)),
        )
        .into()),
        Err(crate::store::StoreError::Thud(e)) => Err(e.renamed("save").into()),
        Err(e) => Err(CliError::Io(format!("cannot save the design: {e}"))),
    }
}

/// `±` a standard error, with 3 significant digits.
fn pm(v: f64, se: f64) -> String {
    format!("{} ± {}", sig(v, 5), sig(se, 2))
}

/// Reads `path` and fits the structure with main mass `m` (kg): the record and its fit.
pub(super) fn structure_fit(ctx: &Ctx, path: &Path, m: f64) -> Result<(Series, StructureFit), CliError> {
    let s = read_series(path, ctx)?;
    let f = fit::structure::fit(&s, m).map_err(|e| data_error(path, e.detail()))?;
    Ok((s, f))
}

/// Reads every `paths` and fits c1 of `d` to them, the work checked first.
pub(super) fn damper_fit(
    ctx: &Ctx,
    flags: &DesignArgs<impl super::design_args::ForceFlag>,
    d: &crate::design::ValidDesign,
    paths: &[OsString],
) -> Result<DamperFit, CliError> {
    let mut records = Vec::with_capacity(paths.len());
    for p in paths {
        records.push(read_series(Path::new(p), ctx)?);
    }
    let span = fit::damper::common_span_s(&records);
    let work = fit::damper::work_design(d, span)?;
    let runs = fit::damper::GRID_POINTS * fit::damper::STARTS;
    flags.check_runs(ctx, &work, fit::damper::GRID_POINTS, fit::damper::STARTS, "--data", &format!("{runs} runs"))?;
    let spinner = super::budget::spinner("fitting", true);
    let first = Path::new(&paths[0]);
    let f = fit::damper::fit(d, &records, None)
        .map_err(|e| if e.param() == fit::DATA_PARAM { data_error(first, e.detail()) } else { e })?
        .ok_or(ThudError::Cancelled)?;
    spinner.finish_and_clear();
    Ok(f)
}

fn structure(a: &StructureArgs, ctx: &Ctx, out: &mut Out) -> Result<(), CliError> {
    let m = quantity("main-mass", &Some(a.main_mass.clone()), Kind::Mass, &limits::MAIN_MASS)?.unwrap_or(1.0);
    if let Some(name) = &a.save {
        crate::store::check_design_name(name).map_err(|e| e.renamed("save"))?;
    }
    let path = Path::new(&a.data);
    let (_, f) = structure_fit(ctx, path, m)?;
    let saved = match (&a.save, f.converged) {
        (Some(name), true) => {
            let mut d = Design::default();
            d.damper.main_mass_kg = m;
            d.damper.stiffness_n_m = f.k_n_m;
            d.damper.damping_n_s_m = f.c_n_s_m;
            let d = d.check().map_err(|e| e.renamed("save"))?.into_design();
            Some(save(name, d, format!("fitted structure from {}", fsio::shown(path)))?)
        }
        _ => None,
    };
    if a.json {
        out.json(&f)?;
    } else {
        out.text(&structure_text(&f, saved.as_deref()))?;
    }
    not_converged(f.converged, &f.termination, f.residual_rms, &f.unit)
}

/// A fit that did not converge: its best estimate was printed; say so, exit 1.
fn not_converged(converged: bool, how: &str, rms: f64, unit: &str) -> Result<(), CliError> {
    if converged {
        return Ok(());
    }
    Err(CliError::Io(format!(
        "the fit did not converge ({how}); the numbers printed are its best estimate, residual rms {} {unit}",
        sig(rms, 3)
    )))
}

fn structure_text(f: &StructureFit, saved: Option<&str>) -> String {
    let mut s = format!(
        "Structure fit ({} samples, {} cycles, {}){}\n",
        f.samples,
        f.cycles,
        f.unit,
        if f.converged { "" } else { " — DID NOT CONVERGE: best estimate" }
    );
    s += &format!("  f_n  {} Hz\n", pm(f.f_n_hz, f.f_n_hz_stderr));
    s += &format!("  ζ    {}\n", pm(f.zeta, f.zeta_stderr));
    s += &format!("  K    {} N/m   (M {} kg)\n", pm(f.k_n_m, f.k_n_m_stderr), sig(f.main_mass_kg, 6));
    s += &format!("  C    {} N·s/m\n", pm(f.c_n_s_m, f.c_n_s_m_stderr));
    s += &format!("  residual rms {} {}\n", sig(f.residual_rms, 3), f.unit);
    s += &format!("  start: spectrum peak {} Hz, log decrement ζ {}\n", sig(f.start_f_hz, 5), sig(f.start_zeta, 3));
    if let Some(p) = saved {
        s += &format!("Saved as {p}\n");
    }
    s
}

fn damper(a: &DamperArgs, ctx: &Ctx, out: &mut Out) -> Result<(), CliError> {
    let d = a.design.design()?;
    if let Some(name) = &a.save {
        crate::store::check_design_name(name).map_err(|e| e.renamed("save"))?;
    }
    let mut records = Vec::with_capacity(a.data.len());
    for p in &a.data {
        records.push(read_series(Path::new(p), ctx)?);
    }
    let span = fit::damper::common_span_s(&records);
    let work = fit::damper::work_design(&d, span)?;
    let runs = fit::damper::GRID_POINTS * fit::damper::STARTS;
    a.design.check_runs(
        ctx,
        &work,
        fit::damper::GRID_POINTS,
        fit::damper::STARTS,
        "--data",
        &format!("{runs} runs"),
    )?;
    let spinner = super::budget::spinner("fitting", true);
    let first = Path::new(&a.data[0]);
    let f = fit::damper::fit(&d, &records, None)
        .map_err(|e| if e.param() == fit::DATA_PARAM { data_error(first, e.detail()) } else { e })?
        .ok_or(ThudError::Cancelled)?;
    spinner.finish_and_clear();
    let saved = match &a.save {
        Some(name) => {
            let mut dd = d.design().clone();
            dd.damper.c1_n_s_m = f.c1_n_s_m;
            let dd = dd.check().map_err(|e| e.renamed("save"))?.into_design();
            Some(save(name, dd, format!("fitted c1 from {}", fsio::shown(first)))?)
        }
        None => None,
    };
    if a.json {
        out.json(&f)?;
    } else {
        out.text(&damper_text(&f, saved.as_deref()))?;
    }
    Ok(())
}

fn damper_text(f: &DamperFit, saved: Option<&str>) -> String {
    let [lo, hi] = f.c1_n_s_m_ci;
    let [rlo, rhi] = f.restitution_ci;
    let mut s = format!(
        "Damper fit ({} record{}, {} periods, {} ball starts × {} values of c1)\n",
        f.records,
        if f.records == 1 { "" } else { "s" },
        f.periods,
        f.starts,
        f.grid_points
    );
    s += &format!(
        "  c1           {} N·s/m   95 % interval [{}, {}]{}\n",
        sig(f.c1_n_s_m, 4),
        sig(lo, 4),
        sig(hi, 4),
        if f.ci_open { " (reaches the end of the grid: open there)" } else { "" }
    );
    s += &format!(
        "  restitution  {}          95 % interval [{}, {}] at the first impact's {} m/s\n",
        sig(f.restitution, 4),
        sig(rlo, 4),
        sig(rhi, 4),
        sig(f.first_impact_speed_m_s, 3)
    );
    s += &format!("  envelope residual rms {} m\n", sig(f.residual_rms, 3));
    if let Some(note) = &f.note {
        s += &format!("  note: {note}\n");
    }
    if let Some(p) = saved {
        s += &format!("Saved as {p}\n");
    }
    s
}
