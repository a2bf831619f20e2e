//! The explorer's state and its one transition function, [`App::update`]: a message in (a key,
//! a click, a worker result, a tick), the state changed, and the work to ask for out. No
//! physics here, and no I/O but saving, listing and loading designs (small TOML files in the
//! data directory), so every behaviour can be tested without a terminal.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use crossterm::event::{Event, KeyCode, KeyEvent, KeyEventKind, KeyModifiers, MouseButton, MouseEventKind};

use super::chart::Geometry;
use super::fields::{Field, Scope};
use super::keys::{Action, Keymap};
use super::theme::Theme;
use super::worker::{
    acoustic_key, chart_key, sim_key, sound_key, AcousticResult, ChartPasses, Done, ExportJob, Grids, Request,
    SimResult, Stage,
};
use crate::config::{self, Config, ConfigLoad, MarkerStyle};
use crate::design::{self, Chart, Design, Metrics, Zone, ZoneBy};
use crate::export::{ExportOptions, Kind};
use crate::presets::{self, PresetInfo};
use crate::store::{self, DesignFile, DesignList};

/// Everything the app reacts to.
#[derive(Debug, Clone)]
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

    fn cycle(self, forward: bool) -> Panel {
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
    /// Typing a value for the selected field.
    Editing(String),
    /// Choosing a preset; the highlighted index.
    Presets(usize),
    /// Typing the name to save the design under.
    SaveAs(String),
    /// Choosing a saved design to load (the list is [`App::saved`]); the highlighted index.
    Saved(usize),
    /// Choosing what to export; the highlighted index in [`EXPORTS`].
    Export(usize),
}

/// What the export menu offers, in menu order, with how it is named there.
pub const EXPORTS: [(Kind, &str); 11] = [
    (Kind::CsvWaveform, "waveform CSV — pressure of the loudest impact"),
    (Kind::SvgWaveform, "waveform SVG"),
    (Kind::CsvHistory, "history CSV — x(t) with and without the damper"),
    (Kind::SvgHistory, "history SVG"),
    (Kind::CsvImpacts, "impacts CSV — every impact of the run"),
    (Kind::CsvSweep, "sweep CSV — the chart's mass × gap grid"),
    (Kind::SvgChart, "chart SVG — zones over mass × gap"),
    (Kind::SvgFig17, "Fig 17 SVG — e against SPLmax"),
    (Kind::SvgDirectivity, "directivity SVG — SPL against θ"),
    (Kind::SvgRestitution, "restitution SVG — e against impact mass"),
    (Kind::Wav, "sound WAV — the whole run at the observer, 48 kHz"),
];

/// The short name of an export kind ("waveform CSV").
pub fn export_name(kind: Kind) -> &'static str {
    let label = EXPORTS.iter().find(|(k, _)| *k == kind).map_or("file", |(_, l)| l);
    label.split(" — ").next().unwrap_or(label)
}

/// One row of a list popup (presets, saved designs, exports).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ListItem {
    pub label: String,
    /// Shown under the list for the highlighted row.
    pub detail: String,
    /// A row that cannot be chosen (e.g. a corrupt saved file).
    pub problem: bool,
}

/// A list popup to draw: title, rows, highlighted row, and a line for an empty list.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ListView {
    pub title: String,
    pub items: Vec<ListItem>,
    pub selected: usize,
    pub empty: String,
}

