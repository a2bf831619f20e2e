// Over 800 lines: the part format's writer, reader and merge must agree field by field; the rest is tests.
//! Parts of a design chart computed apart and joined again:
//! `thud sweep --shard K/N` computes part K of N and writes it as JSON lines or CSV;
//! `thud merge PARTS…` checks the parts and joins them into the chart one `thud sweep` gives.
//! The batch system (GNU parallel, a Slurm job array, …) runs the parts; thud runs no server.
//!
//! **The split** is the engine's [`design::shard_range`]: contiguous ranges of the row-major
//! cell index (`g·masses + m`), part K (0-based, like `SLURM_ARRAY_TASK_ID`) holding cells
//! `⌊K·C/N⌋ .. ⌊(K+1)·C/N⌋` of the C cells.
//!
//! **A part** starts with a header ([`Header`]): the format and its version, the thud version,
//! K, N, the chart's cell count and the part's first and end cell, the whole study ([`Study`]:
//! the resolved design with its thresholds, both axes, the Table 5 band width and the runs per
//! cell) and a hash of that study. Then one entry per cell, in index order, with every run of the
//! cell ([`Member`]: all its metrics, so the merged chart is the one `sweep` prints, byte for
//! byte):
//!
//! - JSON lines: the header object on the first line, then one `{"index", "mass_kg", "gap_m",
//!   "runs": [...]}` object per line.
//! - CSV: the header object on the first line after `# `, then a table with one row per run
//!   ([`CSV_COLUMNS`]); an empty field is "none", numbers are Rust's shortest round-trip form.
//!
//! **The hash** is SHA-256 (the `sha2` crate) of the study's canonical JSON: serde_json's compact
//! form of [`Study`] — fields in declaration order, floats in their shortest round-trip form — so
//! the same study gives the same bytes on every machine. It is a digest, not a signature: it
//! tells parts of different studies apart (a changed mass axis, gap, threshold, band, ensemble
//! size or any design field), which two parts that merely claim the same K/N cannot. SHA-256
//! rather than a hand-written 64-bit FNV-1a: the crate is small and well kept, an accidental
//! match of two studies is out of the question rather than merely unlikely, and the cost (one
//! hash of a few kB per part) is nothing. JSON is read with `serde_json`'s `float_roundtrip`, so
//! every number reads back to the same `f64` it was written from.
//!
//! **The merge** ([`merge`]) checks every part on its own (its header, its hash against its
//! study, exactly its cells, each run at its offset) and then the parts together: one study
//! (hash), one thud version, one N, no K twice and none missing. Every refusal names the part
//! file and the K at fault.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};
use thiserror::Error;

use crate::design::{self, Cell, Chart, Design, Metrics};
use crate::ensemble::{self, Ensemble, EnsembleCell, EnsembleChart, Member};
use crate::{limits, params};

/// The `format` of a part's header.
pub const FORMAT: &str = "thud-sweep-shard";
/// The version of the part format this thud writes and reads.
pub const FORMAT_VERSION: u32 = 1;
/// The largest part file `thud merge` reads (1 GiB): a part of the largest chart the run caps
/// allow (1e5 runs) is about 25–35 MB. A part is also refused, before it is read, when it is
/// larger than its own header allows ([`Header::max_part_bytes`]).
pub const MAX_PART_BYTES: u64 = 1 << 30;
/// The longest first line (the header) of a part read (1 MiB): the header of the largest grid
/// (1000 × 1000 grid points) is about 40 kB. `merge` reads only this much of every part before
/// it checks the parts together and the merged chart against its cap.
pub const MAX_HEADER_BYTES: usize = 1 << 20;
/// The most bytes a run takes in a part (a JSON run is about 330 bytes, a CSV row about 250).
pub const MAX_BYTES_PER_RUN: u64 = 1024;
/// The most bytes a cell takes in a part besides its runs (index, mass and gap).
pub const MAX_BYTES_PER_CELL: u64 = 256;
/// The largest magnitude of a number in a part's cell: far beyond anything thud computes within
/// its ranges (a forced run's inclination reaches about 1e7 cm/s), and small enough that sums,
/// spans and squares of any cells stay finite.
pub const MAX_CELL_MAGNITUDE: f64 = 1e100;

/// What a chart is of: everything that decides its numbers and its printout. Its hash names it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Study {
    /// The resolved design (K_HZ from materials already set), with its zone thresholds.
    pub design: Design,
    pub masses_kg: Vec<f64>,
    pub gaps_m: Vec<f64>,
    /// Width of the Table 5 inclination bands (cm/s).
    pub band_cm_s: f64,
    /// Runs per cell (1: the ordinary chart).
    pub ensemble: usize,
}

