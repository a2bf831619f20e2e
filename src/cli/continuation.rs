//! `thud continue --vary NAME=FROM:TO`: pseudo-arclength continuation of the design's periodic
//! orbit over one numeric parameter (docs/model.md §6.8), through folds and along unstable
//! parts, with its fold, period-doubling, Neimark–Sacker and grazing points. Text (the branch's
//! stretches and special points), `--json` or `--csv` (one row per point); `--svg`/`--pdf` draw
//! each branch's amplitude against the parameter, stable solid, unstable dashed, the special
//! points marked.

use std::path::PathBuf;

use clap::Args;

use super::design_args::{DesignArgs, ForceAmplitude};
use super::figure_out::FigureOutputs;
use super::format::num;
use super::simulate::describe;
use super::{CliError, Ctx, Out, OutputArgs, OutputFormat};
use crate::continuation::{self, Branch};
use crate::design::Design;
use crate::error::ThudError;
use crate::orbit::Request;
use crate::params::Spelling;
use crate::study::Vary;

#[derive(Debug, Clone, Args)]
pub struct ContinueArgs {
    #[command(flatten)]
    design: DesignArgs<ForceAmplitude>,
    /// The parameter to continue in over its range: NAME=FROM:TO (e.g. f=3Hz:8Hz) continues
    /// the orbit found at FROM; NAME=FROM:TO:N (e.g. f=3Hz:8Hz:26) every branch through the
    /// stable orbits found from the design's start at N evenly spaced values, each both ways. The
    /// continuation chooses its own steps.
    #[arg(long, value_name = "NAME=FROM:TO:N", allow_hyphen_values = true)]
    vary: String,
    /// The orbit's period in forcing periods, 1 to 16 [default: the one the design's motion
    /// repeats with].
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    period: Option<String>,
    /// Look for the symmetric orbit, x(t + T/2) = −x(t) (period one forcing period), stable
    /// or not.
    #[arg(long)]
    symmetric: bool,
    /// At each period doubling, also continue the branch of the doubled orbit born there (found
    /// just past the doubling, where a supercritical doubling's doubled orbit is stable), and at
    /// its doublings in turn, up to a period of 16.
    #[arg(long)]
    doublings: bool,
    /// Also write the figure as SVG to this file.
    #[arg(long, value_name = "FILE")]
    svg: Option<PathBuf>,
    /// Also write the figure as PDF to this file.
    #[arg(long, value_name = "FILE")]
    pdf: Option<PathBuf>,
    /// Write the result (text, --json or --csv) to this file instead of standard output (`-`:
    /// standard output); an existing file is kept unless --force.
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// Replace the --out, --svg or --pdf file if it exists.
    #[arg(long)]
    force: bool,
    #[command(flatten)]
    ascii: super::AsciiArgs,
    #[command(flatten)]
    output: OutputArgs,
}

impl ContinueArgs {
    /// Where the table and its figure go.
    fn outputs(&self) -> FigureOutputs<'_> {
        FigureOutputs::new(&self.out, &self.svg, &self.pdf, self.force, self.ascii)
    }
}

/// The figure's title: what varies over which range, and the rest of the design.
fn title(d: &Design, vary: &Vary) -> String {
    crate::export::dynamics::range_title("Orbits continued", d, vary.name(), vary.unit(), &vary.values)
}

/// The figure of `branches` as SVG, if one is asked for.
fn figure(a: &ContinueArgs, d: &Design, vary: &Vary, branches: &[Branch]) -> Option<String> {
    a.outputs()
        .wants_figure()
        .then(|| crate::export::continuation::continuation_svg(branches, &title(d, vary), &super::bifurcation::look()))
}

#[derive(serde::Serialize)]
struct BranchJson<'a> {
    design: &'a Design,
    #[serde(flatten)]
    branch: &'a Branch,
}

#[derive(serde::Serialize)]
struct FamilyJson<'a> {
    design: &'a Design,
    name: &'a str,
    unit: &'a str,
    branches: &'a [Branch],
}

