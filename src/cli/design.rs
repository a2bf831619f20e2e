// Over 800 lines: the command's flags, checks, one-set writes of the front and its files, and its text.
//! `thud design`: the best dampers within the user's limits, as a Pareto front. The search is
//! the engine's ([`crate::design::search`]); each design is run as `thud simulate` runs it, so
//! every front design saved with `--save DIR` and run again gives exactly its printed
//! objectives.

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use clap::Args;
use serde::Serialize;

use super::design_args::{DesignArgs, ForceAmplitude};
use super::format::num;
use super::simulate::describe;
use super::sweep::Target;
use super::{count, CliError, Ctx, Out, OutputArgs, OutputFormat};
use crate::design::search::{
    self, Bound, Candidate, Column, Constraint, Objective, Outcome, Problem, Progress, Robust, Sense, Settings, Value,
    Variable,
};
use crate::design::Design;
use crate::error::ThudError;
use crate::fsio;
use crate::limits;
use crate::units::Kind;

#[derive(Debug, Clone, Args)]
pub struct DesignSearchArgs {
    #[command(flatten)]
    design: DesignArgs<ForceAmplitude>,
    /// A variable of the search, NAME=FROM:TO:N over any numeric parameter in its units (e.g.
    /// mass=20g:120g, gap=1cm:6cm, c1=10:60); N is unused (the search picks the values) and
    /// may be left out; repeatable.
    #[arg(long, value_name = "NAME=FROM:TO:N", allow_hyphen_values = true)]
    vary: Vec<String>,
    /// A discrete variable, NAME=A,B,C: the ball's material (sphere=steel,acrylic,nylon), the
    /// enclosure's (plate=…) or a choice of the design (source=…); repeatable.
    #[arg(long, value_name = "NAME=A,B,C")]
    choose: Vec<String>,
    /// A result column to make as small as possible (spl_max_db, u0_max_m_s,
    /// steady_amplitude_m, steady_leq_db, …); repeatable.
    #[arg(long, value_name = "COLUMN")]
    minimize: Vec<String>,
    /// A result column to make as large as possible (inclination_cm_s, steady_reduction_db,
    /// …); repeatable.
    #[arg(long, value_name = "COLUMN")]
    maximize: Vec<String>,
    /// A limit every reported design meets, COLUMN<=VALUE or COLUMN>=VALUE, on a result column
    /// (a plain number in its unit: spl_max_db<=100) or a parameter (its units: mass<=60g);
    /// repeatable.
    #[arg(long, value_name = "COLUMN<=VALUE", allow_hyphen_values = true)]
    require: Vec<String>,
    /// A band of forcing frequencies, freqs=FROM:TO:N: each design runs at every one and each
    /// result is taken at its worst over the band (a forced design).
    #[arg(long, value_name = "freqs=FROM:TO:N", allow_hyphen_values = true)]
    over: Option<String>,
    /// Robust mode: each design runs N times, from ball offsets spread evenly over the
    /// clearance (y0 = −d/2 + (k + ½)·d/N, at rest), and each result is taken at --quantile
    /// over the runs (1: the single trajectory).
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    ensemble: Option<String>,
    /// With --ensemble: the share Q of the ball offsets that do at least as well as each
    /// reported result (the Q-quantile of a column minimised or bounded above, the
    /// (1 − Q)-quantile of one maximised or bounded below, by nearest rank) [default: 0.5]
    #[arg(long, value_name = "Q", allow_hyphen_values = true)]
    quantile: Option<String>,
    /// Designs the search evaluates at most (its budget).
    #[arg(long, value_name = "N", default_value = "400", allow_hyphen_values = true)]
    evaluations: String,
    /// The seed of the search: the same seed gives the same front whatever the thread count.
    #[arg(long, value_name = "N", default_value = "0", allow_hyphen_values = true)]
    seed: String,
    /// The reference point of the hypervolume with two objectives, V1,V2 in the columns' units
    /// (e.g. 106,0) [default: the worst of each objective among the first designs].
    #[arg(long, value_name = "V1,V2", allow_hyphen_values = true)]
    reference: Option<String>,
    /// Save each front design as a design file named design-K.toml in the folder DIR (written
    /// whole or not at all); `--design DIR/design-K.toml` loads one in every command.
    #[arg(long, value_name = "DIR")]
    save: Option<PathBuf>,
    /// Write to this file instead of standard output (`-`: standard output); an existing file is
    /// kept unless --force. Written whole or not at all.
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// Also write the figure as SVG to this file.
    #[arg(long, value_name = "FILE")]
    svg: Option<PathBuf>,
    /// Also write the figure as PDF to this file.
    #[arg(long, value_name = "FILE")]
    pdf: Option<PathBuf>,
    /// Replace the --out, --svg or --pdf file (or the --save folder's previous designs) if it
    /// exists.
    #[arg(long)]
    force: bool,
    #[command(flatten)]
    output: OutputArgs,
}