/// What a key does in a list popup.
enum ListNav {
    Stay,
    Choose(usize),
    Close,
    Quit,
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

/// The explorer's whole state.
pub struct App {
    pub design: Design,
    pub preset: String,
    pub selected: usize,
    pub focus: Panel,
    /// The plot shown in the compact layout (the last focused plot).
    pub plot: Panel,
    pub mode: Mode,
    pub status: Option<Status>,
    pub undo: Vec<Design>,
    pub pinned: Option<Pinned>,
    pub chart_view: ChartView,
    pub grids: Grids,
    pub sim: Option<Arc<SimResult>>,
    /// The simulation key `sim` was computed for.
    pub sim_for: Option<String>,
    pub acoustic: Option<Arc<AcousticResult>>,
    /// The acoustics key `acoustic` was computed for.
    pub acoustic_for: Option<String>,
    pub chart: ChartState,
    /// An error from the chart sweep, if it failed.
    pub chart_error: Option<String>,
    /// An error from the physics for the current design (e.g. a field point the source rejects).
    pub work_error: Option<String>,
    pub theme: Theme,
    pub mouse: bool,
    pub spinner: usize,
    pub quit: bool,
    /// Where the chart's cells were last drawn (for mouse clicks).
    pub chart_geometry: Option<Geometry>,
    /// The presets offered by the `P` list.
    pub preset_list: Vec<PresetInfo>,
    /// The keys in effect (the table with the config's overrides).
    pub keys: Keymap,
    /// The user's settings (defaults if there is no usable `config.toml`).
    pub config: Config,
    /// Where designs are saved (`designs/` inside); None: no home directory, saving refused.
    pub data_dir: Option<PathBuf>,
    /// Where exports are written (the current directory by default).
    pub export_dir: PathBuf,
    /// The saved designs offered by the load list (read when it opens).
    pub saved: DesignList,
    /// Export files being written.
    pub exports: Vec<PathBuf>,
}

impl App {
    /// A new app on `design` (named `preset`) with the default chart grids.
    pub fn new(design: Design, preset: &str, theme: Theme) -> Self {
        Self::with_grids(design, preset, theme, Grids::default())
    }