/// `NAME=FROM:TO` as a two-value study axis, and `NAME=FROM:TO:N`'s N (the seed values).
fn parse_vary(text: &str) -> Result<(Vary, Option<usize>), ThudError> {
    let colons = text.split_once('=').map_or(0, |(_, spec)| spec.matches(':').count());
    if colons == 2 {
        // N counts seed values: 2 to MAX_SEEDS (a sweep axis's 1 is no range to continue over).
        let n = text.rsplit(':').next().unwrap_or_default().trim();
        let whole =
            n.parse::<f64>().is_ok_and(|x| x.fract() == 0.0 && (2.0..=continuation::MAX_SEEDS as f64).contains(&x));
        if !whole {
            return Err(ThudError::invalid(
                "--vary",
                format!(
                    "'{text}': N = '{n}'; give a whole number of seed values from 2 to {}",
                    continuation::MAX_SEEDS
                ),
            ));
        }
    }
    let full = if colons == 1 { format!("{text}:2") } else { text.to_string() };
    // An error quotes what was typed, not the two-value form it was read as.
    let v = Vary::parse(&full, Spelling::Flag).map_err(|e| match e {
        ThudError::Invalid { param, message } => {
            ThudError::Invalid { param, message: message.replace(&format!("'{full}'"), &format!("'{text}'")) }
        }
        e => e,
    })?;
    let (Some(&a), Some(&b)) = (v.values.first(), v.values.last()) else {
        return Err(ThudError::invalid("--vary", format!("'{text}'; expected NAME=FROM:TO")));
    };
    let seeds = (colons == 2).then_some(v.values.len());
    if let Some(n) = seeds.filter(|&n| n > continuation::MAX_SEEDS) {
        return Err(ThudError::invalid(
            "--vary",
            format!("'{text}': {n} seed values; give 2 to {}", continuation::MAX_SEEDS),
        ));
    }
    Ok((Vary::of_values(v.name(), &[a, b], Spelling::Flag)?, seeds))
}

fn renamed(e: ThudError) -> ThudError {
    match e.param() {
        "force" => e.renamed("--force-amplitude"),
        "period" => e.renamed("--period"),
        "solver" => e.renamed("--solver"),
        "vary" => e.renamed("--vary"),
        _ => e,
    }
}

pub fn run(a: &ContinueArgs, ctx: &Ctx, out: &mut Out) -> Result<(), CliError> {
    let (vary, seeds) = parse_vary(&a.vary)?;
    super::bifurcation::refuse_motionless(&vary, &a.vary)?;
    // A varied frequency is the design's (FROM stands in for --freq).
    let d = a.design.design_over(&[&vary])?;
    a.outputs().check()?;
    let periods = super::orbit::parse_period(a.period.as_deref())?;
    let mut branches = if let Some(n) = seeds {
        if periods.is_some() || a.symmetric {
            return Err(ThudError::invalid(
                    "--vary",
                    format!("'{}' with N: the branches start from the motion's own orbits; give NAME=FROM:TO with --period or --symmetric", a.vary),
                )
                .into());
        }
        if d.solver != crate::damper::Solver::Event {
            return Err(renamed(ThudError::invalid(
                "solver",
                "newmark: orbits are found with the event solver; use --solver event",
            ))
            .into());
        }
        // No force at any seed value: no orbit to start a branch from, refused as one branch is.
        if !d.damper.forced() && vary.name() != "force" {
            return Err(renamed(ThudError::invalid(
                "force",
                "0 N: a periodic orbit needs a harmonic force; give a force and a frequency",
            ))
            .into());
        }
        // Each seed's design checked as one branch's is: a seed outside a range (a ball start
        // outside the clearance) is refused, not skipped.
        let (from, to) = (vary.values[0], vary.values[vary.values.len() - 1]);
        let axis = Vary::of_values(vary.name(), &crate::design::linspace(from, to, n), Spelling::Flag)?;
        let grid = crate::study::Grid::new(d.clone(), vec![axis], Spelling::Flag)?;
        for i in 0..grid.cells() {
            grid.point(i).map_err(renamed)?;
        }
        ctx.enforce(crate::limits::family_seed_periods(n), "--vary", &a.vary, "give fewer seed values")?;
        continuation::continue_family(&d, &vary, n, None, &|_| {}).map_err(renamed)?
    } else {
        let req = Request { periods, symmetric: a.symmetric, guess: None };
        vec![continuation::continue_branch(&d, &vary, &req, None, &|_| {}).map_err(renamed)?]
    };
    if a.doublings {
        branches = continuation::with_doublings(&d, &vary, branches, None, &|_| {}).map_err(renamed)?;
    }
    super::output::check_finite(&branches)?;
    // One branch as it is; a family (N seeds, or the doubled branches added) branch by branch.
    let text = match (a.output.format(), branches.as_slice()) {
        (OutputFormat::Json, [branch]) if seeds.is_none() => json(&BranchJson { design: &d, branch })?,
        (OutputFormat::Json, _) => {
            json(&FamilyJson { design: &d, name: vary.name(), unit: vary.unit(), branches: &branches })?
        }
        (OutputFormat::Csv, [branch]) if seeds.is_none() => {
            warn_truncated(&branches);
            csv(branch)
        }
        (OutputFormat::Csv, _) => {
            warn_truncated(&branches);
            family_csv(&vary, &branches)
        }
        (OutputFormat::Text, [branch]) if seeds.is_none() => text(&d, branch),
        (OutputFormat::Text, _) => family_text(&d, &vary, seeds, a.doublings, &branches),
    };
    a.outputs().write(&text, figure(a, &d, &vary, &branches), out)
}

