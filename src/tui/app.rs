//! The explorer's state and its one transition function, [`App::update`]: a message in (a key,
//! a click, a worker result, a tick), the state changed, and the work to ask for out. No
//! physics and no drawing here, so every behaviour can be tested without a terminal. The
//! other halves of `App` live beside it: what each key does in each mode in `input.rs`,
//! saving, loading and exporting in `files.rs`; the screen (popups too) is drawn by `ui.rs`.

use std::fmt::Display;
use std::path::PathBuf;
use std::sync::Arc;

use crossterm::event::{Event, MouseButton, MouseEventKind};

use super::chart::{DesignZone, Geometry};
use super::compute::{
    chart_key_runs, default_band, nearest, readout_key, response_key, sim_key, sound_key, AcousticResult, ChartPasses,
    Grids, SimResult, Stage,
};
use super::explain;
use super::fields::{Knob, Scope, Setup};
use super::keys::{Action, Keymap};
use super::theme::Palette;
use super::tour::{Tour, TourSource};
pub use super::view::{Panel, PulseView};
use super::worker::{ChartWork, Done, Request};
use crate::config::{self, Config, ConfigLoad, MarkerStyle};
use crate::design::{self, Chart, Design, Metrics, Thresholds, Zone};
use crate::ensemble::Ensemble;
use crate::presets::{self, PresetInfo};
use crate::response::Response;
use crate::store::DesignList;
use crate::units::sig;

/// Everything the app reacts to.
#[derive(Debug)]
pub enum Msg {
    /// A terminal event (key, mouse, resize).
    Input(Event),
    /// A worker result.
    Work(Done),
    /// Spinner tick (only sent while work is in flight).
    Tick,
    /// The terminal hung up (see `tui::hangup`): the explorer ends.
    Hangup,
}

/// The guided tour while it runs: the tour and the step shown.
#[derive(Debug, Clone)]
pub struct TourState {
    pub tour: Arc<Tour>,
    pub step: usize,
}

/// A design (with its ensemble size) as it was before a change, for undo.
#[derive(Debug, Clone)]
pub(crate) struct UndoEntry {
    pub design: Design,
    pub runs: usize,
    pub preset: String,
}

/// The zone-3 design of a chart furthest inside both thresholds, and why.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Best {
    pub mass_kg: f64,
    pub gap_m: f64,
    /// The smaller of `quiet` and `strong`: how far inside zone 3 the design is.
    pub margin: f64,
    /// 1 − p/p*: the fraction by which its rms pressure at SPLmax is under the pressure of L*.
    pub quiet: f64,
    /// (e − e*)/e*: the fraction by which its inclination is over e* (∞ when e* = 0).
    pub strong: f64,
    /// dB under L*.
    pub db_under: f64,
    /// How many computed cells are in zone 3.
    pub count: usize,
}

/// The zone-3 cell of `chart` with the largest margin under `t`: margin = min(1 − 10^((SPLmax −
/// L*)/20), (e − e*)/e*), the smaller of the relative distances inside the two thresholds (sound
/// pressure under L*'s, inclination over e*, both as fractions). None without a zone-3 cell.
pub fn best_zone3(chart: &Chart, t: &Thresholds) -> Option<Best> {
    let mut best: Option<Best> = None;
    let mut count = 0;
    for cell in chart.cells.iter().flatten() {
        let m = &cell.metrics;
        if m.zone(t) != Some(Zone::QuietStrong) {
            continue;
        }
        let (Some(spl), Some(e)) = (m.spl_max_db, m.inclination_by(t.zone_by)) else { continue };
        count += 1;
        let quiet = 1.0 - 10f64.powf((spl - t.spl_db) / 20.0);
        let strong =
            if t.inclination_cm_s > 0.0 { (e - t.inclination_cm_s) / t.inclination_cm_s } else { f64::INFINITY };
        let margin = quiet.min(strong);
        if best.is_none_or(|b| margin > b.margin) {
            best = Some(Best {
                mass_kg: cell.mass_kg,
                gap_m: cell.gap_m,
                margin,
                quiet,
                strong,
                db_under: t.spl_db - spl,
                count: 0,
            });
        }
    }
    best.map(|b| Best { count, ..b })
}

/// Which picture the chart panel shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ChartView {
    /// Mass × gap grid coloured by zone.
    Zones,
    /// e against SPLmax (Fig 17).
    Scatter,
    /// The frequency response of the forced design: amplitude with and without the damper,
    /// and Leq, against the forcing frequency, f marked.
    Response,
}