impl Study {
    /// Cells of the chart: masses × gaps.
    #[must_use]
    pub fn cells(&self) -> usize {
        self.masses_kg.len() * self.gaps_m.len()
    }

    /// `sha256:` and the hex SHA-256 of the study's canonical JSON (see the module doc).
    #[must_use]
    pub fn hash(&self) -> String {
        hash_of(self)
    }
}

/// `sha256:` and the hex SHA-256 of `study`'s canonical JSON: the hash every part's header
/// carries (the chart's, a study's over any parameter, a bifurcation's).
pub fn hash_of(study: &impl Serialize) -> String {
    // Serializing these plain structs to memory cannot fail.
    let canonical = serde_json::to_vec(study).unwrap_or_default();
    let hex: String = Sha256::digest(&canonical).iter().map(|b| format!("{b:02x}")).collect();
    format!("sha256:{hex}")
}

/// The first line of a part: of the mass × gap chart's ([`Study`]), or of a study over any
/// parameter's (`S` its own description, `thud sweep --vary`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Header<S = Study> {
    /// [`FORMAT`].
    pub format: String,
    /// [`FORMAT_VERSION`].
    pub format_version: u32,
    /// The thud that computed the part.
    pub thud_version: String,
    /// [`hash_of`] `study`.
    pub hash: String,
    /// K: which part, 0-based.
    pub shard: usize,
    /// N: parts in all.
    pub shards: usize,
    /// Cells of the whole chart.
    pub cells: usize,
    /// The part's first cell (row-major index).
    pub first_cell: usize,
    /// One past the part's last cell.
    pub end_cell: usize,
    pub study: S,
}

impl Header {
    /// The header of part `k` of `n` of `study`.
    #[must_use]
    pub fn new(study: Study, k: usize, n: usize) -> Self {
        let cells = study.cells();
        let range = design::shard_range(cells, k, n);
        Header {
            format: FORMAT.to_string(),
            format_version: FORMAT_VERSION,
            thud_version: env!("CARGO_PKG_VERSION").to_string(),
            hash: study.hash(),
            shard: k,
            shards: n,
            cells,
            first_cell: range.start,
            end_cell: range.end,
            study,
        }
    }

    /// The most bytes a part with this header can hold: its header line, the CSV column line
    /// and [`MAX_BYTES_PER_CELL`] + [`MAX_BYTES_PER_RUN`] × runs for each of its cells.
    #[must_use]
    pub fn max_part_bytes(&self) -> u64 {
        let cells = self.end_cell.saturating_sub(self.first_cell) as u64;
        let per_cell = MAX_BYTES_PER_CELL.saturating_add(MAX_BYTES_PER_RUN.saturating_mul(self.study.ensemble as u64));
        (2 * MAX_HEADER_BYTES as u64).saturating_add(cells.saturating_mul(per_cell)).min(MAX_PART_BYTES)
    }

    /// "K/N".
    fn k_of_n(&self) -> String {
        format!("{}/{}", self.shard, self.shards)
    }
}

/// One cell of a part: its index, mass and gap and every run of it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PartCell {
    pub index: usize,
    pub mass_kg: f64,
    pub gap_m: f64,
    pub runs: Vec<Member>,
}

impl PartCell {
    /// The part cell of an ensemble cell.
    #[must_use]
    pub fn new(index: usize, cell: &EnsembleCell) -> Self {
        PartCell { index, mass_kg: cell.mass_kg, gap_m: cell.gap_m, runs: cell.ensemble.ensemble.clone() }
    }
}

/// How a part is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// The header and one JSON object per cell, a line each.
    JsonLines,
    /// `# ` and the header, then a CSV table with a row per run.
    Csv,
}

/// The columns of a CSV part, one row per run: the schema's `shard_part` table.
pub const CSV_COLUMNS: &[thud_core::schema::Column] = thud_core::schema::SHARD_PART.columns;

/// The names of [`CSV_COLUMNS`].
pub fn csv_header() -> Vec<&'static str> {
    thud_core::schema::SHARD_PART.names()
}

