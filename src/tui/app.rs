//! The explorer's state and its one transition function, [`App::update`]: a message in (a key,
//! a click, a worker result, a tick), the state changed, and the work to ask for out. No
//! physics and no drawing here, so every behaviour can be tested without a terminal. The
//! other halves of `App` live beside it: what each key does in each mode in `input.rs`,
//! saving, loading and exporting in `files.rs`; the screen (popups too) is drawn by `ui.rs`.

use std::fmt::Display;
use std::path::PathBuf;
use std::sync::Arc;

use crossterm::event::{Event, MouseButton, MouseEventKind};

use super::chart::Geometry;
use super::compute::{
    acoustic_key, chart_key, nearest, sim_key, sound_key, AcousticResult, ChartPasses, Grids, SimResult, Stage,
};
use super::fields::{Param, Scope};
use super::keys::{Action, Keymap};
use super::theme::Palette;
use super::worker::{Done, Request};
use crate::config::{self, Config, ConfigLoad, MarkerStyle};
use crate::design::{self, Chart, Design, Metrics, Zone};
use crate::presets::{self, PresetInfo};
use crate::store::DesignList;

/// Everything the app reacts to.
#[derive(Debug)]
pub enum Msg {
    /// A terminal event (key, mouse, resize).
    Input(Event),
    /// A worker result.
    Work(Done),
    /// Spinner tick (only sent while work is in flight).
    Tick,
}

/// The panels; Tab cycles through them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Panel {
    Params,
    Waveform,
    Polar,
    History,
    Chart,
}

impl Panel {
    pub const ALL: [Panel; 5] = [Panel::Params, Panel::Waveform, Panel::Polar, Panel::History, Panel::Chart];

    pub(crate) fn cycle(self, forward: bool) -> Panel {
        let i = Self::ALL.iter().position(|p| *p == self).unwrap_or(0);
        let n = Self::ALL.len();
        Self::ALL[if forward { (i + 1) % n } else { (i + n - 1) % n }]
    }
}

/// Which picture the chart panel shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ChartView {
    /// Mass × gap grid coloured by zone.
    Zones,
    /// e against SPLmax (Fig 17).
    Scatter,
}

/// Modal state: the normal screen, or one popup / input line on top of it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Mode {
    Normal,
    Help,
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
}

