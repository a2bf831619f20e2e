//! What the explorer's jobs compute: one design simulated with its history, its sound (metrics,
//! loudest-impact waveform, directivity, a forced run's steady state with its Leq, and with
//! N > 1 the ensemble's spread), the chart sweep over mass × gap (of single runs, or of
//! ensembles of N runs a cell), the chart's levels at a new observer, and the frequency
//! response of a forced design. Calls into the engine only; no threads, no slots, no messages
//! — the worker (`worker.rs`) runs these on its threads and `tui::compute_sync` on the caller's.
//!
//! Each result is tagged with a key of the parameters it depends on (`cache_key.rs`).

use std::sync::atomic::{AtomicBool, Ordering};

use crate::acoustics::{Field, Observer};
use crate::contact::{Impact, Target};
use crate::continuation;
use crate::damper;
use crate::design::{self, linspace, Cell, Chart, Design, Evaluation, Metrics, Thresholds};
use crate::dynamics::{self, Bifurcation, BifurcationPoint};
use crate::ensemble::{self, Ensemble, EnsembleCell, EnsembleChart, Member};
use crate::error::ThudError;
use crate::limits;
use crate::params::Spelling;
use crate::response::{self, Response, ResponseOptions, Steady};
use crate::study::Vary;

/// History samples kept for the x(t) plot.
pub const HISTORY_SAMPLES: usize = 600;
/// Samples of the pressure waveform.
pub const WAVEFORM_SAMPLES: usize = 400;
/// Angle step of the directivity polar (deg).
pub const POLAR_STEP_DEG: f64 = 5.0;

/// A mass × gap grid (SI).
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    pub masses_kg: Vec<f64>,
    pub gaps_m: Vec<f64>,
}

impl Grid {
    /// `nm` masses from 20 to 100 g and `ng` gaps from 1 to 7 cm.
    pub fn standard(nm: usize, ng: usize) -> Self {
        Self { masses_kg: linspace(0.02, 0.1, nm), gaps_m: linspace(0.01, 0.07, ng) }
    }

