//! The explorer's state: the live design and what was computed for it, what the screen shows,
//! and the host's set-up, grouped by concern in small structs; with the queries the view
//! (`ui.rs`) draws from. Nothing here asks for work or reads a file: the changes are the
//! other modules' (`change`, `screen`, `guide`, `files`, `input`, `update`).

use std::fmt::Display;
use std::path::PathBuf;
use std::sync::Arc;

use crate::config::{self, Config, ConfigLoad, MarkerStyle};
use crate::design::{Chart, Design, Metrics, Thresholds, Zone};
use crate::dynamics::Bifurcation;
use crate::ensemble::Ensemble;
use crate::presets::{self, PresetInfo};
use crate::response::Response;
use crate::store::DesignList;
use crate::tui::cache_key::{BifurcationKey, ChartKey, ReadoutKey, ResponseKey, SimKey, SoundKey};
use crate::tui::chart::DesignZone;
use crate::tui::compute::{
    bifurcation_band, default_band, AcousticResult, ChartPasses, Grids, SimResult, BIFURCATION_VALUES,
};
use crate::tui::fields::{Knob, Setup};
use crate::tui::keys::{Action, Keymap};
use crate::tui::theme::Palette;
use crate::tui::tour::{Tour, TourSource};
use crate::tui::view::{Drawn, Panel, PulseView};
use crate::tui::worker::Request;

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

/// Undo depth.
const UNDO_MAX: usize = 200;

/// The designs before each change, newest last (at most [`UNDO_MAX`]).
#[derive(Debug, Clone, Default)]
pub(crate) struct UndoStack(Vec<UndoEntry>);

impl UndoStack {
    /// Remembers `entry`, forgetting the oldest beyond [`UNDO_MAX`].
    pub(crate) fn push(&mut self, entry: UndoEntry) {
        self.0.push(entry);
        if self.0.len() > UNDO_MAX {
            self.0.remove(0);
        }
    }

    /// The newest entry, taken off the stack.
    pub(crate) fn pop(&mut self) -> Option<UndoEntry> {
        self.0.pop()
    }
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
    /// The bifurcation diagram of the forced design over f: x(kT) against f, f marked.
    Bifurcation,
}

/// Modal state: the normal screen, or one popup / input line on top of it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Mode {
    Normal,
    /// The help's first page, the keys, scrolled down this many lines.
    Help(u16),
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
    /// `q` with unsaved changes: `y` quits, any other key stays.
    ConfirmQuit,
    /// Choosing a saved design to load (from the list read when it opened); the highlighted index.
    Saved(usize),
    /// Choosing what to export; the highlighted index in `files::EXPORTS`.
    Export(usize),
    /// The `/` filter over the fields: the text typed and the highlighted match (an index
    /// into [`crate::tui::fields::find`]'s answer for it).
    Find(String, usize),
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
    pub key: ChartKey,
    /// The sound (observer, radiation) the cells' SPLmax were computed for.
    pub levels_for: SoundKey,
    pub coarse: Option<Chart>,
    pub fine: Chart,
    /// Runs a cell N; with N > 1 the cells hold the medians of their ensembles.
    pub runs: usize,
    /// The ensembles of the fine pass's cells (N > 1), index as in `fine.cells`.
    pub ensembles: Vec<Option<Arc<Ensemble>>>,
    /// The mass × gap grids the chart is swept over (a coarse pass first, then the fine one).
    pub grids: Grids,
    /// An error from the chart sweep, if it failed.
    pub(crate) error: Option<String>,
}