/// Modal state: the normal screen, or one popup / input line on top of it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Mode {
    Normal,
    /// The help's first page: the keys.
    Help,
    /// The help's second page, "what the numbers mean", scrolled down this many lines.
    Glossary(u16),
    /// Typing a value for the selected parameter.
    Editing(String),
    /// Choosing a preset; the highlighted index.
    Presets(usize),
    /// Typing the name to save the design under.
    SaveAs(String),
    /// A saved design of this name exists: `y` overwrites it, any other key keeps it.
    ConfirmOverwrite(String),
    /// Choosing a saved design to load (from the list read when it opened); the highlighted index.
    Saved(usize),
    /// Choosing what to export; the highlighted index in `files::EXPORTS`.
    Export(usize),
}

/// The status line's message.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Status {
    pub text: String,
    pub error: bool,
}

/// A design frozen with its results, shown beside the live one.
#[derive(Debug, Clone)]
pub struct Pinned {
    pub design: Design,
    pub sim: Option<Arc<SimResult>>,
    pub acoustic: Option<Arc<AcousticResult>>,
}

/// The chart as it fills in: the coarse pass and the fine pass, cell by cell.
#[derive(Debug, Clone)]
pub struct ChartState {
    pub key: String,
    /// The sound key (observer, radiation) the cells' SPLmax were computed for.
    pub levels_for: String,
    pub coarse: Option<Chart>,
    pub fine: Chart,
    /// Runs a cell N; with N > 1 the cells hold the medians of their ensembles.
    pub runs: usize,
    /// The ensembles of the fine pass's cells (N > 1), index as in `fine.cells`.
    pub ensembles: Vec<Option<Arc<Ensemble>>>,
}

impl ChartState {
    fn empty(design: &Design, grids: &Grids, runs: usize) -> Self {
        let fine = Chart::empty(grids.fine.masses_kg.clone(), grids.fine.gaps_m.clone(), design.thresholds);
        Self {
            key: chart_key_runs(design, grids, runs),
            levels_for: sound_key(design),
            coarse: grids
                .coarse
                .as_ref()
                .map(|g| Chart::empty(g.masses_kg.clone(), g.gaps_m.clone(), design.thresholds)),
            ensembles: vec![None; fine.cells.len()],
            fine,
            runs,
        }
    }

    /// The passes, for a relevel request.
    pub fn passes(&self) -> ChartPasses {
        ChartPasses { coarse: self.coarse.clone(), fine: self.fine.clone() }
    }

    /// (cells done, cells in all passes).
    pub fn progress(&self) -> (usize, usize) {
        let c = self.coarse.as_ref();
        let done = c.map_or(0, Chart::done) + self.fine.done();
        let total = c.map_or(0, |c| c.cells.len()) + self.fine.cells.len();
        (done, total)
    }
}

/// Options from the command line.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Options {
    pub preset: String,
    pub ascii: bool,
    pub mouse: bool,
    /// Where exports go; None: the current directory.
    pub export_dir: Option<PathBuf>,
    /// Start with the guided tour from here (the built-in one or a file).
    pub tour: Option<TourSource>,
}

impl Default for Options {
    fn default() -> Self {
        Self { preset: "default".into(), ascii: false, mouse: false, export_dir: None, tour: None }
    }
}

/// Undo depth.
const UNDO_MAX: usize = 200;

/// The explorer's whole state. The public fields are the ones a host (and the tests) set up
/// or inspect; the rest is the app's own.
pub struct App {
    pub design: Design,
    /// Runs per design N (the ensemble field; 1: the single trajectory).
    pub runs: usize,
    /// The name of the preset or saved design the live one came from.
    pub preset: String,
    /// The selected parameter (index into [`Knob::ALL`]).
    pub selected: usize,
    pub focus: Panel,
    pub mode: Mode,
    pub(crate) status: Option<Status>,
    pub(crate) undo: Vec<UndoEntry>,
    pub pinned: Option<Pinned>,
    pub(crate) chart_view: ChartView,
    pub(crate) grids: Grids,
    pub(crate) sim: Option<Arc<SimResult>>,
    /// The simulation key `sim` was computed for.
    pub(crate) sim_for: Option<String>,
    pub(crate) acoustic: Option<Arc<AcousticResult>>,
    /// The acoustics key `acoustic` was computed for.
    pub(crate) acoustic_for: Option<String>,
    pub chart: ChartState,
    /// An error from the chart sweep, if it failed.
    pub(crate) chart_error: Option<String>,
    /// An error from the physics for the current design (e.g. a field point the source rejects).
    pub(crate) work_error: Option<String>,
    pub theme: Palette,
    /// Mouse clicks select chart cells.
    pub mouse: bool,
    pub(crate) spinner: usize,
    pub quit: bool,
    /// Where the chart's cells were last drawn (for mouse clicks).
    pub chart_geometry: Option<Geometry>,
    /// The presets offered by the `P` list.
    pub preset_list: Vec<PresetInfo>,
    /// The keys in effect (the table with the config's overrides).
    pub(crate) keys: Keymap,
    /// The user's settings (defaults if there is no usable `config.toml`).
    pub(crate) config: Config,
    /// Where designs are saved (`designs/` inside); None: no home directory, saving refused.
    pub data_dir: Option<PathBuf>,
    /// Where exports are written (the current directory by default).
    pub export_dir: PathBuf,
    /// The saved designs offered by the load list (read when it opens).
    pub(crate) saved: DesignList,
    /// Export files being written.
    pub exports: Vec<PathBuf>,
    /// Which impact the pulse panel shows.
    pub pulse: PulseView,
    /// The guided tour, while it runs.
    pub tour: Option<TourState>,
    /// The tour `T` starts (the built-in one unless `--tour FILE` gave another).
    pub tour_def: Option<Arc<Tour>>,
    /// Whether the last frame showed the chart panel.
    pub chart_shown: bool,
    /// Jump to the best zone-3 design as soon as the chart is complete (a tour step asks).
    pub(crate) pending_best: bool,
    /// The response curve shown by the response view, and the key it was computed for.
    pub(crate) response: Option<Arc<Response>>,
    pub(crate) response_for: Option<String>,
    /// The key of the response curve last asked for (not asked again while it computes).
    pub(crate) response_asked: Option<String>,
    /// Why the response curve for `response_asked` could not be computed.
    pub(crate) response_error: Option<String>,
    /// (frequencies done, all) of the response curve being computed.
    pub(crate) response_progress: (usize, usize),
}

