//! Background computation. Three kinds of job — simulate one design, its acoustics, the chart
//! sweep — each with one slot on its own thread: a new request replaces the queued one
//! ("newest wins") and cancels the running one if its parameters differ. Results are tagged
//! with the key (serialized parameters) they were computed for, so the app drops stale ones,
//! and cached by that key so going back (undo, presets) is instant.

use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex};

use crate::damper;
use crate::design::{self, linspace, Cell, Chart, Design, Evaluation, Metrics, Thresholds};
use crate::error::ThudError;
use crate::export::{self, ExportOptions, Kind};

use super::fields::theta_range_deg;

/// History samples kept for the x(t) plot.
pub const HISTORY_SAMPLES: usize = 600;
/// Samples of the pressure waveform.
pub const WAVEFORM_SAMPLES: usize = 400;
/// Angle step of the directivity polar (deg).
pub const POLAR_STEP_DEG: f64 = 5.0;
/// Cache entries kept per job kind before the cache is cleared.
const CACHE_MAX: usize = 256;

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
}

/// The sound of a simulated design at its observer.
#[derive(Debug, Clone)]
pub struct AcousticResult {
    pub metrics: Metrics,
    /// (ms after the direct arrival, Pa) of the loudest impact.
    pub waveform: Vec<(f64, f64)>,
    /// (θ in deg, SPL in dB) at the observer's distance.
    pub polar: Vec<(f64, f64)>,
}

/// What the app asks for.
#[derive(Debug, Clone)]
pub enum Request {
    Sim(Design),
    Acoustic(Design, Arc<SimResult>),
    Chart(Design, Grids),
    /// The chart's SPLmax for the design's observer and radiation, from each cell's U0max:
    /// acoustics only, no simulation. Carries the chart passes to relevel.
    Relevel(Design, Arc<ChartPasses>),
    /// Write an export file (CSV, SVG or WAV) of the design: never cancelled, never cached;
    /// each one runs on its own short-lived thread.
    Export(Box<ExportJob>),
}

/// One file to export.
#[derive(Debug, Clone)]
pub struct ExportJob {
    pub kind: Kind,
    pub design: Design,
    pub options: ExportOptions,
    pub path: PathBuf,
}

impl ExportJob {
    /// Renders and writes the file.
    pub fn run(&self) -> Done {
        let result =
            export::export_to_path(self.kind, &self.design, &self.options, &self.path).map_err(|e| e.to_string());
        Done::Export { kind: self.kind, path: self.path.clone(), result }
    }
}

/// The passes of a chart (coarse, if any, and fine), as the app holds them.
#[derive(Debug, Clone, PartialEq)]
pub struct ChartPasses {
    pub coarse: Option<Chart>,
    pub fine: Chart,
}

/// What comes back, tagged with the key of the parameters it was computed for.
#[derive(Debug, Clone)]
pub enum Done {
    Sim {
        key: String,
        result: Result<Arc<SimResult>, String>,
    },
    Acoustic {
        key: String,
        result: Result<Arc<AcousticResult>, String>,
    },
    /// `sound` is the [`sound_key`] the cell's SPLmax was computed for.
    ChartCell {
        key: String,
        sound: String,
        stage: Stage,
        index: usize,
        cell: Cell,
    },
    Chart {
        key: String,
        sound: String,
        stage: Stage,
        result: Result<Arc<Chart>, String>,
    },
    /// The chart's passes relevelled for `sound`; `key` is the chart key.
    Relevel {
        key: String,
        sound: String,
        passes: Arc<ChartPasses>,
    },
    /// An export finished (or failed) writing `path`.
    Export {
        kind: Kind,
        path: PathBuf,
        result: Result<(), String>,
    },
}

fn json<T: serde::Serialize>(v: &T) -> String {
    serde_json::to_string(v).unwrap_or_default()
}

/// Key of what a simulation depends on: the damper, the ball, materials and solver.
pub fn sim_key(d: &Design) -> String {
    json(&(&d.damper, &d.ball, &d.materials, &d.solver))
}

/// Key of the acoustics: everything but the zone thresholds (zones are classified on draw).
pub fn acoustic_key(d: &Design) -> String {
    let mut d = d.clone();
    d.thresholds = Thresholds::default();
    json(&d)
}

