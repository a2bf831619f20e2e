//! `thud bifurcation --vary NAME=FROM:TO:N`: the bifurcation diagram of a forced design over
//! any numeric parameter: per value, after `--transient` periods, the stroboscopic
//! samples x(kT), x'(kT) over `--periods` N and every impact (phase, wall, relative speed),
//! the orbit's type and the bands of equal types. Also the shared flags and writers of
//! `impact-map` and `basins`.

use std::path::PathBuf;

use clap::Args;

use super::budget;
use super::design_args::{DesignArgs, ForceAmplitude};
use super::format::num;
use super::simulate::describe;
use super::sweep::Target;
use super::{CliError, Ctx, Out, OutputArgs, OutputFormat};
use crate::continuation;
use crate::design::{Design, ValidDesign};
use crate::dynamics::{self, Bifurcation, Settings};
use crate::error::ThudError;
use crate::export::svg::Look;
use crate::limits::{self, short};
use crate::params::{Group, Spelling};
use crate::study::Vary;

/// The flags every study of orbits shares: the transient, the files, the output.
#[derive(Debug, Clone, Args)]
pub struct OrbitArgs {
    /// Forcing periods run before sampling (0 to 1e5) [default: 200]; --periods N sets how many
    /// are sampled [default here: 100].
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    transient: Option<String>,
    /// Also write the figure as SVG to this file.
    #[arg(long, value_name = "FILE")]
    svg: Option<PathBuf>,
    /// Also write the figure as PDF to this file.
    #[arg(long, value_name = "FILE")]
    pdf: Option<PathBuf>,
    /// Write the table (text, --json or --csv) to this file instead of standard output (`-`:
    /// standard output); an existing file is kept unless --force.
    #[arg(long, value_name = "FILE")]
    pub(super) out: Option<PathBuf>,
    /// Replace the --out, --svg or --pdf file if it exists.
    #[arg(long)]
    pub(super) force: bool,
    #[command(flatten)]
    ascii: super::AsciiArgs,
    #[command(flatten)]
    output: OutputArgs,
}

impl OrbitArgs {
    /// The run lengths: `--transient` and the design's `--periods` (if given; else 100).
    pub(super) fn settings(&self, design: &DesignArgs<ForceAmplitude>, d: &Design) -> Result<Settings, ThudError> {
        let transient = match &self.transient {
            Some(t) => limits::TRANSIENT.parse_count("--transient", t)?,
            None => dynamics::DEFAULT_TRANSIENT_PERIODS as usize,
        };
        let periods = if design.has("periods") { d.damper.steady_periods } else { dynamics::DEFAULT_PERIODS };
        Ok(Settings { transient_periods: u32::try_from(transient).unwrap_or(u32::MAX), periods })
    }

    /// Where the table and its figure go.
    fn outputs(&self) -> super::figure_out::FigureOutputs<'_> {
        super::figure_out::FigureOutputs::new(&self.out, &self.svg, &self.pdf, self.force, self.ascii)
    }

    /// Whether a figure is asked for (`--svg` or `--pdf`).
    pub(super) fn wants_figure(&self) -> bool {
        self.outputs().wants_figure()
    }

    /// Writes the table as `--json`, `--csv` or text, and the figure to `--svg` and `--pdf`,
    /// as one set ([`super::figure_out::FigureOutputs::write`]).
    pub(super) fn write(
        &self,
        table: impl FnOnce(OutputFormat) -> Result<String, CliError>,
        figure: impl Fn() -> String,
        out: &mut Out,
    ) -> Result<(), CliError> {
        let outputs = self.outputs();
        outputs.check()?;
        let text = table(self.output.format())?;
        outputs.write(&text, outputs.wants_figure().then(figure), out)
    }

    /// Checks the files up front (an existing one without --force is refused before the work).
    pub(super) fn check_targets(&self) -> Result<(), ThudError> {
        self.outputs().check()
    }
}