    pub fn len(&self) -> usize {
        self.masses_kg.len() * self.gaps_m.len()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// The chart's grids: an optional coarse pass first, then the fine grid shown.
#[derive(Debug, Clone, PartialEq)]
pub struct Grids {
    pub coarse: Option<Grid>,
    pub fine: Grid,
}

impl Default for Grids {
    /// 6 × 5 first, then 16 × 12.
    fn default() -> Self {
        Self { coarse: Some(Grid::standard(6, 5)), fine: Grid::standard(16, 12) }
    }
}

/// Which pass of the chart a result belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Stage {
    Coarse,
    Fine,
}

/// A simulated design: the evaluation and its history in plotting units.
#[derive(Debug, Clone)]
pub struct SimResult {
    pub eval: Evaluation,
    /// (t in s, x in cm) with the damper.
    pub history_cm: Vec<(f64, f64)>,
    /// (t in s, x in cm) of the same structure without the damper.
    pub free_cm: Vec<(f64, f64)>,
    /// The run's cycle maxima X_k (t in s, X in cm), the points of Eq 27: the decay envelope.
    pub maxima_cm: Vec<(f64, f64)>,
    /// The cycle maxima of the structure without the damper (t in s, X in cm).
    pub free_maxima_cm: Vec<(f64, f64)>,
}

/// The sound of a simulated design at its observer.
#[derive(Debug, Clone)]
pub struct AcousticResult {
    pub metrics: Metrics,
    /// (ms after the direct arrival, Pa) of the loudest impact.
    pub waveform: Vec<(f64, f64)>,
    /// (θ in deg, SPL in dB) at the observer's distance.
    pub polar: Vec<(f64, f64)>,
    /// One impact of the ball at U0 = v0 on a fixed plate (what `thud pulse` computes for the
    /// design: Fig 2, Table 1); an error text when v0 gives no impact.
    pub single: Result<SingleImpact, ThudError>,
    /// A forced design's steady state over its last N periods with the Leq of its rattle at
    /// this observer ([`response::steady`]); None without a force. The readout job
    /// ([`compute_readout`]) replaces it by the settled state (as `thud simulate --settle`).
    pub steady: Option<Steady>,
    /// With N > 1 runs and a force: the settled steady state of the N runs at f (median and
    /// p10–p90, as `thud response --ensemble N` at this f).
    pub forced_ensemble: Option<response::EnsemblePoint>,
    /// A forced design: the engine's point at exactly its f from rest (v0 = 0, settled), as
    /// `thud response --freqs f:f:1` computes it; the response view shows it at its marker
    /// (the curve's band points rarely fall on f). None without a force.
    pub rest_at_f: Option<response::ResponsePoint>,
    /// With N > 1 runs: the ensemble of the design (its runs from N spread ball offsets).
    pub ensemble: Option<Ensemble>,
    /// The level (dB) of each of the run's impacts at the observer, index as in the run's
    /// impacts: [`design::impact_spls`], as `thud simulate --json` reports them (None where the
    /// engine refuses that impact's field). The animation's flash reads it: no field is
    /// computed on the UI thread.
    pub impact_spl_db: Vec<Option<f64>>,
    /// A forced design: its orbit at its own f, as `thud bifurcation --vary f=f:f:1` samples
    /// and classifies it ([`orbit_at_f`]); the readout names its type and the bifurcation view
    /// marks its samples at f. None without a force.
    pub orbit: Option<dynamics::BifurcationPoint>,
}

/// One impact at U0 = v0 on a fixed plate (K* = 1/m, Eq 8), heard at the design's observer.
#[derive(Debug, Clone, PartialEq)]
pub struct SingleImpact {
    /// The impact speed (m/s).
    pub u0_m_s: f64,
    /// The design's headline level (dB): the paper's SPL (rms over τ from the direct arrival)
    /// or the physical model's peak level ([`Design::level_db`]).
    pub spl_db: f64,
    /// (ms after the direct arrival, Pa).
    pub waveform: Vec<(f64, f64)>,
    /// (θ in deg, SPL in dB) at the observer's distance.
    pub polar: Vec<(f64, f64)>,
    /// The waveform's significant extrema (ms after the direct arrival, Pa): the humps of the M.
    pub peaks: Vec<(f64, f64)>,
}

/// The passes of a chart (coarse, if any, and fine), as the app holds them.
#[derive(Debug, Clone, PartialEq)]
pub struct ChartPasses {
    pub coarse: Option<Chart>,
    pub fine: Chart,
}

/// Index of the value nearest `x` (0 for an empty slice): the grid cell a design falls in.
pub fn nearest(values: &[f64], x: f64) -> usize {
    values.iter().enumerate().min_by(|a, b| (a.1 - x).abs().total_cmp(&(b.1 - x).abs())).map_or(0, |(i, _)| i)
}

/// The grids of held chart passes (for their key).
pub fn grids_of(p: &ChartPasses) -> Grids {
    let grid = |c: &Chart| Grid { masses_kg: c.masses_kg.clone(), gaps_m: c.gaps_m.clone() };
    Grids { coarse: p.coarse.as_ref().map(grid), fine: grid(&p.fine) }
}

/// Simulates `d` with history; `None` if cancelled.
pub fn compute_sim(d: &Design, cancel: Option<&AtomicBool>) -> Result<Option<SimResult>, ThudError> {
    let d = d.clone().check()?;
    let eval = design::evaluate(&d, HISTORY_SAMPLES, cancel)?;
    if eval.run.cancelled {
        return Ok(None);
    }
    let p = d.into_design().damper;
    let history_cm = eval.run.history.iter().map(|h| (h.t_s, 100.0 * h.x_m)).collect();
    let free_cm = eval.run.history.iter().map(|h| (h.t_s, 100.0 * damper::free_response(&p, h.t_s))).collect();
    let cm = |m: &damper::Maximum| (m.t_s, 100.0 * m.x_m);
    let maxima_cm = eval.run.maxima.iter().map(cm).collect();
    let free_maxima_cm = damper::free_maxima(&p).iter().map(cm).collect();
    Ok(Some(SimResult { eval, history_cm, free_cm, maxima_cm, free_maxima_cm }))
}

/// Metrics, loudest-impact waveform, directivity and steady state of `d` from its cached run.
pub fn compute_acoustic(d: &Design, sim: &SimResult) -> Result<AcousticResult, ThudError> {
    let r = d.clone().check()?;
    let metrics = design::metrics(&sim.eval.run, &r)?;
    let steady = response::steady(&sim.eval.run, &r)?;
    let (mut waveform, mut polar) = (Vec::new(), Vec::new());
    if metrics.spl_max_db.is_some() {
        let u0 = metrics.u0_max_m_s;
        let field = r.impact_field(u0)?;
        let arrival = field.arrival_s();
        let (t, p) = field.waveform(WAVEFORM_SAMPLES);
        waveform = t.iter().zip(&p).map(|(t, p)| (1e3 * (t - arrival), *p)).collect();
        polar = directivity(&r, u0);
    }
    let single = single_impact(&r);
    let impact_spl_db =
        sim.eval.run.impacts.iter().map(|i| r.impact_spl_db(i.u_in_m_s).ok().filter(|db| db.is_finite())).collect();
    Ok(AcousticResult {
        metrics,
        waveform,
        polar,
        single,
        steady,
        ensemble: None,
        forced_ensemble: None,
        rest_at_f: None,
        impact_spl_db,
        orbit: None,
    })
}

/// The readout of `d` with `runs` runs: [`compute_acoustic`], and with N > 1 the ensemble of
/// N runs ([`ensemble::evaluate`]). `None` if cancelled.
pub fn compute_readout(
    d: &Design,
    sim: &SimResult,
    runs: usize,
    cancel: Option<&AtomicBool>,
) -> Result<Option<AcousticResult>, ThudError> {
    let mut a = compute_acoustic(d, sim)?;
    let d = &d.clone().check()?;
    if runs > 1 {
        match ensemble::evaluate(d, runs, cancel)? {
            Some(e) => a.ensemble = Some(e),
            None => return Ok(None),
        }
    }
    if d.damper.forced() {
        match settled_steady(d, cancel)? {
            Some(s) => a.steady = Some(s),
            None => return Ok(None),
        }
        match rest_point(d, cancel)? {
            Some(p) => a.rest_at_f = Some(p),
            None => return Ok(None),
        }
        match orbit_at_f(d, cancel) {
            Ok(Some(p)) => a.orbit = Some(p),
            Ok(None) => return Ok(None),
            // The engine samples orbits with the event solver only: with Newmark no type is named.
            Err(_) => {}
        }
        if runs > 1 {
            let opts = ResponseOptions { continuation: false, settle: true };
            let f = d.damper.freq_hz;
            let r = response::response_ensemble(d, &[f], runs, &opts, cancel, &|| {})?;
            if cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
                return Ok(None);
            }
            a.forced_ensemble = r.sweeps.into_iter().next().and_then(|s| s.points.into_iter().next());
        }
    }
    Ok(Some(a))
}

