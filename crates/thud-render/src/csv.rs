//! CSV files: a header of keys with their SI unit in the name, then one row per point. One writer
//! for every table thud prints or saves: the `csv` crate, fed serde rows, so quoting is the
//! same everywhere (a field with a comma, a quote or a line break is quoted). Numbers are written
//! in full precision in Rust's shortest round-trip form (`0.00001`, not `1e-5`), so they parse
//! back to the same `f64`.

use std::io::Write;

use serde::{Serialize, Serializer};

use crate::acoustics::Field;
use crate::damper::{free_response, DamperParams, Run};
use crate::design::{Chart, Metrics};
use crate::ensemble::{EnsembleChart, Percentiles};
use crate::paper::{Table, Value};
use thud_core::schema;

/// A number as CSV writes it: Rust's `Display` (shortest round trip, never an exponent).
#[derive(Debug, Clone, Copy)]
struct Num(f64);

impl Serialize for Num {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(&self.0)
    }
}

/// `header`, then one record per row, as text.
fn to_csv<R: Serialize>(header: &[&str], rows: impl IntoIterator<Item = R>) -> Result<String, csv::Error> {
    let mut w = csv::WriterBuilder::new().has_headers(false).from_writer(Vec::new());
    w.write_record(header)?;
    for row in rows {
        w.serialize(row)?;
    }
    into_string(w)
}

/// The header of the schema's `table`, then one record per row (each row type's fields are
/// the table's columns in order; the tests below check it).
fn table_csv<R: Serialize>(table: &schema::Table, rows: impl IntoIterator<Item = R>) -> Result<String, csv::Error> {
    to_csv(&table.names(), rows)
}

/// The text of a writer over memory.
fn into_string(w: csv::Writer<Vec<u8>>) -> Result<String, csv::Error> {
    let bytes = w.into_inner().map_err(|e| csv::Error::from(e.into_error()))?;
    String::from_utf8(bytes)
        .map_err(|e| csv::Error::from(std::io::Error::new(std::io::ErrorKind::InvalidData, e.utf8_error())))
}

#[derive(Serialize)]
struct WaveformRow {
    t_s: Num,
    p_pa: Num,
}

/// The pressure waveform of one impact, `n` uniform samples: `t_s,p_pa` (time after the
/// contact starts, so the first sound arrives at the propagation delay).
pub fn waveform(field: &Field, n: usize) -> Result<String, csv::Error> {
    let (t, p) = field.waveform(n);
    table_csv(&schema::PULSE, t.iter().zip(&p).map(|(&t, &p)| WaveformRow { t_s: Num(t), p_pa: Num(p) }))
}

#[derive(Serialize)]
struct HistoryRow {
    t_s: Num,
    x_m: Num,
    y_m: Num,
    x_free_m: Num,
}

/// The time history of a run: `t_s,x_m,y_m,x_free_m`, with the main mass's motion without the
/// damper (`x_free_m`) beside it.
pub fn history(run: &Run, damper: &DamperParams) -> Result<String, csv::Error> {
    table_csv(
        &schema::HISTORY,
        run.history.iter().map(|h| HistoryRow {
            t_s: Num(h.t_s),
            x_m: Num(h.x_m),
            y_m: Num(h.y_m),
            x_free_m: Num(free_response(damper, h.t_s)),
        }),
    )
}

#[derive(Serialize)]
struct ImpactRow {
    t_s: Num,
    wall: i8,
    u_in_m_s: Num,
    u_out_m_s: Num,
    restitution: Num,
    t_end_s: Num,
    duration_s: Num,
    penetration_max_m: Num,
    spl_db: Option<Num>,
}

