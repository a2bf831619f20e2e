//! `thud sweep --vary NAME=FROM:TO:N` (repeatable): a study over any numeric parameter of the
//! engine's table. The grid is the product of the axes in C order (the last
//! `--vary` fastest); each cell is the base design with its values, checked again as a whole,
//! and run as `thud simulate` runs it (with a force, its steady state too).

use serde::Serialize;

use super::budget;
use super::design_args::{DesignArgs, ForceAmplitude};
use super::format::num;
use super::simulate::describe;
use super::{CliError, Ctx, OutputFormat};
use crate::design::{Design, ValidDesign};
use crate::error::ThudError;
use crate::params::Spelling;
use crate::study::{self, Axis, Grid, Study, Vary};

/// Parses every `--vary` (one engine parser, [`Vary::parse`]) into the grid over `base`.
pub(super) fn grid(base: crate::design::ValidDesign, vary: &[String]) -> Result<Grid, ThudError> {
    Grid::new(base, axes(vary)?, Spelling::Flag)
}

/// Every `--vary` parsed.
fn axes(vary: &[String]) -> Result<Vec<Vary>, ThudError> {
    vary.iter().map(|t| Vary::parse(t, Spelling::Flag)).collect()
}

/// The design of a study over `vary` (a varied frequency supplies the one a force needs), and
/// a refusal of a varied frequency that changes nothing: without a force (none given, none
/// varied) every row would be the same.
pub(super) fn design_for(design: &DesignArgs<ForceAmplitude>, vary: &[String]) -> Result<ValidDesign, ThudError> {
    let axes = axes(vary)?;
    let d = design.design_over(&axes.iter().collect::<Vec<_>>())?;
    let force_varied = axes.iter().any(|a| a.name() == "force");
    if let Some(i) = axes.iter().position(|a| a.name() == "freq") {
        if d.damper.force_n == 0.0 && !force_varied {
            return Err(ThudError::invalid(
                "--vary",
                format!(
                    "'{}': the frequency changes nothing without a force (every row would be the same); give --force-amplitude F0",
                    vary[i]
                ),
            ));
        }
    }
    Ok(d)
}

#[derive(Serialize)]
struct StudyJson<'a> {
    design: &'a Design,
    #[serde(flatten)]
    study: &'a Study,
}

/// `thud sweep --vary …`: the study, as `format` prints it, and the study itself.
pub(super) fn sweep_vary(
    design: &DesignArgs<ForceAmplitude>,
    vary: &[String],
    ctx: &Ctx,
    format: OutputFormat,
) -> Result<(String, Study), CliError> {
    let d = design_for(design, vary)?;
    let grid = grid(d.clone(), vary)?;
    design.check_study(ctx, &grid)?;
    let bar = budget::bar(grid.cells() as u64, "sweep");
    let s = study::sweep(&grid, None, &|_, _| bar.inc(1))?;
    bar.finish_and_clear();
    Ok((render(&d, &s, format)?, s))
}

/// The figure of a study over one or two parameters (None over more), titled with what varies
/// over its whole range.
pub(super) fn figure(s: &Study) -> Option<String> {
    crate::export::studies::study(s, &crate::export::studies::study_title(s), &crate::export::svg::Look::default())
}

/// The study as `thud sweep --vary` prints it (checked finite).
pub(super) fn render(d: &Design, s: &Study, format: OutputFormat) -> Result<String, CliError> {
    super::output::check_finite(s)?;
    Ok(match format {
        OutputFormat::Json => {
            let mut t =
                serde_json::to_string_pretty(&StudyJson { design: d, study: s }).map_err(std::io::Error::from)?;
            t.push('\n');
            t
        }
        OutputFormat::Csv => crate::export::dynamics::study_csv(s)
            .map_err(|e| ThudError::invalid("csv", format!("cannot write: {e}")))?,
        OutputFormat::Text => text(d, s),
    })
}