/// The problem the flags describe, every part checked (the error names what was typed).
fn problem(a: &DesignSearchArgs) -> Result<Problem, ThudError> {
    let base = a.design.design()?;
    let mut variables: Vec<Variable> = a.vary.iter().map(|t| Variable::parse_range(t)).collect::<Result<_, _>>()?;
    for t in &a.choose {
        variables.push(Variable::parse_choice(t)?);
    }
    let mut objectives: Vec<Objective> =
        a.minimize.iter().map(|t| Objective::parse(t, Sense::Minimize)).collect::<Result<_, _>>()?;
    for t in &a.maximize {
        objectives.push(Objective::parse(t, Sense::Maximize)?);
    }
    let constraints = a.require.iter().map(|t| Constraint::parse(t)).collect::<Result<Vec<_>, _>>()?;
    let band_hz = match &a.over {
        None => Vec::new(),
        Some(t) => {
            let spec = t.strip_prefix("freqs=").ok_or_else(|| {
                ThudError::invalid("--over", format!("'{t}'; expected freqs=FROM:TO:N, e.g. freqs=4.5Hz:5.5Hz:21"))
            })?;
            super::design_args::parse_range("over", spec, Kind::Frequency, &limits::FREQ)?
        }
    };
    let robust = robust(a)?;
    let p = Problem { base, variables, objectives, constraints, band_hz, robust };
    p.check()?;
    Ok(p)
}

/// `--ensemble N --quantile Q`: robust mode, or None without `--ensemble`.
fn robust(a: &DesignSearchArgs) -> Result<Option<Robust>, ThudError> {
    let quantile = a
        .quantile
        .as_deref()
        .map(|t| {
            t.trim().parse::<f64>().ok().filter(|q| *q > 0.0 && *q <= 1.0).ok_or_else(|| {
                ThudError::invalid("--quantile", format!("'{t}' is not a fraction above 0 and at most 1 (e.g. 0.9)"))
            })
        })
        .transpose()?;
    let Some(text) = &a.ensemble else {
        if let Some(t) = &a.quantile {
            return Err(ThudError::invalid(
                "--quantile",
                format!("{t}: a quantile over ball offsets needs --ensemble N"),
            ));
        }
        return Ok(None);
    };
    let runs = count("ensemble", text, &limits::ENSEMBLE)?;
    if a.design.has("ball-position") {
        return Err(ThudError::invalid(
            "--ball-position",
            format!("cannot be combined with --ensemble {text}: the ensemble sets the ball's initial offsets"),
        ));
    }
    Robust::new(runs, quantile.unwrap_or(0.5)).map(Some)
}

/// `--reference V1,V2`.
fn reference(text: &str, objectives: usize) -> Result<Vec<f64>, ThudError> {
    let bad = |why: &str| ThudError::invalid("--reference", format!("'{text}': {why}"));
    let v: Vec<f64> = text
        .split(',')
        .map(|t| t.trim().parse::<f64>().ok().filter(|v| v.is_finite()))
        .collect::<Option<_>>()
        .ok_or_else(|| bad("expected two numbers V1,V2, e.g. 106,0"))?;
    if v.len() != 2 {
        return Err(bad("expected two numbers V1,V2, e.g. 106,0"));
    }
    if v.iter().any(|x| x.abs() > search::REFERENCE_MAX) {
        return Err(bad(&format!("each value must be within ±{:e}", search::REFERENCE_MAX)));
    }
    if objectives != 2 {
        return Err(bad("a hypervolume is computed with two objectives only"));
    }
    Ok(v)
}