/// Refuses the flags of a simulation's length that a study of orbits does not use (it runs
/// `--transient` and `--periods` forcing periods): `--duration` and `--settle` would change
/// nothing. `what` names the study ("a bifurcation").
pub(super) fn refuse_run_flags(design: &DesignArgs<ForceAmplitude>, what: &str) -> Result<(), ThudError> {
    for flag in ["duration", "settle"] {
        if design.typed_row(flag) {
            return Err(ThudError::invalid(
                format!("--{flag}"),
                format!("{what} runs --transient and --periods forcing periods, not a simulated time; leave out --{flag} and give --transient N or --periods N"),
            ));
        }
    }
    Ok(())
}

/// Refuses a study of orbits over `runs` runs whose work is over its cap.
pub(super) fn check_work(
    ctx: &Ctx,
    runs: usize,
    s: Settings,
    continuation: bool,
    counted: (&str, &str),
) -> Result<(), CliError> {
    let Err(r) = dynamics::check_work(runs, s, continuation) else { return Ok(()) };
    let hint = if r.param == dynamics::PERIODS_PARAM {
        format!(
            "use fewer values, a shorter --transient or fewer --periods (at most {} periods in all)",
            short(r.estimate.cap.max)
        )
    } else {
        format!("use at most {} values", short(r.estimate.cap.max))
    };
    ctx.enforce(r.estimate, counted.0, counted.1, &hint)
}

/// An engine error about the solver named as its flag (`--solver`).
pub(super) fn flagged(e: ThudError) -> ThudError {
    if e.param() == "solver" {
        e.renamed("--solver")
    } else {
        e
    }
}

/// The figure's look: the default size, title drawn.
pub(super) fn look() -> Look {
    Look::default()
}

#[derive(Debug, Clone, Args)]
pub struct BifurcationArgs {
    #[command(flatten)]
    design: DesignArgs<ForceAmplitude>,
    /// The parameter to vary, NAME=FROM:TO:N: any numeric row (freq or f, force or F0, gap,
    /// mass, c1, …; e.g. f=3Hz:8Hz:200).
    #[arg(long, value_name = "NAME=FROM:TO:N", allow_hyphen_values = true, required = true)]
    vary: String,
    /// Start each value from the previous value's end state, rising then falling (shows
    /// hysteresis); without it every value starts from the design's own start.
    #[arg(long)]
    continuation: bool,
    /// Compute only part K of N of the values (K from 0, like SLURM_ARRAY_TASK_ID) and write it
    /// as JSON lines for `thud merge` (not with --continuation, whose values run in turn).
    #[arg(long, value_name = "K/N", allow_hyphen_values = true, conflicts_with = "continuation")]
    shard: Option<String>,
    /// Draw the periodic orbits' branches over the --svg/--pdf figure's x(kT) panel, stable
    /// solid, unstable dashed: every branch through the stable orbits found from the design's
    /// start at N evenly spaced values of the range, continued both ways (as `thud continue
    /// --vary NAME=FROM:TO:N`, which gives their numbers); N from 2 to 1000.
    #[arg(long, value_name = "N", allow_hyphen_values = true, conflicts_with = "shard")]
    branches: Option<String>,
    #[command(flatten)]
    orbit: OrbitArgs,
}

/// `--branches N`: a whole number of seed values from 2 to [`continuation::MAX_SEEDS`], given
/// with a figure (the branches are drawn, not tabled) and the event solver.
fn parse_branches(a: &BifurcationArgs, d: &Design) -> Result<Option<usize>, ThudError> {
    let Some(text) = &a.branches else { return Ok(None) };
    let max = continuation::MAX_SEEDS;
    let n = text.trim().parse::<f64>().ok().filter(|x| x.fract() == 0.0 && (2.0..=max as f64).contains(x)).ok_or_else(
        || ThudError::invalid("--branches", format!("'{text}'; give a whole number of seed values from 2 to {max}")),
    )?;
    if !a.orbit.wants_figure() {
        return Err(ThudError::invalid(
            "--branches",
            format!("'{text}' draws the branches in the figure; give --svg or --pdf too (their numbers: thud continue --vary NAME=FROM:TO:N)"),
        ));
    }
    if d.solver != crate::damper::Solver::Event {
        return Err(ThudError::invalid(
            "--solver",
            "newmark: orbits are continued with the event solver; use --solver event with --branches",
        ));
    }
    Ok(Some(n as usize))
}