/// The impacts of a run with the SPL of each (`spl_db[k]` for impact k, dB re 20 µPa, rms
/// over τ from the direct arrival).
pub fn impacts(run: &Run, spl_db: &[f64]) -> Result<String, csv::Error> {
    table_csv(
        &schema::IMPACTS,
        run.impacts.iter().enumerate().map(|(k, i)| ImpactRow {
            t_s: Num(i.t_s),
            wall: i.wall.into(),
            u_in_m_s: Num(i.u_in_m_s),
            u_out_m_s: Num(i.u_out_m_s),
            restitution: Num(i.u_out_m_s / i.u_in_m_s),
            t_end_s: Num(i.t_end_s),
            duration_s: Num(i.t_end_s - i.t_s),
            penetration_max_m: Num(i.penetration_max_m),
            spl_db: spl_db.get(k).copied().map(Num),
        }),
    )
}

#[derive(Serialize)]
struct SweepRow {
    mass_kg: Num,
    gap_m: Num,
    /// The cell's metrics (written in place: no header is serialized).
    metrics: MetricsRow,
}

impl SweepRow {
    /// The row of the cell at (`mass_kg`, `gap_m`) with metrics `m`.
    fn new(mass_kg: f64, gap_m: f64, m: &Metrics) -> Self {
        SweepRow { mass_kg: Num(mass_kg), gap_m: Num(gap_m), metrics: m.into() }
    }
}

/// The design chart, one row per computed cell (mass × gap).
pub fn sweep(chart: &Chart) -> Result<String, csv::Error> {
    table_csv(&schema::SWEEP, chart.cells.iter().flatten().map(|c| SweepRow::new(c.mass_kg, c.gap_m, &c.metrics)))
}

#[derive(Serialize)]
struct EnsembleSweepRow {
    mass_kg: Num,
    gap_m: Num,
    runs: usize,
    /// The medians as a design's metrics (written in place: no header is serialized).
    medians: MetricsRow,
    inclination_cm_s: Three,
    inclination_fit_cm_s: Three,
    u0_max_m_s: Three,
    spl_max_db: Three,
    zone3_probability: Num,
    agreement: Num,
}

#[derive(Serialize)]
struct MetricsRow {
    n_impacts: usize,
    inclination_cm_s: Option<Num>,
    inclination_fit_cm_s: Option<Num>,
    u0_max_m_s: Num,
    zdot_abs_max_m_s: Num,
    spl_max_db: Option<Num>,
    contact_duration_s: Option<Num>,
    restitution_mean: Option<Num>,
    zone: Option<u8>,
}

impl From<&Metrics> for MetricsRow {
    fn from(m: &Metrics) -> Self {
        MetricsRow {
            n_impacts: m.n_impacts,
            inclination_cm_s: m.inclination_cm_s.map(Num),
            inclination_fit_cm_s: m.inclination_fit_cm_s.map(Num),
            u0_max_m_s: Num(m.u0_max_m_s),
            zdot_abs_max_m_s: Num(m.zdot_abs_max_m_s),
            spl_max_db: m.spl_max_db.map(Num),
            contact_duration_s: m.contact_duration_s.map(Num),
            restitution_mean: m.restitution_mean.map(Num),
            zone: m.zone.map(thud_core::design::Zone::number),
        }
    }
}

/// The design chart of ensembles, one row per computed cell: a cell of `sweep --ensemble N
/// --json` flattened (schema `sweep_ensemble`): mass, gap, runs, the medians as metrics (the
/// zone that of the medians), the p10, median and p90 of e, e_fit, U0max and SPLmax, the
/// zone-3 probability and the agreement.
pub fn sweep_ensemble(chart: &EnsembleChart) -> Result<String, csv::Error> {
    table_csv(
        &schema::SWEEP_ENSEMBLE,
        chart.cells.iter().flatten().map(|c| {
            let (e, s) = (&c.ensemble, &c.ensemble.spread);
            EnsembleSweepRow {
                mass_kg: Num(c.mass_kg),
                gap_m: Num(c.gap_m),
                runs: e.runs,
                medians: (&e.metrics).into(),
                inclination_cm_s: (&s.inclination_cm_s).into(),
                inclination_fit_cm_s: (&s.inclination_fit_cm_s).into(),
                u0_max_m_s: (&s.u0_max_m_s).into(),
                spl_max_db: (&s.spl_max_db).into(),
                zone3_probability: Num(e.zone3_probability),
                agreement: Num(e.agreement),
            }
        }),
    )
}

