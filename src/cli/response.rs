//! `thud response`: the frequency response of a design under a harmonic force — per frequency
//! the steady amplitude with the damper and without it, the impacts per period and the level
//! `Leq` of the rattle (docs/model.md §6.4).

use clap::Args;

use super::budget;
use super::design_args::{parse_range, DesignArgs, ForceFlag};
use super::format::num;
use super::simulate::describe;
use super::{count, CliError, Ctx, Out, OutputArgs, OutputFormat};
use crate::design::{Design, ValidDesign};
use crate::error::ThudError;
use crate::limits::{self, short};
use crate::report::{ResponseEnsembleReport, ResponseReport};
use crate::response::{self, Direction, Response, ResponseEnsemble, ResponseOptions};
use crate::units::Kind;

#[derive(Debug, Clone, Args)]
pub struct ResponseArgs {
    #[command(flatten)]
    design: DesignArgs,
    /// Forcing frequencies FROM:TO:N (Hz, e.g. 3Hz:8Hz:101) [default: 0.6–1.6 × the natural frequency, 101 points].
    #[arg(long, value_name = "FROM:TO:N", allow_hyphen_values = true)]
    freqs: Option<String>,
    /// Start each frequency from the previous one's final state, rising then falling (shows
    /// jumps and hysteresis); without it every frequency starts from rest.
    #[arg(long)]
    continuation: bool,
    /// Runs per frequency from ball offsets spread evenly over the clearance (y0 = −d/2 +
    /// (k + ½)·d/N, at rest): each steady figure as median [p10–p90], with every run (1: the
    /// single trajectory).
    #[arg(long, value_name = "N", default_value = "1", allow_hyphen_values = true)]
    ensemble: String,
    #[command(flatten)]
    output: OutputArgs,
}

/// Refuses a response whose work is over a cap.
pub(crate) fn check_work(
    ctx: &Ctx,
    d: &ValidDesign,
    freqs: &[f64],
    freqs_text: &str,
    continuation: bool,
) -> Result<(), CliError> {
    check_runs_work(ctx, d, freqs, freqs_text, continuation, (1, "1"))
}

/// Refuses a response of `runs` runs per frequency (`runs_text` as typed) whose work is over
/// a cap: the forcing periods and Newmark steps summed over the runs (blaming `--ensemble`
/// when one run alone would be inside the cap), and the cycles of one run.
fn check_runs_work(
    ctx: &Ctx,
    d: &ValidDesign,
    freqs: &[f64],
    freqs_text: &str,
    continuation: bool,
    (runs, runs_text): (usize, &str),
) -> Result<(), CliError> {
    let Err(r) = response::check_response(d, freqs, continuation, runs) else { return Ok(()) };
    let value = match (r.param, d.solver) {
        (limits::RUNS_PARAM, _) => runs_text.to_string(),
        ("dt", crate::damper::Solver::Newmark { dt_s }) => format!("{} s", short(dt_s)),
        _ => freqs_text.to_string(),
    };
    let flag = match r.param {
        limits::RUNS_PARAM => "--ensemble".to_string(),
        param => format!("--{param}"),
    };
    ctx.enforce(r.estimate, &flag, &value, &super::design_args::hint(&r, &flag))
}

/// The design of a response and its frequencies: `--freqs` as typed (`text`), else the
/// engine's default band of the design ([`response::default_freqs_hz`]); with the frequencies
/// as a message shows them (as typed, or the default band as `FROM:TO:N`).
pub(crate) fn response_setup<F: ForceFlag>(
    args: &DesignArgs<F>,
    text: Option<&str>,
) -> Result<(ValidDesign, Vec<f64>, String), ThudError> {
    let typed = text.map(|t| parse_range("freqs", t, Kind::Frequency, &limits::FREQ)).transpose()?;
    let (d, freqs) = args.response_setup(typed)?;
    let shown = text.map_or_else(|| freqs_text(&freqs), str::to_string);
    Ok((d, freqs, shown))
}