pub fn run(a: &DesignSearchArgs, ctx: &Ctx, out: &mut Out) -> Result<(), CliError> {
    let p = problem(a)?;
    let evaluations = count("evaluations", &a.evaluations, &limits::EVALUATIONS)?;
    let seed: u64 = a.seed.trim().parse().map_err(|_| {
        ThudError::invalid("--seed", format!("'{}' is not a whole number from 0 to {}", a.seed, u64::MAX))
    })?;
    let reference = a.reference.as_deref().map(|t| reference(t, p.objectives.len())).transpose()?;
    let target = Target::new(a.out.as_deref(), a.force)?;
    check_figure(a, &p)?;
    if let Some(dir) = &a.save {
        check_save(
            dir,
            a.force,
            &[("--out", a.out.as_deref()), ("--svg", a.svg.as_deref()), ("--pdf", a.pdf.as_deref())],
        )?;
    }
    let r = search::check_work(&p, evaluations, &|n| a.design.has(n));
    a.design.refuse_work(ctx, &p.base, r, ("--evaluations", &a.evaluations))?;
    let format = a.output.format();
    // What a stop writes: the front so far, marked partial, kept up to date after each batch.
    let latest: Arc<Mutex<Option<String>>> = Arc::new(Mutex::new(None));
    let stop = on_stop(latest.clone(), a.out.clone().filter(|p| !fsio::is_stdout(p)), a.force);
    let progress = Progress_::new();
    let settings = Settings { evaluations, seed };
    let on_batch = |pr: Progress, all: &[Candidate], front: &[usize]| {
        progress.show(pr);
        let partial = Outcome {
            all: all.to_vec(),
            front: front.to_vec(),
            partial: true,
            reference: None,
            hypervolume: pr.hypervolume,
        };
        if let Ok(text) = render(&p, &partial, settings, format, None) {
            *latest.lock().unwrap_or_else(std::sync::PoisonError::into_inner) = Some(text);
        }
    };
    let started = std::time::Instant::now();
    let outcome = search::search(&p, settings, reference.as_deref(), None, &on_batch)?;
    // The search is over: from here a stop leaves the outputs as the writes below leave them
    // (the old files, or the new set), never a partial front beside a complete --save folder.
    drop(stop);
    let search_s = started.elapsed().as_secs_f64();
    progress.done();
    let saved = match &a.save {
        Some(dir) => Some(stage_save(dir, &p, &outcome, a.force)?),
        None => None,
    };
    let text = render(&p, &outcome, settings, format, saved.as_ref().map(|(_, names)| names.as_slice()))?;
    let svg = (a.svg.is_some() || a.pdf.is_some()).then(|| {
        let zones = zone_chart(a, &p, evaluations, search_s / outcome.all.len().max(1) as f64);
        figure(&p, &outcome, zones)
    });
    write_all(a, &target, &text, svg.as_deref(), saved, out)
}

/// Cells a side of the zone chart behind the front: about the search's budget in all, 8 to 40.
fn chart_side(evaluations: usize) -> usize {
    ((evaluations as f64).sqrt().round() as usize).clamp(8, 40)
}

/// The zone chart behind the front in the variables' panel, for two numeric (not counted)
/// variables of a problem of single runs at the design's own frequency: the engine's study of
/// those two axes over their ranges ([`crate::study::sweep`], as `thud sweep --vary` runs it),
/// [`chart_side`] cells a side, its work checked as a study's. Its cost, estimated from the
/// search's own pace (`per_design_s`), is said before it runs; a refused chart is left out
/// with a line saying why.
fn zone_chart(
    a: &DesignSearchArgs,
    p: &Problem,
    evaluations: usize,
    per_design_s: f64,
) -> Option<crate::export::front::ZoneChart> {
    use crate::params::{Accepts, Spelling};
    use crate::study::{self, Grid, Vary};
    if !p.band_hz.is_empty() || p.robust.is_some() {
        return None;
    }
    let [Variable::Range { row: rx, lo: x0, hi: x1 }, Variable::Range { row: ry, lo: y0, hi: y1 }] = &p.variables[..]
    else {
        return None;
    };
    if [rx, ry].iter().any(|r| !matches!(r.accepts, Accepts::Quantity { .. })) {
        return None;
    }
    let n = chart_side(evaluations);
    let axis = |row, lo, hi| Vary { row, values: crate::design::linspace(lo, hi, n) };
    let grid = Grid::new(p.base.clone(), vec![axis(*rx, *x0, *x1), axis(*ry, *y0, *y1)], Spelling::Flag).ok()?;
    if let Err(r) = study::check_grid(&grid, &|name| a.design.has(name)) {
        super::warn(&format!("the zone chart behind the front is left out: {r}"));
        return None;
    }
    super::warn(&format!(
        "zone chart behind the front: {n} × {n} designs, about {} s",
        crate::units::sig(per_design_s * (n * n) as f64, 2)
    ));
    let s = match study::sweep(&grid, None, &|_, _| {}) {
        Ok(s) => s,
        Err(e) => {
            super::warn(&format!("the zone chart behind the front is left out: {e}"));
            return None;
        }
    };
    let mut zones = vec![None; n * n];
    for c in &s.cells {
        // The study's C order: the second axis fastest.
        let ij = grid.indices(c.index);
        zones[ij[1] * n + ij[0]] = c.metrics.zone;
    }
    Some(crate::export::front::ZoneChart {
        xs: grid.axes[0].values.clone(),
        ys: grid.axes[1].values.clone(),
        zones,
        thresholds: p.base.thresholds,
    })
}