#[derive(Serialize)]
struct MemberRow {
    ball_position_m: Num,
    /// The run's metrics (written in place: no header is serialized).
    metrics: MetricsRow,
}

/// The runs of one design's ensemble, one row each: the ball's initial offset and the run's
/// metrics.
pub fn ensemble_members(members: &[crate::ensemble::Member]) -> Result<String, csv::Error> {
    table_csv(
        &schema::ENSEMBLE,
        members.iter().map(|r| MemberRow { ball_position_m: Num(r.ball_position_m), metrics: (&r.metrics).into() }),
    )
}

#[derive(Serialize)]
struct ResponseRow {
    direction: &'static str,
    freq_hz: Num,
    periods: u32,
    window_start_s: Num,
    window_end_s: Num,
    amplitude_m: Num,
    amplitude_linear_m: Option<Num>,
    reduction_db: Option<Num>,
    impacts_per_period: Num,
    leq_db: Option<Num>,
    periodic: bool,
    settled: bool,
    truncated: bool,
    verdict: String,
    final_time_s: Num,
}

/// A frequency response, one row per frequency and sweep (`from_rest`, or `up` and `down`);
/// an empty cell where a value does not exist (no linear amplitude at an undamped resonance,
/// no level without impacts).
pub fn response(r: &crate::response::Response) -> Result<String, csv::Error> {
    table_csv(
        &schema::RESPONSE,
        r.sweeps.iter().flat_map(|sw| {
            sw.points.iter().map(move |p| {
                let st = &p.steady;
                ResponseRow {
                    direction: sweep_name(sw.direction),
                    freq_hz: Num(p.freq_hz),
                    periods: st.periods,
                    window_start_s: Num(st.window_start_s),
                    window_end_s: Num(st.window_end_s),
                    amplitude_m: Num(st.amplitude_m),
                    amplitude_linear_m: st.amplitude_linear_m.map(Num),
                    reduction_db: st.reduction_db.map(Num),
                    impacts_per_period: Num(st.impacts_per_period),
                    leq_db: st.leq_db.map(Num),
                    periodic: st.periodic,
                    settled: st.settled,
                    truncated: st.truncated,
                    verdict: st.verdict.label(),
                    final_time_s: Num(p.final_time_s),
                }
            })
        }),
    )
}

/// One cell of a table: numbers in full, text as it is (the writer quotes it when needed),
/// nothing for a missing value.
fn cell(v: &Value) -> String {
    match v {
        Value::Num(x) => x.to_string(),
        Value::Text(s) => s.clone(),
        Value::Missing => String::new(),
    }
}

/// Writes a reproduced paper table to `out`: a header of column keys, then the rows. The one
/// table writer of both `thud paper ID --csv` and `thud paper all`.
pub fn write_table(out: impl Write, t: &Table) -> Result<(), csv::Error> {
    let mut w = csv::WriterBuilder::new().flexible(true).from_writer(out);
    w.write_record(t.columns.iter().map(|c| c.key))?;
    for row in &t.rows {
        w.write_record(row.iter().map(cell))?;
    }
    w.flush()?;
    Ok(())
}

/// A CSV error as an I/O error, keeping the kind of one that was I/O (a closed pipe stays
/// `BrokenPipe`).
pub fn into_io(e: csv::Error) -> std::io::Error {
    if !e.is_io_error() {
        return std::io::Error::other(e);
    }
    match e.into_kind() {
        csv::ErrorKind::Io(io) => io,
        kind => std::io::Error::other(format!("{kind:?}")),
    }
}

/// A reproduced paper table as CSV text (see [`write_table`]).
pub fn table(t: &Table) -> Result<String, csv::Error> {
    let mut bytes = Vec::new();
    write_table(&mut bytes, t)?;
    String::from_utf8(bytes)
        .map_err(|e| csv::Error::from(std::io::Error::new(std::io::ErrorKind::InvalidData, e.utf8_error())))
}