/// Why a part or a set of parts is refused. `file` is the part as the user named it.
#[derive(Debug, Error, PartialEq)]
pub enum ShardError {
    #[error("no part to merge")]
    NoParts,
    #[error("{file} is not a part written by `thud sweep --shard` ({why})")]
    NotAPart { file: String, why: String },
    #[error("{file} is a part of format version {found}; this thud reads version {FORMAT_VERSION}")]
    FormatVersion { file: String, found: String },
    #[error("{file}: {why}")]
    Invalid { file: String, why: String },
    #[error("{file} line {line}: {why}")]
    BadCell { file: String, line: usize, why: String },
    #[error(
        "{file} holds {have} of the {want} cells of shard {k_of_n} (cells {first}–{last}); was it cut short? Run shard {k_of_n} again"
    )]
    Incomplete { file: String, k_of_n: String, have: usize, want: usize, first: usize, last: usize },
    #[error("{file} is from a different study than {first_file} (grid, design, thresholds, band or ensemble differ: {hash} vs {first_hash})")]
    DifferentStudy { file: String, first_file: String, hash: String, first_hash: String },
    #[error("{file} was computed by thud {version} but {first_file} by thud {first_version}; compute every part with one thud")]
    DifferentVersion { file: String, first_file: String, version: String, first_version: String },
    #[error("{file} is shard {k_of_n} but {first_file} is shard {first_k_of_n}: parts of different splits")]
    DifferentSplit { file: String, first_file: String, k_of_n: String, first_k_of_n: String },
    #[error("{file} repeats shard {k_of_n}, already given as {other}")]
    Doubled { file: String, other: String, k_of_n: String },
    #[error("{}", missing_message(.missing, *.shards))]
    Missing { missing: Vec<usize>, shards: usize },
}

/// "shard 4/7 is missing" / "shards 1/7, 4/7 are missing", listing at most 8.
fn missing_message(missing: &[usize], n: usize) -> String {
    let listed: Vec<String> = missing.iter().take(8).map(|k| format!("{k}/{n}")).collect();
    let more = if missing.len() > 8 { format!(" and {} more", missing.len() - 8) } else { String::new() };
    let (noun, verb) = if missing.len() == 1 { ("shard", "is") } else { ("shards", "are") };
    format!(
        "{noun} {}{more} {verb} missing; run {} and merge again",
        listed.join(", "),
        if missing.len() == 1 { "it" } else { "them" }
    )
}

/// What serde_json says is wrong, without its "at line L column C" (the line is the file's, not
/// its) and with every quoted value cut to 40 characters, so the reason after a long value
/// stays on the message's one line.
fn serde_reason(e: &serde_json::Error) -> String {
    let text = e.to_string();
    let what = text.split(" at line ").next().unwrap_or(&text);
    let mut out = String::new();
    let mut parts = what.split('"');
    if let Some(first) = parts.next() {
        out.push_str(first);
    }
    for (i, p) in parts.enumerate() {
        out.push('"');
        out.push_str(&if i % 2 == 0 { cut(p, 40) } else { p.to_string() });
    }
    out
}

/// `s` cut to `max` characters with "…" when longer.
fn cut(s: &str, max: usize) -> String {
    if s.chars().count() <= max {
        s.to_string()
    } else {
        s.chars().take(max - 1).chain(['…']).collect()
    }
}

/// A number as a CSV field: Rust's shortest round-trip form; "" for none.
fn field(v: Option<f64>) -> String {
    v.map_or_else(String::new, |x| x.to_string())
}

/// A part as JSON lines: `header` on the first line, then one line per record of `rows` (the
/// chart's, a study's and a bifurcation's parts alike).
pub fn json_lines<R: Serialize>(header: &impl Serialize, rows: &[R]) -> Result<String, std::io::Error> {
    let mut s = serde_json::to_string(header)?;
    s.push('\n');
    for r in rows {
        s += &serde_json::to_string(r)?;
        s.push('\n');
    }
    Ok(s)
}

/// The text of a part: `header`, then `cells` (in index order) in `format`.
pub fn write(format: Format, header: &Header, cells: &[PartCell]) -> Result<String, csv::Error> {
    match format {
        Format::JsonLines => Ok(json_lines(header, cells)?),
        Format::Csv => {
            let mut w = csv::WriterBuilder::new().has_headers(false).from_writer(Vec::new());
            w.write_record(csv_header())?;
            for c in cells {
                for (k, r) in c.runs.iter().enumerate() {
                    let truncated = r.truncated.map(|t| {
                        serde_json::to_value(t).ok().and_then(|v| v.as_str().map(str::to_string)).unwrap_or_default()
                    });
                    w.write_record([
                        c.index.to_string(),
                        k.to_string(),
                        c.mass_kg.to_string(),
                        c.gap_m.to_string(),
                        r.ball_position_m.to_string(),
                        r.metrics.n_impacts.to_string(),
                        field(r.metrics.inclination_cm_s),
                        field(r.metrics.inclination_fit_cm_s),
                        r.metrics.u0_max_m_s.to_string(),
                        r.metrics.zdot_abs_max_m_s.to_string(),
                        field(r.metrics.spl_max_db),
                        field(r.metrics.contact_duration_s),
                        field(r.metrics.restitution_mean),
                        r.metrics.zone.map_or_else(String::new, |z| z.number().to_string()),
                        truncated.unwrap_or_default(),
                    ])?;
                }
            }
            let bytes = w.into_inner().map_err(|e| csv::Error::from(e.into_error()))?;
            let table = String::from_utf8(bytes)
                .map_err(|e| csv::Error::from(std::io::Error::new(std::io::ErrorKind::InvalidData, e.utf8_error())))?;
            let head = serde_json::to_string(header).map_err(std::io::Error::from)?;
            Ok(format!("# {head}\n{table}"))
        }
    }
}