/// A table: one row per cell, the varied values then the metrics.
fn text(d: &Design, s: &Study) -> String {
    let mut t = format!("base      {}\n", describe(d));
    let dims: Vec<String> = s
        .axes
        .iter()
        .map(|a| format!("{} ({} value{})", heading(a), a.values.len(), if a.values.len() == 1 { "" } else { "s" }))
        .collect();
    let n = s.cells.len();
    t += &format!("study     {} = {n} cell{}\n\n", dims.join(" × "), if n == 1 { "" } else { "s" });
    for a in &s.axes {
        t += &format!("{:>14}", heading(a));
    }
    let forced = s.cells.iter().any(|c| c.steady.is_some());
    t += "   impacts  e (cm/s)  U0max (m/s)  SPLmax (dB)  zone";
    if forced {
        t += "  amplitude (mm)";
    }
    t += "\n";
    for c in &s.cells {
        for v in &c.values {
            t += &format!("{:>14}", num(*v));
        }
        let m = &c.metrics;
        let opt = |v: Option<f64>| v.map_or("—".to_string(), num);
        t += &format!(
            "   {:>7}  {:>8}  {:>11}  {:>11}  {:>4}",
            m.n_impacts,
            opt(m.inclination_cm_s),
            num(m.u0_max_m_s),
            opt(m.spl_max_db),
            m.zone.map_or("—".to_string(), |z| z.number().to_string())
        );
        if let Some(st) = &c.steady {
            t += &format!("  {:>14}", num(st.amplitude_m * 1e3));
        }
        t += "\n";
    }
    t += "\n(--json or --csv for every metric of every cell)\n";
    t
}

/// `v0 (m/s)`.
fn heading(a: &Axis) -> String {
    if a.unit.is_empty() {
        a.name.clone()
    } else {
        format!("{} ({})", a.name, a.unit)
    }
}

/// The `format` of a part of a study over any parameter (`sweep --vary … --shard K/N`).
pub const STUDY_FORMAT: &str = "thud-study-shard";
/// The version of that format.
pub const STUDY_FORMAT_VERSION: u32 = 1;

/// What a study is of: the resolved base design and each axis (name as in the table, values in
/// its plain unit). Its hash (SHA-256 of its canonical JSON, as [`crate::shard::Study::hash`])
/// names it.
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize)]
pub struct StudySpec {
    pub design: Design,
    pub axes: Vec<Axis>,
}

impl StudySpec {
    fn hash(&self) -> String {
        crate::shard::hash_of(self)
    }

    /// The grid again, every value and the base design checked as when it was typed.
    fn grid(&self) -> Result<Grid, ThudError> {
        let axes = self
            .axes
            .iter()
            .map(|a| Vary::of_values(&a.name, &a.values, Spelling::Flag))
            .collect::<Result<Vec<_>, _>>()?;
        Grid::new(self.design.clone().check()?, axes, Spelling::Flag)
    }
}

/// The first line of a part of a study: the chart's part header around the study's own
/// description.
pub type StudyHeader = crate::shard::Header<StudySpec>;

/// `thud sweep --vary … --shard K/N`: part `k` of `n` of the study's cells (contiguous C-order
/// indices, [`crate::design::shard_range`]) as JSON lines: the header, then one cell a line.
pub(super) fn write_shard(
    design: &DesignArgs<ForceAmplitude>,
    ctx: &Ctx,
    grid: &Grid,
    (k, n): (usize, usize),
    csv: bool,
) -> Result<String, CliError> {
    if csv {
        return Err(ThudError::invalid("--csv", "parts of a study with --vary are JSON lines; leave out --csv").into());
    }
    let cells = grid.cells();
    design.check_study(ctx, grid)?;
    let range = crate::design::shard_range(cells, k, n);
    let spec = StudySpec { design: grid.base.design().clone(), axes: grid.axes() };
    let header = StudyHeader {
        format: STUDY_FORMAT.into(),
        format_version: STUDY_FORMAT_VERSION,
        thud_version: env!("CARGO_PKG_VERSION").into(),
        hash: spec.hash(),
        shard: k,
        shards: n,
        cells,
        first_cell: range.start,
        end_cell: range.end,
        study: spec,
    };
    let bar = budget::bar((range.end - range.start) as u64, "shard");
    let part = study::sweep_cells(grid, range, None, &|_, _| bar.inc(1))?;
    bar.finish_and_clear();
    super::output::check_finite(&part)?;
    Ok(crate::shard::json_lines(&header, &part)?)
}