impl App {
    /// A new app on `design` (named `preset`) with the default chart grids.
    pub fn new(design: Design, preset: &str, theme: Palette) -> Self {
        Self::with_grids(design, preset, theme, Grids::default())
    }

    /// A new app with given chart grids (tests use a small one).
    pub fn with_grids(design: Design, preset: &str, theme: Palette, grids: Grids) -> Self {
        let chart = ChartState::empty(&design, &grids, 1);
        Self {
            design,
            runs: 1,
            preset: preset.to_string(),
            selected: 0,
            focus: Panel::Params,
            mode: Mode::Normal,
            status: Some(Status {
                text: "ready — ? help (twice: what the numbers mean), T guided tour".into(),
                error: false,
            }),
            undo: Vec::new(),
            pinned: None,
            chart_view: ChartView::Zones,
            grids,
            sim: None,
            sim_for: None,
            acoustic: None,
            acoustic_for: None,
            chart,
            chart_error: None,
            work_error: None,
            theme,
            mouse: false,
            spinner: 0,
            quit: false,
            chart_geometry: None,
            preset_list: presets::list().unwrap_or_else(|_| {
                presets::names().map(|name| PresetInfo { name, description: String::new() }).collect()
            }),
            keys: Keymap::default(),
            config: Config::default(),
            data_dir: None,
            export_dir: PathBuf::from("."),
            saved: DesignList::default(),
            exports: Vec::new(),
            pulse: PulseView::for_preset(preset),
            tour: None,
            tour_def: None,
            chart_shown: false,
            pending_best: false,
            response: None,
            response_for: None,
            response_asked: None,
            response_error: None,
            response_progress: (0, 0),
        }
    }

    /// Applies the user's settings (call before [`App::initial_requests`]): `mono` turns colour
    /// off, `ascii` markers avoid Braille, the thresholds become the design's, and the key
    /// overrides take effect. A problem with the file or an override goes to the status line;
    /// the rest of the settings still apply.
    pub fn configure(&mut self, load: &ConfigLoad) {
        let c = &load.config;
        if c.theme == config::Theme::Mono {
            self.theme.color = false;
        }
        if c.markers == MarkerStyle::Ascii {
            self.theme.ascii = true;
        }
        self.design.thresholds = c.thresholds(self.design.thresholds);
        let (keys, problems) = Keymap::with_overrides(&c.keys);
        self.keys = keys;
        self.config = c.clone();
        let mut warnings: Vec<String> = load.warning().into_iter().collect();
        warnings.extend(problems.iter().map(|p| format!("warning: {}: {p}", load.path.display())));
        if !warnings.is_empty() {
            self.status = Some(Status { text: warnings.join("; "), error: true });
        }
    }

    /// The work to start with: simulate the design and sweep the chart.
    pub fn initial_requests(&self) -> Vec<Request> {
        vec![
            Request::Sim(self.design.clone()),
            Request::Chart(self.design.clone(), ChartWork::Zones(self.grids.clone(), self.runs)),
        ]
    }

    /// The live design with the ensemble size: what the knobs turn.
    pub fn setup(&self) -> Setup {
        Setup { design: self.design.clone(), runs: self.runs }
    }

    /// Starts the guided tour (`tour_def`, else the built-in one) at its first step; returns
    /// the work that step needs. A tour that cannot be loaded is an error in the status line.
    pub fn start_tour(&mut self) -> Vec<Request> {
        let tour = match &self.tour_def {
            Some(t) => t.clone(),
            None => match Tour::load(&TourSource::BuiltIn) {
                Ok(t) => {
                    let t = Arc::new(t);
                    self.tour_def = Some(t.clone());
                    t
                }
                Err(e) => return self.error(e),
            },
        };
        self.tour = Some(TourState { tour, step: 0 });
        self.tour_step(0)
    }