/// Pretty JSON with a final newline.
fn json(value: &impl serde::Serialize) -> Result<String, CliError> {
    let mut t = serde_json::to_string_pretty(value).map_err(std::io::Error::from)?;
    t.push('\n');
    Ok(t)
}

/// The CSV has no column for why a branch ended: a branch its work cap cut says so on stderr
/// (the text and the JSON say it in the branch's `ended`).
fn warn_truncated(branches: &[Branch]) {
    for (k, _) in branches.iter().enumerate().filter(|(_, b)| b.truncated()) {
        super::warn(&format!("branch {} was cut short by {}; --no-limit lifts it", k + 1, continuation::CAPPED));
    }
}

/// The branches of a family in words, one after the other.
fn family_text(d: &Design, vary: &Vary, seeds: Option<usize>, doublings: bool, branches: &[Branch]) -> String {
    let mut t = format!("design      {}\n", describe(d));
    let through = match seeds {
        Some(n) => format!("through the stable orbits found from the start at {n} values of {}", vary.name()),
        None => format!("through the orbit found at the first value of {}", vary.name()),
    };
    let doubled = if doublings { ", and the doubled orbits born at their period doublings" } else { "" };
    t += &format!("family      {} branches {through}{doubled}\n", branches.len());
    for (k, b) in branches.iter().enumerate() {
        t += &format!("\n[branch {}]\n", k + 1);
        let body = text(d, b);
        t += body.split_once('\n').map_or(body.as_str(), |(_, rest)| rest);
    }
    t
}

/// One row per point of every branch, the branch's number (from 1) first.
fn family_csv(vary: &Vary, branches: &[Branch]) -> String {
    let mut t = String::new();
    for (k, b) in branches.iter().enumerate() {
        let rows = csv(b);
        let (header, body) = rows.split_once('\n').unwrap_or((rows.as_str(), ""));
        if k == 0 {
            t += &format!("branch,{header}\n");
        }
        for row in body.lines() {
            t += &format!("{},{row}\n", k + 1);
        }
    }
    if branches.is_empty() {
        t += &format!(
            "branch,{},orbit,periods,impacts_per_orbit,stable,multiplier_abs_max,amplitude_m,x_m,v_m_s,z_m,zdot_m_s\n",
            crate::study::column(vary.name(), vary.unit())
        );
    }
    t
}

/// The branch in words: its stretches of one orbit type and stability, and its special points.
fn text(d: &Design, b: &Branch) -> String {
    let unit = if b.unit.is_empty() { String::new() } else { format!(" {}", b.unit) };
    let mut t = format!("design      {}\n", describe(d));
    t += &format!("branch      {} points over {}", b.points.len(), b.name);
    if let (Some(f), Some(l)) = (b.points.first(), b.points.last()) {
        t += &format!(" {}{unit} → {}{unit}", num(f.value), num(l.value));
    }
    t += "\n\n  from        to          orbit     stability   amplitude (mm)\n";
    let mut i = 0;
    while i < b.points.len() {
        let p = &b.points[i];
        let mut j = i;
        while j + 1 < b.points.len() && b.points[j + 1].orbit == p.orbit && b.points[j + 1].stable == p.stable {
            j += 1;
        }
        let q = &b.points[j];
        t += &format!(
            "  {:<10}  {:<10}  {:<8}  {:<10}  {} → {}\n",
            num(p.value),
            num(q.value),
            p.orbit,
            if p.stable { "stable" } else { "unstable" },
            num(p.amplitude_m * 1e3),
            num(q.amplitude_m * 1e3)
        );
        i = j + 1;
    }
    if b.specials.is_empty() {
        t += "\nno special point\n";
    } else {
        t += "\n  special point      at            amplitude (mm)\n";
        for s in &b.specials {
            t += &format!(
                "  {:<17}  {:<12}  {}\n",
                s.kind.label(),
                format!("{}{unit}", num(s.value)),
                num(s.amplitude_m * 1e3)
            );
        }
    }
    if let Some(why) = &b.ended {
        t += &format!("\nthe branch ended early: {why}\n");
    }
    t
}

/// One row per point.
fn csv(b: &Branch) -> String {
    let col = crate::study::column(&b.name, &b.unit);
    let mut t =
        format!("{col},orbit,periods,impacts_per_orbit,stable,multiplier_abs_max,amplitude_m,x_m,v_m_s,z_m,zdot_m_s\n");
    for p in &b.points {
        t += &format!(
            "{:e},{},{},{},{},{:e},{:e},{:e},{:e},{:e},{:e}\n",
            p.value,
            p.orbit,
            p.periods,
            p.impacts_per_orbit,
            p.stable,
            p.multiplier_abs_max,
            p.amplitude_m,
            p.x_m,
            p.v_m_s,
            p.z_m,
            p.zdot_m_s
        );
    }
    t
}
