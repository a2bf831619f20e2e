//! `thud fit structure|damper`: calibration from a measured free decay (CSV), by the engine's
//! [`crate::fit`]. The file is read through [`crate::fsio`] and parsed with the csv crate; its
//! columns carry their units in their names (`t_s`, `x_mm`, `v_m_s`, `a_g`, …).

use std::ffi::OsString;
use std::path::Path;

use clap::{Args, Subcommand};

use super::design_args::{DesignArgs, FitRows, Force, Rows};
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
    /// Save the fitted structure (the default design with this M, K and C) as the design file
    /// FILE.toml (or a path), or as a saved design NAME; `--design` loads either.
    #[arg(long, value_name = "FILE|NAME")]
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
    design: DesignArgs<Force, FitRows>,
    /// Save the design with the fitted c1 as the design file FILE.toml (or a path), or as a
    /// saved design NAME; `--design` loads either.
    #[arg(long, value_name = "FILE|NAME")]
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

/// What a column of a measurement file holds, from its name.
#[derive(Debug, Clone, PartialEq)]
enum Column {
    /// `t_<time unit>`: the sample times, × the factor to s.
    Time(f64),
    /// `x_<length>`, `v_<speed>` or `a_<acceleration>`: the signal, × the factor to SI.
    Signal(Quantity, f64),
    /// Any other name with a unit (an index, the ball's `y_m`): not read.
    Other,
    /// A name that starts like a time or signal column but whose rest is not a unit
    /// (`x_free_m`, another quantity): not read; why, for the message when no column is found.
    Unread(String),
}

/// Reads a column's name: `<q>_<unit>`, the quantity letter t, x, v or a and its unit with
/// `_` for `/` (`t_ms`, `x_mm`, `v_m_s`, `a_m_s2`, `a_g`). The unit is looked up in the table
/// every unit thud reads goes through ([`units::unit_factor`]): a unit name, nothing else (a
/// number in it, `t_0ms`, `t_10us`, is refused, not read as a factor). The error names `data`
/// and the column, for a line naming the file.
fn column(name: &str) -> Result<Column, ThudError> {
    let Some((q, unit)) = name.split_once('_') else {
        return Err(ThudError::invalid(
            fit::DATA_PARAM,
            format!(
                "column '{name}' has no unit; name the columns with their units, e.g. t_s and x_m, v_m_s or a_m_s2"
            ),
        ));
    };
    let (kind, what, example) = match q {
        "t" => (Kind::Time, "time", "t_s, t_ms or t_us"),
        "x" => (Kind::Length, "length", "x_m, x_mm or x_um"),
        "v" => (Kind::Speed, "speed", "v_m_s or v_mm_s"),
        "a" => (Kind::Acceleration, "acceleration", "a_m_s2, a_mm_s2 or a_g"),
        _ => return Ok(Column::Other),
    };
    let unit_text = unit.replace('_', "/");
    match units::unit_factor(kind, &unit_text).filter(|f| !unit.is_empty() && f.is_finite() && *f > 0.0) {
        Some(f) if kind == Kind::Time => Ok(Column::Time(f)),
        Some(f) => {
            let quantity = match q {
                "x" => Quantity::Displacement,
                "v" => Quantity::Velocity,
                _ => Quantity::Acceleration,
            };
            Ok(Column::Signal(quantity, f))
        }
        None => {
            let why = format!(
                "column '{name}': '{unit}' is not a {what} unit (known: {}; '_' stands for '/'); name it e.g. {example}",
                units::unit_names(kind)
            );
            // A number in the unit (`t_0ms`, `t_10us`) is a mistyped unit, refused; a word
            // (`x_free_m`) names another quantity, left unread.
            if unit.chars().any(|c| c.is_ascii_digit()) {
                Err(ThudError::invalid(fit::DATA_PARAM, why))
            } else {
                Ok(Column::Unread(why))
            }
        }
    }
}

/// The header line of `text` (the first line that is neither empty nor a `#` comment).
fn header_line(text: &str) -> &str {
    text.lines().map(str::trim).find(|l| !l.is_empty() && !l.starts_with('#')).unwrap_or("")
}

/// What a line separated otherwise than by commas is, if it is: "';' separated", "tab
/// separated".
fn other_separator(line: &str) -> Option<&'static str> {
    if line.contains(',') {
        return None;
    }
    if line.contains(';') {
        Some("';' separated")
    } else if line.contains('\t') {
        Some("tab separated")
    } else {
        None
    }
}