    /// Shows step `i` of the running tour: its design (undoable), pulse view and panel.
    pub(crate) fn tour_step(&mut self, i: usize) -> Vec<Request> {
        let Some(state) = self.tour.as_mut() else { return vec![] };
        let Some(step) = state.tour.steps.get(i).cloned() else { return vec![] };
        state.step = i;
        let n = state.tour.steps.len();
        let mut d = step.design.clone();
        if !step.sets_thresholds {
            d.thresholds = self.config.thresholds(d.thresholds);
        }
        self.pulse = step.pulse;
        self.focus = if Panel::ALL.contains(&step.panel) { step.panel } else { Panel::Params };
        self.mode = Mode::Normal;
        let mut reqs = self.apply_setup(Setup { design: d, runs: step.runs }, Scope::All, String::new());
        self.preset.clone_from(&step.preset);
        self.set_status(&format!("tour {}/{n}: {} — → next, ← back, Esc explores from here", i + 1, step.title), false);
        self.pending_best = step.best;
        if step.best && !self.chart_busy() {
            reqs.extend(self.best());
        }
        reqs
    }

    /// Leaves the tour, keeping the design on screen to explore.
    pub(crate) fn leave_tour(&mut self, finished: bool) {
        self.tour = None;
        // Finishing lets the last step's jump to the best design happen; Esc keeps the state.
        if !finished {
            self.pending_best = false;
        }
        let text = if finished {
            "tour finished — explore from here (T starts it again)"
        } else {
            "left the tour — explore from here (T starts it again)"
        };
        self.set_status(text, false);
    }

    /// The panel the running tour's step talks about.
    pub fn tour_panel(&self) -> Option<Panel> {
        let t = self.tour.as_ref()?;
        t.tour.steps.get(t.step).map(|s| s.panel)
    }

    /// The zone the chart's marker shows: the live design's own, as the readout shows it.
    pub fn design_zone(&self) -> DesignZone {
        match self.metrics() {
            Some(m) if !self.design_busy() => DesignZone::Known(self.zone(m)),
            _ if self.work_error.is_some() => DesignZone::Known(None),
            _ => DesignZone::Computing,
        }
    }

    /// Jumps to the zone-3 design of the chart with the largest margin (see [`best_zone3`]),
    /// saying why in the status line; "none in zone 3" if there is none.
    pub fn best(&mut self) -> Vec<Request> {
        let fine = &self.chart.fine;
        let chart = if fine.done() > 0 { Some(fine) } else { self.chart.coarse.as_ref() };
        let (done, total) = self.chart.progress();
        let filling = if done < total { format!(" (chart still filling: {done}/{total})") } else { String::new() };
        let Some(b) = chart.and_then(|c| best_zone3(c, &self.design.thresholds)) else {
            self.set_status(
                &format!("none in zone 3 on this chart{filling}: no design is both quiet and strong"),
                false,
            );
            return vec![];
        };
        let reqs = self.select_design(b.mass_kg, b.gap_m);
        let by = match self.design.thresholds.zone_by {
            design::ZoneBy::Paper => "e",
            design::ZoneBy::Fit => "e_fit",
        };
        let strong = if b.strong.is_finite() {
            format!("{by} {:.0} % over e*", 100.0 * b.strong)
        } else {
            format!("{by} > e* = 0")
        };
        self.set_status(
            &format!(
                "best zone 3: m {} g, d {} cm; margin {:.0} % = min(sound pressure {:.0} % under L* ({} dB), {strong}), best of {} zone-3 cells{filling}",
                sig(b.mass_kg * 1e3, 3),
                sig(b.gap_m * 1e2, 3),
                100.0 * b.margin,
                100.0 * b.quiet,
                sig(b.db_under, 2),
                b.count
            ),
            false,
        );
        reqs
    }

    /// The status line's hint for the selected field (what it is, unit, range).
    pub(crate) fn show_hint(&mut self) {
        let h = explain::field_hint(self.param(), &self.design);
        self.set_status(&h, false);
    }

    /// The selected parameter.
    pub fn param(&self) -> Knob {
        Knob::ALL[self.selected.min(Knob::ALL.len() - 1)]
    }

    /// The status line's message, if any.
    pub fn status(&self) -> Option<&Status> {
        self.status.as_ref()
    }

    /// True while results for the current design are missing or being recomputed.
    pub fn busy(&self) -> bool {
        !self.exports.is_empty()
            || (self.work_error.is_none() && (self.design_busy() || self.chart_busy() || self.response_busy()))
    }

    /// True while the live design's readout is not for its current parameters.
    pub fn design_busy(&self) -> bool {
        self.acoustic_for.as_deref() != Some(readout_key(&self.design, self.runs).as_str())
    }