/// The settled steady state of forced `d`: its run going on until the amplitude settles (at
/// most [`damper::SETTLE_PERIODS_MAX`] periods more), as `thud simulate --settle` reports it,
/// not the last periods of its own duration, which may still be the start-up transient (the
/// structure's time constant 2M/C is 20 s for Table 2). `None` if cancelled.
pub fn settled_steady(d: &Design, cancel: Option<&AtomicBool>) -> Result<Option<Steady>, ThudError> {
    let mut s = d.clone();
    s.damper.settle = true;
    let eval = design::evaluate(&s.check()?, 0, cancel)?;
    Ok(if eval.run.cancelled { None } else { eval.steady })
}

/// The response of forced `d` at exactly its f from rest: the point the response curve's
/// engine call ([`compute_response`]) computes for that frequency, as `thud response --freqs
/// f:f:1` does (each frequency from rest, settled). `None` if cancelled.
pub fn rest_point(d: &Design, cancel: Option<&AtomicBool>) -> Result<Option<response::ResponsePoint>, ThudError> {
    let f = d.damper.freq_hz;
    let mut rd = response_design(d);
    rd.damper.freq_hz = f;
    let r = response::response(&rd.check()?, &[f], &ResponseOptions::default(), cancel, &|| {})?;
    if cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
        return Ok(None);
    }
    Ok(r.sweeps.into_iter().next().and_then(|s| s.points.into_iter().next()))
}