/// Reads one measurement file: the header names a time column and one signal column, each
/// with its unit; every row two numbers. Errors name `--data` and the file, as one line, and
/// say what they see (a file separated by ';' or tabs, a decimal comma, an empty column name).
fn read_series(path: &Path, ctx: &Ctx) -> Result<Series, CliError> {
    let text = fsio::read_to_string(path, MAX_DATA_BYTES).map_err(|e| data_error(path, e.reason()))?;
    series_from_text(path, &text, ctx)
}

/// The measurement `text` read from `path` (see `read_series`): the reader of outside input.
// Over 80 lines: one pass over the file, each refusal naming what it saw in the user's terms.
pub fn series_from_text(path: &Path, text: &str, ctx: &Ctx) -> Result<Series, CliError> {
    if let Some(sep) = other_separator(header_line(text)) {
        return Err(
            data_error(path, format!("the header is {sep}: use ',' between columns (and '.' in numbers)")).into()
        );
    }
    let mut r =
        csv::ReaderBuilder::new().trim(csv::Trim::All).comment(Some(b'#')).flexible(true).from_reader(text.as_bytes());
    let header: Vec<String> = r
        .headers()
        .map_err(|e| data_error(path, format!("cannot read the header: {e}")))?
        .iter()
        .map(str::to_ascii_lowercase)
        .collect();
    if let Some(i) = header.iter().position(String::is_empty) {
        let why = if i + 1 == header.len() { " (a ',' at the end of the header line?)" } else { "" };
        return Err(
            data_error(path, format!("column {} of the header has no name{why}; remove it or name it", i + 1)).into()
        );
    }
    let columns: Vec<Column> =
        header.iter().map(|h| column(h)).collect::<Result<_, _>>().map_err(|e| data_error(path, e.detail()))?;
    let unread = |kind: &str| {
        columns.iter().zip(&header).find_map(|(c, h)| match c {
            Column::Unread(why) if h.starts_with(kind) => Some(why.clone()),
            _ => None,
        })
    };
    let time = columns.iter().enumerate().find_map(|(i, c)| match c {
        Column::Time(f) => Some((i, *f)),
        _ => None,
    });
    let Some((ti, tf)) = time else {
        let why = unread("t_").unwrap_or_else(|| "no time column; the header needs t_s (or t_ms, t_us)".into());
        return Err(data_error(path, why).into());
    };
    if columns.iter().filter(|c| matches!(c, Column::Time(_))).count() > 1 {
        return Err(data_error(path, "more than one time column; give one of t_s, t_ms or t_us").into());
    }
    let signals: Vec<(usize, Quantity, f64)> = columns
        .iter()
        .enumerate()
        .filter_map(|(i, c)| match c {
            Column::Signal(q, f) => Some((i, *q, *f)),
            _ => None,
        })
        .collect();
    let (si, q, sf) = match signals.as_slice() {
        [one] => *one,
        [] => {
            if let Some(why) = ["x_", "v_", "a_"].iter().find_map(|k| unread(k)) {
                return Err(data_error(path, why).into());
            }
            let other = header.iter().enumerate().find(|&(i, _)| i != ti).map_or("", |(_, h)| h.as_str());
            return Err(data_error(
                path,
                format!("no signal column (found '{other}'); use x_m, v_m_s or a_m_s2 (or x_mm, v_mm_s, a_g, …)"),
            )
            .into());
        }
        _ => return Err(data_error(path, "more than one signal column; give one of x, v or a").into()),
    };
    let (mut t, mut y) = (Vec::new(), Vec::new());
    for rec in r.records() {
        // The cap is checked as the rows come: a record far over it is refused at its first
        // row past the cap, not after all of it is parsed.
        if t.len() as f64 >= limits::HISTORY_SAMPLES.max && !ctx.no_limit {
            return Err(over_cap(path));
        }
        let rec = rec.map_err(|e| data_error(path, format!("cannot read a row: {e}")))?;
        let row = rec.position().map_or(0, csv::Position::line);
        if rec.len() != header.len() {
            let joined = rec.iter().collect::<Vec<_>>().join(",");
            let why = match other_separator(&joined) {
                Some(sep) => format!("; it is {sep}: use ',' between columns"),
                None if rec.len() > header.len()
                    && rec.iter().all(|c| c.chars().all(|ch| ch.is_ascii_digit() || "+-eE".contains(ch))) =>
                {
                    "; a decimal comma? write 0.5, not 0,5".to_string()
                }
                None => String::new(),
            };
            return Err(data_error(
                path,
                format!("line {row} has {} fields but the header {} columns{why}", rec.len(), header.len()),
            )
            .into());
        }
        let cell = |k: usize| -> Result<f64, ThudError> {
            let s = rec.get(k).unwrap_or("");
            s.parse::<f64>().map_err(|_| {
                let hint = if s.contains(',') { " (a decimal comma? write 0.5, not 0,5)" } else { "" };
                data_error(path, format!("line {row}: '{s}' is not a number{hint}"))
            })
        };
        t.push(cell(ti)? * tf);
        y.push(cell(si)? * sf);
    }
    check_rows(ctx, path, t.len())?;
    Series::new(t, y, q).map_err(|e| data_error(path, e.detail()).into())
}