/// Refuses `--svg`/`--pdf` up front where no figure can be drawn (not two objectives), a file
/// there without `--force`, or two outputs naming one file.
fn check_figure(a: &DesignSearchArgs, p: &Problem) -> Result<(), ThudError> {
    let outputs = [("--out", a.out.as_deref()), ("--svg", a.svg.as_deref()), ("--pdf", a.pdf.as_deref())];
    for (flag, path) in &outputs[1..] {
        let Some(path) = path else { continue };
        if p.objectives.len() != 2 {
            return Err(ThudError::invalid(
                *flag,
                format!(
                    "{}: the front is drawn for two objectives; give two of --minimize/--maximize",
                    fsio::shown(path)
                ),
            ));
        }
        if fsio::is_stdout(path) {
            return Err(ThudError::invalid(*flag, "'-': the figure goes to a file; give a file name"));
        }
        Target::new(Some(path), a.force).map_err(|e| e.renamed(*flag))?;
    }
    for (i, (flag, path)) in outputs.iter().enumerate() {
        let Some(path) = path else { continue };
        if let Some((other, _)) =
            outputs[..i].iter().find(|(_, q)| q.is_some_and(|q| super::figure_out::same_output(q, path)))
        {
            return Err(ThudError::invalid(
                *flag,
                format!("'{}' is the {other} file too; give each output a file of its own", fsio::shown(path)),
            ));
        }
    }
    Ok(())
}

/// The figure of the search: the front among every feasible design evaluated, in the
/// objectives (as the columns read), and in the variables when there are two numeric ones
/// (over `zones`, the zone chart of those two variables, when computed).
fn figure(p: &Problem, o: &Outcome, zones: Option<crate::export::front::ZoneChart>) -> String {
    use crate::export::front::{front_svg, FrontFigure, Panel};
    let feasible: Vec<&Candidate> = o.all.iter().filter(|c| c.feasible()).collect();
    let front: Vec<&Candidate> = o.front.iter().map(|&i| &o.all[i]).collect();
    let pair = |c: &Candidate| -> Option<(f64, f64)> { Some((c.objectives[0]?, c.objectives[1]?)) };
    let label = |ob: &Objective| {
        format!("{} ({})", ob.column.name(), if ob.sense == Sense::Minimize { "minimised" } else { "maximised" })
    };
    let objectives = Panel {
        x_label: label(&p.objectives[0]),
        y_label: label(&p.objectives[1]),
        evaluated: feasible.iter().filter_map(|c| pair(c)).collect(),
        front: front.iter().filter_map(|c| pair(c)).collect(),
    };
    let numbers = |c: &Candidate| -> Option<(f64, f64)> {
        match (&c.values[0], &c.values[1]) {
            (Value::Number(x), Value::Number(y)) => Some((*x, *y)),
            _ => None,
        }
    };
    let two_numbers = p.variables.len() == 2 && p.variables.iter().all(|v| matches!(v, Variable::Range { .. }));
    let variables = two_numbers.then(|| Panel {
        x_label: p.variables[0].column(),
        y_label: p.variables[1].column(),
        evaluated: feasible.iter().filter_map(|c| numbers(c)).collect(),
        front: front.iter().filter_map(|c| numbers(c)).collect(),
    });
    let title = format!(
        "Pareto front: {} designs of {} evaluated{}",
        front.len(),
        o.all.len(),
        if o.partial { " (partial)" } else { "" }
    );
    // SPLmax against e: the design's thresholds are the zones' borders.
    let t = &p.base.thresholds;
    let zone_borders = match (p.objectives[0].column, p.objectives[1].column) {
        (Column::SplMax, Column::Inclination) => Some((t.spl_db, t.inclination_cm_s)),
        (Column::Inclination, Column::SplMax) => Some((t.inclination_cm_s, t.spl_db)),
        _ => None,
    };
    front_svg(&FrontFigure { title, objectives, variables, zone_borders, zones }, &crate::export::svg::Look::default())
}