#[derive(serde::Serialize)]
struct BifurcationJson<'a> {
    design: &'a Design,
    #[serde(flatten)]
    bifurcation: &'a Bifurcation,
}

/// Refuses a varied parameter that does not move the damper (the listener, the air, the zone
/// thresholds): its orbits and diagram would be one motion repeated at every value.
pub(super) fn refuse_motionless(vary: &Vary, typed: &str) -> Result<(), ThudError> {
    if matches!(vary.row.group, Group::Listener | Group::Study) {
        return Err(ThudError::invalid(
            "--vary",
            format!(
                "'{typed}': {} does not change the motion (only how its sound is heard or judged); vary a parameter of the damper or its force",
                vary.name()
            ),
        ));
    }
    Ok(())
}

pub fn run(a: &BifurcationArgs, ctx: &Ctx, out: &mut Out) -> Result<(), CliError> {
    let vary = Vary::parse(&a.vary, Spelling::Flag)?;
    refuse_motionless(&vary, &a.vary)?;
    refuse_run_flags(&a.design, "a bifurcation")?;
    let d = a.design.design_over(&[&vary])?;
    let s = a.orbit.settings(&a.design, &d)?;
    a.orbit.check_targets()?;
    check_work(ctx, vary.values.len(), s, a.continuation, ("--vary", &a.vary))?;
    let seeds = parse_branches(a, &d)?;
    if let (Some(n), Some(text)) = (seeds, &a.branches) {
        ctx.enforce(crate::limits::family_seed_periods(n), "--branches", text, "give fewer seed values")?;
    }
    if let Some(text) = &a.shard {
        return write_part(a, &d, &vary, s, text, out);
    }
    let n = vary.values.len() * if a.continuation { 2 } else { 1 };
    let bar = budget::bar(n as u64, "bifurcation");
    let b = dynamics::bifurcation(&d, &vary, s, a.continuation, "--force-amplitude", None, &|_| bar.inc(1))
        .map_err(super::bifurcation::flagged)?;
    bar.finish_and_clear();
    super::output::check_finite(&b)?;
    let branches = match seeds {
        Some(n) => continuation::continue_family(&d, &vary, n, None, &|_| {}).map_err(flagged)?,
        None => Vec::new(),
    };
    let title = crate::export::dynamics::bifurcation_title(&d, &b);
    a.orbit.write(
        |format| render(&d, &b, format),
        || crate::export::dynamics::bifurcation_with_branches_svg(&b, &branches, &title, &look()),
        out,
    )
}

/// The `format` of a part of a bifurcation (`thud bifurcation --shard K/N`).
pub const PART_FORMAT: &str = "thud-bifurcation-shard";

/// What a bifurcation is of: the resolved design, the axis and the run lengths. Its SHA-256
/// names it (as a chart's study, [`crate::shard::Study::hash`]).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PartStudy {
    pub design: Design,
    pub axis: crate::study::Axis,
    pub settings: Settings,
}

impl PartStudy {
    fn hash(&self) -> String {
        crate::shard::hash_of(self)
    }
}

/// The first line of a part of a bifurcation.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PartHeader {
    pub format: String,
    pub format_version: u32,
    pub thud_version: String,
    pub hash: String,
    pub shard: usize,
    pub shards: usize,
    pub values: usize,
    pub first: usize,
    pub end: usize,
    pub study: PartStudy,
}