/// The three figures of one metric: p10, median, p90 (an empty cell for "none").
#[derive(Serialize)]
struct Three(Option<Num>, Option<Num>, Option<Num>);

impl From<&Percentiles> for Three {
    fn from(p: &Percentiles) -> Self {
        Three(p.p10.map(Num), p.median.map(Num), p.p90.map(Num))
    }
}

#[derive(Serialize)]
struct ResponseEnsembleRow {
    direction: &'static str,
    freq_hz: Num,
    runs: usize,
    amplitude_linear_m: Option<Num>,
    amplitude_m: Three,
    reduction_db: Three,
    impacts_per_period: Three,
    leq_db: Three,
    periodic_fraction: Num,
    settled_fraction: Num,
    truncated: bool,
}

/// A frequency response of ensembles, one row per frequency and sweep: the p10, median and p90
/// of each steady figure over the runs (an empty cell where a value does not exist).
pub fn response_ensemble(r: &crate::response::ResponseEnsemble) -> Result<String, csv::Error> {
    table_csv(
        &schema::RESPONSE_ENSEMBLE,
        r.sweeps.iter().flat_map(|sw| {
            sw.points.iter().map(move |p| ResponseEnsembleRow {
                direction: sweep_name(sw.direction),
                freq_hz: Num(p.freq_hz),
                runs: p.ensemble.len(),
                amplitude_linear_m: p.amplitude_linear_m.map(Num),
                amplitude_m: (&p.spread.amplitude_m).into(),
                reduction_db: (&p.spread.reduction_db).into(),
                impacts_per_period: (&p.spread.impacts_per_period).into(),
                leq_db: (&p.spread.leq_db).into(),
                periodic_fraction: Num(p.periodic_fraction),
                settled_fraction: Num(p.settled_fraction),
                truncated: p.truncated,
            })
        }),
    )
}