/// The ensemble `e` under thresholds `t`: each run's zone and the zone of the medians
/// reclassified ([`Ensemble::from_members`]), so threshold edits need no new runs.
pub fn ensemble_under(e: &Ensemble, t: &Thresholds) -> Ensemble {
    let members =
        e.ensemble.iter().map(|m| Member { metrics: Metrics { zone: m.metrics.zone(t), ..m.metrics }, ..*m }).collect();
    Ensemble::from_members(members, t)
}

/// Fraction of the runs that must agree with the zone of the medians for a chart cell to be
/// drawn as sure (shaded when fewer than 70 % agree).
pub const AGREEMENT_SURE: f64 = 0.7;

/// The frequencies of a response curve: `points` from `from_hz` to `to_hz`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FreqBand {
    pub from_hz: f64,
    pub to_hz: f64,
    pub points: usize,
}

impl FreqBand {
    /// The frequencies (Hz).
    pub fn freqs(&self) -> Vec<f64> {
        linspace(self.from_hz, self.to_hz, self.points)
    }

    /// Whether `f` lies inside the band.
    pub fn contains(&self, f: f64) -> bool {
        f >= self.from_hz && f <= self.to_hz
    }
}

/// Points of the explorer's response curve: the engine's default
/// ([`thud_core::response::DEFAULT_POINTS`]), so the curve is `thud response`'s without
/// `--freqs`, point for point.
pub const RESPONSE_POINTS: usize = thud_core::response::DEFAULT_POINTS;

/// The band a response curve spans for `d`: the engine's default
/// ([`thud_core::response::default_band_hz`], as `thud response` without `--freqs`): 0.6 to
/// 1.6 times the structure's natural frequency (its resonance and both flanks), or 1–10 Hz
/// without one (no spring, or overdamped). It does not depend on the forcing frequency f, so
/// changing f only moves the marker.
pub fn default_band(d: &Design) -> FreqBand {
    let (from_hz, to_hz) = thud_core::response::default_band_hz(d);
    FreqBand { from_hz, to_hz, points: RESPONSE_POINTS }
}

/// The design a response curve runs: `d` from rest (v0 = 0), as `thud response` runs a design
/// whose start is not typed; each frequency sets its own f. The ball starts at the design's y0.
pub fn response_design(d: &Design) -> Design {
    let mut r = d.clone();
    r.damper.v0_m_s = 0.0;
    r.damper.freq_hz = 0.0;
    r.thresholds = Thresholds::default();
    r
}

/// The work of the response curve of `d` over `band`, checked against the caps `thud
/// response` uses ([`limits::response_work`], and the cycles of the highest frequency's
/// settled run): the first estimate over its cap, as an error naming the force.
pub fn check_response_work(d: &Design, band: &FreqBand) -> Result<(), ThudError> {
    let freqs = band.freqs();
    let rd = response_design(d);
    let f_max = freqs.iter().copied().fold(0.0, f64::max);
    let over = limits::response_work(&rd, &freqs, false)
        .into_iter()
        .chain([limits::design_run(&response::at_frequency(&rd, f_max, true), 0)[1]])
        .find(limits::Estimate::exceeded);
    match over {
        Some(e) => Err(ThudError::invalid("response", format!("{} points: {}", band.points, e.describe()))),
        None => Ok(()),
    }
}

/// The frequency response of `d` over `band` (every frequency from rest, settled, as `thud
/// response`): `on_point` hears each finished point. Refused without a force or over the work
/// caps; `None` if cancelled.
pub fn compute_response(
    d: &Design,
    band: &FreqBand,
    cancel: Option<&AtomicBool>,
    on_point: &(dyn Fn() + Sync),
) -> Result<Option<Response>, ThudError> {
    if !d.damper.forced() {
        return Err(ThudError::invalid("force", "0 N: a response needs a force; set F0 > 0"));
    }
    check_response_work(d, band)?;
    // Checked with the design's own f (a forced design needs one); each point sets its own.
    let mut rd = response_design(d);
    rd.damper.freq_hz = d.damper.freq_hz;
    let r = response::response(&rd.check()?, &band.freqs(), &ResponseOptions::default(), cancel, on_point)?;
    if cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
        return Ok(None);
    }
    Ok(Some(r))
}