/// Key of what the sound at the observer depends on beyond each impact: observer and radiation.
pub fn sound_key(d: &Design) -> String {
    json(&(&d.observer, &d.radiation))
}

/// Key of the chart's simulations: everything but the mass, the gap, the thresholds and the
/// sound (a change of observer relevels the chart instead of re-sweeping it), plus the grids.
pub fn chart_key(d: &Design, grids: &Grids) -> String {
    let mut d = design::variant(d, 0.0, 0.0);
    d.thresholds = Thresholds::default();
    d.observer = crate::acoustics::Observer::new(0.0, 0.0);
    d.radiation = Default::default();
    format!(
        "{}|{:?}|{:?}",
        json(&d),
        grids.coarse.as_ref().map(|g| (g.masses_kg.len(), g.gaps_m.len())),
        (grids.fine.masses_kg.len(), grids.fine.gaps_m.len())
    )
}

/// The key a request's result will carry.
pub fn request_key(r: &Request) -> String {
    match r {
        Request::Sim(d) => sim_key(d),
        Request::Acoustic(d, _) => acoustic_key(d),
        Request::Chart(d, g) => chart_key(d, g),
        Request::Relevel(d, _) => sound_key(d),
        Request::Export(job) => job.path.display().to_string(),
    }
}

/// Simulates `d` with history; `None` if cancelled.
pub fn compute_sim(d: &Design, cancel: Option<&AtomicBool>) -> Result<Option<SimResult>, ThudError> {
    let eval = design::evaluate(d, HISTORY_SAMPLES, cancel)?;
    if eval.run.cancelled {
        return Ok(None);
    }
    let p = d.resolved()?.damper;
    let history_cm = eval.run.history.iter().map(|h| (h.t_s, 100.0 * h.x_m)).collect();
    let free_cm = eval.run.history.iter().map(|h| (h.t_s, 100.0 * damper::free_response(&p, h.t_s))).collect();
    Ok(Some(SimResult { eval, history_cm, free_cm }))
}

/// Metrics, loudest-impact waveform and directivity of `d` from its cached run.
pub fn compute_acoustic(d: &Design, sim: &SimResult) -> Result<AcousticResult, ThudError> {
    let r = d.resolved()?;
    let metrics = design::metrics(&sim.eval.run, &r)?;
    let (mut waveform, mut polar) = (Vec::new(), Vec::new());
    if metrics.spl_max_db.is_some() {
        let u0 = metrics.u0_max_m_s;
        let field = r.impact_field(u0)?;
        let arrival = field.arrival_s();
        let (t, p) = field.waveform(WAVEFORM_SAMPLES);
        waveform = t.iter().zip(&p).map(|(t, p)| (1e3 * (t - arrival), *p)).collect();
        polar = directivity(&r, u0);
    }
    Ok(AcousticResult { metrics, waveform, polar })
}

/// SPL (dB) every [`POLAR_STEP_DEG`] over the valid angles of the source, at the design's r.
fn directivity(d: &Design, u0: f64) -> Vec<(f64, f64)> {
    let (lo, hi) = theta_range_deg(d.radiation.source);
    let n = ((hi - lo) / POLAR_STEP_DEG).round() as usize;
    (0..=n)
        .filter_map(|i| {
            let deg = lo + i as f64 * POLAR_STEP_DEG;
            let mut v = d.clone();
            v.observer.theta_rad = deg.to_radians();
            v.impact_spl_db(u0).ok().map(|l| (deg, l))
        })
        .collect()
}

/// Sweeps the coarse grid (if any) then the fine one, reporting every cell and each pass.
/// Returns false if cancelled.
pub fn compute_chart(
    d: &Design,
    grids: &Grids,
    key: &str,
    cancel: Option<&AtomicBool>,
    notify: &(dyn Fn(Done) + Sync),
) -> bool {
    let sound = sound_key(d);
    let passes = grids.coarse.iter().map(|g| (Stage::Coarse, g)).chain([(Stage::Fine, &grids.fine)]);
    for (stage, grid) in passes {
        let on_cell = |index: usize, cell: &Cell| {
            notify(Done::ChartCell { key: key.to_string(), sound: sound.clone(), stage, index, cell: *cell })
        };
        let result = design::sweep(d, &grid.masses_kg, &grid.gaps_m, cancel, &on_cell);
        if cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
            return false;
        }
        let result = result.map(Arc::new).map_err(|e| e.to_string());
        notify(Done::Chart { key: key.to_string(), sound: sound.clone(), stage, result });
    }
    true
}