/// `--shard K/N`: part K of N of the values (contiguous), the header then one point a line.
fn write_part(
    a: &BifurcationArgs,
    d: &ValidDesign,
    vary: &Vary,
    s: Settings,
    text: &str,
    out: &mut Out,
) -> Result<(), CliError> {
    let n_values = vary.values.len();
    let (k, n) = super::sweep::parse_shard(text, n_values)?;
    let target = Target::new(a.orbit.out.as_deref(), a.orbit.force)?;
    let range = crate::design::shard_range(n_values, k, n);
    let study = PartStudy { design: d.design().clone(), axis: vary.axis(), settings: s };
    let header = PartHeader {
        format: PART_FORMAT.into(),
        format_version: 1,
        thud_version: env!("CARGO_PKG_VERSION").into(),
        hash: study.hash(),
        shard: k,
        shards: n,
        values: n_values,
        first: range.start,
        end: range.end,
        study,
    };
    let bar = budget::bar((range.end - range.start) as u64, "shard");
    let points =
        dynamics::bifurcation_part(d, vary, range, s, "--force-amplitude", None, &|_| bar.inc(1)).map_err(flagged)?;
    bar.finish_and_clear();
    super::output::check_finite(&points)?;
    target.write(&crate::shard::json_lines(&header, &points)?, out)
}

/// Whether `first` (a part's first line) is the header of a part of a bifurcation.
pub(super) fn is_part(first: &str) -> bool {
    serde_json::from_str::<serde_json::Value>(first)
        .ok()
        .and_then(|v| v.get("format").and_then(|f| f.as_str()).map(|f| f == PART_FORMAT))
        .unwrap_or(false)
}

/// Joins the parts (`(name, text)`) of a bifurcation into the one `thud bifurcation` prints:
/// each part checked (header, hash, its points exactly, each at its value), then together
/// (one study, one N, every K once); printed as `--json` or `--csv`.
pub(super) fn merge(parts: &[(String, String)], format: OutputFormat) -> Result<String, CliError> {
    let refuse = |name: &str, why: String| CliError::Refused(format!("merge: {name} {why}"));
    let mut read: Vec<(String, PartHeader, Vec<dynamics::BifurcationPoint>)> = Vec::with_capacity(parts.len());
    for (name, text) in parts {
        let (first, rest) = text.split_once('\n').unwrap_or((text, ""));
        let h: PartHeader = serde_json::from_str(first)
            .map_err(|e| refuse(name, format!("is not a part of a bifurcation: its header does not read ({e})")))?;
        if h.format != PART_FORMAT || h.format_version != 1 {
            return Err(refuse(
                name,
                format!("is format {} version {}, not {PART_FORMAT} 1", h.format, h.format_version),
            ));
        }
        if h.hash != h.study.hash() {
            return Err(refuse(name, "has a hash that is not its study's (was the header edited?)".into()));
        }
        let mut points = Vec::new();
        for line in rest.lines().filter(|l| !l.trim().is_empty()) {
            let p: dynamics::BifurcationPoint = serde_json::from_str(line)
                .map_err(|e| refuse(name, format!("has a point that does not read ({e})")))?;
            points.push(p);
        }
        read.push((name.clone(), h, points));
    }
    let first_name = read[0].0.clone();
    let h0 = read[0].1.clone();
    let first_name = first_name.as_str();
    let n = h0.shards;
    let vary = Vary::of_values(&h0.study.axis.name, &h0.study.axis.values, Spelling::Flag)
        .map_err(|e| refuse(first_name, format!("holds a study that does not check: {e}")))?;
    let design = h0
        .study
        .design
        .clone()
        .check()
        .map_err(|e| refuse(first_name, format!("holds a design that does not check: {e}")))?;
    if h0.values != vary.values.len() || n == 0 || n > h0.values {
        return Err(refuse(first_name, "has a value count that is not its study's".into()));
    }
    let mut seen = vec![false; n];
    let mut all: Vec<Option<dynamics::BifurcationPoint>> = vec![None; h0.values];
    for (name, h, points) in read {
        if h.hash != h0.hash || h.shards != n {
            return Err(refuse(&name, format!("is of another study or split than {first_name}")));
        }
        if h.shard >= n || std::mem::replace(&mut seen[h.shard], true) {
            return Err(refuse(&name, format!("repeats part {}/{n}", h.shard)));
        }
        let range = crate::design::shard_range(h.values, h.shard, n);
        if (h.first, h.end) != (range.start, range.end) || points.len() != range.len() {
            return Err(refuse(&name, "does not hold exactly its part's values".into()));
        }
        for (i, p) in range.zip(points) {
            if p.value != vary.values[i] || p.direction != crate::response::Direction::FromRest {
                return Err(refuse(&name, format!("has value {} out of place", p.value)));
            }
            all[i] = Some(p);
        }
    }
    if let Some(k) = seen.iter().position(|s| !s) {
        return Err(CliError::Refused(format!("merge: part {k}/{n} is missing")));
    }
    let points: Vec<dynamics::BifurcationPoint> = all.into_iter().flatten().collect();
    super::output::check_finite(&points)?;
    let bands = dynamics::bands(&points);
    let b = Bifurcation { axis: vary.axis(), settings: h0.study.settings, points, bands };
    render(&design, &b, format)
}