/// Frequencies evenly spaced from the first to the last as `FROM:TO:N` (Hz).
pub(crate) fn freqs_text(freqs: &[f64]) -> String {
    let (from, to) = (freqs.first().copied().unwrap_or(0.0), freqs.last().copied().unwrap_or(0.0));
    format!("{}Hz:{}Hz:{}", short(from), short(to), freqs.len())
}

pub fn run(a: &ResponseArgs, ctx: &Ctx, out: &mut Out) -> Result<(), CliError> {
    let (d, freqs, freqs_text) = response_setup(&a.design, a.freqs.as_deref())?;
    let runs = count("ensemble", &a.ensemble, &limits::ENSEMBLE)?;
    a.design.check_ensemble(runs)?;
    check_runs_work(ctx, &d, &freqs, &freqs_text, a.continuation, (runs, &a.ensemble))?;
    let n = (freqs.len() * runs) as u64 * if a.continuation { 2 } else { 1 };
    let bar = budget::bar(n, "response");
    let opts = ResponseOptions { continuation: a.continuation, settle: true };
    if runs > 1 {
        let r = response::response_ensemble(&d, &freqs, runs, &opts, None, &|| bar.inc(1))?;
        bar.finish_and_clear();
        return print_ensemble(&d, &r, a.continuation, a.output.format(), out);
    }
    let r = response::response(&d, &freqs, &opts, None, &|| bar.inc(1))?;
    bar.finish_and_clear();
    match a.output.format() {
        OutputFormat::Json => out.json(&ResponseReport::new(&d, &r, a.continuation))?,
        OutputFormat::Csv => out.text(
            &crate::export::csv::response(&r).map_err(|e| ThudError::invalid("csv", format!("cannot write: {e}")))?,
        )?,
        OutputFormat::Text => {
            super::output::check_finite(&r)?;
            out.text(&text(&d, &r, a.continuation))?;
        }
    }
    Ok(())
}

/// `thud response --ensemble N` (N > 1) in `format`.
fn print_ensemble(
    d: &Design,
    r: &ResponseEnsemble,
    continuation: bool,
    format: OutputFormat,
    out: &mut Out,
) -> Result<(), CliError> {
    match format {
        OutputFormat::Json => out.json(&ResponseEnsembleReport::new(d, r, continuation)),
        OutputFormat::Csv => {
            super::output::check_finite(r)?;
            out.text(
                &crate::export::csv::response_ensemble(r)
                    .map_err(|e| ThudError::invalid("csv", format!("cannot write: {e}")))?,
            )
        }
        OutputFormat::Text => {
            super::output::check_finite(r)?;
            out.text(&ensemble_text(d, r, continuation))
        }
    }
}

/// A response ensemble as a table per sweep (median [p10–p90] of each figure) and a plot of
/// the median runs.
fn ensemble_text(d: &Design, r: &ResponseEnsemble, continuation: bool) -> String {
    let mut s = format!("design    {}\n", describe(d));
    let half = 0.5 * d.damper.gap_m;
    let edge = (half - half / r.runs as f64) * 1e2;
    s += &forcing_line(d, r.force_n, continuation);
    s += &format!(
        "ensemble  {} runs a frequency, the ball at rest from y0 = −d/2 + (k + ½)·d/{} ({} to {} cm); median [p10–p90] by nearest rank\n\n",
        r.runs,
        r.runs,
        num(-edge),
        num(edge)
    );
    let spread = |p: &crate::ensemble::Percentiles, scale: f64, digits: usize| {
        let f = |v: Option<f64>| v.map_or("—".into(), |x| fixed(x * scale, digits));
        format!("{} [{}–{}]", f(p.median), f(p.p10), f(p.p90))
    };
    for sweep in &r.sweeps {
        if continuation {
            s += &format!("{} sweep\n", sweep.direction.name());
        }
        s += "   f (Hz)  with (mm) median [p10–p90]  without (mm)  cut (dB)  impacts/T  Leq (dB) median [p10–p90]  periodic  settled\n";
        for p in &sweep.points {
            let sp = &p.spread;
            s += &format!(
                "  {:>7.3}  {:>28}  {:>12}  {:>8}  {:>9}  {:>27}  {:>7.0}%  {:>6.0}%{}\n",
                p.freq_hz,
                spread(&sp.amplitude_m, 1e3, 4),
                opt(p.amplitude_linear_m, 1e3, 4),
                opt(sp.reduction_db.median, 1.0, 2),
                opt(sp.impacts_per_period.median, 1.0, 3),
                spread(&sp.leq_db, 1.0, 2),
                100.0 * p.periodic_fraction,
                100.0 * p.settled_fraction,
                if p.truncated { "  TRUNCATED" } else { "" }
            );
        }
        s += "\n";
    }
    s += "(the plot draws the run of median amplitude at each frequency)\n";
    s += &plot(&r.medians(), 61, 14);
    s
}