    /// The response curve of the live design, if computed for it (f aside: the curve does
    /// not depend on it).
    pub fn response(&self) -> Option<&Response> {
        let key = response_key(&self.design, &default_band(&self.design));
        self.response.as_deref().filter(|_| self.response_for.as_deref() == Some(key.as_str()))
    }

    /// True while the response view waits for its curve.
    pub fn response_busy(&self) -> bool {
        self.chart_view == ChartView::Response
            && self.design.damper.forced()
            && self.response().is_none()
            && self.response_error.is_none()
    }

    /// True while the chart is still filling in.
    pub fn chart_busy(&self) -> bool {
        let (done, total) = self.chart.progress();
        (done < total || self.chart.levels_for != sound_key(&self.design)) && self.chart_error.is_none()
    }

    /// Handles one message; returns the work to ask the worker for.
    pub fn update(&mut self, msg: Msg) -> Vec<Request> {
        match msg {
            Msg::Input(Event::Key(k)) => self.key(k),
            Msg::Input(Event::Mouse(m)) if self.mouse => match m.kind {
                MouseEventKind::Down(MouseButton::Left) => self.click(m.column, m.row),
                _ => vec![],
            },
            Msg::Input(_) => vec![],
            Msg::Work(done) => self.work(done),
            Msg::Tick => {
                self.spinner = self.spinner.wrapping_add(1);
                vec![]
            }
            Msg::Hangup => {
                self.quit = true;
                vec![]
            }
        }
    }

    /// Steps the selected parameter once (`up`: increase; `fine`: a small step).
    pub(crate) fn step(&mut self, up: bool, fine: bool) -> Vec<Request> {
        self.step_knob(self.param(), up, fine)
    }

    /// Steps field `f` once (`up`: increase; `fine`: a small step).
    pub(crate) fn step_knob(&mut self, f: Knob, up: bool, fine: bool) -> Vec<Request> {
        match f.stepped(&self.setup(), up, fine) {
            Ok(s) => {
                let message = self.change_message(f, &s, "");
                self.apply_setup(s, f.scope(), message)
            }
            Err(e) => self.error(e),
        }
    }

    /// Sets the selected parameter from typed text (a plain number in the unit the field
    /// shows); a bad value is refused with a message naming the field, and a value off the
    /// chart's range is accepted with a word saying so.
    pub fn submit_text(&mut self, text: &str) -> Vec<Request> {
        let f = self.param();
        match f.parsed(&self.setup(), text) {
            Ok(s) => {
                let off = self.off_chart(f, &s.design);
                let message = self.change_message(f, &s, &off);
                self.apply_setup(s, f.scope(), message)
            }
            Err(e) => self.error(e),
        }
    }

    /// The status line after field `f` changed to give `s`: "label value", with f when a force
    /// was switched on with it, and where f falls on the response curve's band.
    fn change_message(&self, f: Knob, s: &Setup, extra: &str) -> String {
        let mut m = format!("{} {}{extra}", f.label(), f.display(s));
        let (was, now) = (&self.design.damper, &s.design.damper);
        if f == Knob::Force && now.freq_hz != was.freq_hz {
            m += &format!("; {} {} (the natural frequency)", Knob::Freq.label(), Knob::Freq.display(s));
        }
        if f == Knob::Freq && self.chart_view == ChartView::Response {
            let band = default_band(&s.design);
            if !band.contains(now.freq_hz) {
                m += &format!(
                    " — off the response curve's band ({}–{} Hz): its marker is an arrow at the edge",
                    sig(band.from_hz, 3),
                    sig(band.to_hz, 3)
                );
            }
        }
        m
    }

    /// " — off the chart (…)" if field `f` of `d` (mass or gap) lies outside the chart's grid.
    fn off_chart(&self, f: Knob, d: &Design) -> String {
        let g = &self.grids.fine;
        let (values, v, unit, k) = match f {
            Knob::Mass => (&g.masses_kg, d.damper.impact_mass_kg, "g", 1e3),
            Knob::Gap => (&g.gaps_m, d.damper.gap_m, "cm", 1e2),
            _ => return String::new(),
        };
        let (Some(lo), Some(hi)) = (values.first(), values.last()) else { return String::new() };
        let half = if values.len() > 1 { 0.5 * (hi - lo) / (values.len() - 1) as f64 } else { 0.0 };
        if v < lo - half || v > hi + half {
            format!(
                " — off the chart ({}–{} {unit}): the chart marks it with an arrow at its edge",
                sig(lo * k, 3),
                sig(hi * k, 3)
            )
        } else {
            String::new()
        }
    }