/// A cell's metrics with SPLmax (and zone) for the observer and radiation of `d`, from its
/// U0max: one sound-field evaluation, no simulation.
pub fn relevel_cell(d: &Design, cell: &Cell) -> Cell {
    let mut out = *cell;
    if cell.metrics.spl_max_db.is_some() {
        let v = design::variant(d, cell.mass_kg, cell.gap_m);
        let spl = v.resolved().and_then(|r| r.impact_spl_db(cell.metrics.u0_max_m_s)).ok();
        out.metrics.spl_max_db = spl;
        out.metrics.zone = spl.and_then(|_| super::app::zone_of(&out.metrics, d));
    }
    out
}

/// Every computed cell of the passes relevelled for `d`.
pub fn compute_relevel(d: &Design, passes: &ChartPasses) -> ChartPasses {
    let re = |c: &Chart| Chart { cells: c.cells.iter().map(|x| x.map(|x| relevel_cell(d, &x))).collect(), ..c.clone() };
    ChartPasses { coarse: passes.coarse.as_ref().map(re), fine: re(&passes.fine) }
}

/// Runs one request on the calling thread, without cache or cancellation (tests, benches).
pub fn run_sync(req: &Request, notify: &(dyn Fn(Done) + Sync)) {
    let key = request_key(req);
    match req {
        Request::Sim(d) => {
            let result = compute_sim(d, None).map(|r| Arc::new(r.expect("not cancelled"))).map_err(|e| e.to_string());
            notify(Done::Sim { key, result });
        }
        Request::Acoustic(d, sim) => {
            notify(Done::Acoustic { key, result: compute_acoustic(d, sim).map(Arc::new).map_err(|e| e.to_string()) })
        }
        Request::Chart(d, g) => {
            compute_chart(d, g, &key, None, notify);
        }
        Request::Relevel(d, passes) => notify(relevelled(d, passes)),
        Request::Export(job) => notify(job.run()),
    }
}

fn relevelled(d: &Design, passes: &ChartPasses) -> Done {
    let key = chart_key(d, &grids_of(passes));
    Done::Relevel { key, sound: sound_key(d), passes: Arc::new(compute_relevel(d, passes)) }
}

/// The grids of held chart passes (for their key).
pub fn grids_of(p: &ChartPasses) -> Grids {
    let grid = |c: &Chart| Grid { masses_kg: c.masses_kg.clone(), gaps_m: c.gaps_m.clone() };
    Grids { coarse: p.coarse.as_ref().map(grid), fine: grid(&p.fine) }
}

/// One job slot: the queued job, and the cancel flag and key of the running one.
struct Slot {
    state: Mutex<SlotState>,
    ready: Condvar,
}

#[derive(Default)]
struct SlotState {
    queued: Option<(String, Request, Arc<AtomicBool>)>,
    running: Option<(String, Arc<AtomicBool>)>,
    closed: bool,
}

impl Slot {
    fn new() -> Self {
        Self { state: Mutex::new(SlotState::default()), ready: Condvar::new() }
    }

    /// Queues `req` (replacing any queued job) and cancels a running job with another key.
    fn put(&self, key: String, req: Request) {
        let mut s = self.state.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((k, flag)) = &s.running {
            // The same work is already running (and not cancelled): its result will do.
            if *k == key && !flag.load(Ordering::Relaxed) {
                s.queued = None;
                return;
            }
            flag.store(true, Ordering::Relaxed);
        }
        s.queued = Some((key, req, Arc::new(AtomicBool::new(false))));
        self.ready.notify_one();
    }

    /// Waits for the next job; None when closed.
    fn take(&self) -> Option<(String, Request, Arc<AtomicBool>)> {
        let mut s = self.state.lock().unwrap_or_else(|e| e.into_inner());
        loop {
            if s.closed {
                return None;
            }
            if let Some(job) = s.queued.take() {
                s.running = Some((job.0.clone(), job.2.clone()));
                return Some(job);
            }
            s = self.ready.wait(s).unwrap_or_else(|e| e.into_inner());
        }
    }