impl ChartState {
    /// The chart of `runs` runs a cell about `design` over `grids`, with no cell computed yet.
    pub(crate) fn empty(design: &Design, grids: &Grids, runs: usize) -> Self {
        let fine = Chart::empty(grids.fine.masses_kg.clone(), grids.fine.gaps_m.clone(), design.thresholds);
        Self {
            key: ChartKey::with_runs(design, grids, runs),
            levels_for: SoundKey::of(design),
            coarse: grids
                .coarse
                .as_ref()
                .map(|g| Chart::empty(g.masses_kg.clone(), g.gaps_m.clone(), design.thresholds)),
            ensembles: vec![None; fine.cells.len()],
            fine,
            runs,
            grids: grids.clone(),
            error: None,
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

/// The live design's own results: its run and its readout, each with the key it was computed
/// for, and the error that stopped them.
#[derive(Debug, Clone, Default)]
pub(crate) struct Results {
    pub sim: Option<Arc<SimResult>>,
    /// The simulation key `sim` was computed for.
    pub sim_for: Option<SimKey>,
    pub acoustic: Option<Arc<AcousticResult>>,
    /// The readout key `acoustic` was computed for.
    pub acoustic_for: Option<ReadoutKey>,
    /// An error from the physics for the current design (e.g. a field point the source
    /// rejects); cleared when the design changes.
    pub error: Option<String>,
}

/// The response view's curve: the one shown, the one asked for, and how far it is.
#[derive(Debug, Clone, Default)]
pub(crate) struct ResponseCurve {
    /// The curve shown by the response view, and the key it was computed for.
    pub curve: Option<Arc<Response>>,
    pub curve_for: Option<ResponseKey>,
    /// The key of the curve last asked for (not asked again while it computes).
    pub asked: Option<ResponseKey>,
    /// Why the curve for `asked` could not be computed.
    pub error: Option<String>,
    /// (frequencies done, all) of the curve being computed.
    pub progress: (usize, usize),
}

/// The bifurcation view's diagram: its coarse and fine passes with the keys they were
/// computed for, the periodic orbits' branches over the fine pass's band (with its key), the
/// fine key last asked for, and why it could not be computed.
#[derive(Debug, Clone, Default)]
pub(crate) struct BifurcationDiagram {
    pub coarse: Option<(BifurcationKey, Arc<Bifurcation>)>,
    pub fine: Option<(BifurcationKey, Arc<Bifurcation>)>,
    pub branches: Option<(BifurcationKey, Arc<Vec<crate::continuation::Branch>>)>,
    pub asked: Option<BifurcationKey>,
    pub error: Option<String>,
}

/// The user's settings and the keys they give.
#[derive(Debug, Clone, Default)]
pub(crate) struct Settings {
    /// The keys in effect (the table with the config's overrides).
    pub keys: Keymap,
    /// The user's settings (defaults if there is no usable `config.toml`).
    pub config: Config,
}

/// Options from the command line.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Options {
    pub preset: String,
    pub ascii: bool,
    /// Capture the mouse (on by default; `--no-mouse` and the config's `mouse = false` turn it
    /// off).
    pub mouse: bool,
    /// Where exports go; None: the current directory.
    pub export_dir: Option<PathBuf>,
    /// Start with the guided tour from here (the built-in one or a file).
    pub tour: Option<TourSource>,
    /// `--theme`: overrides the `theme` of `config.toml`.
    pub theme: Option<config::Theme>,
    /// `--front FILE`: the report of `thud design --json` whose front the front view shows.
    pub front: Option<PathBuf>,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            preset: "default".into(),
            ascii: false,
            mouse: true,
            export_dir: None,
            tour: None,
            theme: None,
            front: None,
        }
    }
}

/// The explorer's whole state. The public fields are the ones a host (and the tests) set up
/// or inspect; the rest is the app's own, grouped by concern.
pub struct App {
    // The live setup: what the knobs turn, and what undo and the pin keep of it.
    pub design: Design,
    /// Runs per design N (the ensemble field; 1: the single trajectory).
    pub runs: usize,
    /// The name of the preset or saved design the live one came from.
    pub preset: String,
    pub(crate) edits: Edits,
    pub pinned: Option<Pinned>,

    // What was computed: for the live design, the chart, the curves over f.
    pub(crate) results: Results,
    pub chart: ChartState,
    pub(crate) curves: Curves,

