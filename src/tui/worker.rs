//! The background worker: what the app asks for ([`Request`]) and what comes back ([`Done`]).
//! Six kinds of job — simulate the live design, its readout (acoustics, steady state, the
//! ensemble of N runs), the chart sweep, the chart's levels at a new observer, the frequency
//! response curve, the bifurcation diagram over f — each in its own [`SingleJob`] slot and thread (newest wins; see
//! [`super::job`]); exports run each on a short-lived thread of their own, never cancelled.
//! Results are tagged with the key of the parameters they were computed for (typed, see
//! [`super::cache_key`]), so the app drops stale ones, and cached by that key so going back
//! (undo, presets) is instant. What
//! the jobs compute is in [`super::compute`].

use std::collections::HashMap;
use std::hash::Hash;
use std::path::PathBuf;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;

use std::sync::atomic::{AtomicUsize, Ordering};

use super::cache_key::{BifurcationKey, ChartKey, ReadoutKey, ResponseKey, SimKey, SoundKey};
use super::compute::{
    bifurcation_band, compute_bifurcation, compute_branches, compute_chart, compute_ensemble_chart, compute_readout,
    compute_relevel, compute_response, compute_sim, grids_of, AcousticResult, ChartPasses, FreqBand, Grids, SimResult,
    Stage, BIFURCATION_VALUES,
};
use super::job::{self, Context, Job, JobError, SingleJob, Sink};
use crate::continuation::Branch;
use crate::design::{Cell, Chart, Design};
use crate::dynamics::Bifurcation;
use crate::ensemble::{Ensemble, EnsembleCell, EnsembleChart};
use crate::error::ThudError;
use crate::export::{self, Artifact, ExportOptions};
use crate::response::Response;

/// Cache entries kept per job kind before the cache is cleared.
const CACHE_MAX: usize = 256;

/// What the app asks for.
#[derive(Debug, Clone)]
pub enum Request {
    Sim(Design),
    /// The readout of a simulated design: its sound and steady state, and with N > 1 runs
    /// (the last field) its ensemble.
    Acoustic(Design, Arc<SimResult>, usize),
    /// A picture of the chart panel: the zone chart or the response curve.
    Chart(Design, ChartWork),
    /// The chart's SPLmax for the design's observer and radiation, from each cell's U0max:
    /// acoustics only, no simulation. Carries the chart passes to relevel.
    Relevel(Design, Arc<ChartPasses>),
    /// Write an export file (CSV, SVG or WAV) of the design: never cancelled, never cached;
    /// each one runs on its own short-lived thread.
    Export(Box<ExportJob>),
}

/// What the chart panel's job computes.
#[derive(Debug, Clone, PartialEq)]
pub enum ChartWork {
    /// The design chart over the grids, with N runs a cell (1: single runs; more: ensembles).
    Zones(Grids, usize),
    /// The frequency response of a forced design over a band (its own slot: it never cancels
    /// the zone chart, nor is cancelled by it).
    Response(FreqBand),
    /// The bifurcation diagram of a forced design over f ([`BIFURCATION_VALUES`]: a coarse
    /// pass, then the fine one; its own slot, newest wins).
    Bifurcation,
}