    fn finished(&self) {
        self.state.lock().unwrap_or_else(|e| e.into_inner()).running = None;
    }

    fn close(&self) {
        let mut s = self.state.lock().unwrap_or_else(|e| e.into_inner());
        s.closed = true;
        if let Some((_, f)) = &s.running {
            f.store(true, Ordering::Relaxed);
        }
        self.ready.notify_all();
    }
}

type Notify = Arc<dyn Fn(Done) + Send + Sync>;

/// The background worker: one thread and one slot per job kind.
pub struct Worker {
    notify: Notify,
    sim: Arc<Slot>,
    acoustic: Arc<Slot>,
    chart: Arc<Slot>,
    levels: Arc<Slot>,
}

impl Worker {
    /// Starts the three threads; results go to `notify` (called from the worker threads).
    pub fn start(notify: impl Fn(Done) + Send + Sync + 'static) -> Self {
        let notify: Notify = Arc::new(notify);
        let new = || Arc::new(Slot::new());
        let w = Self { notify: notify.clone(), sim: new(), acoustic: new(), chart: new(), levels: new() };
        for slot in [&w.sim, &w.acoustic, &w.chart, &w.levels] {
            let (slot, notify) = (slot.clone(), notify.clone());
            std::thread::Builder::new()
                .name("thud-worker".into())
                .spawn(move || serve(&slot, &notify))
                .expect("spawn worker thread");
        }
        w
    }

    /// Queues a request in its slot (newest wins); an export gets a thread of its own.
    pub fn submit(&self, req: Request) {
        let key = request_key(&req);
        let slot = match req {
            Request::Export(job) => {
                let (kind, notify) = (job.kind, self.notify.clone());
                let spawned = std::thread::Builder::new().name("thud-export".into()).spawn(move || notify(job.run()));
                if let Err(e) = spawned {
                    let path = PathBuf::from(key);
                    (self.notify)(Done::Export { kind, path, result: Err(format!("cannot start: {e}")) });
                }
                return;
            }
            Request::Sim(_) => &self.sim,
            Request::Acoustic(..) => &self.acoustic,
            Request::Chart(..) => &self.chart,
            Request::Relevel(..) => &self.levels,
        };
        slot.put(key, req);
    }
}

impl Drop for Worker {
    fn drop(&mut self) {
        for s in [&self.sim, &self.acoustic, &self.chart, &self.levels] {
            s.close();
        }
    }
}

/// Per-thread caches of finished results, keyed by their parameters.
#[derive(Default)]
struct Caches {
    sim: HashMap<String, Arc<SimResult>>,
    acoustic: HashMap<String, Arc<AcousticResult>>,
    chart: HashMap<String, CachedChart>,
}

/// A finished chart: the sound key its levels are for, and its passes.
type CachedChart = (String, Vec<(Stage, Arc<Chart>)>);

fn bounded<V>(map: &mut HashMap<String, V>) -> &mut HashMap<String, V> {
    if map.len() >= CACHE_MAX {
        map.clear();
    }
    map
}

/// A worker thread: takes jobs from its slot until the worker is dropped.
fn serve(slot: &Slot, notify: &Notify) {
    let mut cache = Caches::default();
    while let Some((key, req, cancel)) = slot.take() {
        execute(&key, &req, &cancel, notify.as_ref(), &mut cache);
        slot.finished();
    }
}