/// Whether the first line `first` is the header of a part of a study over any parameter.
pub(super) fn is_study_part(first: &str) -> bool {
    serde_json::from_str::<serde_json::Value>(first)
        .ok()
        .and_then(|v| v.get("format").and_then(|f| f.as_str()).map(|f| f == STUDY_FORMAT))
        .unwrap_or(false)
}

/// Joins the parts (`(name, text)`) of a study into the study `sweep --vary` prints: every part
/// checked on its own (header, hash, its cells exactly, each at its grid point), then together
/// (one study, one N, every K once).
pub(super) fn merge(parts: &[(String, String)]) -> Result<(Design, Study), CliError> {
    let refuse = |name: &str, why: String| CliError::Refused(format!("merge: {name} {why}"));
    let mut headers: Vec<(String, StudyHeader, &str)> = Vec::with_capacity(parts.len());
    for (name, text) in parts {
        let (first, rest) = text.split_once('\n').unwrap_or((text, ""));
        let h: StudyHeader = serde_json::from_str(first)
            .map_err(|e| refuse(name, format!("is not a part of a study: its header does not read ({e})")))?;
        if h.format != STUDY_FORMAT || h.format_version != STUDY_FORMAT_VERSION {
            return Err(refuse(
                name,
                format!("is format {} version {}, not {STUDY_FORMAT} 1", h.format, h.format_version),
            ));
        }
        if h.hash != h.study.hash() {
            return Err(refuse(name, "has a hash that is not its study's (was the header edited?)".into()));
        }
        headers.push((name.clone(), h, rest));
    }
    let (first_name, h0, _) = &headers[0];
    for (name, h, _) in &headers[1..] {
        if h.hash != h0.hash {
            return Err(refuse(name, format!("is of another study than {first_name}")));
        }
        if h.shards != h0.shards {
            return Err(refuse(name, format!("is a part of {} parts, {first_name} of {}", h.shards, h0.shards)));
        }
    }
    let n = h0.shards;
    let mut seen = vec![false; n];
    for (name, h, _) in &headers {
        if h.shard >= n || std::mem::replace(&mut seen[h.shard], true) {
            return Err(refuse(name, format!("repeats part {}/{n}", h.shard)));
        }
    }
    if let Some(k) = seen.iter().position(|s| !s) {
        return Err(CliError::Refused(format!("merge: part {k}/{n} is missing")));
    }
    let grid = h0.study.grid().map_err(|e| refuse(first_name, format!("holds a study that does not check: {e}")))?;
    crate::limits::check_cells(grid.cells()).map_err(|r| CliError::Refused(format!("merge: {r}")))?;
    if grid.cells() != h0.cells || n == 0 || n > h0.cells {
        return Err(refuse(first_name, "has a cell count that is not its study's".into()));
    }
    let mut cells: Vec<Option<study::StudyCell>> = vec![None; grid.cells()];
    for (name, h, rest) in &headers {
        let range = crate::design::shard_range(h.cells, h.shard, n);
        if (h.first_cell, h.end_cell) != (range.start, range.end) {
            return Err(refuse(name, "has a cell range that is not its part's".into()));
        }
        let mut expect = range.clone();
        for line in rest.lines().filter(|l| !l.trim().is_empty()) {
            let c: study::StudyCell =
                serde_json::from_str(line).map_err(|e| refuse(name, format!("has a cell that does not read ({e})")))?;
            if expect.next() != Some(c.index) || c.values != grid.values(c.index) {
                return Err(refuse(name, format!("has cell {} out of place", c.index)));
            }
            let i = c.index;
            cells[i] = Some(c);
        }
        if expect.next().is_some() {
            return Err(refuse(name, "is cut short: cells are missing".into()));
        }
    }
    let cells: Vec<study::StudyCell> = cells.into_iter().flatten().collect();
    super::output::check_finite(&cells)?;
    Ok((h0.study.design.clone(), Study { axes: grid.axes(), cells }))
}