/// A part as read back.
#[derive(Debug, Clone, PartialEq)]
pub struct Part {
    pub format: Format,
    pub header: Header,
    pub cells: Vec<PartCell>,
}

/// Reads the part `text` of the file the user named `file`, and checks it on its own: the
/// header (format, version, ranges, hash, K/N and the cell range), then exactly the header's
/// cells in order, each at its grid point with its N runs at their offsets.
pub fn parse(file: &str, text: &str) -> Result<Part, ShardError> {
    let (first, rest) = text.split_once('\n').unwrap_or((text, ""));
    let (format, header) = parse_header(file, first)?;
    let cells = parse_cells(file, format, &header, rest)?;
    Ok(Part { format, header, cells })
}

/// Reads and checks the first line of a part alone (nothing of its cells): what it is, its
/// version, every value of its study in its flag's range (so a forged ensemble of 2^63 or a
/// grid of 1e12 points is refused before anything is sized by it), its hash and its K/N.
pub fn parse_header(file: &str, first: &str) -> Result<(Format, Header), ShardError> {
    let (format, head) = match first.strip_prefix("# ") {
        Some(h) => (Format::Csv, h),
        None => (Format::JsonLines, first),
    };
    let not_a_part = |why: String| ShardError::NotAPart { file: file.to_string(), why };
    let value: serde_json::Value =
        serde_json::from_str(head).map_err(|_| not_a_part("its first line is not a shard header".into()))?;
    if value.get("format").and_then(|f| f.as_str()) != Some(FORMAT) {
        return Err(not_a_part(format!("its first line has no \"format\": \"{FORMAT}\"")));
    }
    let version = value.get("format_version");
    if version.and_then(serde_json::Value::as_u64) != Some(u64::from(FORMAT_VERSION)) {
        // Reported as written (1.0, "1", none), never as a number it was read to.
        let found = version.map_or_else(|| "none".to_string(), |v| cut(&v.to_string(), 40));
        return Err(ShardError::FormatVersion { file: file.to_string(), found });
    }
    let header: Header = serde_json::from_value(value).map_err(|e| ShardError::Invalid {
        file: file.to_string(),
        why: format!("the header does not read: {}", serde_reason(&e)),
    })?;
    check_ranges(file, &header.study)?;
    check_header(file, &header)?;
    Ok((format, header))
}

/// The cells of a part after its header line (`rest`), checked against `header`.
pub fn parse_cells(file: &str, format: Format, header: &Header, rest: &str) -> Result<Vec<PartCell>, ShardError> {
    let cells = match format {
        Format::JsonLines => read_json_cells(file, rest)?,
        Format::Csv => read_csv_cells(file, rest)?,
    };
    check_cells(file, header, &cells)?;
    Ok(cells)
}

/// The header on its own: hash, K/N and range consistent with its study.
fn check_header(file: &str, h: &Header) -> Result<(), ShardError> {
    let bad = |why: String| Err(ShardError::Invalid { file: file.to_string(), why });
    if h.hash != h.study.hash() {
        return bad(format!("its hash {} is not that of the study in its header (was the header edited?)", h.hash));
    }
    if h.study.ensemble == 0 || h.cells != h.study.cells() || h.cells == 0 {
        return bad(format!("{} cells of {} runs do not make a chart", h.cells, h.study.ensemble));
    }
    if h.shards == 0 || h.shard >= h.shards || h.shards > h.cells {
        return bad(format!("shard {} is not a part of {} cells", h.k_of_n(), h.cells));
    }
    let range = design::shard_range(h.cells, h.shard, h.shards);
    if (h.first_cell, h.end_cell) != (range.start, range.end) {
        return bad(format!(
            "shard {} of {} cells is cells {}–{}, not {}–{}",
            h.k_of_n(),
            h.cells,
            range.start,
            range.end - 1,
            h.first_cell,
            h.end_cell.saturating_sub(1)
        ));
    }
    Ok(())
}

/// Every value of a header's study in the range of the flag that sets it.
fn check_ranges(file: &str, s: &Study) -> Result<(), ShardError> {
    let bad = |e: crate::error::ThudError| ShardError::Invalid {
        file: file.to_string(),
        why: format!("its header is out of range ({e}); was it edited?"),
    };
    let count = |n: usize| n as f64;
    limits::ENSEMBLE.check(count(s.ensemble)).map_err(bad)?;
    limits::GRID_N.check_as("masses", count(s.masses_kg.len())).map_err(bad)?;
    limits::GRID_N.check_as("gaps", count(s.gaps_m.len())).map_err(bad)?;
    for &m in &s.masses_kg {
        limits::MASS.check(m).map_err(bad)?;
    }
    for &g in &s.gaps_m {
        limits::GAP.check(g).map_err(bad)?;
    }
    limits::BAND.check(s.band_cm_s).map_err(bad)?;
    params::check_design(&s.design).map_err(bad)
}