/// Refuses a record of `rows` rows over the sample cap (unless `--no-limit`).
fn check_rows(ctx: &Ctx, path: &Path, rows: usize) -> Result<(), CliError> {
    let e = Estimate { cap: limits::HISTORY_SAMPLES, value: rows as f64 };
    ctx.enforce(e, "--data", &fsio::shown(path), "use a shorter or decimated record")
}

/// The refusal of a record with more rows than the sample cap, made at its first row past it.
fn over_cap(path: &Path) -> CliError {
    let max = limits::short(limits::HISTORY_SAMPLES.max);
    CliError::Refused(format!(
        "--data {}: more than {max} rows, over the limit of {max} {}; use a shorter or decimated record, or add --no-limit",
        fsio::shown(path),
        limits::HISTORY_SAMPLES.what
    ))
}

/// Checks `--save`'s value before the fit: a file (a path, or a name ending in `.toml`) or a
/// saved design's name.
fn check_save(name: &str) -> Result<(), ThudError> {
    if crate::store::names_a_file(name) {
        return Ok(());
    }
    crate::store::check_design_name(name).map_err(|e| e.renamed("save"))
}

/// Saves `design` as `name` (refusing to replace one), with a one-line description: as the
/// design file `name` when it names a file ([`crate::store::names_a_file`]), else as a saved
/// design in the data directory. Either loads with `--design`.
fn save(
    name: &str,
    design: Design,
    description: String,
    uncertainty: std::collections::BTreeMap<String, f64>,
) -> Result<String, CliError> {
    let file = crate::store::DesignFile { description, ensemble: None, uncertainty, design };
    if crate::store::names_a_file(name) {
        let path = Path::new(name);
        let text = file.to_toml().map_err(|e| e.renamed("save"))?;
        return match fsio::write(path, text.as_bytes(), fsio::Overwrite::Refuse) {
            Ok(()) => Ok(fsio::shown(path)),
            Err(e @ fsio::FsError::Io { .. }) => Err(CliError::Io(format!("cannot save the design: {e}"))),
            Err(e) => Err(ThudError::invalid("save", format!("{e}; choose another file")).into()),
        };
    }
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

/// `±` a standard error, with 2 significant digits (in powers of ten when far below 1).
fn pm(v: f64, se: f64) -> String {
    if se != 0.0 && se.abs() < 1e-4 {
        format!("{} ± {se:.1e}", sig(v, 5))
    } else {
        format!("{} ± {}", sig(v, 5), sig(se, 2))
    }
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
    flags: &DesignArgs<impl super::design_args::ForceFlag, impl Rows>,
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
    // The main mass may be typed with its uncertainty (`0.5kg±2%`): K and C carry it on.
    let (value, u) = units::split_uncertainty(&a.main_mass);
    let m = quantity("main-mass", &Some(value.to_string()), Kind::Mass, &limits::MAIN_MASS)?.unwrap_or(1.0);
    let m_rel = if u.is_some() { units::parse_uncertain("main-mass", &a.main_mass, Kind::Mass)?.1 / m } else { 0.0 };
    if let Some(name) = &a.save {
        check_save(name)?;
    }
    let path = Path::new(&a.data);
    let (series, f) = structure_fit(ctx, path, m)?;
    let saved = match (&a.save, f.converged) {
        (Some(name), true) => {
            let d = structure_design(&series, &f)?;
            let description = format!(
                "fitted structure from {} (the structure alone: the gap is set wide so the ball is never hit; give your damper's --mass, --gap and --c1)",
                fsio::shown(path)
            );
            // What the fit knows of its values, for `fit damper --design` (relative standard
            // uncertainties: K = M·ω_n² and C = 2·M·σ carry M's and their own).
            let rel = |se: f64, v: f64| if v == 0.0 { 0.0 } else { (se / v).abs() };
            let mut unc = std::collections::BTreeMap::new();
            for (name, u) in [
                ("main-mass", m_rel),
                ("k", m_rel.hypot(rel(f.k_n_m_stderr, f.k_n_m))),
                ("c", m_rel.hypot(rel(f.c_n_s_m_stderr, f.c_n_s_m))),
            ] {
                if u > 0.0 && u.is_finite() {
                    unc.insert(name.to_string(), u);
                }
            }
            Some(save(name, d, description, unc)?)
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

/// The design of a fitted structure as the record shows it: the default design with the
/// fitted M, K and C, struck at the record's start velocity for the record's span, with a
/// clearance wide enough (4 swings of the main mass, at least the default's) that the ball is
/// never hit, so that `thud simulate --design` replays the record; a damper's flags
/// (`--mass`, `--gap`, `--c1`) override it.
fn structure_design(series: &Series, f: &StructureFit) -> Result<Design, ThudError> {
    let mut d = Design::default();
    d.damper.main_mass_kg = f.main_mass_kg;
    d.damper.stiffness_n_m = f.k_n_m;
    d.damper.damping_n_s_m = f.c_n_s_m;
    let v0 = fit::structure::start_velocity_m_s(&f.model, series.quantity());
    if limits::V0.check(v0).is_ok() {
        d.damper.v0_m_s = v0;
        let swing = v0.abs() / f.model.omega_d_rad_s;
        d.damper.gap_m = (4.0 * swing).max(d.damper.gap_m).min(limits::GAP.max);
    }
    if limits::DURATION.check(series.span_s()).is_ok() {
        d.damper.duration_s = series.span_s();
    }
    Ok(d.check().map_err(|e| e.renamed("save"))?.into_design())
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

/// The structure values `fit damper` takes with an uncertainty (`--main-mass 0.5kg±2%`), and
/// their kinds.
const UNCERTAIN: [(&str, Kind); 6] = [
    ("main-mass", Kind::Mass),
    ("k", Kind::Stiffness),
    ("c", Kind::Damping),
    ("mass", Kind::Mass),
    ("gap", Kind::Length),
    ("v0", Kind::Speed),
];

fn damper(a: &DamperArgs, ctx: &Ctx, out: &mut Out) -> Result<(), CliError> {
    // A value typed with `±` (or `+-`) gives the design its value and the fit its relative
    // standard uncertainty.
    let mut flags = a.design.clone();
    let mut given = Vec::new();
    for (name, kind) in UNCERTAIN {
        if let Some(whole) = flags.take_uncertainty(name) {
            let (value, sd) = units::parse_uncertain(name, &whole, kind)?;
            if let (Some(input), true) = (fit::damper::Input::from_name(name), value != 0.0) {
                given.push((input, sd / value.abs()));
            }
        }
    }
    for (name, u) in flags.file_uncertainty() {
        if let Some(input) = fit::damper::Input::from_name(&name).filter(|_| u.is_finite() && u > 0.0) {
            given.push((input, u));
        }
    }
    let d = flags.design()?;
    if let Some(name) = &a.save {
        check_save(name)?;
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
    let f = fit::damper::fit_with_inputs(&d, &records, &given, None)
        .map_err(|e| if e.param() == fit::DATA_PARAM { data_error(first, e.detail()) } else { e })?
        .ok_or(ThudError::Cancelled)?;
    spinner.finish_and_clear();
    if let (Some(v), Some(sd)) = (f.v0_m_s_record, f.v0_m_s_record_stderr) {
        let stated = given.iter().rev().find(|(i, _)| *i == fit::damper::Input::V0).map_or(0.0, |(_, u)| *u);
        let strike = fit::strike::Strike { v0_m_s: v, stderr_m_s: sd };
        if fit::strike::disagreement(d.damper.v0_m_s, stated, &strike).is_some() {
            super::warn(&format!(
                "the record's strike was {} ± {} m/s, not the design's v0 {} m/s: the difference is carried into c1's interval (give --v0 the record's value, or its uncertainty with ±)",
                sig(v, 4),
                sig(sd, 2),
                sig(d.damper.v0_m_s, 4)
            ));
        }
    }
    let saved = match &a.save {
        Some(name) => {
            let mut dd = d.design().clone();
            dd.damper.c1_n_s_m = f.c1_n_s_m;
            let dd = dd.check().map_err(|e| e.renamed("save"))?.into_design();
            Some(save(
                name,
                dd,
                format!("fitted c1 from {}", fsio::shown(first)),
                std::collections::BTreeMap::default(),
            )?)
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
    if let (Some(v), Some(sd)) = (f.v0_m_s_record, f.v0_m_s_record_stderr) {
        s += &format!("  v0 of the record's strike {} m/s\n", pm(v, sd));
    }
    for i in &f.inputs {
        s += &format!(
            "  {:<12} ± {} % moves c1 by {} %: in the interval\n",
            i.input.name(),
            sig(100.0 * i.relative_sd, 2),
            sig(100.0 * i.ln_c1_shift.exp_m1(), 2)
        );
    }
    s += &format!("  envelope residual rms {} m\n", sig(f.residual_rms, 3));
    if let Some(note) = &f.note {
        s += &format!("  note: {note}\n");
    }
    if let Some(p) = saved {
        s += &format!("Saved as {p}\n");
    }
    s
}