/// Writes the result as one set: the `--save` folder (staged), the report (to `--out` or
/// standard output) and the figure `svg` to `--svg`/`--pdf`; all in place, or (a failure, a
/// signal) none, the old files and folder left as they were.
fn write_all(
    a: &DesignSearchArgs,
    target: &Target,
    text: &str,
    svg: Option<&str>,
    saved: Option<(fsio::StagedFolder, Vec<String>)>,
    out: &mut Out,
) -> Result<(), CliError> {
    super::output::check_text(text)?;
    let pdf = match (&a.pdf, svg) {
        (Some(_), Some(svg)) => Some(
            crate::export::pdf::from_svg(svg)
                .map_err(|e| ThudError::invalid("--pdf", format!("cannot draw the PDF: {e}")))?,
        ),
        _ => None,
    };
    let mut files: Vec<(&Path, &[u8])> = Vec::new();
    if let (Some(p), Some(svg)) = (&a.svg, svg) {
        files.push((p, svg.as_bytes()));
    }
    if let (Some(p), Some(pdf)) = (&a.pdf, &pdf) {
        files.push((p, pdf));
    }
    if let Some(p) = target.file() {
        files.push((p, text.as_bytes()));
    }
    let (folder, designs) = saved.map_or((None, None), |(f, names)| (Some(f), Some(names.len())));
    if let Err(e) = fsio::write_set_with_folder(&files, folder, fsio::Overwrite::from_force(a.force)) {
        let p = e.path().to_path_buf();
        let flag = [("--svg", &a.svg), ("--pdf", &a.pdf), ("--save", &a.save)]
            .into_iter()
            .find(|(_, f)| f.as_deref() == Some(p.as_path()))
            .map_or("--out", |(flag, _)| flag);
        return Err(super::export::write_error_as(flag, &p, &e));
    }
    if let (Some(dir), Some(n)) = (&a.save, designs) {
        super::warn(&format!("saved {n} front designs in {}", fsio::shown(dir)));
    }
    for (p, _) in &files {
        super::warn(&format!("wrote {}", fsio::shown(p)));
    }
    match target.file() {
        Some(_) => Ok(()),
        None => target.write(text, out),
    }
}

/// The progress line on stderr (a terminal only): evaluations, front size, hypervolume.
struct Progress_ {
    shown: bool,
}

impl Progress_ {
    fn new() -> Self {
        use std::io::IsTerminal;
        Progress_ { shown: std::io::stderr().is_terminal() }
    }

    fn show(&self, p: Progress) {
        if self.shown {
            use std::io::Write;
            let hv = p.hypervolume.map_or(String::new(), |h| format!(", hypervolume {}", num(h)));
            let _ = write!(std::io::stderr(), "\rdesign: {} evaluations, front {}{hv}   ", p.evaluations, p.front);
        }
    }

    fn done(&self) {
        if self.shown {
            use std::io::Write;
            let _ = writeln!(std::io::stderr());
        }
    }
}

/// On a stop signal (Ctrl-C), writes the front found so far (marked partial) to the output
/// before the process ends: to standard output, or to the `--out` file as every write is made
/// ([`fsio::write_from_cleanup`]). The `--save` folder is not written.
fn on_stop(latest: Arc<Mutex<Option<String>>>, out: Option<PathBuf>, force: bool) -> crate::signals::Registration {
    crate::signals::on_signal(move || {
        let Some(text) = latest.lock().unwrap_or_else(std::sync::PoisonError::into_inner).clone() else { return };
        match &out {
            None => {
                let _ = fsio::write_stdout(text.as_bytes());
            }
            Some(path) => {
                // As the run's own write would: a stream written through, a planted link or
                // anything new at the path (without --force) left alone.
                if let Err(e) = fsio::write_from_cleanup(path, text.as_bytes(), fsio::Overwrite::from_force(force)) {
                    super::warn(&format!("stopped: the front so far was not written: {e}"));
                    return;
                }
            }
        }
        super::warn("stopped: wrote the front found so far, marked partial");
    })
    .0
}