/// A number of a part's run outside what any run can give: not finite, beyond
/// [`MAX_CELL_MAGNITUDE`], or a negative speed or duration.
#[derive(Debug, Error)]
#[error("{name} {} is out of range (a finite number, {})", crate::units::short(*.value), if *.non_negative { "0 to 1e100" } else { "-1e100 to 1e100" })]
struct CellOutOfRange {
    /// The column (JSON key) of the number.
    name: &'static str,
    value: f64,
    /// Whether the number must be ≥ 0 (speeds, durations, restitution).
    non_negative: bool,
}

/// Every number of a run finite and at most [`MAX_CELL_MAGNITUDE`], speeds and durations ≥ 0.
fn check_member(r: &Member) -> Result<(), CellOutOfRange> {
    let signed =
        [("inclination_cm_s", r.metrics.inclination_cm_s), ("inclination_fit_cm_s", r.metrics.inclination_fit_cm_s)];
    let positive = [
        ("u0_max_m_s", Some(r.metrics.u0_max_m_s)),
        ("zdot_abs_max_m_s", Some(r.metrics.zdot_abs_max_m_s)),
        ("contact_duration_s", r.metrics.contact_duration_s),
        ("restitution_mean", r.metrics.restitution_mean),
    ];
    let any = [("ball_position_m", Some(r.ball_position_m)), ("spl_max_db", r.metrics.spl_max_db)];
    for (name, v, min) in signed
        .iter()
        .chain(&any)
        .map(|(n, v)| (n, v, -MAX_CELL_MAGNITUDE))
        .chain(positive.iter().map(|(n, v)| (n, v, 0.0)))
    {
        if let Some(x) = *v {
            if !x.is_finite() || x < min || x > MAX_CELL_MAGNITUDE {
                return Err(CellOutOfRange { name, value: x, non_negative: min == 0.0 });
            }
        }
    }
    Ok(())
}

/// The cells of a JSON-lines part (`text` after the header line; line numbers from 2, blank
/// lines counted).
fn read_json_cells(file: &str, text: &str) -> Result<Vec<PartCell>, ShardError> {
    text.lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty())
        .map(|(i, l)| {
            let bad = |why: String| ShardError::BadCell { file: file.to_string(), line: i + 2, why };
            let cell: PartCell = serde_json::from_str(l)
                .map_err(|e| bad(format!("not a cell ({}, column {})", serde_reason(&e), e.column())))?;
            cell.runs.iter().try_for_each(check_member).map_err(|e| bad(e.to_string()))?;
            Ok(cell)
        })
        .collect()
}