/// The impact of the design's ball at U0 = v0 on a fixed plate (as `thud pulse --preset`).
fn plate_impact(d: &Design) -> Impact {
    Impact {
        mass_kg: d.damper.impact_mass_kg,
        u0_m_s: d.damper.v0_m_s,
        k_hz: d.damper.k_hz,
        target: Target::FixedPlate,
    }
}

/// The sound field of the plate impact of `d` (resolved) at observer `observer`.
fn plate_field(d: &Design, observer: &Observer) -> Result<Field, ThudError> {
    let impact = plate_impact(d);
    impact.validate()?;
    Field::new(d.ball_radius_m(), &impact.contact(), observer, &d.sound())
}

/// One impact at U0 = v0 on a fixed plate: waveform, directivity and its peaks (`d` resolved).
pub fn single_impact(d: &Design) -> Result<SingleImpact, ThudError> {
    let field = plate_field(d, &d.observer)?;
    let arrival = field.arrival_s();
    let (t, p) = field.waveform(WAVEFORM_SAMPLES);
    let waveform = t.iter().zip(&p).map(|(t, p)| (1e3 * (t - arrival), *p)).collect();
    let peaks = field.significant_extrema(0.02).iter().map(|e| (1e3 * (e.t_s - arrival), e.p_pa)).collect();
    let polar = polar_angles(d)
        .into_iter()
        .filter_map(|(deg, theta_rad)| {
            let at = Observer { theta_rad, ..d.observer };
            plate_field(d, &at).ok().map(|f| (deg, d.level_db(&f)))
        })
        .collect();
    Ok(SingleImpact { u0_m_s: d.damper.v0_m_s, spl_db: d.level_db(&field), waveform, polar, peaks })
}

/// The angles a polar is computed at, as (deg, rad): every [`POLAR_STEP_DEG`] over the valid
/// angles of the source, and the observer's own θ exactly (its radians as the design holds
/// them, its degrees as [`listener_deg`] gives them), so the listener's level is the level at
/// θ, the one `thud simulate`/`thud pulse` report, not the nearest grid angle's.
fn polar_angles(d: &Design) -> Vec<(f64, f64)> {
    let (lo, hi) = d.radiation.source.theta_range_deg();
    let n = ((hi - lo) / POLAR_STEP_DEG).round() as usize;
    let mut angles: Vec<(f64, f64)> = (0..=n)
        .map(|i| {
            let deg = lo + i as f64 * POLAR_STEP_DEG;
            (deg, deg.to_radians())
        })
        .collect();
    let own = listener_deg(d);
    if (lo..=hi).contains(&own) {
        angles.retain(|a| a.0 != own);
        angles.push((own, d.observer.theta_rad));
        angles.sort_by(|a, b| a.0.total_cmp(&b.0));
    }
    angles
}

/// The listener's θ in degrees as the polar is keyed on it: the design's radians in degrees.
pub fn listener_deg(d: &Design) -> f64 {
    d.observer.theta_rad.to_degrees()
}

/// SPL (dB) every [`POLAR_STEP_DEG`] over the valid angles of the source and at the observer's
/// own θ ([`polar_angles`]), at the design's r.
fn directivity(d: &Design, u0: f64) -> Vec<(f64, f64)> {
    polar_angles(d)
        .into_iter()
        .filter_map(|(deg, theta_rad)| {
            let mut v = d.clone();
            v.observer.theta_rad = theta_rad;
            v.impact_spl_db(u0).ok().map(|l| (deg, l))
        })
        .collect()
}

/// Sweeps the coarse grid (if any) then the fine one: `on_cell` hears every cell as it is
/// done (from the sweep's threads), `on_pass` every finished pass. Returns false if cancelled
/// (the cancelled pass is not reported).
pub fn compute_chart(
    d: &Design,
    grids: &Grids,
    cancel: Option<&AtomicBool>,
    on_cell: &(dyn Fn(Stage, usize, &Cell) + Sync),
    on_pass: &mut dyn FnMut(Stage, Result<Chart, ThudError>),
) -> bool {
    let passes = grids.coarse.iter().map(|g| (Stage::Coarse, g)).chain([(Stage::Fine, &grids.fine)]);
    for (stage, grid) in passes {
        let result = d
            .clone()
            .check()
            .and_then(|d| design::sweep(&d, &grid.masses_kg, &grid.gaps_m, cancel, &|i, cell| on_cell(stage, i, cell)));
        if cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
            return false;
        }
        on_pass(stage, result);
    }
    true
}