/// The name of a sweep of a response in CSV files (its `direction` in the JSON).
fn sweep_name(d: crate::response::Direction) -> &'static str {
    use crate::response::Direction;
    match d {
        Direction::FromRest => "from_rest",
        Direction::Up => "up",
        Direction::Down => "down",
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::paper::col;

    /// The header a row type writes itself (its field names), to check the constants.
    fn serde_header<R: Serialize>(row: R) -> String {
        let mut w = csv::Writer::from_writer(Vec::new());
        w.serialize(row).unwrap();
        String::from_utf8(w.into_inner().unwrap()).unwrap().lines().next().unwrap().to_string()
    }

    #[test]
    fn each_header_is_its_row_type_s_field_names() {
        let n = Num(0.0);
        let head = |t: &schema::Table| t.names().join(",");
        assert_eq!(serde_header(WaveformRow { t_s: n, p_pa: n }), head(&schema::PULSE));
        assert_eq!(serde_header(HistoryRow { t_s: n, x_m: n, y_m: n, x_free_m: n }), head(&schema::HISTORY));
        let imp = ImpactRow {
            t_s: n,
            wall: 1,
            u_in_m_s: n,
            u_out_m_s: n,
            restitution: n,
            t_end_s: n,
            duration_s: n,
            penetration_max_m: n,
            spl_db: None,
        };
        assert_eq!(serde_header(imp), head(&schema::IMPACTS));
        // The metrics' columns close a chart cell's row and an ensemble member's.
        let metrics = crate::design::Metrics { n_impacts: 7, ..Default::default() };
        let names = |t: &schema::Table, skip: usize| t.names()[skip..].join(",");
        assert_eq!(serde_header(MetricsRow::from(&metrics)), names(&schema::SWEEP, 2));
        assert_eq!(serde_header(MetricsRow::from(&metrics)), names(&schema::ENSEMBLE, 1));
        // Before them, a cell's mass and gap and a member's ball offset, each one column.
        let cell = record(SweepRow::new(1.5, 2.5, &metrics));
        assert_eq!(cell.len(), schema::SWEEP.names().len());
        assert_eq!(cell[..3], ["1.5", "2.5", "7"]);
        let member = record(MemberRow { ball_position_m: Num(-0.5), metrics: (&metrics).into() });
        assert_eq!(member.len(), schema::ENSEMBLE.names().len());
        assert_eq!(member[..2], ["-0.5", "7"]);
    }

    /// The cells a row type writes, without a header.
    fn record<R: Serialize>(row: R) -> Vec<String> {
        let mut w = csv::WriterBuilder::new().has_headers(false).from_writer(Vec::new());
        w.serialize(row).unwrap();
        let line = String::from_utf8(w.into_inner().unwrap()).unwrap();
        line.trim_end().split(',').map(str::to_string).collect()
    }

    #[test]
    fn an_ensemble_chart_row_is_mass_gap_runs_the_medians_then_the_spread() {
        let mut d = crate::design::Design::default();
        d.damper.duration_s = 0.2;
        let chart = crate::ensemble::sweep(&d.check().unwrap(), &[0.03, 0.05], &[0.03], 3, None, &|_, _| {}).unwrap();
        let text = sweep_ensemble(&chart).unwrap();
        let medians = sweep(&chart.medians()).unwrap();
        let mut r = csv::Reader::from_reader(text.as_bytes());
        let head: Vec<String> = r.headers().unwrap().iter().map(str::to_string).collect();
        assert_eq!(head, schema::SWEEP_ENSEMBLE.names());
        for (line, want) in text.lines().zip(medians.lines()).skip(1) {
            // mass, gap, runs, then the medians' metrics: the sweep row with the runs inserted.
            let cells: Vec<&str> = want.split(',').collect();
            let with_runs = format!("{},{},3,{},", cells[0], cells[1], cells[2..].join(","));
            assert!(line.starts_with(&with_runs), "{line} / {with_runs}");
        }
        let rows: Vec<csv::StringRecord> = r.records().map(Result::unwrap).collect();
        assert_eq!(rows.len(), 2);
        let c = chart.cell(1, 0).unwrap();
        let col = |k: &str| head.iter().position(|h| h == k).unwrap();
        assert_eq!(rows[1][col("zone3_probability")].parse::<f64>().unwrap(), c.ensemble.zone3_probability);
        assert_eq!(rows[1][col("spl_max_db_p90")].parse::<f64>().ok(), c.ensemble.spread.spl_max_db.p90);
        assert_eq!(rows[1][col("u0_max_m_s_median")].parse::<f64>().ok(), c.ensemble.spread.u0_max_m_s.median);
    }

    #[test]
    fn numbers_are_written_in_full_without_exponents() {
        let s = to_csv(&["a", "b"], [WaveformRow { t_s: Num(1e-5), p_pa: Num(-2.5) }]).unwrap();
        assert_eq!(s, "a,b\n0.00001,-2.5\n");
        assert_eq!(to_csv::<WaveformRow>(&["a", "b"], []).unwrap(), "a,b\n", "the header even with no rows");
    }

    #[test]
    fn text_with_commas_quotes_or_line_breaks_is_quoted_the_same_way_everywhere() {
        let t = Table {
            id: "t",
            title: "t".into(),
            columns: vec![col("a", "a"), col("b", "b")],
            rows: vec![
                vec![Value::Text("x, y".into()), Value::Num(0.5)],
                vec![Value::Text("say \"hi\"".into()), Value::Missing],
                vec![Value::Text("two\nlines".into()), Value::Text("plain".into())],
            ],
            notes: vec![],
            summary: Vec::new(),
        };
        let s = table(&t).unwrap();
        assert_eq!(s, "a,b\n\"x, y\",0.5\n\"say \"\"hi\"\"\",\n\"two\nlines\",plain\n");
        let mut r = csv::Reader::from_reader(s.as_bytes());
        let rows: Vec<csv::StringRecord> = r.records().map(Result::unwrap).collect();
        assert_eq!(rows.len(), 3, "a line break inside a field does not start a row");
        assert_eq!(&rows[2][0], "two\nlines");
    }
}