    /// Moves the design to the neighbouring chart cell along mass (`axis` 1) or gap (0).
    pub(crate) fn chart_move(&mut self, axis: usize, up: bool) -> Vec<Request> {
        let g = &self.grids.fine;
        let (values, now) = if axis == 1 {
            (&g.masses_kg, self.design.damper.impact_mass_kg)
        } else {
            (&g.gaps_m, self.design.damper.gap_m)
        };
        let i = nearest(values, now);
        let j = if up { (i + 1).min(values.len() - 1) } else { i.saturating_sub(1) };
        let j = if values[i] != now && ((up && values[i] > now) || (!up && values[i] < now)) { i } else { j };
        let (m, d) = if axis == 1 {
            (values[j], self.design.damper.gap_m)
        } else {
            (self.design.damper.impact_mass_kg, values[j])
        };
        self.select_design(m, d)
    }

    /// Makes (mass, gap) the live design.
    pub fn select_design(&mut self, mass_kg: f64, gap_m: f64) -> Vec<Request> {
        let d = design::variant(&self.design, mass_kg, gap_m);
        let msg = format!(
            "m {} g, d {} cm",
            Knob::Mass.display(&d).trim_end_matches(" g"),
            Knob::Gap.display(&d).trim_end_matches(" cm")
        );
        self.apply(d, Scope::Design, msg)
    }

    fn click(&mut self, x: u16, y: u16) -> Vec<Request> {
        let Some((m, g)) = self.chart_geometry.as_ref().and_then(|geo| geo.hit(x, y)) else {
            return vec![];
        };
        self.focus = Panel::Chart;
        let grid = &self.grids.fine;
        let (mass, gap) = (grid.masses_kg[m], grid.gaps_m[g]);
        self.select_design(mass, gap)
    }

    pub(crate) fn toggle_pin(&mut self) {
        if self.pinned.take().is_some() {
            self.set_status("unpinned", false);
        } else {
            self.pinned =
                Some(Pinned { design: self.design.clone(), sim: self.sim.clone(), acoustic: self.acoustic.clone() });
            self.set_status("pinned this design: it stays on the plots (dim) while you change the live one", false);
        }
    }

    pub(crate) fn toggle_chart_view(&mut self) {
        self.chart_view = match self.chart_view {
            ChartView::Zones => ChartView::Scatter,
            ChartView::Scatter | ChartView::Response => ChartView::Zones,
        };
        self.say_chart_view();
    }

    /// Switches the chart panel to the response curve and back to the zones; returns the work
    /// the curve needs (none if it is cached, or without a force).
    pub(crate) fn toggle_response(&mut self) -> Vec<Request> {
        self.chart_view = match self.chart_view {
            ChartView::Response => ChartView::Zones,
            ChartView::Zones | ChartView::Scatter => ChartView::Response,
        };
        self.say_chart_view();
        self.response_request().into_iter().collect()
    }

    /// Says which picture the chart panel shows (and how to bring it on screen).
    fn say_chart_view(&mut self) {
        let view = match self.chart_view {
            ChartView::Zones => "zones over mass × gap".to_string(),
            ChartView::Scatter => "e vs SPLmax (Fig 17)".to_string(),
            ChartView::Response if self.design.damper.forced() => {
                let b = default_band(&self.design);
                format!(
                    "response over {}–{} Hz (0.6–1.6 × the natural frequency), f marked",
                    sig(b.from_hz, 3),
                    sig(b.to_hz, 3)
                )
            }
            ChartView::Response => {
                format!("frequency response: no force; set {} > 0 (↑ from mass m) to draw it", Knob::Force.label())
            }
        };
        let text = if self.chart_shown {
            format!("chart view: {view}")
        } else {
            format!("chart view: {view}; not on screen: press {} to show the chart", self.key_label(Action::FocusNext))
        };
        self.set_status(&text, false);
    }

    /// Switches the pulse panel between the run's loudest impact and one impact on a plate.
    pub(crate) fn toggle_pulse(&mut self) {
        self.pulse = match self.pulse {
            PulseView::Loudest => PulseView::Single,
            PulseView::Single => PulseView::Loudest,
        };
        let text = match self.pulse {
            PulseView::Loudest => "pulse: the loudest impact of the run (at U0max, against the main mass)".to_string(),
            PulseView::Single => format!(
                "pulse: one impact at U0 = v0 = {} m/s on a fixed plate (as thud pulse; the paper's Fig 2)",
                sig(self.design.damper.v0_m_s, 3)
            ),
        };
        self.set_status(&text, false);
    }

    pub(crate) fn undo(&mut self) -> Vec<Request> {
        if let Some(entry) = self.undo.pop() {
            let then = Setup { design: entry.design, runs: entry.runs };
            let what = changes(&self.setup(), &self.preset, &then, &entry.preset);
            self.design = then.design;
            self.runs = then.runs;
            self.preset = entry.preset;
            self.set_status(&format!("undo: {what}"), false);
            self.requests(Scope::All)
        } else {
            self.set_status("nothing to undo", false);
            vec![]
        }
    }