/// Refuses `--save DIR` before the search: DIR a symbolic link, not a folder, read-only or in
/// a folder that cannot be written; holding anything without `--force`, or (with it) anything
/// but a previous front's design files; or one of `outputs` (flag, file) naming DIR or a file
/// inside it.
fn check_save(dir: &Path, force: bool, outputs: &[(&str, Option<&Path>)]) -> Result<(), ThudError> {
    let bad = |why: String| ThudError::invalid("--save", format!("{} {why}", fsio::shown(dir)));
    let writable = |p: &Path, m: &std::fs::Metadata| {
        use rustix::fs::{access, Access};
        !m.permissions().readonly() && access(p, Access::WRITE_OK | Access::EXEC_OK).is_ok()
    };
    for (flag, path) in outputs {
        let Some(path) = path.filter(|p| !fsio::is_stdout(p)) else { continue };
        let inside = match (std::path::absolute(dir), std::path::absolute(path)) {
            (Ok(d), Ok(f)) => f.starts_with(d),
            _ => false,
        };
        if inside || super::figure_out::same_output(dir, path) {
            return Err(bad(format!("is the folder of the {flag} file {} too; write it elsewhere", fsio::shown(path))));
        }
    }
    // DIR is put in place by renaming a folder onto it, which no path ending in `.` or `..`
    // can take.
    let mut typed = dir.as_os_str().as_encoded_bytes();
    while let Some(t) = typed.strip_suffix(b"/") {
        typed = t;
    }
    let last = typed.rsplit(|&b| b == b'/').next().unwrap_or_default();
    if last == b"." || last == b".." {
        return Err(bad("ends in . or ..; name the folder itself".into()));
    }
    match std::fs::symlink_metadata(dir) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
        Err(e) => return Err(bad(format!("cannot be read: {e}"))),
        Ok(m) if m.file_type().is_symlink() => {
            return Err(bad("is a symbolic link; thud neither follows nor replaces one: name the folder itself".into()))
        }
        Ok(m) if !m.is_dir() => return Err(bad("is not a folder".into())),
        Ok(m) if !writable(dir, &m) => return Err(bad("is read-only; give a folder thud may write".into())),
        Ok(_) => {
            let entries = std::fs::read_dir(dir).map_err(|e| bad(format!("cannot be read: {e}")))?;
            for entry in entries {
                let entry = entry.map_err(|e| bad(format!("cannot be read: {e}")))?;
                if !force {
                    return Err(bad(
                        "is not empty; give a new or empty folder, or --force to replace its designs".into()
                    ));
                }
                if !is_previous_design(&entry) {
                    return Err(bad(format!(
                        "holds {} that thud design does not write; give a new or empty folder (or, with --force, one holding only a previous front)",
                        fsio::shown(Path::new(&entry.file_name()))
                    )));
                }
            }
        }
    }
    // The folder is written beside DIR, then renamed into place: the nearest folder there is
    // must be writable.
    let parent = dir.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    if let Some((above, m)) = parent.ancestors().find_map(|d| std::fs::metadata(d).ok().map(|m| (d, m))) {
        if !m.is_dir() || !writable(above, &m) {
            return Err(bad(format!("cannot be written: {} is not a folder thud may write", fsio::shown(above))));
        }
    }
    Ok(())
}

/// Whether `entry` is a design file of a previous front: a regular file `design-K.toml`.
fn is_previous_design(entry: &std::fs::DirEntry) -> bool {
    let name = entry.file_name();
    let name = name.to_string_lossy();
    let k = name.strip_prefix("design-").and_then(|n| n.strip_suffix(".toml"));
    k.is_some_and(|k| !k.is_empty() && k.bytes().all(|b| b.is_ascii_digit()))
        && entry.file_type().is_ok_and(|t| t.is_file())
}

/// The file name of front design `k` (from 1).
fn file_name(k: usize, n: usize) -> String {
    let width = n.to_string().len().max(2);
    format!("design-{k:0width$}.toml")
}

/// Writes each front design as a design file into a folder staged beside `dir`, put in place
/// with the other outputs by [`write_all`] (with `force`, over the previous front's design
/// files); returns it with the names in front order.
fn stage_save(
    dir: &Path,
    p: &Problem,
    o: &Outcome,
    force: bool,
) -> Result<(fsio::StagedFolder, Vec<String>), CliError> {
    let mut files: Vec<(String, String)> = Vec::with_capacity(o.front.len());
    for (k, &i) in o.front.iter().enumerate() {
        let c = &o.all[i];
        let d = p.design_at(&c.values)?.into_design();
        let what: Vec<String> = p
            .objectives
            .iter()
            .zip(&c.objectives)
            .map(|(ob, v)| format!("{} {}", ob.column.name(), v.map_or("—".into(), num)))
            .collect();
        let file = crate::store::DesignFile {
            description: format!("thud design: front design {} of {}: {}", k + 1, o.front.len(), what.join(", ")),
            ensemble: p.robust.map(|r| r.runs),
            uncertainty: std::collections::BTreeMap::new(),
            design: d,
        };
        files.push((file_name(k + 1, o.front.len()), file.to_toml().map_err(|e| e.renamed("save"))?));
    }
    let refs: Vec<(&str, &[u8])> = files.iter().map(|(n, t)| (n.as_str(), t.as_bytes())).collect();
    let previous: Vec<String> = std::fs::read_dir(dir)
        .map(|d| d.flatten().filter(is_previous_design).map(|e| e.file_name().to_string_lossy().into_owned()).collect())
        .unwrap_or_default();
    let staged = fsio::StagedFolder::new(dir, &refs, force, &previous)
        .map_err(|e| super::export::write_error_as("--save", dir, &e))?;
    Ok((staged, files.into_iter().map(|(n, _)| n).collect()))
}

/// One front design as `--json` writes it.
#[derive(Serialize)]
struct FrontJson<'a> {
    index: usize,
    /// Each variable by its column (`mass_kg`, `sphere`).
    variables: serde_json::Map<String, serde_json::Value>,
    /// Each objective by its column.
    objectives: serde_json::Map<String, serde_json::Value>,
    /// Each constraint's margin (≥ 0: met), by the constraint as typed.
    margins: serde_json::Map<String, serde_json::Value>,
    #[serde(skip_serializing_if = "Option::is_none")]
    file: Option<&'a str>,
}