fn execute(key: &str, req: &Request, cancel: &AtomicBool, notify: &(dyn Fn(Done) + Send + Sync), cache: &mut Caches) {
    let key = key.to_string();
    match req {
        Request::Sim(d) => {
            let result = match cache.sim.get(&key) {
                Some(hit) => Ok(hit.clone()),
                None => match compute_sim(d, Some(cancel)) {
                    Ok(None) => return,
                    Ok(Some(r)) => Ok(bounded(&mut cache.sim).entry(key.clone()).or_insert(Arc::new(r)).clone()),
                    Err(e) => Err(e.to_string()),
                },
            };
            notify(Done::Sim { key, result });
        }
        Request::Acoustic(d, sim) => {
            let result = match cache.acoustic.get(&key) {
                Some(hit) => Ok(hit.clone()),
                None => compute_acoustic(d, sim)
                    .map(|r| bounded(&mut cache.acoustic).entry(key.clone()).or_insert(Arc::new(r)).clone())
                    .map_err(|e| e.to_string()),
            };
            notify(Done::Acoustic { key, result });
        }
        Request::Chart(d, grids) => {
            if let Some((sound, hit)) = cache.chart.get(&key) {
                for (stage, chart) in hit {
                    let (key, sound, stage) = (key.clone(), sound.clone(), *stage);
                    notify(Done::Chart { key, sound, stage, result: Ok(chart.clone()) });
                }
                return;
            }
            let done: Mutex<Vec<(Stage, Arc<Chart>)>> = Mutex::new(Vec::new());
            let collect = |msg: Done| {
                if let Done::Chart { stage, result: Ok(c), .. } = &msg {
                    done.lock().unwrap_or_else(|e| e.into_inner()).push((*stage, c.clone()));
                }
                notify(msg);
            };
            if compute_chart(d, grids, &key, Some(cancel), &collect) {
                let passes = done.into_inner().unwrap_or_else(|e| e.into_inner());
                bounded(&mut cache.chart).insert(key, (sound_key(d), passes));
            }
        }
        Request::Relevel(d, passes) => notify(relevelled(d, passes)),
        Request::Export(job) => notify(job.run()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::mpsc;
    use std::time::Duration;

    #[test]
    fn keys_separate_what_they_should() {
        let d = Design::default();
        let moved = design::variant(&d, 0.05, 0.03);
        assert_ne!(sim_key(&d), sim_key(&moved));
        assert_eq!(chart_key(&d, &Grids::default()), chart_key(&moved, &Grids::default()));
        let mut heard = d.clone();
        heard.observer.r_m = 1.0;
        assert_eq!(sim_key(&d), sim_key(&heard));
        assert_ne!(acoustic_key(&d), acoustic_key(&heard));
        assert_eq!(chart_key(&d, &Grids::default()), chart_key(&heard, &Grids::default()), "observer relevels");
        assert_ne!(sound_key(&d), sound_key(&heard));
    }

    #[test]
    fn relevel_equals_a_fresh_sweep_at_the_new_observer() {
        let d = Design::default();
        let (m, g) = ([0.03, 0.06], [0.02, 0.04]);
        let chart = design::sweep(&d, &m, &g, None, &|_, _| {}).unwrap();
        let mut far = d.clone();
        far.observer = crate::acoustics::Observer::new(1.5, 30.0);
        let fresh = design::sweep(&far, &m, &g, None, &|_, _| {}).unwrap();
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
    fn slot_requeues_work_whose_running_copy_was_cancelled() {
        let slot = Slot::new();
        let (a, b) = (Design::default(), design::variant(&Design::default(), 0.05, 0.03));
        slot.put(sim_key(&a), Request::Sim(a.clone()));
        let (_, _, flag_a) = slot.take().unwrap();
        slot.put(sim_key(&b), Request::Sim(b));
        assert!(flag_a.load(Ordering::Relaxed), "a newer job cancels the running one");
        slot.put(sim_key(&a), Request::Sim(a.clone()));
        let queued = slot.state.lock().unwrap().queued.as_ref().map(|q| q.0.clone());
        assert_eq!(queued, Some(sim_key(&a)), "back to A: A runs again, B is dropped");
    }

    #[test]
    fn worker_answers_and_newest_wins() {
        let (tx, rx) = mpsc::channel();
        let w = Worker::start(move |d| {
            let _ = tx.send(d);
        });
        let a = Design::default();
        let b = design::variant(&a, 0.06, 0.03);
        w.submit(Request::Sim(a));
        w.submit(Request::Sim(b.clone()));
        let want = sim_key(&b);
        let got = loop {
            match rx.recv_timeout(Duration::from_secs(20)).expect("worker answered") {
                Done::Sim { key, result } if key == want => break result,
                _ => continue,
            }
        };
        let sim = got.unwrap();
        assert!(!sim.history_cm.is_empty() && sim.history_cm.len() == sim.free_cm.len());
    }
}