/// Sweeps the coarse grid (if any) then the fine one with `runs` runs a cell
/// ([`ensemble::sweep`]); reports as [`compute_chart`] does. Returns false if cancelled.
pub fn compute_ensemble_chart(
    d: &Design,
    grids: &Grids,
    runs: usize,
    cancel: Option<&AtomicBool>,
    on_cell: &(dyn Fn(Stage, usize, &EnsembleCell) + Sync),
    on_pass: &mut dyn FnMut(Stage, Result<EnsembleChart, ThudError>),
) -> bool {
    let passes = grids.coarse.iter().map(|g| (Stage::Coarse, g)).chain([(Stage::Fine, &grids.fine)]);
    for (stage, grid) in passes {
        let result = d.clone().check().and_then(|d| {
            ensemble::sweep(&d, &grid.masses_kg, &grid.gaps_m, runs, cancel, &|i, cell| on_cell(stage, i, cell))
        });
        if cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
            return false;
        }
        on_pass(stage, result);
    }
    true
}

/// A cell's metrics with SPLmax (and zone) for the observer and radiation of `d`, from its
/// U0max: one sound-field evaluation, no simulation.
pub fn relevel_cell(d: &Design, cell: &Cell) -> Cell {
    let mut out = *cell;
    if cell.metrics.spl_max_db.is_some() {
        let v = design::variant(d, cell.mass_kg, cell.gap_m);
        out.metrics.spl_max_db = v.check().and_then(|r| r.impact_spl_db(cell.metrics.u0_max_m_s)).ok();
        out.metrics.zone = out.metrics.zone(&d.thresholds);
    }
    out
}

/// Every computed cell of the passes relevelled for `d`.
pub fn compute_relevel(d: &Design, passes: &ChartPasses) -> ChartPasses {
    let re = |c: &Chart| Chart { cells: c.cells.iter().map(|x| x.map(|x| relevel_cell(d, &x))).collect(), ..c.clone() };
    ChartPasses { coarse: passes.coarse.as_ref().map(re), fine: re(&passes.fine) }
}

/// The main mass's damped natural frequency (Hz) of `d`: the engine's
/// [`thud_core::damper::DamperParams::natural_frequency_hz`] (Eq 25), unrounded; 0 without a
/// spring or when overdamped.
pub fn natural_frequency_hz(d: &Design) -> f64 {
    thud_core::response::natural_frequency_hz(d)
}

/// The forcing frequencies of the explorer's bifurcation diagram: a coarse pass first, then the
/// fine one, over the response curve's band ([`default_band`]: 0.6–1.6 × the natural
/// frequency), so the two views of a forced design span the same f.
pub const BIFURCATION_VALUES: [usize; 2] = [20, 100];

/// How long each orbit runs in the explorer: the engine's defaults, as `thud bifurcation`
/// without `--transient` and `--periods` (200 periods of transient, 100 sampled).
pub fn orbit_settings() -> dynamics::Settings {
    dynamics::Settings::default()
}

/// The frequencies of a bifurcation pass of `d` with `points` values over its band.
pub fn bifurcation_band(d: &Design, points: usize) -> FreqBand {
    FreqBand { points, ..default_band(d) }
}

/// `Err` naming the values when a diagram of `values` values would pass the work caps of
/// every study of orbits ([`dynamics::check_work`], as `thud bifurcation` checks).
fn check_orbit_work(values: usize) -> Result<(), ThudError> {
    dynamics::check_work(values, orbit_settings(), false).map_err(|r| {
        ThudError::invalid(
            "bifurcation",
            format!("{values} value{}: {}", if values == 1 { "" } else { "s" }, r.estimate.describe()),
        )
    })
}