    // The screen: selection, focus, popups, views, the tour.
    /// The selected parameter (index into [`Knob::ALL`]).
    pub selected: usize,
    pub focus: Panel,
    pub mode: Mode,
    /// The guided tour, while it runs.
    pub tour: Option<TourState>,
    /// The animation view, while it shows (`a`).
    pub anim: Option<crate::tui::anim::Anim>,
    /// The Table 1 view, while it shows (`M`; the tour's Table 1 step).
    pub table1: Option<crate::tui::table1::Table1>,
    pub quit: bool,
    pub screen: Screen,
    /// What the last frame drew that a click needs (written back by the draw, one value).
    pub drawn: Drawn,

    // The host's set-up and the files.
    pub theme: Palette,
    /// Mouse clicks select chart cells.
    pub mouse: bool,
    pub host: Host,
}

/// The setup as last loaded or saved, and the designs before each change.
#[derive(Debug, Clone)]
pub(crate) struct Edits {
    /// The setup as last loaded (preset, saved design, tour step) or saved: the live one
    /// differs from it when the header marks the design modified (`*`).
    pub origin: (Design, usize),
    pub undo: UndoStack,
}

/// The live design's curves over f, each computed while its view shows.
#[derive(Debug, Clone, Default)]
pub(crate) struct Curves {
    pub response: ResponseCurve,
    /// The bifurcation view's diagram.
    pub bifurcation: BifurcationDiagram,
}

/// The screen's state beside the selection, the mode and the views: the input line, the
/// zoom, the chart's and the pulse's views, the tour's loose ends and the status line.
#[derive(Debug, Clone)]
pub struct Screen {
    /// The input line's text is selected (just opened with the current value or name):
    /// typing replaces it.
    pub line_selected: bool,
    /// The focused panel fills the body (the `z` key; the tour turns it on).
    pub zoom: bool,
    pub(crate) chart_view: ChartView,
    /// Which impact the pulse panel shows.
    pub pulse: PulseView,
    /// The tour just finished: the next key that would change the design (→ as "next" once
    /// more) only says what it will do from now on.
    pub(crate) tour_over: bool,
    /// Jump to the best zone-3 design as soon as the chart is complete (a tour step asks).
    pub(crate) pending_best: bool,
    /// The front view shows, with this front design selected (`D`; `--front FILE`).
    pub front: Option<usize>,
    pub(crate) status: Option<Status>,
    pub(crate) spinner: usize,
}

/// The host's set-up: the settings and their keys, the lists offered, and where files go.
#[derive(Debug, Clone)]
pub struct Host {
    pub(crate) settings: Settings,
    /// The presets offered by the `P` list.
    pub preset_list: Vec<PresetInfo>,
    /// The tour `T` starts (the built-in one unless `--tour FILE` gave another).
    pub tour_def: Option<Arc<Tour>>,
    /// Where designs are saved (`designs/` inside); None: no home directory, saving refused.
    pub data_dir: Option<PathBuf>,
    /// Where exports are written (the current directory by default).
    pub export_dir: PathBuf,
    /// The saved designs offered by the load list (read when it opens).
    pub(crate) saved: DesignList,
    /// Why the last load from that list failed (shown whole in the list, which stays open).
    pub(crate) load_error: Option<String>,
    /// Export files being written.
    pub exports: Vec<PathBuf>,
    /// The design front the front view shows (`--front FILE`).
    pub front: Option<Arc<crate::tui::front::Front>>,
}

/// Making an app.
impl App {
    /// A new app on `design` (named `preset`) with the default chart grids.
    pub fn new(design: Design, preset: &str, theme: Palette) -> Self {
        Self::with_grids(design, preset, theme, Grids::default())
    }