#[derive(Serialize)]
struct ReportJson<'a> {
    design: &'a Design,
    variables: Vec<serde_json::Value>,
    objectives: Vec<serde_json::Value>,
    constraints: Vec<&'a str>,
    #[serde(skip_serializing_if = "<[f64]>::is_empty")]
    band_hz: &'a [f64],
    /// Robust mode: the ball offsets (runs) and the quantile each result is taken at.
    #[serde(skip_serializing_if = "Option::is_none")]
    ensemble: Option<Robust>,
    evaluations: usize,
    budget: usize,
    seed: u64,
    partial: bool,
    reference: Option<&'a [f64]>,
    hypervolume: Option<f64>,
    front: Vec<FrontJson<'a>>,
    /// When no design is feasible: the constraint that binds and its best margin.
    #[serde(skip_serializing_if = "Option::is_none")]
    binding: Option<serde_json::Value>,
}

fn value_json(v: &Value) -> serde_json::Value {
    match v {
        Value::Number(x) => serde_json::json!(x),
        Value::Choice(s) => serde_json::json!(s),
    }
}

/// The constraint's margin column in the CSV: `margin_mass_le`, `margin_spl_max_db_ge`.
fn margin_column(c: &Constraint) -> String {
    let name = match &c.bound {
        Bound::Result(col) => col.name().to_string(),
        Bound::Param(row) => row.name.replace('-', "_"),
    };
    format!("margin_{name}_{}", if c.at_most { "le" } else { "ge" })
}

/// The sentence for an infeasible problem: which constraint binds.
fn binding_line(p: &Problem, o: &Outcome) -> Option<String> {
    if !o.front.is_empty() {
        return None;
    }
    let ran = o.all.iter().filter(|c| c.error.is_none()).count();
    if ran == 0 {
        let why = o.all.first().and_then(|c| c.error.clone()).unwrap_or_default();
        return Some(format!("no design of the search could be run ({why})"));
    }
    match p.binding(&o.all) {
        Some((k, best)) => Some(format!(
            "no design meets every constraint: {} binds (the best of {ran} designs misses it by {})",
            p.constraints[k].text,
            num(-best)
        )),
        None => Some(format!("no design of {ran} has every objective defined (no impact?)")),
    }
}