/// The cells of a CSV part (`text` after the header line), rows grouped by cell index.
// Over 80 lines: one pass over the part's rows, each refusal naming its row and column.
fn read_csv_cells(file: &str, text: &str) -> Result<Vec<PartCell>, ShardError> {
    let mut r = csv::ReaderBuilder::new().has_headers(false).from_reader(text.as_bytes());
    let mut cells: Vec<PartCell> = Vec::new();
    for (i, rec) in r.records().enumerate() {
        // The line in the file: the csv reader's own count (blank lines included) after the
        // header line.
        let at = |p: Option<&csv::Position>| p.map_or(i + 2, |p| usize::try_from(p.line()).unwrap_or(usize::MAX) + 1);
        let line = match &rec {
            Ok(r) => at(r.position()),
            Err(e) => at(e.position()),
        };
        let bad = |why: String| ShardError::BadCell { file: file.to_string(), line, why };
        let rec = rec.map_err(|e| bad(format!("not a CSV row ({e})")))?;
        if i == 0 {
            if rec.iter().ne(csv_header()) {
                return Err(bad(format!("the columns must be {}", csv_header().join(","))));
            }
            continue;
        }
        if rec.len() != CSV_COLUMNS.len() {
            return Err(bad(format!("{} fields; a row has {}", rec.len(), CSV_COLUMNS.len())));
        }
        let num = |j: usize| -> Result<f64, ShardError> {
            rec[j].parse::<f64>().map_err(|_| bad(format!("{} '{}' is not a number", CSV_COLUMNS[j].name, &rec[j])))
        };
        let opt = |j: usize| -> Result<Option<f64>, ShardError> {
            if rec[j].is_empty() {
                Ok(None)
            } else {
                num(j).map(Some)
            }
        };
        let whole = |j: usize| -> Result<usize, ShardError> {
            rec[j]
                .parse::<usize>()
                .map_err(|_| bad(format!("{} '{}' is not a whole number", CSV_COLUMNS[j].name, &rec[j])))
        };
        let zone = match &rec[13] {
            "" => None,
            z => Some(
                z.parse::<u8>()
                    .ok()
                    .and_then(ensemble::zone_from_number)
                    .ok_or_else(|| bad(format!("zone '{z}' is not 1 to 4")))?,
            ),
        };
        let truncated = match &rec[14] {
            "" => None,
            t => Some(
                serde_json::from_value(serde_json::Value::String(t.to_string()))
                    .map_err(|_| bad(format!("truncated '{t}' is not a solver work cap")))?,
            ),
        };
        let (index, run) = (whole(0)?, whole(1)?);
        let member = Member {
            ball_position_m: num(4)?,
            metrics: Metrics {
                n_impacts: whole(5)?,
                inclination_cm_s: opt(6)?,
                inclination_fit_cm_s: opt(7)?,
                u0_max_m_s: num(8)?,
                zdot_abs_max_m_s: num(9)?,
                spl_max_db: opt(10)?,
                contact_duration_s: opt(11)?,
                restitution_mean: opt(12)?,
                zone,
            },
            truncated,
        };
        check_member(&member).map_err(|e| bad(e.to_string()))?;
        let (mass_kg, gap_m) = (num(2)?, num(3)?);
        match cells.last_mut() {
            Some(c) if c.index == index => {
                if run != c.runs.len() || (c.mass_kg, c.gap_m) != (mass_kg, gap_m) {
                    return Err(bad(format!("run {run} of cell {index} is out of order or at another grid point")));
                }
                c.runs.push(member);
            }
            _ => {
                if run != 0 {
                    return Err(bad(format!("cell {index} starts at run {run}, not 0")));
                }
                cells.push(PartCell { index, mass_kg, gap_m, runs: vec![member] });
            }
        }
    }
    Ok(cells)
}

/// The part holds exactly the header's cells, in order, each at its grid point with its runs at
/// their offsets. A part that stops early (the last cells, or the last runs of its last cell,
/// absent: a job killed while writing) is [`ShardError::Incomplete`].
fn check_cells(file: &str, h: &Header, cells: &[PartCell]) -> Result<(), ShardError> {
    let want = h.end_cell - h.first_cell;
    let s = &h.study;
    let bad = |why: String| ShardError::Invalid { file: file.to_string(), why };
    let incomplete = |have: usize| ShardError::Incomplete {
        file: file.to_string(),
        k_of_n: h.k_of_n(),
        have,
        want,
        first: h.first_cell,
        last: h.end_cell - 1,
    };
    for (j, c) in cells.iter().enumerate() {
        let expected = h.first_cell + j;
        if j >= want || c.index != expected {
            return Err(bad(format!(
                "cell {} is not cell {expected} of shard {} (cells {}–{})",
                c.index,
                h.k_of_n(),
                h.first_cell,
                h.end_cell - 1
            )));
        }
        let (m, g) = design_point(s, c.index);
        if (c.mass_kg, c.gap_m) != (m, g) {
            return Err(bad(format!(
                "cell {} is at m {} kg, d {} m; the grid has m {m} kg, d {g} m",
                c.index, c.mass_kg, c.gap_m
            )));
        }
        let last = j + 1 == cells.len();
        if last && c.runs.len() < s.ensemble {
            return Err(incomplete(j));
        }
        let offsets = ensemble::ball_positions(c.gap_m, s.ensemble);
        if c.runs.len() != s.ensemble || c.runs.iter().zip(&offsets).any(|(r, y0)| r.ball_position_m != *y0) {
            return Err(bad(format!(
                "cell {} has {} runs, not the study's {} at the offsets −d/2 + (k + ½)·d/N",
                c.index,
                c.runs.len(),
                s.ensemble
            )));
        }
    }
    if cells.len() < want {
        return Err(incomplete(cells.len()));
    }
    Ok(())
}

/// The (mass, gap) of cell `index` of the study's grid.
fn design_point(s: &Study, index: usize) -> (f64, f64) {
    (s.masses_kg[index % s.masses_kg.len()], s.gaps_m[index / s.masses_kg.len()])
}

/// The parts joined: the study and every cell, in index order.
#[derive(Debug, Clone, PartialEq)]
pub struct Merged {
    pub study: Study,
    pub cells: Vec<PartCell>,
    /// Whether every part was CSV.
    pub all_csv: bool,
}