fn opt(v: Option<f64>, scale: f64, digits: usize) -> String {
    v.map_or("—".into(), |x| fixed(x * scale, digits))
}

/// `x` to `digits` decimals, without a minus on a value that rounds to zero ("0.00", not
/// "-0.00": a cut of −0.001 dB is no cut).
fn fixed(x: f64, digits: usize) -> String {
    let s = format!("{x:.digits$}");
    match s.strip_prefix('-') {
        Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_string(),
        _ => s,
    }
}

/// The line that says how each point's steady state was reached: with the event solver, the
/// periodic orbit the motion settles to, found by shooting (or a ball proved never met), else
/// the run simulated until its windows settle; with Newmark, always the latter.
fn forcing_line(d: &Design, force_n: f64, continuation: bool) -> String {
    let from = if continuation { "from the previous one's final state (up, then down)" } else { "from rest" };
    let n = d.damper.steady_periods;
    let how = if d.solver == crate::damper::Solver::Event {
        format!(
            "steady state over {n} periods (whole orbits) of the periodic orbit each frequency {from} settles to, found by shooting (a ball never met: proved so, the steady state without it); where there is none, over the last {n} periods of its run, settled"
        )
    } else {
        format!("steady state over the last {n} periods, each frequency {from}, settled")
    };
    format!("forcing   F0 {} N on the main mass; {how}\n", num(force_n))
}

/// The response as a table and a plot.
fn text(d: &Design, r: &Response, continuation: bool) -> String {
    let mut s = format!("design    {}\n", describe(d));
    s += &forcing_line(d, r.force_n, continuation);
    s += "without   the main mass alone: F0/√((K − MΩ²)² + (CΩ)²), its steady state in closed form\n\n";
    for sweep in &r.sweeps {
        if continuation {
            s += &format!("{} sweep\n", sweep.direction.name());
        }
        s += "   f (Hz)   with (mm)   without (mm)   cut (dB)  impacts/T   Leq (dB)  orbit\n";
        for p in &sweep.points {
            let st = &p.steady;
            let orbit = if st.verdict.is_marked() { st.verdict.label().to_uppercase() } else { st.verdict.label() };
            s += &format!(
                "  {:>7.3}  {:>10.4}  {:>13}  {:>9}  {:>9.3}  {:>9}  {orbit}\n",
                p.freq_hz,
                st.amplitude_m * 1e3,
                opt(st.amplitude_linear_m, 1e3, 4),
                opt(st.reduction_db, 1.0, 2),
                st.impacts_per_period,
                opt(st.leq_db, 1.0, 2),
            );
        }
        s += "\n";
    }
    s += "(orbit: m/n = m impacts per n periods, sym = x(t+T/2) = −x(t); NOT SETTLED and TRUNCATED points are not a steady state)\n";
    s += &plot(r, 61, 14);
    s
}