    /// A new app with given chart grids (tests use a small one).
    pub fn with_grids(design: Design, preset: &str, theme: Theme, grids: Grids) -> Self {
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

    /// The selected field.
    pub fn field(&self) -> Field {
        Field::ALL[self.selected.min(Field::ALL.len() - 1)]
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

    fn key(&mut self, k: KeyEvent) -> Vec<Request> {
        if k.kind == KeyEventKind::Release {
            return vec![];
        }
        if k.code == KeyCode::Char('c') && k.modifiers.contains(KeyModifiers::CONTROL) {
            self.quit = true;
            return vec![];
        }
        match self.mode.clone() {
            Mode::Editing(buf) => self.edit_key(k, buf),
            Mode::SaveAs(buf) => self.save_key(k, buf),
            Mode::Presets(i) => self.preset_key(k, i),
            Mode::Saved(i) => self.saved_key(k, i),
            Mode::Export(i) => self.export_key(k, i),
            Mode::Help => {
                match self.keys.action_for(&k) {
                    Some(Action::Quit) if k.code != KeyCode::Esc => self.quit = true,
                    _ => self.mode = Mode::Normal,
                }
                vec![]
            }
            Mode::Normal => self.keys.action_for(&k).map_or_else(Vec::new, |a| self.act(a)),
        }
    }

    /// Performs one action of the key table.
    pub fn act(&mut self, a: Action) -> Vec<Request> {
        match a {
            Action::Quit => self.quit = true,
            Action::Help => self.mode = Mode::Help,
            Action::FocusNext | Action::FocusPrev => {
                self.focus = self.focus.cycle(a == Action::FocusNext);
                if self.focus != Panel::Params {
                    self.plot = self.focus;
                }
            }
            Action::Up | Action::Down if self.focus == Panel::Chart => return self.chart_move(0, a == Action::Up),
            Action::Up => self.selected = (self.selected + Field::ALL.len() - 1) % Field::ALL.len(),
            Action::Down => self.selected = (self.selected + 1) % Field::ALL.len(),
            Action::Decrease { .. } | Action::Increase { .. } if self.focus == Panel::Chart => {
                return self.chart_move(1, matches!(a, Action::Increase { .. }))
            }
            Action::Decrease { fine } => return self.step(false, fine),
            Action::Increase { fine } => return self.step(true, fine),
            Action::Edit => self.mode = Mode::Editing(String::new()),
            Action::Presets => {
                let i = self.preset_list.iter().position(|p| p.name == self.preset).unwrap_or(0);
                self.mode = Mode::Presets(i);
            }
            Action::Pin => self.toggle_pin(),
            Action::Undo => return self.undo(),
            Action::ToggleChartView => {
                self.chart_view = match self.chart_view {
                    ChartView::Zones => ChartView::Scatter,
                    ChartView::Scatter => ChartView::Zones,
                }
            }
            Action::Save => self.mode = Mode::SaveAs(self.suggested_name()),
            Action::Load => self.open_saved(),
            Action::Export => self.mode = Mode::Export(0),
        }
        vec![]
    }

    fn step(&mut self, up: bool, fine: bool) -> Vec<Request> {
        let f = self.field();
        match f.stepped(&self.design, up, fine) {
            Ok(d) => {
                let shown = f.display(&d);
                self.apply(d, f.scope(), format!("{} {}", f.label(), shown))
            }
            Err(e) => self.error(e.to_string()),
        }
    }

    fn edit_key(&mut self, k: KeyEvent, buf: String) -> Vec<Request> {
        match line_key(k, buf, 40) {
            Line::Typing(buf) => self.mode = Mode::Editing(buf),
            Line::Cancel => {
                self.mode = Mode::Normal;
                self.set_status("input cancelled", false);
            }
            Line::Submit(buf) => {
                self.mode = Mode::Normal;
                return self.submit_text(&buf);
            }
        }
        vec![]
    }

    fn save_key(&mut self, k: KeyEvent, buf: String) -> Vec<Request> {
        match line_key(k, buf, 64) {
            Line::Typing(buf) => self.mode = Mode::SaveAs(buf),
            Line::Cancel => {
                self.mode = Mode::Normal;
                self.set_status("save cancelled", false);
            }
            Line::Submit(name) => {
                self.mode = Mode::Normal;
                self.save_as(name.trim());
            }
        }
        vec![]
    }

    /// The name offered when saving: the preset's or saved design's name, or the first free
    /// `design-N`.
    pub fn suggested_name(&self) -> String {
        if self.preset != "default" && store::check_design_name(&self.preset).is_ok() {
            return self.preset.clone();
        }
        let taken = |name: &str| {
            self.data_dir.as_deref().is_some_and(|d| store::design_path(d, name).is_ok_and(|p| p.exists()))
        };
        (1..).map(|n| format!("design-{n}")).find(|n| !taken(n)).unwrap_or_else(|| "design-1".into())
    }

    /// Saves the live design as `name` in the data directory (a small file, written
    /// atomically on this thread); the outcome goes to the status line.
    pub fn save_as(&mut self, name: &str) {
        if let Err(e) = store::check_design_name(name) {
            self.error(format!("cannot save: {e}"));
            return;
        }
        let Some(dir) = self.data_dir.clone() else {
            self.error("cannot save: no home directory, so no data directory".into());
            return;
        };
        let p = &self.design.damper;
        let description = format!(
            "saved from the explorer: m {} g, d {} cm (from {})",
            crate::units::sig(p.impact_mass_kg * 1e3, 4),
            crate::units::sig(p.gap_m * 1e2, 3),
            self.preset
        );
        let file = DesignFile { description, design: self.design.clone() };
        match store::save_design(&dir, name, &file, false) {
            Ok(path) => {
                self.preset = name.to_string();
                self.set_status(&format!("saved {name} to {}", path.display()), false);
            }
            Err(e) => {
                self.error(format!("cannot save {name}: {e}"));
            }
        }
    }

    /// Opens the list of saved designs (read from the data directory now: a few small files).
    fn open_saved(&mut self) {
        let Some(dir) = self.data_dir.clone() else {
            self.error("cannot load: no home directory, so no data directory".into());
            return;
        };
        match store::list_designs(&dir) {
            Ok(list) => {
                let i = list.designs.iter().position(|d| d.name == self.preset).unwrap_or(0);
                self.saved = list;
                self.mode = Mode::Saved(i);
            }
            Err(e) => {
                self.error(format!("cannot list saved designs: {e}"));
            }
        }
    }

    /// The popup list of the current mode, if it shows one.
    pub fn list_view(&self) -> Option<ListView> {
        let (title, items, selected, empty) = match &self.mode {
            Mode::Presets(i) => (
                " presets (↑↓, Enter applies, Esc closes) ".to_string(),
                self.preset_list
                    .iter()
                    .map(|p| ListItem { label: p.name.to_string(), detail: p.description.clone(), problem: false })
                    .collect(),
                *i,
                String::new(),
            ),
            Mode::Saved(i) => {
                let good = self.saved.designs.iter().map(|d| ListItem {
                    label: d.name.clone(),
                    detail: d.description.clone(),
                    problem: false,
                });
                let bad = self.saved.problems.iter().map(|p| ListItem {
                    label: format!(
                        "✗ {} (cannot be loaded)",
                        p.path.file_name().map_or_else(|| p.path.display().to_string(), |n| n.to_string_lossy().into())
                    ),
                    detail: p.to_string(),
                    problem: true,
                });
                let dir = self.data_dir.as_deref().map_or_else(PathBuf::new, store::designs_dir);
                (
                    " saved designs (↑↓, Enter loads, Esc closes) ".to_string(),
                    good.chain(bad).collect(),
                    *i,
                    format!(
                        "No saved designs in {}; press {} to save one.",
                        dir.display(),
                        self.key_label(Action::Save)
                    ),
                )
            }
            Mode::Export(i) => (
                " export (↑↓, Enter writes the file, Esc closes) ".to_string(),
                EXPORTS
                    .iter()
                    .map(|(k, label)| ListItem {
                        label: label.to_string(),
                        detail: format!("{} in {}", k.default_file_name(), self.export_dir_name()),
                        problem: false,
                    })
                    .collect(),
                *i,
                String::new(),
            ),
            _ => return None,
        };
        Some(ListView { title, items, selected, empty })
    }

    /// The key shown for `action` (its first binding).
    pub fn key_label(&self, action: Action) -> &str {
        self.keys.label_of(action).unwrap_or("?")
    }

    /// Up/down/Enter/Esc in a list of `n` rows with row `i` highlighted.
    fn list_nav(&mut self, k: KeyEvent, i: usize, n: usize, mode: fn(usize) -> Mode) -> ListNav {
        let n = n.max(1);
        match k.code {
            KeyCode::Up | KeyCode::Char('k') => self.mode = mode((i + n - 1) % n),
            KeyCode::Down | KeyCode::Char('j') => self.mode = mode((i + 1) % n),
            KeyCode::Home => self.mode = mode(0),
            KeyCode::End => self.mode = mode(n - 1),
            KeyCode::Enter => {
                self.mode = Mode::Normal;
                return ListNav::Choose(i);
            }
            KeyCode::Char('q') => {
                self.quit = true;
                return ListNav::Quit;
            }
            _ => {
                self.mode = Mode::Normal;
                return ListNav::Close;
            }
        }
        ListNav::Stay
    }

    fn saved_key(&mut self, k: KeyEvent, i: usize) -> Vec<Request> {
        let n = self.saved.designs.len() + self.saved.problems.len();
        let ListNav::Choose(i) = self.list_nav(k, i, n, Mode::Saved) else { return vec![] };
        if let Some(entry) = self.saved.designs.get(i) {
            let name = entry.name.clone();
            let Some(dir) = self.data_dir.clone() else { return vec![] };
            return match store::load_design(&dir, &name) {
                Ok(file) => {
                    self.preset = name.clone();
                    self.apply(file.design, Scope::All, format!("loaded {name} (u undoes)"))
                }
                Err(e) => self.error(format!("cannot load {name}: {e}")),
            };
        }
        match i.checked_sub(self.saved.designs.len()).and_then(|j| self.saved.problems.get(j)) {
            Some(p) => self.error(format!("cannot load {p}")),
            None => vec![],
        }
    }

    fn export_key(&mut self, k: KeyEvent, i: usize) -> Vec<Request> {
        let ListNav::Choose(i) = self.list_nav(k, i, EXPORTS.len(), Mode::Export) else { return vec![] };
        let Some(&(kind, _)) = EXPORTS.get(i) else { return vec![] };
        vec![self.export(kind)]
    }

    /// Asks the worker to write an export of `kind` into the export directory, under its
    /// default name (with -1, -2 … added if that file exists or is being written).
    pub fn export(&mut self, kind: Kind) -> Request {
        let path = unique_path(&self.export_dir, kind.default_file_name(), &self.exports);
        self.exports.push(path.clone());
        // Sweeps use the chart's grid, so the file shows what the screen does.
        let g = &self.grids.fine;
        let options = if kind.needs_sweep() {
            ExportOptions {
                masses_kg: Some(g.masses_kg.clone()),
                gaps_m: Some(g.gaps_m.clone()),
                ..ExportOptions::default()
            }
        } else {
            ExportOptions::default()
        };
        self.set_status(&format!("exporting {} to {} …", export_name(kind), self.shown_path(&path)), false);
        Request::Export(Box::new(ExportJob { kind, design: self.design.clone(), options, path }))
    }

    /// The export directory as shown.
    fn export_dir_name(&self) -> String {
        if self.export_dir == Path::new(".") {
            "the current directory".into()
        } else {
            self.export_dir.display().to_string()
        }
    }

    /// An export path as shown: the file name alone in the current directory.
    fn shown_path(&self, path: &Path) -> String {
        if self.export_dir == Path::new(".") {
            path.file_name().map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned())
        } else {
            path.display().to_string()
        }
    }

    /// Sets the selected field from typed text; a bad value is refused with a message.
    pub fn submit_text(&mut self, text: &str) -> Vec<Request> {
        let f = self.field();
        match f.parsed(&self.design, text) {
            Ok(d) => {
                let shown = f.display(&d);
                self.apply(d, f.scope(), format!("{} {}", f.label(), shown))
            }
            Err(e) => self.error(e.to_string()),
        }
    }

    fn preset_key(&mut self, k: KeyEvent, i: usize) -> Vec<Request> {
        let ListNav::Choose(i) = self.list_nav(k, i, self.preset_list.len(), Mode::Presets) else { return vec![] };
        let Some(name) = self.preset_list.get(i).map(|p| p.name) else { return vec![] };
        match presets::preset(name) {
            Ok(mut d) => {
                d.thresholds = self.config.thresholds(d.thresholds);
                self.preset = name.to_string();
                self.apply(d, Scope::All, format!("preset {name}"))
            }
            Err(e) => self.error(e.to_string()),
        }
    }

    /// Moves the design to the neighbouring chart cell along mass (`axis` 1) or gap (0).
    fn chart_move(&mut self, axis: usize, up: bool) -> Vec<Request> {
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
            Field::Mass.display(&d).trim_end_matches(" g"),
            Field::Gap.display(&d).trim_end_matches(" cm")
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

    fn toggle_pin(&mut self) {
        if self.pinned.take().is_some() {
            self.set_status("unpinned", false);
        } else {
            self.pinned =
                Some(Pinned { design: self.design.clone(), sim: self.sim.clone(), acoustic: self.acoustic.clone() });
            self.set_status("pinned this design: it stays on the plots (dim) while you change the live one", false);
        }
    }

    fn undo(&mut self) -> Vec<Request> {
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
    fn apply(&mut self, new: Design, scope: Scope, message: String) -> Vec<Request> {
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

    /// Takes a worker result if it is for the current parameters; drops stale ones.
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
                Err(e) => {
                    self.chart_error = Some(e.clone());
                    self.error(e);
                }
            },
            Done::Relevel { key, sound, passes } if key == self.chart.key && sound == sound_key(&self.design) => {
                self.merge_levels(&passes);
                self.chart.levels_for = sound;
            }
            Done::ChartCell { .. } | Done::Chart { .. } | Done::Relevel { .. } => {}
            Done::Export { kind, path, result } => {
                self.exports.retain(|p| *p != path);
                let shown = self.shown_path(&path);
                match result {
                    Ok(()) => self.set_status(&format!("exported {} to {shown}", export_name(kind)), false),
                    Err(e) => {
                        self.error(format!("export of {} failed: {e}", export_name(kind)));
                    }
                }
            }
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

    fn fail(&mut self, e: String) {
        self.work_error = Some(e.clone());
        self.error(e);
    }

    fn error(&mut self, e: String) -> Vec<Request> {
        self.status = Some(Status { text: format!("error: {e}"), error: true });
        vec![]
    }

    fn set_status(&mut self, text: &str, error: bool) {
        self.status = Some(Status { text: text.to_string(), error });
    }

    /// The metrics of the live design, if computed for it.
    pub fn metrics(&self) -> Option<&Metrics> {
        self.acoustic.as_ref().map(|a| &a.metrics)
    }

    /// The zone of metrics under the current thresholds.
    pub fn zone(&self, m: &Metrics) -> Option<Zone> {
        zone_of(m, &self.design)
    }
}

/// The zone of `m` under the thresholds of `d` (classified on draw so threshold edits are free).
pub fn zone_of(m: &Metrics, d: &Design) -> Option<Zone> {
    let e = match d.thresholds.zone_by {
        ZoneBy::Paper => m.inclination_cm_s,
        ZoneBy::Fit => m.inclination_fit_cm_s,
    }?;
    Some(Zone::classify(m.spl_max_db?, e, &d.thresholds))
}

/// What a key did to an input line.
enum Line {
    Typing(String),
    Cancel,
    Submit(String),
}

/// Esc, Enter, Backspace and typing (at most `max` characters) in an input line.
fn line_key(k: KeyEvent, mut buf: String, max: usize) -> Line {
    match k.code {
        KeyCode::Esc => Line::Cancel,
        KeyCode::Enter => Line::Submit(buf),
        KeyCode::Backspace => {
            buf.pop();
            Line::Typing(buf)
        }
        KeyCode::Char(c) if !k.modifiers.contains(KeyModifiers::CONTROL) => {
            if buf.chars().count() < max {
                buf.push(c);
            }
            Line::Typing(buf)
        }
        _ => Line::Typing(buf),
    }
}

/// `dir/name`, or `dir/stem-1.ext`, `dir/stem-2.ext` … the first that neither exists nor is
/// in `pending`.
pub fn unique_path(dir: &Path, name: &str, pending: &[PathBuf]) -> PathBuf {
    let free = |p: &PathBuf| !p.exists() && !pending.contains(p);
    let first = dir.join(name);
    if free(&first) {
        return first;
    }
    let (stem, ext) = match name.rsplit_once('.') {
        Some((s, e)) => (s, format!(".{e}")),
        None => (name, String::new()),
    };
    (1..).map(|n| dir.join(format!("{stem}-{n}{ext}"))).find(free).unwrap_or(first)
}

/// Index of the value nearest `x` (0 for an empty slice).
pub fn nearest(values: &[f64], x: f64) -> usize {
    values.iter().enumerate().min_by(|a, b| (a.1 - x).abs().total_cmp(&(b.1 - x).abs())).map_or(0, |(i, _)| i)
}