impl Merged {
    /// The ordinary chart (a study of one run per cell): each cell's metrics are its run's.
    #[must_use]
    pub fn chart(&self) -> Chart {
        let mut chart = Chart::empty(self.study.masses_kg.clone(), self.study.gaps_m.clone(), self.thresholds());
        for c in &self.cells {
            chart.cells[c.index] =
                c.runs.first().map(|r| Cell { mass_kg: c.mass_kg, gap_m: c.gap_m, metrics: r.metrics });
        }
        chart
    }

    /// The chart of ensembles, each cell's summary recomputed from its runs by the engine (the
    /// runs move into it: a merged chart is held in memory once).
    #[must_use]
    pub fn into_ensemble_chart(self) -> EnsembleChart {
        let t = self.thresholds();
        let mut chart = EnsembleChart::empty(self.study.masses_kg, self.study.gaps_m, self.study.ensemble, t);
        for c in self.cells {
            let ensemble = Ensemble::from_members(c.runs, &t);
            chart.cells[c.index] = Some(EnsembleCell { mass_kg: c.mass_kg, gap_m: c.gap_m, ensemble });
        }
        chart
    }

    fn thresholds(&self) -> design::Thresholds {
        self.study.design.thresholds
    }
}

/// Checks the headers of a set of parts together (each with the file name the user gave): one
/// study, one thud version, one split, every K exactly once. Needs only the headers, so a set
/// is refused before any cell is read.
pub fn check_set<'a>(headers: impl IntoIterator<Item = (&'a str, &'a Header)>) -> Result<(), ShardError> {
    let mut headers = headers.into_iter();
    let Some((first_file, first)) = headers.next() else {
        return Err(ShardError::NoParts);
    };
    let mut by_k: BTreeMap<usize, String> = BTreeMap::new();
    by_k.insert(first.shard, first_file.to_string());
    for (file, h) in headers {
        if h.hash != first.hash {
            return Err(ShardError::DifferentStudy {
                file: file.to_string(),
                first_file: first_file.to_string(),
                hash: short_hash(&h.hash),
                first_hash: short_hash(&first.hash),
            });
        }
        if h.thud_version != first.thud_version {
            return Err(ShardError::DifferentVersion {
                file: file.to_string(),
                first_file: first_file.to_string(),
                version: h.thud_version.clone(),
                first_version: first.thud_version.clone(),
            });
        }
        if h.shards != first.shards {
            return Err(ShardError::DifferentSplit {
                file: file.to_string(),
                first_file: first_file.to_string(),
                k_of_n: h.k_of_n(),
                first_k_of_n: first.k_of_n(),
            });
        }
        if let Some(other) = by_k.insert(h.shard, file.to_string()) {
            return Err(ShardError::Doubled { file: file.to_string(), other, k_of_n: h.k_of_n() });
        }
    }
    let missing: Vec<usize> = (0..first.shards).filter(|k| !by_k.contains_key(k)).collect();
    if !missing.is_empty() {
        return Err(ShardError::Missing { missing, shards: first.shards });
    }
    Ok(())
}

/// Joins `parts` (each with the file name the user gave) after [`check_set`].
pub fn merge(parts: Vec<(String, Part)>) -> Result<Merged, ShardError> {
    check_set(parts.iter().map(|(f, p)| (f.as_str(), &p.header)))?;
    let study = parts[0].1.header.study.clone();
    let all_csv = parts.iter().all(|(_, p)| p.format == Format::Csv);
    let mut ordered: Vec<Part> = parts.into_iter().map(|(_, p)| p).collect();
    ordered.sort_by_key(|p| p.header.shard);
    let cells = ordered.into_iter().flat_map(|p| p.cells).collect();
    Ok(Merged { study, cells, all_csv })
}