    /// A new app with given chart grids (tests use a small one).
    pub fn with_grids(design: Design, preset: &str, theme: Palette, grids: Grids) -> Self {
        let chart = ChartState::empty(&design, &grids, 1);
        Self {
            edits: Edits { origin: (design.clone(), 1), undo: UndoStack::default() },
            screen: Screen {
                line_selected: false,
                zoom: false,
                chart_view: ChartView::Zones,
                pulse: PulseView::for_preset(preset),
                tour_over: false,
                pending_best: false,
                front: None,
                status: Some(Status {
                    text: "ready — ? help (twice: what the numbers mean), T guided tour".into(),
                    error: false,
                }),
                spinner: 0,
            },
            design,
            runs: 1,
            preset: preset.to_string(),
            pinned: None,
            results: Results::default(),
            chart,
            curves: Curves::default(),
            selected: 0,
            focus: Panel::Params,
            mode: Mode::Normal,
            tour: None,
            anim: None,
            table1: None,
            quit: false,
            drawn: Drawn::default(),
            theme,
            mouse: false,
            host: Host {
                settings: Settings::default(),
                preset_list: presets::list().unwrap_or_else(|_| {
                    presets::names().map(|name| PresetInfo { name, description: String::new() }).collect()
                }),
                tour_def: None,
                data_dir: None,
                export_dir: PathBuf::from("."),
                saved: DesignList::default(),
                load_error: None,
                exports: Vec::new(),
                front: None,
            },
        }
    }

    /// Applies the user's settings (call before [`App::initial_requests`]): `mono` turns colour
    /// off, `ascii` markers avoid Braille, the thresholds become the design's, and the key
    /// overrides take effect. A problem with the file or an override goes to the status line;
    /// the rest of the settings still apply.
    pub fn configure(&mut self, load: &ConfigLoad) {
        let c = &load.config;
        self.theme = self.theme.with_theme(c.theme);
        if c.markers == MarkerStyle::Ascii {
            self.theme.ascii = true;
        }
        self.mouse &= c.mouse_on();
        self.design.thresholds = c.thresholds(self.design.thresholds);
        self.mark_unmodified();
        let (keys, problems) = Keymap::with_overrides(&c.keys);
        self.host.settings.keys = keys;
        self.host.settings.config = c.clone();
        let mut warnings: Vec<String> = load.warning().into_iter().collect();
        warnings.extend(problems.iter().map(|p| format!("warning: {}: {p}", load.path.display())));
        if !warnings.is_empty() {
            self.screen.status = Some(Status { text: warnings.join("; "), error: true });
        }
    }
}

/// What the view reads: the live setup, its results and how far the work is.
impl App {
    /// The live design with the ensemble size: what the knobs turn.
    pub fn setup(&self) -> Setup {
        Setup { design: self.design.clone(), runs: self.runs }
    }

    /// True if the live design (or N) differs from the one last loaded or saved.
    pub fn modified(&self) -> bool {
        self.design != self.edits.origin.0 || self.runs != self.edits.origin.1
    }

    /// The panel that fills the body while zoomed: the focused one (the readout when a tour
    /// step points at it).
    pub fn zoomed_panel(&self) -> Panel {
        match self.tour_panel() {
            Some(Panel::Readout) if self.focus == Panel::Params => Panel::Readout,
            _ => self.focus,
        }
    }

    /// The panel the running tour's step talks about.
    pub fn tour_panel(&self) -> Option<Panel> {
        let t = self.tour.as_ref()?;
        t.tour.steps.get(t.step).map(|s| s.panel)
    }

    /// The zone the chart's marker shows: the live design's own, as the readout shows it (with
    /// N > 1 the zone of its own ensemble's medians, never a single run's or a neighbour's).
    pub fn design_zone(&self) -> DesignZone {
        match self.acoustic() {
            Some(a) if !self.design_busy() => DesignZone::Known(match &a.ensemble {
                Some(e) => e.zone_under(&self.design.thresholds).0,
                None => self.zone(&a.metrics),
            }),
            _ if self.results.error.is_some() => DesignZone::Known(None),
            _ => DesignZone::Computing,
        }
    }

    /// The selected parameter.
    pub fn param(&self) -> Knob {
        Knob::ALL[self.selected.min(Knob::ALL.len() - 1)]
    }

    /// The status line's message, if any.
    pub fn status(&self) -> Option<&Status> {
        self.screen.status.as_ref()
    }

    /// True while results for the current design are missing or being recomputed.
    pub fn busy(&self) -> bool {
        !self.host.exports.is_empty()
            || (self.results.error.is_none()
                && (self.design_busy() || self.chart_busy() || self.response_busy() || self.bifurcation_busy()))
    }