/// The front as `format` prints it (checked finite).
// Over 80 lines: one match over the three formats, each a plain table.
#[allow(clippy::too_many_lines)] // one match over the three formats, each a plain table
fn render(
    p: &Problem,
    o: &Outcome,
    settings: Settings,
    format: OutputFormat,
    files: Option<&[String]>,
) -> Result<String, CliError> {
    let front: Vec<&Candidate> = o.front.iter().map(|&i| &o.all[i]).collect();
    let binding = binding_line(p, o);
    Ok(match format {
        OutputFormat::Json => {
            let rows = front
                .iter()
                .enumerate()
                .map(|(k, c)| FrontJson {
                    index: c.index,
                    variables: p.variables.iter().zip(&c.values).map(|(v, x)| (v.column(), value_json(x))).collect(),
                    objectives: p
                        .objectives
                        .iter()
                        .zip(&c.objectives)
                        .map(|(ob, v)| (ob.column.name().to_string(), serde_json::json!(v)))
                        .collect(),
                    margins: p
                        .constraints
                        .iter()
                        .zip(&c.margins)
                        .map(|(k, m)| (k.text.clone(), serde_json::json!(m)))
                        .collect(),
                    file: files.and_then(|f| f.get(k)).map(String::as_str),
                })
                .collect();
            let report = ReportJson {
                design: p.base.design(),
                variables: p
                    .variables
                    .iter()
                    .map(|v| match v {
                        Variable::Range { row, lo, hi } => serde_json::json!({"name": row.name, "column": v.column(),
                            "unit": row.unit(), "from": lo, "to": hi}),
                        Variable::Choice { row, options } => {
                            serde_json::json!({"name": row.name, "column": v.column(), "options": options})
                        }
                    })
                    .collect(),
                objectives: p
                    .objectives
                    .iter()
                    .map(|o| serde_json::json!({"column": o.column.name(), "sense": o.sense}))
                    .collect(),
                constraints: p.constraints.iter().map(|c| c.text.as_str()).collect(),
                band_hz: &p.band_hz,
                ensemble: p.robust,
                evaluations: o.all.len(),
                budget: settings.evaluations,
                seed: settings.seed,
                partial: o.partial,
                reference: o.reference.as_deref(),
                hypervolume: o.hypervolume,
                front: rows,
                binding: binding.map(|b| serde_json::json!(b)),
            };
            super::output::check_finite(&report)?;
            let mut s = serde_json::to_string_pretty(&report).map_err(std::io::Error::from)?;
            s.push('\n');
            s
        }
        OutputFormat::Csv => {
            let mut header: Vec<String> = vec!["index".into()];
            header.extend(p.variables.iter().map(Variable::column));
            header.extend(p.objectives.iter().map(|o| o.column.name().to_string()));
            header.extend(p.constraints.iter().map(margin_column));
            if files.is_some() {
                header.push("file".into());
            }
            let mut w = csv::Writer::from_writer(Vec::new());
            let csv_error = |e: csv::Error| ThudError::invalid("csv", format!("cannot write: {e}"));
            w.write_record(&header).map_err(csv_error)?;
            for (k, c) in front.iter().enumerate() {
                let mut r = vec![c.index.to_string()];
                r.extend(c.values.iter().map(|v| match v {
                    Value::Number(x) => x.to_string(),
                    Value::Choice(s) => s.clone(),
                }));
                r.extend(c.objectives.iter().map(|v| v.map_or(String::new(), |x| x.to_string())));
                r.extend(c.margins.iter().map(|v| v.map_or(String::new(), |x| x.to_string())));
                if let Some(f) = files {
                    r.push(f.get(k).cloned().unwrap_or_default());
                }
                w.write_record(&r).map_err(csv_error)?;
            }
            let bytes = w.into_inner().map_err(|e| ThudError::invalid("csv", format!("cannot write: {e}")))?;
            let s = String::from_utf8(bytes).map_err(|e| ThudError::invalid("csv", format!("cannot write: {e}")))?;
            if let Some(b) = &binding {
                super::warn(b);
            }
            s
        }
        OutputFormat::Text => {
            let mut t = format!("base      {}\n", describe(p.base.design()));
            let vars: Vec<String> = p.variables.iter().map(|v| format!("{v:?}")).collect();
            t += &format!("vary      {}\n", vars.join(", "));
            let obs: Vec<String> = p
                .objectives
                .iter()
                .map(|o| format!("{} {}", if o.sense == Sense::Minimize { "min" } else { "max" }, o.column.name()))
                .collect();
            t += &format!("goals     {}\n", obs.join(", "));
            if !p.constraints.is_empty() {
                let cs: Vec<&str> = p.constraints.iter().map(|c| c.text.as_str()).collect();
                t += &format!("require   {}\n", cs.join(", "));
            }
            if let (Some(first), Some(last)) = (p.band_hz.first(), p.band_hz.last()) {
                t += &format!(
                    "over      {} Hz to {} Hz, {} frequencies: each result at its worst\n",
                    num(*first),
                    num(*last),
                    p.band_hz.len()
                );
            }
            if let Some(r) = &p.robust {
                t += &format!(
                    "robust    {} ball offsets: each result as {} % of them do at least as well\n",
                    r.runs,
                    num(100.0 * r.quantile)
                );
            }
            let hv = match (&o.hypervolume, &o.reference) {
                (Some(h), Some(r)) => format!(", hypervolume {} (reference {}, {})", num(*h), num(r[0]), num(r[1])),
                _ => String::new(),
            };
            t += &format!(
                "search    {} of {} evaluations, seed {}{}{hv}\n\n",
                o.all.len(),
                settings.evaluations,
                settings.seed,
                if o.partial { " — PARTIAL (stopped)" } else { "" }
            );
            if let Some(b) = &binding {
                t += &format!("{b}\n");
                return Ok(t);
            }
            t += &format!("front     {} designs\n", front.len());
            let mut head = format!("{:>6}", "#");
            for v in &p.variables {
                head += &format!("  {:>14}", v.column());
            }
            for ob in &p.objectives {
                head += &format!("  {:>18}", ob.column.name());
            }
            for c in &p.constraints {
                head += &format!("  {:>18}", margin_column(c));
            }
            if files.is_some() {
                head += "  file";
            }
            t += &head;
            t += "\n";
            for (k, c) in front.iter().enumerate() {
                let mut row = format!("{:>6}", c.index);
                for v in &c.values {
                    row += &format!(
                        "  {:>14}",
                        match v {
                            Value::Number(x) => num(*x),
                            Value::Choice(s) => s.clone(),
                        }
                    );
                }
                for v in &c.objectives {
                    row += &format!("  {:>18}", v.map_or("—".into(), num));
                }
                for m in &c.margins {
                    row += &format!("  {:>18}", m.map_or("—".into(), num));
                }
                if let Some(f) = files.and_then(|f| f.get(k)) {
                    row += &format!("  {f}");
                }
                t += &row;
                t += "\n";
            }
            t += "\n(--json or --csv for every digit; --save DIR writes each front design as a design file)\n";
            t
        }
    })
}