    /// Makes `new` the live design (pushing the old one for undo) and asks for what it needs.
    pub(crate) fn apply(&mut self, new: Design, scope: Scope, message: String) -> Vec<Request> {
        self.apply_setup(Setup { design: new, runs: self.runs }, scope, message)
    }

    /// Makes `new` the live design and ensemble size (pushing the old ones for undo) and asks
    /// for what they need.
    pub(crate) fn apply_setup(&mut self, new: Setup, scope: Scope, message: String) -> Vec<Request> {
        if new.design == self.design && new.runs == self.runs {
            self.set_status(&message, false);
            return vec![];
        }
        let old = std::mem::replace(&mut self.design, new.design);
        let old_runs = std::mem::replace(&mut self.runs, new.runs);
        self.undo.push(UndoEntry { design: old, runs: old_runs, preset: self.preset.clone() });
        if self.undo.len() > UNDO_MAX {
            self.undo.remove(0);
        }
        self.work_error = None;
        self.set_status(&message, false);
        self.requests(scope)
    }

    /// The work a change of `scope` needs (the worker's caches make repeats cheap).
    fn requests(&mut self, scope: Scope) -> Vec<Request> {
        let mut out = Vec::new();
        let sim_fresh = self.sim_for.as_deref() == Some(sim_key(&self.design).as_str());
        match (scope, &self.sim) {
            (Scope::Thresholds, _) => {}
            (Scope::Acoustics, Some(sim)) if sim_fresh => {
                out.push(Request::Acoustic(self.design.clone(), sim.clone(), self.runs));
            }
            _ => out.push(Request::Sim(self.design.clone())),
        }
        let key = chart_key_runs(&self.design, &self.grids, self.runs);
        if key != self.chart.key {
            self.chart = ChartState::empty(&self.design, &self.grids, self.runs);
            self.chart_error = None;
            out.push(Request::Chart(self.design.clone(), ChartWork::Zones(self.grids.clone(), self.runs)));
        } else if self.chart.levels_for != sound_key(&self.design) {
            out.push(self.relevel());
        }
        out.extend(self.response_request());
        out
    }

    /// The response curve's job, if the response view is shown, the design is forced and its
    /// curve (which does not depend on f) is neither in nor already asked for.
    fn response_request(&mut self) -> Option<Request> {
        if self.chart_view != ChartView::Response || !self.design.damper.forced() {
            return None;
        }
        let band = default_band(&self.design);
        let key = response_key(&self.design, &band);
        if self.response_for.as_deref() == Some(key.as_str()) || self.response_asked.as_deref() == Some(key.as_str()) {
            return None;
        }
        self.response_asked = Some(key);
        self.response_error = None;
        self.response_progress = (0, band.points);
        Some(Request::Chart(self.design.clone(), ChartWork::Response(band)))
    }

    /// Asks for the chart's levels at the current observer (acoustics only).
    fn relevel(&self) -> Request {
        Request::Relevel(self.design.clone(), Arc::new(self.chart.passes()))
    }

    /// Takes a worker result if it is for the current parameters; drops stale ones. A failed
    /// job (refused by the physics, or crashed) is an error in the status line.
    fn work(&mut self, done: Done) -> Vec<Request> {
        match done {
            Done::Sim { key, result } => {
                if key != sim_key(&self.design) {
                    return vec![];
                }
                match result {
                    Ok(sim) => {
                        if let Some(why) = sim.eval.run.truncated {
                            self.error(format_args!(
                                "run cut short: {} at t = {} s of {} s; the numbers cover only that time",
                                why.describe(),
                                crate::limits::short(sim.eval.run.final_time_s),
                                crate::limits::short(self.design.damper.duration_s)
                            ));
                        }
                        self.sim = Some(sim.clone());
                        self.sim_for = Some(key);
                        return vec![Request::Acoustic(self.design.clone(), sim, self.runs)];
                    }
                    Err(e) => self.fail(e),
                }
            }
            Done::Acoustic { key, result } => {
                if key != readout_key(&self.design, self.runs) {
                    return vec![];
                }
                match result {
                    Ok(a) => {
                        self.acoustic = Some(a);
                        self.acoustic_for = Some(key);
                    }
                    Err(e) => self.fail(e),
                }
            }
            Done::ChartCell { key, sound, stage, index, cell, ensemble } if key == self.chart.key => {
                if let Some(slot) = self.stage_chart(stage).and_then(|c| c.cells.get_mut(index)) {
                    *slot = Some(cell);
                }
                if let (Stage::Fine, Some(e)) = (stage, ensemble) {
                    if let Some(slot) = self.chart.ensembles.get_mut(index) {
                        *slot = Some(e);
                    }
                }
                if sound != sound_key(&self.design) {
                    self.chart.levels_for = sound;
                }
            }
            Done::Chart { key, sound, stage, result, ensembles } if key == self.chart.key => match result {
                Ok(chart) => {
                    if let Some(c) = self.stage_chart(stage) {
                        *c = (*chart).clone();
                    }
                    if let (Stage::Fine, Some(e)) = (stage, ensembles) {
                        self.chart.ensembles =
                            e.cells.iter().map(|c| c.as_ref().map(|c| Arc::new(c.ensemble.clone()))).collect();
                    }
                    if sound != sound_key(&self.design) {
                        self.chart.levels_for = sound;
                        return vec![self.relevel()];
                    }
                }
                Err(e) => self.chart_failed(e),
            },
            Done::Relevel { key, sound, result } if key == self.chart.key && sound == sound_key(&self.design) => {
                match result {
                    Ok(passes) => {
                        self.merge_levels(&passes);
                        self.chart.levels_for = sound;
                    }
                    Err(e) => self.chart_failed(e),
                }
            }
            Done::ChartCell { .. } | Done::Chart { .. } | Done::Relevel { .. } => {}
            Done::Response { key, result } => {
                if self.response_asked.as_deref() != Some(key.as_str()) {
                    return vec![];
                }
                match result {
                    Ok(r) => {
                        self.response = Some(r);
                        self.response_for = Some(key);
                    }
                    Err(e) => {
                        self.response_error = Some(e.to_string());
                        self.error(format_args!("response curve: {e}"));
                    }
                }
            }
            Done::ResponseProgress { key, done, total } => {
                if self.response_asked.as_deref() == Some(key.as_str()) {
                    self.response_progress = (done, total);
                }
            }
            Done::Export { kind, path, result } => self.export_finished(kind, &path, result),
        }
        if self.pending_best && !self.chart_busy() {
            self.pending_best = false;
            return self.best();
        }
        vec![]
    }