    /// True while the live design's readout is not for its current parameters.
    pub fn design_busy(&self) -> bool {
        self.results.acoustic_for.as_ref() != Some(&ReadoutKey::of(&self.design, self.runs))
    }

    /// The response curve of the live design, if computed for it (f aside: the curve does
    /// not depend on it).
    pub fn response(&self) -> Option<&Response> {
        let key = ResponseKey::of(&self.design, &default_band(&self.design));
        self.curves.response.curve.as_deref().filter(|_| self.curves.response.curve_for.as_ref() == Some(&key))
    }

    /// True while the response view waits for its curve.
    pub fn response_busy(&self) -> bool {
        self.screen.chart_view == ChartView::Response
            && self.design.damper.forced()
            && self.response().is_none()
            && self.curves.response.error.is_none()
    }

    /// True while the chart is still filling in.
    /// The keys of the live design's bifurcation passes (coarse, fine).
    pub(crate) fn bifurcation_keys(&self) -> [BifurcationKey; 2] {
        BIFURCATION_VALUES.map(|n| BifurcationKey::of(&self.design, &bifurcation_band(&self.design, n)))
    }

    /// The live design's bifurcation diagram as far as it is computed: the fine pass, else the
    /// coarse one (with `false`: refining).
    pub fn bifurcation(&self) -> Option<(&Bifurcation, bool)> {
        let [coarse, fine] = self.bifurcation_keys();
        let d = &self.curves.bifurcation;
        match (&d.fine, &d.coarse) {
            (Some((k, b)), _) if *k == fine => Some((b, true)),
            (_, Some((k, b))) if *k == coarse => Some((b, false)),
            _ => None,
        }
    }

    /// The periodic orbits' branches over the live design's band, once computed.
    pub fn branches(&self) -> Option<&[crate::continuation::Branch]> {
        let [_, fine] = self.bifurcation_keys();
        match &self.curves.bifurcation.branches {
            Some((k, b)) if *k == fine => Some(b.as_slice()),
            _ => None,
        }
    }

    /// True while the bifurcation view is shown for a forced design and its fine pass is not in.
    pub fn bifurcation_busy(&self) -> bool {
        self.screen.chart_view == ChartView::Bifurcation
            && self.design.damper.forced()
            && !self.bifurcation().is_some_and(|(_, fine)| fine)
            && self.curves.bifurcation.error.is_none()
    }

    pub fn chart_busy(&self) -> bool {
        let (done, total) = self.chart.progress();
        (done < total || self.chart.levels_for != SoundKey::of(&self.design)) && self.chart.error.is_none()
    }

    /// The sound of the live design (metrics, pulses, polars), if computed.
    pub fn acoustic(&self) -> Option<&AcousticResult> {
        self.results.acoustic.as_deref()
    }

    /// The metrics of the live design, if computed for it.
    pub fn metrics(&self) -> Option<&Metrics> {
        self.results.acoustic.as_ref().map(|a| &a.metrics)
    }

    /// The zone of metrics under the current thresholds (classified on draw so threshold
    /// edits are free).
    pub fn zone(&self, m: &Metrics) -> Option<Zone> {
        m.zone(&self.design.thresholds)
    }

    /// The key shown for `action` (its first binding).
    pub fn key_label(&self, action: Action) -> &str {
        self.host.settings.keys.label_of(action).unwrap_or("?")
    }
}

/// The status line.
impl App {
    /// The live setup becomes the one that counts as unmodified (just loaded or saved).
    pub(crate) fn mark_unmodified(&mut self) {
        self.edits.origin = (self.design.clone(), self.runs);
    }

    /// Shows `e` as an error in the status line; asks for nothing.
    pub(crate) fn error(&mut self, e: impl Display) -> Vec<Request> {
        self.screen.status = Some(Status { text: format!("error: {e}"), error: true });
        vec![]
    }

    /// Shows `text` in the status line (red if `error`).
    pub(crate) fn set_status(&mut self, text: &str, error: bool) {
        self.screen.status = Some(Status { text: text.to_string(), error });
    }
}