/// Why a job has no result.
#[derive(Debug, thiserror::Error)]
pub enum WorkError {
    /// The physics refused the design (a parameter out of range, a field point behind a wall).
    #[error(transparent)]
    Physics(#[from] ThudError),
    /// An export could not be rendered or written.
    #[error(transparent)]
    Export(crate::export::ExportError),
    /// The job panicked or could not start.
    #[error(transparent)]
    Job(#[from] JobError),
}

/// What comes back, tagged with the key of the parameters it was computed for.
#[derive(Debug)]
pub enum Done {
    Sim {
        key: SimKey,
        result: Result<Arc<SimResult>, WorkError>,
    },
    Acoustic {
        key: ReadoutKey,
        result: Result<Arc<AcousticResult>, WorkError>,
    },
    /// `sound` is the [`SoundKey`] the cell's SPLmax was computed for. In an ensemble chart
    /// `cell` holds the medians and `ensemble` the cell's runs.
    ChartCell {
        key: ChartKey,
        sound: SoundKey,
        stage: Stage,
        index: usize,
        cell: Cell,
        ensemble: Option<Arc<Ensemble>>,
    },
    /// A finished pass (of medians, with the ensembles, in an ensemble chart).
    Chart {
        key: ChartKey,
        sound: SoundKey,
        stage: Stage,
        result: Result<Arc<Chart>, WorkError>,
        ensembles: Option<Arc<EnsembleChart>>,
    },
    /// The response curve for `key`.
    Response {
        key: ResponseKey,
        result: Result<Arc<Response>, WorkError>,
    },
    /// `done` of `total` frequencies of the response curve for `key` are in.
    ResponseProgress {
        key: ResponseKey,
        done: usize,
        total: usize,
    },
    /// A pass of the bifurcation diagram over f: `key` is the pass's own (its band).
    Bifurcation {
        key: BifurcationKey,
        stage: Stage,
        result: Result<Arc<Bifurcation>, WorkError>,
    },
    /// The periodic orbits' branches over the fine pass's band: `key` is the fine pass's.
    Branches {
        key: BifurcationKey,
        result: Result<Arc<Vec<Branch>>, WorkError>,
    },
    /// The chart's passes relevelled for `sound`; `key` is the chart key.
    Relevel {
        key: ChartKey,
        sound: SoundKey,
        result: Result<Arc<ChartPasses>, WorkError>,
    },
    /// An export finished (or failed) writing `path`.
    Export {
        kind: Artifact,
        path: PathBuf,
        result: Result<(), WorkError>,
    },
}

/// One file to export.
#[derive(Debug, Clone)]
pub struct ExportJob {
    pub kind: Artifact,
    pub design: Design,
    pub options: ExportOptions,
    pub path: PathBuf,
    /// A figure's text spelled in ASCII (the explorer's `--ascii`), as `thud export --ascii` writes it.
    pub ascii: bool,
}

impl ExportJob {
    /// Renders and writes the file (a panic while doing so is reported as a failed export).
    pub fn run(&self) -> Done {
        let written = job::catch("export", || {
            let ascii = self.ascii && self.kind.is_figure();
            export::export_to_path_with(self.kind, &self.design, &self.options, &self.path, |bytes| {
                if ascii {
                    crate::ascii::figure(String::from_utf8_lossy(&bytes).into_owned()).into_bytes()
                } else {
                    bytes
                }
            })
        });
        let result = match written {
            Ok(r) => r.map_err(WorkError::Export),
            Err(e) => Err(e.into()),
        };
        Done::Export { kind: self.kind, path: self.path.clone(), result }
    }
}

/// Finished results kept on a job's thread, keyed by their parameters; cleared when full.
struct Cache<K, V>(HashMap<K, Arc<V>>);

impl<K, V> Default for Cache<K, V> {
    fn default() -> Self {
        Self(HashMap::new())
    }
}

impl<K: Hash + Eq, V> Cache<K, V> {
    fn get(&self, key: &K) -> Option<Arc<V>> {
        self.0.get(key).cloned()
    }

    fn insert(&mut self, key: K, value: V) -> Arc<V> {
        if self.0.len() >= CACHE_MAX {
            self.0.clear();
        }
        self.0.entry(key).or_insert(Arc::new(value)).clone()
    }
}

/// Simulate one design with its history.
struct SimJob {
    key: SimKey,
    design: Design,
}

impl Job for SimJob {
    const NAME: &'static str = "simulation";
    type Report = Done;
    type State = Cache<SimKey, SimResult>;
    type Key = SimKey;

    fn key(&self) -> &SimKey {
        &self.key
    }

    fn run(&self, cache: &mut Cache<SimKey, SimResult>, cx: &Context<'_, Done>) {
        let result = match cache.get(&self.key) {
            Some(hit) => Ok(hit),
            None => match compute_sim(&self.design, Some(cx.cancel_flag())) {
                Ok(None) => return,
                Ok(Some(r)) => Ok(cache.insert(self.key.clone(), r)),
                Err(e) => Err(e.into()),
            },
        };
        cx.report(Done::Sim { key: self.key.clone(), result });
    }

    fn failed(&self, error: JobError) -> Done {
        Done::Sim { key: self.key.clone(), result: Err(error.into()) }
    }
}

/// The readout of a simulated design: metrics, waveform, directivity, steady state, ensemble.
struct AcousticJob {
    key: ReadoutKey,
    design: Design,
    sim: Arc<SimResult>,
    runs: usize,
}

impl Job for AcousticJob {
    const NAME: &'static str = "acoustics";
    type Report = Done;
    type State = Cache<ReadoutKey, AcousticResult>;
    type Key = ReadoutKey;

    fn key(&self) -> &ReadoutKey {
        &self.key
    }

    fn run(&self, cache: &mut Cache<ReadoutKey, AcousticResult>, cx: &Context<'_, Done>) {
        let result = match cache.get(&self.key) {
            Some(hit) => Ok(hit),
            None => match compute_readout(&self.design, &self.sim, self.runs, Some(cx.cancel_flag())) {
                Ok(None) => return,
                Ok(Some(r)) => Ok(cache.insert(self.key.clone(), r)),
                Err(e) => Err(e.into()),
            },
        };
        cx.report(Done::Acoustic { key: self.key.clone(), result });
    }

    fn failed(&self, error: JobError) -> Done {
        Done::Acoustic { key: self.key.clone(), result: Err(error.into()) }
    }
}

/// A finished pass: the chart (of medians in an ensemble chart) and the ensembles.
type Pass = (Stage, Arc<Chart>, Option<Arc<EnsembleChart>>);

/// A finished chart: the sound key its levels are for, and its passes.
struct CachedChart {
    sound: SoundKey,
    passes: Vec<Pass>,
}

/// The chart sweep: every cell as it is done, then each pass.
struct ChartJob {
    key: ChartKey,
    design: Design,
    grids: Grids,
    /// Runs a cell (1: single runs).
    runs: usize,
}

impl ChartJob {
    /// The ensemble sweep: each cell reported as its medians with its runs.
    fn run_ensembles(&self, cx: &Context<'_, Done>, passes: &mut Vec<Pass>) -> bool {
        let (key, sound) = (&self.key, SoundKey::of(&self.design));
        let on_cell = |stage: Stage, index: usize, c: &EnsembleCell| {
            let cell = Cell { mass_kg: c.mass_kg, gap_m: c.gap_m, metrics: c.ensemble.metrics };
            let ensemble = Some(Arc::new(c.ensemble.clone()));
            cx.report(Done::ChartCell { key: key.clone(), sound: sound.clone(), stage, index, cell, ensemble });
        };
        let mut on_pass = |stage: Stage, result: Result<EnsembleChart, ThudError>| {
            let (result, ensembles) = match result {
                Ok(e) => {
                    let (chart, e) = (Arc::new(e.medians()), Arc::new(e));
                    passes.push((stage, chart.clone(), Some(e.clone())));
                    (Ok(chart), Some(e))
                }
                Err(e) => (Err(WorkError::from(e)), None),
            };
            cx.report(Done::Chart { key: key.clone(), sound: sound.clone(), stage, result, ensembles });
        };
        compute_ensemble_chart(&self.design, &self.grids, self.runs, Some(cx.cancel_flag()), &on_cell, &mut on_pass)
    }
}

impl Job for ChartJob {
    const NAME: &'static str = "chart";
    type Report = Done;
    type State = Cache<ChartKey, CachedChart>;
    type Key = ChartKey;

    fn key(&self) -> &ChartKey {
        &self.key
    }

    fn run(&self, cache: &mut Cache<ChartKey, CachedChart>, cx: &Context<'_, Done>) {
        let key = &self.key;
        if let Some(hit) = cache.get(key) {
            for (stage, chart, ensembles) in &hit.passes {
                let (key, sound, stage) = (key.clone(), hit.sound.clone(), *stage);
                let ensembles = ensembles.clone();
                cx.report(Done::Chart { key, sound, stage, result: Ok(chart.clone()), ensembles });
            }
            return;
        }
        let sound = SoundKey::of(&self.design);
        let mut passes = Vec::new();
        let finished = if self.runs > 1 {
            self.run_ensembles(cx, &mut passes)
        } else {
            let on_cell = |stage: Stage, index: usize, cell: &Cell| {
                let (key, sound, cell) = (key.clone(), sound.clone(), *cell);
                cx.report(Done::ChartCell { key, sound, stage, index, cell, ensemble: None });
            };
            let mut on_pass = |stage: Stage, result: Result<Chart, ThudError>| {
                let result = result.map(Arc::new).map_err(WorkError::from);
                if let Ok(c) = &result {
                    passes.push((stage, c.clone(), None));
                }
                cx.report(Done::Chart { key: key.clone(), sound: sound.clone(), stage, result, ensembles: None });
            };
            compute_chart(&self.design, &self.grids, Some(cx.cancel_flag()), &on_cell, &mut on_pass)
        };
        if finished {
            cache.insert(key.clone(), CachedChart { sound, passes });
        }
    }

    fn failed(&self, error: JobError) -> Done {
        let (key, sound) = (self.key.clone(), SoundKey::of(&self.design));
        Done::Chart { key, sound, stage: Stage::Fine, result: Err(error.into()), ensembles: None }
    }
}

/// The chart's levels at the design's observer, from each cell's U0max.
struct RelevelJob {
    /// The slot's key: the sound it relevels for.
    sound: SoundKey,
    design: Design,
    passes: Arc<ChartPasses>,
}

impl RelevelJob {
    /// The chart key its result carries.
    fn chart_key(&self) -> ChartKey {
        ChartKey::of(&self.design, &grids_of(&self.passes))
    }
}

impl Job for RelevelJob {
    const NAME: &'static str = "relevel";
    type Report = Done;
    type State = ();
    type Key = SoundKey;

    fn key(&self) -> &SoundKey {
        &self.sound
    }

    fn run(&self, (): &mut (), cx: &Context<'_, Done>) {
        let result = Ok(Arc::new(compute_relevel(&self.design, &self.passes)));
        cx.report(Done::Relevel { key: self.chart_key(), sound: self.sound.clone(), result });
    }

    fn failed(&self, error: JobError) -> Done {
        Done::Relevel { key: self.chart_key(), sound: self.sound.clone(), result: Err(error.into()) }
    }
}

/// The frequency response curve of a forced design (the key leaves out f: see
/// [`ResponseKey`]); progress as each frequency is done.
struct ResponseJob {
    key: ResponseKey,
    design: Design,
    band: FreqBand,
}

impl Job for ResponseJob {
    const NAME: &'static str = "response";
    type Report = Done;
    type State = Cache<ResponseKey, Response>;
    type Key = ResponseKey;

    fn key(&self) -> &ResponseKey {
        &self.key
    }

    fn run(&self, cache: &mut Cache<ResponseKey, Response>, cx: &Context<'_, Done>) {
        let result = if let Some(hit) = cache.get(&self.key) {
            Ok(hit)
        } else {
            let done = AtomicUsize::new(0);
            let total = self.band.points;
            let on_point = || {
                let n = done.fetch_add(1, Ordering::Relaxed) + 1;
                cx.report(Done::ResponseProgress { key: self.key.clone(), done: n, total });
            };
            match compute_response(&self.design, &self.band, Some(cx.cancel_flag()), &on_point) {
                Ok(None) => return,
                Ok(Some(r)) => Ok(cache.insert(self.key.clone(), r)),
                Err(e) => Err(e.into()),
            }
        };
        cx.report(Done::Response { key: self.key.clone(), result });
    }

    fn failed(&self, error: JobError) -> Done {
        Done::Response { key: self.key.clone(), result: Err(error.into()) }
    }
}

/// The bifurcation diagram of a forced design over f: the coarse pass, reported, then the
/// fine one (each cached by its own key; cancelled as soon as a newer design asks).
struct BifurcationJob {
    /// The fine pass's key (the job's).
    key: BifurcationKey,
    design: Design,
}

impl BifurcationJob {
    fn new(design: Design) -> Self {
        Self { key: BifurcationKey::of(&design, &bifurcation_band(&design, BIFURCATION_VALUES[1])), design }
    }
}

impl Job for BifurcationJob {
    const NAME: &'static str = "bifurcation";
    type Report = Done;
    type State = Cache<BifurcationKey, Bifurcation>;
    type Key = BifurcationKey;

    fn key(&self) -> &BifurcationKey {
        &self.key
    }

    fn run(&self, cache: &mut Cache<BifurcationKey, Bifurcation>, cx: &Context<'_, Done>) {
        for (stage, points) in [(Stage::Coarse, BIFURCATION_VALUES[0]), (Stage::Fine, BIFURCATION_VALUES[1])] {
            let band = bifurcation_band(&self.design, points);
            let key = BifurcationKey::of(&self.design, &band);
            let result = if let Some(hit) = cache.get(&key) {
                Ok(hit)
            } else {
                match compute_bifurcation(&self.design, &band, Some(cx.cancel_flag()), &|_| {}) {
                    Ok(None) => return,
                    Ok(Some(b)) => Ok(cache.insert(key.clone(), b)),
                    Err(e) => Err(e.into()),
                }
            };
            let failed = result.is_err();
            cx.report(Done::Bifurcation { key, stage, result });
            if failed {
                return;
            }
        }
        // Then the branches over the fine pass's band, drawn over its samples.
        let result = match compute_branches(
            &self.design,
            &bifurcation_band(&self.design, BIFURCATION_VALUES[1]),
            Some(cx.cancel_flag()),
        ) {
            Ok(None) => return,
            Ok(Some(b)) => Ok(Arc::new(b)),
            Err(e) => Err(e.into()),
        };
        cx.report(Done::Branches { key: self.key.clone(), result });
    }

    fn failed(&self, error: JobError) -> Done {
        Done::Bifurcation { key: self.key.clone(), stage: Stage::Fine, result: Err(error.into()) }
    }
}

/// A request as the job that answers it (an export is not a slot's job).
enum Work {
    Sim(SimJob),
    Acoustic(AcousticJob),
    Chart(ChartJob),
    Relevel(RelevelJob),
    Response(ResponseJob),
    Bifurcation(BifurcationJob),
    Export(Box<ExportJob>),
}

impl From<Request> for Work {
    fn from(req: Request) -> Self {
        match req {
            Request::Sim(design) => Work::Sim(SimJob { key: SimKey::of(&design), design }),
            Request::Acoustic(design, sim, runs) => {
                Work::Acoustic(AcousticJob { key: ReadoutKey::of(&design, runs), design, sim, runs })
            }
            Request::Chart(design, ChartWork::Zones(grids, runs)) => {
                Work::Chart(ChartJob { key: ChartKey::with_runs(&design, &grids, runs), design, grids, runs })
            }
            Request::Chart(design, ChartWork::Response(band)) => {
                Work::Response(ResponseJob { key: ResponseKey::of(&design, &band), design, band })
            }
            Request::Chart(design, ChartWork::Bifurcation) => Work::Bifurcation(BifurcationJob::new(design)),
            Request::Relevel(design, passes) => {
                Work::Relevel(RelevelJob { sound: SoundKey::of(&design), design, passes })
            }
            Request::Export(job) => Work::Export(job),
        }
    }
}

/// Runs one request on the calling thread, without cache or cancellation (tests, benches).
pub fn run_sync(req: &Request, notify: &(dyn Fn(Done) + Sync)) {
    fn once<J: Job>(job: &J, cx: &Context<'_, J::Report>) {
        job.run(&mut J::State::default(), cx);
    }
    let never = AtomicBool::new(false);
    let cx = Context::new(&never, notify);
    match Work::from(req.clone()) {
        Work::Sim(j) => once(&j, &cx),
        Work::Acoustic(j) => once(&j, &cx),
        Work::Chart(j) => once(&j, &cx),
        Work::Relevel(j) => once(&j, &cx),
        Work::Response(j) => once(&j, &cx),
        Work::Bifurcation(j) => once(&j, &cx),
        Work::Export(j) => notify(j.run()),
    }
}

/// The background worker: one slot and thread per kind of job, and exports on their own.
pub struct Worker {
    notify: Arc<Sink<Done>>,
    sim: SingleJob<SimJob>,
    acoustic: SingleJob<AcousticJob>,
    chart: SingleJob<ChartJob>,
    levels: SingleJob<RelevelJob>,
    response: SingleJob<ResponseJob>,
    bifurcation: SingleJob<BifurcationJob>,
}

impl Worker {
    /// Starts the six threads; results go to `notify` (called from the worker threads). A
    /// thread that cannot start answers each of its requests with that error.
    pub fn start(notify: impl Fn(Done) + Send + Sync + 'static) -> Self {
        let notify: Arc<Sink<Done>> = Arc::new(notify);
        Self {
            sim: SingleJob::start(notify.clone()),
            acoustic: SingleJob::start(notify.clone()),
            chart: SingleJob::start(notify.clone()),
            levels: SingleJob::start(notify.clone()),
            response: SingleJob::start(notify.clone()),
            bifurcation: SingleJob::start(notify.clone()),
            notify,
        }
    }

    /// Queues a request in its slot (newest wins); an export gets a thread of its own.
    pub fn submit(&self, req: Request) {
        match Work::from(req) {
            Work::Sim(j) => self.sim.spawn(j),
            Work::Acoustic(j) => self.acoustic.spawn(j),
            Work::Chart(j) => self.chart.spawn(j),
            Work::Relevel(j) => self.levels.spawn(j),
            Work::Response(j) => self.response.spawn(j),
            Work::Bifurcation(j) => self.bifurcation.spawn(j),
            Work::Export(j) => self.export(j),
        }
    }

    /// Writes an export on a thread of its own; if none can be started, says so.
    fn export(&self, job: Box<ExportJob>) {
        let (kind, path) = (job.kind, job.path.clone());
        let notify = self.notify.clone();
        let spawned = std::thread::Builder::new().name("thud-export".into()).spawn(move || notify(job.run()));
        if let Err(source) = spawned {
            let result = Err(JobError::NoThread { job: "export", source }.into());
            (self.notify)(Done::Export { kind, path, result });
        }
    }

    /// True while any slot has work queued or running (exports not counted).
    pub fn is_pending(&self) -> bool {
        self.sim.is_pending()
            || self.acoustic.is_pending()
            || self.chart.is_pending()
            || self.levels.is_pending()
            || self.response.is_pending()
            || self.bifurcation.is_pending()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::design;

    use std::sync::mpsc;
    use std::time::Duration;

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
        let want = SimKey::of(&b);
        let got = loop {
            match rx.recv_timeout(Duration::from_secs(20)).expect("worker answered") {
                Done::Sim { key, result } if key == want => break result,
                _ => {}
            }
        };
        let sim = got.unwrap();
        assert!(!sim.history_cm.is_empty() && sim.history_cm.len() == sim.free_cm.len());
    }

    #[test]
    fn a_refused_design_is_a_physics_error_not_a_stuck_slot() {
        let (tx, rx) = mpsc::channel();
        let w = Worker::start(move |d| {
            let _ = tx.send(d);
        });
        let mut bad = Design::default();
        bad.damper.impact_mass_kg = -1.0;
        w.submit(Request::Sim(bad));
        match rx.recv_timeout(Duration::from_secs(20)).expect("worker answered") {
            Done::Sim { result: Err(WorkError::Physics(e)), .. } => assert!(e.to_string().contains("mass"), "{e}"),
            other => panic!("expected a physics error, got {other:?}"),
        }
    }
}