/// The first 12 hex digits of a hash, for messages.
fn short_hash(h: &str) -> String {
    let hex = h.strip_prefix("sha256:").unwrap_or(h);
    format!("{}…", hex.chars().take(12).collect::<String>())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn study(ensemble: usize) -> Study {
        let mut design = Design::default();
        design.damper.duration_s = 0.2;
        Study { design, masses_kg: vec![0.03, 0.05, 0.07], gaps_m: vec![0.02, 0.03], band_cm_s: 0.2, ensemble }
    }

    /// The parts of `study` as `sweep --shard k/n` computes them.
    fn parts(s: &Study, n: usize, format: Format) -> Vec<(String, String)> {
        (0..n)
            .map(|k| {
                let h = Header::new(s.clone(), k, n);
                let cells: Vec<PartCell> = ensemble::sweep_cells(
                    &s.design.clone().check().unwrap(),
                    &s.masses_kg,
                    &s.gaps_m,
                    s.ensemble,
                    h.first_cell..h.end_cell,
                    None,
                    &|_, _| {},
                )
                .unwrap()
                .iter()
                .map(|(i, c)| PartCell::new(*i, c))
                .collect();
                (format!("part{k}"), write(format, &h, &cells).unwrap())
            })
            .collect()
    }

    fn read(parts: &[(String, String)]) -> Result<Merged, ShardError> {
        let parsed: Result<Vec<(String, Part)>, ShardError> =
            parts.iter().map(|(f, t)| parse(f, t).map(|p| (f.clone(), p))).collect();
        merge(parsed?)
    }

    #[test]
    fn the_hash_names_the_study() {
        let s = study(1);
        assert_eq!(s.hash(), study(1).hash());
        assert!(s.hash().starts_with("sha256:") && s.hash().len() == 7 + 64);
        let mut other = study(1);
        other.design.thresholds.spl_db += 1.0;
        assert_ne!(other.hash(), s.hash(), "a threshold");
        let mut other = study(1);
        other.gaps_m[1] = 0.0300000001;
        assert_ne!(other.hash(), s.hash(), "a grid point");
        assert_ne!(study(2).hash(), s.hash(), "the ensemble");
    }

    #[test]
    fn merged_parts_are_the_whole_chart_in_both_formats() {
        for ens in [1, 3] {
            let s = study(ens);
            let whole =
                ensemble::sweep(&s.design.clone().check().unwrap(), &s.masses_kg, &s.gaps_m, ens, None, &|_, _| {})
                    .unwrap();
            for format in [Format::JsonLines, Format::Csv] {
                for n in [1, 4, 6] {
                    let m = read(&parts(&s, n, format)).unwrap();
                    assert_eq!(m.study, s);
                    assert_eq!(m.clone().into_ensemble_chart(), whole, "{ens} runs, {n} parts, {format:?}");
                    assert_eq!(m.all_csv, format == Format::Csv);
                }
            }
        }
        let s = study(1);
        let plain =
            design::sweep(&s.design.clone().check().unwrap(), &s.masses_kg, &s.gaps_m, None, &|_, _| {}).unwrap();
        assert_eq!(read(&parts(&s, 5, Format::Csv)).unwrap().chart(), plain);
    }

    #[test]
    fn missing_doubled_and_foreign_parts_are_named() {
        let s = study(1);
        let p = parts(&s, 3, Format::JsonLines);
        let e = read(&[p[0].clone(), p[2].clone()]).unwrap_err();
        assert_eq!(e.to_string(), "shard 1/3 is missing; run it and merge again");
        let e = read(&[p[0].clone(), p[1].clone(), p[1].clone(), p[2].clone()]).unwrap_err();
        assert_eq!(e.to_string(), "part1 repeats shard 1/3, already given as part1");
        let four = parts(&s, 4, Format::JsonLines);
        let e = read(&[p[0].clone(), four[1].clone()]).unwrap_err().to_string();
        assert_eq!(e, "part1 is shard 1/4 but part0 is shard 0/3: parts of different splits");
        let mut other = study(1);
        other.band_cm_s = 0.3;
        let q = parts(&other, 3, Format::JsonLines);
        let e = read(&[p[0].clone(), q[1].clone(), p[2].clone()]).unwrap_err().to_string();
        assert!(e.starts_with("part1 is from a different study than part0"), "{e}");
        assert!(matches!(read(&[]), Err(ShardError::NoParts)));
    }

    #[test]
    fn a_part_cut_short_or_edited_is_refused() {
        let s = study(2);
        for format in [Format::JsonLines, Format::Csv] {
            let (f, text) = parts(&s, 2, format).remove(1);
            let cut: String = text.lines().take(text.lines().count() - 1).map(|l| format!("{l}\n")).collect();
            let e = parse(&f, &cut).unwrap_err().to_string();
            assert!(e.contains("holds 2 of the 3 cells of shard 1/2 (cells 3–5)"), "{format:?}: {e}");
            let edited = text.replacen("\"spl_db\":103.0", "\"spl_db\":90.0", 1);
            assert_ne!(edited, text);
            let e = parse(&f, &edited).unwrap_err().to_string();
            assert!(e.contains("was the header edited?"), "{e}");
            assert!(parse(&f, "mass_kg,gap_m\n1,2\n").unwrap_err().to_string().contains("is not a part written by"));
        }
        let (f, text) = parts(&s, 2, Format::JsonLines).remove(0);
        let newer = text.replacen("\"format_version\":1", "\"format_version\":2", 1);
        assert_eq!(
            parse(&f, &newer).unwrap_err().to_string(),
            "part0 is a part of format version 2; this thud reads version 1"
        );
    }

    #[test]
    fn csv_numbers_read_back_to_the_same_bits() {
        let s = study(1);
        let (f, text) = parts(&s, 1, Format::Csv).remove(0);
        let (_, json) = parts(&s, 1, Format::JsonLines).remove(0);
        assert_eq!(parse(&f, &text).unwrap().cells, parse(&f, &json).unwrap().cells);
    }
}