/// A short name of the design for a figure's title (one copy, shared with the Python module).
pub(super) use thud_render::dynamics::short_design;

/// The bifurcation as `format`.
fn render(d: &Design, b: &Bifurcation, format: OutputFormat) -> Result<String, CliError> {
    Ok(match format {
        OutputFormat::Json => {
            let mut t = serde_json::to_string_pretty(&BifurcationJson { design: d, bifurcation: b })
                .map_err(std::io::Error::from)?;
            t.push('\n');
            t
        }
        OutputFormat::Csv => crate::export::dynamics::bifurcation_csv(b)
            .map_err(|e| ThudError::invalid("csv", format!("cannot write: {e}")))?,
        OutputFormat::Text => {
            let unit = if b.axis.unit.is_empty() { String::new() } else { format!(" ({})", b.axis.unit) };
            let mut t = format!("base      {}\n", describe(d));
            t += &format!(
                "study     {}{unit}: {} value{}; {} transient periods, then {} sampled\n\n",
                b.axis.name,
                b.axis.values.len(),
                plural(b.axis.values.len()),
                b.settings.transient_periods,
                b.settings.periods
            );
            t += &format!(
                "{:>12}  {:<9}  {:<12}  {:>8}  {:>14}  {:>12}\n",
                b.axis.name, "sweep", "orbit", "impacts", "amplitude (mm)", "max u (m/s)"
            );
            for p in &b.points {
                let umax = p.run.impacts.iter().map(|i| i.u_in_m_s).fold(0.0, f64::max);
                t += &format!(
                    "{:>12}  {:<9}  {:<12}  {:>8}  {:>14}  {:>12}\n",
                    num(p.value),
                    crate::export::dynamics::direction(p.direction),
                    p.run.orbit.label(),
                    p.run.impacts.len(),
                    num(p.run.amplitude_m * 1e3),
                    num(umax)
                );
            }
            t += "\nbands (consecutive values with the same orbit; m/n = m impacts per n periods, sym = x(t+T/2) = −x(t)):\n";
            for band in &b.bands {
                t += &format!(
                    "  {:<9} {:>10} – {:<10} {:>4} value{:<1}  {}\n",
                    crate::export::dynamics::direction(band.direction),
                    num(band.from),
                    num(band.to),
                    band.values,
                    plural(band.values),
                    band.orbit
                );
            }
            t += "\n(--csv: one row per sample and per impact; --json: everything; --svg/--pdf FILE: the figure)\n";
            t
        }
    })
}

/// The plural ending of a count of `n`: "" for one, "s" otherwise.
fn plural(n: usize) -> &'static str {
    if n == 1 {
        ""
    } else {
        "s"
    }
}