/// The bifurcation diagram of forced `d` over f for `band` (each value from the design's own
/// start, as `thud bifurcation --vary f=FROM:TO:N` without continuation): `on_point` hears
/// each finished value. Refused without a force or over the caps; `None` if cancelled.
pub fn compute_bifurcation(
    d: &Design,
    band: &FreqBand,
    cancel: Option<&AtomicBool>,
    on_point: &(dyn Fn(usize) + Sync),
) -> Result<Option<Bifurcation>, ThudError> {
    check_orbit_work(band.points)?;
    let vary = Vary::of_values("f", &band.freqs(), Spelling::Flag)?;
    match dynamics::bifurcation(&d.clone().check()?, &vary, orbit_settings(), false, "force", cancel, on_point) {
        Ok(b) => Ok(Some(b)),
        Err(ThudError::Cancelled) => Ok(None),
        Err(e) => Err(e),
    }
}

/// Seed values of the periodic orbits' branches the bifurcation view draws over its band.
pub const BRANCH_SEEDS: usize = 12;

/// The periodic orbits' branches of forced `d` over `band`, continued both ways from the stable
/// orbits found from the design's start at [`BRANCH_SEEDS`] values (as `thud bifurcation
/// --branches 12` draws them); none for the Newmark solver (orbits are the event solver's).
/// `None` if cancelled.
pub fn compute_branches(
    d: &Design,
    band: &FreqBand,
    cancel: Option<&AtomicBool>,
) -> Result<Option<Vec<continuation::Branch>>, ThudError> {
    if d.solver != crate::damper::Solver::Event {
        return Ok(Some(Vec::new()));
    }
    let work = limits::family_seed_periods(BRANCH_SEEDS);
    if work.exceeded() {
        return Err(ThudError::invalid("branches", work.describe()));
    }
    let vary = Vary::of_values("f", &[band.from_hz, band.to_hz], Spelling::Flag)?;
    match continuation::continue_family(&d.clone().check()?, &vary, BRANCH_SEEDS, cancel, &|_| {}) {
        Ok(b) => Ok(Some(b)),
        Err(ThudError::Cancelled) => Ok(None),
        Err(e) => Err(e),
    }
}

/// The orbit of forced `d` at its own f: the one value of `thud bifurcation --vary f=f:f:1`
/// (from the design's own start, the engine's default run lengths). `None` if cancelled.
pub fn orbit_at_f(d: &Design, cancel: Option<&AtomicBool>) -> Result<Option<BifurcationPoint>, ThudError> {
    let band = FreqBand { from_hz: d.damper.freq_hz, to_hz: d.damper.freq_hz, points: 1 };
    Ok(compute_bifurcation(d, &band, cancel, &|_| {})?.and_then(|b| b.points.into_iter().next()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn relevel_equals_a_fresh_sweep_at_the_new_observer() {
        let d = Design::default();
        let (m, g) = ([0.03, 0.06], [0.02, 0.04]);
        let chart = design::sweep(&d.clone().check().unwrap(), &m, &g, None, &|_, _| {}).unwrap();
        let mut far = d.clone();
        far.observer = Observer::new(1.5, 30.0);
        let fresh = design::sweep(&far.clone().check().unwrap(), &m, &g, None, &|_, _| {}).unwrap();
        let re = compute_relevel(&far, &ChartPasses { coarse: None, fine: chart });
        for (a, b) in re.fine.cells.iter().zip(&fresh.cells) {
            let (a, b) = (a.unwrap().metrics, b.unwrap().metrics);
            assert_eq!(a.spl_max_db.is_some(), b.spl_max_db.is_some());
            if let (Some(x), Some(y)) = (a.spl_max_db, b.spl_max_db) {
                assert!((x - y).abs() < 1e-9, "{x} vs {y}");
            }
            assert_eq!(a.zone, b.zone);
        }
    }

    #[test]
    fn the_polar_spans_the_open_side_of_the_source() {
        for source in crate::acoustics::Source::ALL {
            let mut d = Design::default();
            d.radiation.source = source;
            d.observer.theta_rad = 0.0;
            let sim = compute_sim(&d, None).unwrap().unwrap();
            let a = compute_acoustic(&d, &sim).unwrap();
            let (lo, hi) = source.theta_range_deg();
            let first = a.polar.first().map(|p| p.0);
            let last = a.polar.last().map(|p| p.0);
            assert_eq!((first, last), (Some(lo), Some(hi)), "{source:?}");
        }
    }
}