    /// Takes the relevelled cells (cells that arrived since the request keep theirs).
    fn merge_levels(&mut self, p: &ChartPasses) {
        let merge = |into: &mut Chart, from: &Chart| {
            for (a, b) in into.cells.iter_mut().zip(&from.cells) {
                if b.is_some() {
                    *a = *b;
                }
            }
        };
        if let (Some(c), Some(from)) = (self.chart.coarse.as_mut(), p.coarse.as_ref()) {
            merge(c, from);
        }
        merge(&mut self.chart.fine, &p.fine);
    }

    fn stage_chart(&mut self, stage: Stage) -> Option<&mut Chart> {
        match stage {
            Stage::Coarse => self.chart.coarse.as_mut(),
            Stage::Fine => Some(&mut self.chart.fine),
        }
    }

    /// The live design's work failed: its readout shows the error until the design changes.
    fn fail(&mut self, e: impl Display) {
        self.work_error = Some(e.to_string());
        self.error(e);
    }

    /// The chart's work failed: the chart stops filling in and the error is shown.
    fn chart_failed(&mut self, e: impl Display) {
        self.chart_error = Some(e.to_string());
        self.error(e);
    }

    /// Shows `e` as an error in the status line; asks for nothing.
    pub(crate) fn error(&mut self, e: impl Display) -> Vec<Request> {
        self.status = Some(Status { text: format!("error: {e}"), error: true });
        vec![]
    }

    pub(crate) fn set_status(&mut self, text: &str, error: bool) {
        self.status = Some(Status { text: text.to_string(), error });
    }

    /// The sound of the live design (metrics, pulses, polars), if computed.
    pub fn acoustic(&self) -> Option<&AcousticResult> {
        self.acoustic.as_deref()
    }

    /// The metrics of the live design, if computed for it.
    pub fn metrics(&self) -> Option<&Metrics> {
        self.acoustic.as_ref().map(|a| &a.metrics)
    }

    /// The zone of metrics under the current thresholds (classified on draw so threshold
    /// edits are free).
    pub fn zone(&self, m: &Metrics) -> Option<Zone> {
        m.zone(&self.design.thresholds)
    }

    /// The key shown for `action` (its first binding).
    pub fn key_label(&self, action: Action) -> &str {
        self.keys.label_of(action).unwrap_or("?")
    }
}

/// What differs between the live design (`now`, from preset `now_preset`) and `then`, as
/// "mass 45.50 g → 40.50 g" (at most three fields, then how many more).
pub fn changes(now: &Setup, now_preset: &str, then: &Setup, then_preset: &str) -> String {
    let mut parts = Vec::new();
    if now_preset != then_preset {
        parts.push(format!("preset {now_preset} → {then_preset}"));
    }
    let fields: Vec<String> = Knob::ALL
        .iter()
        .filter_map(|p| {
            let (a, b) = (p.display(now), p.display(then));
            (a != b).then(|| format!("{} {a} → {b}", p.param()))
        })
        .collect();
    let more = fields.len().saturating_sub(3);
    parts.extend(fields.into_iter().take(3));
    if more > 0 {
        parts.push(format!("and {more} more"));
    }
    if parts.is_empty() {
        "the design is as it was".into()
    } else {
        parts.join(", ")
    }
}