impl ChartState {
    fn empty(design: &Design, grids: &Grids) -> Self {
        Self {
            key: chart_key(design, grids),
            levels_for: sound_key(design),
            coarse: grids
                .coarse
                .as_ref()
                .map(|g| Chart::empty(g.masses_kg.clone(), g.gaps_m.clone(), design.thresholds)),
            fine: Chart::empty(grids.fine.masses_kg.clone(), grids.fine.gaps_m.clone(), design.thresholds),
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
}

impl Default for Options {
    fn default() -> Self {
        Self { preset: "default".into(), ascii: false, mouse: false, export_dir: None }
    }
}

/// Undo depth.
const UNDO_MAX: usize = 200;

/// The explorer's whole state. The public fields are the ones a host (and the tests) set up
/// or inspect; the rest is the app's own.
pub struct App {
    pub design: Design,
    /// The name of the preset or saved design the live one came from.
    pub preset: String,
    /// The selected parameter (index into [`Param::ALL`]).
    pub selected: usize,
    pub focus: Panel,
    /// The plot shown in the compact layout (the last focused plot).
    pub(crate) plot: Panel,
    pub mode: Mode,
    pub(crate) status: Option<Status>,
    pub(crate) undo: Vec<Design>,
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
}

impl App {
    /// A new app on `design` (named `preset`) with the default chart grids.
    pub fn new(design: Design, preset: &str, theme: Palette) -> Self {
        Self::with_grids(design, preset, theme, Grids::default())
    }

    /// A new app with given chart grids (tests use a small one).
    pub fn with_grids(design: Design, preset: &str, theme: Palette, grids: Grids) -> Self {
        let chart = ChartState::empty(&design, &grids);
        Self {
            design,
            preset: preset.to_string(),
            selected: 0,
            focus: Panel::Params,
            plot: Panel::Chart,
            mode: Mode::Normal,
            status: Some(Status { text: "ready — press ? for help".into(), error: false }),
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
        vec![Request::Sim(self.design.clone()), Request::Chart(self.design.clone(), self.grids.clone())]
    }

    /// The selected parameter.
    pub fn param(&self) -> Param {
        Param::ALL[self.selected.min(Param::ALL.len() - 1)]
    }

    /// The status line's message, if any.
    pub fn status(&self) -> Option<&Status> {
        self.status.as_ref()
    }

    /// True while results for the current design are missing or being recomputed.
    pub fn busy(&self) -> bool {
        !self.exports.is_empty() || (self.work_error.is_none() && (self.design_busy() || self.chart_busy()))
    }

    /// True while the live design's readout is not for its current parameters.
    pub fn design_busy(&self) -> bool {
        self.acoustic_for.as_deref() != Some(acoustic_key(&self.design).as_str())
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
        }
    }

    /// Steps the selected parameter once (`up`: increase; `fine`: a small step).
    pub(crate) fn step(&mut self, up: bool, fine: bool) -> Vec<Request> {
        let f = self.param();
        match f.stepped(&self.design, up, fine) {
            Ok(d) => {
                let shown = f.display(&d);
                self.apply(d, f.scope(), format!("{} {}", f.label(), shown))
            }
            Err(e) => self.error(e),
        }
    }

    /// Sets the selected parameter from typed text; a bad value is refused with a message.
    pub fn submit_text(&mut self, text: &str) -> Vec<Request> {
        let f = self.param();
        match f.parsed(&self.design, text) {
            Ok(d) => {
                let shown = f.display(&d);
                self.apply(d, f.scope(), format!("{} {}", f.label(), shown))
            }
            Err(e) => self.error(e),
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
            Param::Mass.display(&d).trim_end_matches(" g"),
            Param::Gap.display(&d).trim_end_matches(" cm")
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
            ChartView::Scatter => ChartView::Zones,
        }
    }

    pub(crate) fn undo(&mut self) -> Vec<Request> {
        match self.undo.pop() {
            Some(d) => {
                self.design = d;
                self.set_status("undone", false);
                self.requests(Scope::All)
            }
            None => {
                self.set_status("nothing to undo", false);
                vec![]
            }
        }
    }

    /// Makes `new` the live design (pushing the old one for undo) and asks for what it needs.
    pub(crate) fn apply(&mut self, new: Design, scope: Scope, message: String) -> Vec<Request> {
        if new == self.design {
            self.set_status(&message, false);
            return vec![];
        }
        self.undo.push(std::mem::replace(&mut self.design, new));
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
            (Scope::Acoustics, Some(sim)) if sim_fresh => out.push(Request::Acoustic(self.design.clone(), sim.clone())),
            _ => out.push(Request::Sim(self.design.clone())),
        }
        let key = chart_key(&self.design, &self.grids);
        if key != self.chart.key {
            self.chart = ChartState::empty(&self.design, &self.grids);
            self.chart_error = None;
            out.push(Request::Chart(self.design.clone(), self.grids.clone()));
        } else if self.chart.levels_for != sound_key(&self.design) {
            out.push(self.relevel());
        }
        out
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
                        self.sim = Some(sim.clone());
                        self.sim_for = Some(key);
                        return vec![Request::Acoustic(self.design.clone(), sim)];
                    }
                    Err(e) => self.fail(e),
                }
            }
            Done::Acoustic { key, result } => {
                if key != acoustic_key(&self.design) {
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
            Done::ChartCell { key, sound, stage, index, cell } if key == self.chart.key => {
                if let Some(slot) = self.stage_chart(stage).and_then(|c| c.cells.get_mut(index)) {
                    *slot = Some(cell);
                }
                if sound != sound_key(&self.design) {
                    self.chart.levels_for = sound;
                }
            }
            Done::Chart { key, sound, stage, result } if key == self.chart.key => match result {
                Ok(chart) => {
                    if let Some(c) = self.stage_chart(stage) {
                        *c = (*chart).clone();
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
            Done::Export { kind, path, result } => self.export_finished(kind, &path, result),
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