/// A text plot of the amplitude (log scale) against the frequency: `*` with the damper (`u`/`d`
/// for the rising and falling sweeps of a continuation, `d` drawn over `u` where they meet), `o`
/// without it; a point that is not a steady state `?` (not settled) or `!` (truncated).
// Over 80 lines: one text canvas: the axes, their ticks and every sweep's marks drawn in order.
pub fn plot(r: &Response, width: usize, height: usize) -> String {
    let all: Vec<&response::ResponsePoint> = r.sweeps.iter().flat_map(|s| &s.points).collect();
    let f_lo = all.iter().map(|p| p.freq_hz).fold(f64::INFINITY, f64::min);
    let f_hi = all.iter().map(|p| p.freq_hz).fold(f64::NEG_INFINITY, f64::max);
    let values = all
        .iter()
        .flat_map(|p| [Some(p.steady.amplitude_m), p.steady.amplitude_linear_m])
        .flatten()
        .filter(|a| *a > 0.0 && a.is_finite());
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), a| (l.min(a.log10()), h.max(a.log10())));
    if !(lo.is_finite() && hi.is_finite() && f_hi >= f_lo) {
        return String::new();
    }
    let (lo, hi) = if hi - lo < 1e-9 { (lo - 0.5, hi + 0.5) } else { (lo, hi) };
    let mut grid = vec![vec![' '; width]; height];
    let col = |f: f64| {
        if f_hi > f_lo {
            (((f - f_lo) / (f_hi - f_lo)) * (width - 1) as f64).round() as usize
        } else {
            width / 2
        }
    };
    let row = |a: f64| {
        let u = (a.log10() - lo) / (hi - lo);
        height - 1 - ((u * (height - 1) as f64).round() as usize).min(height - 1)
    };
    let mut put = |f: f64, a: f64, c: char, over: bool| {
        if a > 0.0 && a.is_finite() {
            let cell = &mut grid[row(a)][col(f)];
            if over || *cell == ' ' {
                *cell = c;
            }
        }
    };
    for p in &all {
        if let Some(a) = p.steady.amplitude_linear_m {
            put(p.freq_hz, a, 'o', false);
        }
    }
    for sweep in &r.sweeps {
        let c = match sweep.direction {
            Direction::FromRest => '*',
            Direction::Up => 'u',
            Direction::Down => 'd',
        };
        for p in &sweep.points {
            // A point that is not a steady state is drawn apart.
            let c = match p.steady.verdict {
                v if v.is_truncated() => '!',
                v if v.is_marked() => '?',
                _ => c,
            };
            put(p.freq_hz, p.steady.amplitude_m, c, true);
        }
    }
    let marked = all.iter().any(|p| p.steady.verdict.is_marked());
    let mm = |e: f64| crate::units::sig(10f64.powf(e) * 1e3, 3);
    let with = if r.sweeps.iter().any(|s| s.direction != Direction::FromRest) {
        "u rising and d falling sweep with the damper"
    } else {
        "* with the damper"
    };
    let apart = if marked { ", ? not settled, ! truncated" } else { "" };
    let mut s = format!("amplitude (mm, log scale) against f: {with}, o without{apart}\n");
    for (i, line) in grid.iter().enumerate() {
        let label = if i == 0 {
            mm(hi)
        } else if i == height - 1 {
            mm(lo)
        } else if i == height / 2 {
            mm(hi - (hi - lo) * i as f64 / (height - 1) as f64)
        } else {
            String::new()
        };
        s += &format!("{label:>9} |{}\n", line.iter().collect::<String>().trim_end());
    }
    s += &format!("{:>9} +{}\n", "", "-".repeat(width));
    let left = format!("{} Hz", crate::units::sig(f_lo, 3));
    let right = format!("{} Hz", crate::units::sig(f_hi, 3));
    let pad = (width + 1).saturating_sub(left.len() + right.len());
    s += &format!("{:>9}  {left}{}{right}\n", "", " ".repeat(pad));
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_value_that_rounds_to_zero_has_no_minus() {
        assert_eq!(fixed(-0.001, 2), "0.00");
        assert_eq!(fixed(-0.004_9, 2), "0.00");
        assert_eq!(fixed(-0.005_1, 2), "-0.01");
        assert_eq!(fixed(149.112_7, 4), "149.1127", "every digit asked for, none cut");
        assert_eq!(opt(Some(0.149_112_7), 1e3, 4), "149.1127");
    }
}
