//! What a key or a click does in each mode: the key table's actions on the normal screen,
//! typing in the input lines (a value, a name to save under), the overwrite question, moving
//! through the list popups (presets, saved designs, exports), and a click on a chart cell.

use crossterm::event::{KeyCode, KeyEvent, KeyEventKind, KeyModifiers};

use super::state::{App, ChartView, Mode};
use crate::presets;
use crate::tui::fields::{self, Knob, Scope};
use crate::tui::keys::Action;
use crate::tui::view::{Panel, PulseView};
use crate::tui::worker::Request;

/// What a key did to an input line.
enum Line {
    Typing(String),
    Cancel,
    Submit(String),
}

/// Esc, Enter, Backspace, Ctrl-U and typing (at most `max` characters) in an input line.
/// While the line's text is `selected` (just opened with the current value), typing replaces
/// it and Backspace/Delete clear it; an arrow, Home or End keeps it to edit.
fn line_key(k: KeyEvent, mut buf: String, max: usize, selected: bool) -> Line {
    let ctrl = k.modifiers.contains(KeyModifiers::CONTROL);
    match k.code {
        KeyCode::Esc => Line::Cancel,
        KeyCode::Enter => Line::Submit(buf),
        KeyCode::Char('u') if ctrl => Line::Typing(String::new()),
        KeyCode::Backspace | KeyCode::Delete if selected => Line::Typing(String::new()),
        KeyCode::Backspace => {
            buf.pop();
            Line::Typing(buf)
        }
        KeyCode::Char(c) if !ctrl => {
            if selected {
                buf.clear();
            }
            if buf.chars().count() < max {
                buf.push(c);
            }
            Line::Typing(buf)
        }
        _ => Line::Typing(buf),
    }
}

/// The character a key types if it starts a value on the main view: a digit or a point.
fn typed_start(k: &KeyEvent) -> Option<char> {
    match k.code {
        KeyCode::Char(c) if (c.is_ascii_digit() || c == '.') && !k.modifiers.contains(KeyModifiers::CONTROL) => Some(c),
        _ => None,
    }
}

/// What a key does in a list popup.
enum ListNav {
    Stay,
    Choose(usize),
    Close,
    Quit,
}

/// Lines a PageUp/PageDown moves the help by.
const HELP_PAGE: u16 = 10;
/// The furthest the help scrolls (the view shows at least its last screenful).
const HELP_SCROLL_MAX: u16 = 500;

/// Longest value typed in the input line (characters).
const VALUE_MAX: usize = 40;
/// Longest name typed in the save line (characters).
const NAME_MAX: usize = 64;

/// Keys and clicks.
impl App {
    /// One key press, in the current mode. Ctrl-C quits from every mode.
    pub(crate) fn key(&mut self, k: KeyEvent) -> Vec<Request> {
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
            Mode::ConfirmOverwrite(name) => self.confirm_key(k, &name),
            Mode::ConfirmQuit => {
                self.confirm_quit_key(k);
                vec![]
            }
            Mode::Presets(i) => self.preset_key(k, i),
            Mode::Saved(i) => self.saved_key(k, i),
            Mode::Export(i) => self.export_key(k, i),
            Mode::Find(buf, i) => {
                self.find_key(k, buf, i);
                vec![]
            }
            Mode::Help(s) | Mode::Glossary(s) => {
                self.help_key(k, s);
                vec![]
            }
            Mode::Normal => {
                let touring = self.tour.is_some();
                let tour_over = std::mem::take(&mut self.screen.tour_over);
                if let Some(a) = self.host.settings.keys.action_mode(&k, touring, self.anim.is_some()) {
                    if tour_over && matches!(a, Action::Increase { .. } | Action::Decrease { .. }) {
                        self.after_tour_notice();
                        return vec![];
                    }
                    self.act(a)
                } else if let Some(c) = typed_start(&k) {
                    // A digit or a point starts typing a value into the selected field.
                    self.mode = Mode::Editing(c.to_string());
                    self.screen.line_selected = false;
                    vec![]
                } else {
                    self.unbound(k);
                    vec![]
                }
            }
        }
    }

    /// The first ← or → after the tour finished (likely one "next" too many) changes nothing:
    /// it says what those keys do now, so the design never changes unseen.
    fn after_tour_notice(&mut self) {
        let (dec, inc) = (
            self.key_label(Action::Decrease { fine: false }).to_string(),
            self.key_label(Action::Increase { fine: false }).to_string(),
        );
        let what = if self.focus == Panel::Chart && self.screen.chart_view != ChartView::Response {
            "move the design on the chart".to_string()
        } else if self.focus == Panel::Chart {
            format!("change {}", Knob::FREQ.label())
        } else {
            format!("change {}", self.param().label())
        };
        let tour = self.key_label(Action::Tour).to_string();
        self.set_status(
            &format!("the tour is over — press {dec} {inc} again to {what} ({tour}: the tour again)"),
            false,
        );
    }

    /// A key bound to nothing on the main view: Esc says how to quit, others point to help.
    fn unbound(&mut self, k: KeyEvent) {
        let help = self.key_label(Action::Help).to_string();
        let quit = self.key_label(Action::Quit).to_string();
        match k.code {
            KeyCode::Modifier(_) | KeyCode::Null => {}
            KeyCode::Esc => self.set_status(&format!("nothing to close — {quit} quits, {help} for help"), false),
            _ => self.set_status(&format!("unknown key — {help} for help"), false),
        }
    }

    /// Keys in the help: ↑↓ (j/k) scroll a line, PageUp/PageDown a page, Home/End to the
    /// ends; → (Tab, 2) the second page, ← (BackTab, 1) the first; Esc, `?` and `q` close it.
    /// Any other key leaves it open. The view clamps the scroll to the text.
    fn help_key(&mut self, k: KeyEvent, scroll: u16) {
        let glossary = matches!(self.mode, Mode::Glossary(_));
        let page = if glossary { Mode::Glossary } else { Mode::Help };
        let closes = matches!(k.code, KeyCode::Esc | KeyCode::Char('?' | 'q'))
            || self.host.settings.keys.action_for(&k) == Some(Action::Help);
        match k.code {
            _ if closes => self.mode = Mode::Normal,
            KeyCode::Right | KeyCode::Tab | KeyCode::Char('2') => self.mode = Mode::Glossary(0),
            KeyCode::Left | KeyCode::BackTab | KeyCode::Char('1') => self.mode = Mode::Help(0),
            KeyCode::Down | KeyCode::Char('j') => self.mode = page(scroll.saturating_add(1).min(HELP_SCROLL_MAX)),
            KeyCode::Up | KeyCode::Char('k') => self.mode = page(scroll.saturating_sub(1)),
            KeyCode::PageDown | KeyCode::Char(' ') => {
                self.mode = page(scroll.saturating_add(HELP_PAGE).min(HELP_SCROLL_MAX));
            }
            KeyCode::PageUp => self.mode = page(scroll.saturating_sub(HELP_PAGE)),
            KeyCode::Home => self.mode = page(0),
            KeyCode::End => self.mode = page(HELP_SCROLL_MAX),
            _ => {}
        }
    }

    /// `q` (the quit action): quits, or first asks if the design has unsaved changes.
    fn quit_or_ask(&mut self) {
        if self.modified() {
            self.mode = Mode::ConfirmQuit;
        } else {
            self.quit = true;
        }
    }

    /// The answer to "quit without saving?": `y` (or the quit key again) quits; any other key
    /// stays.
    fn confirm_quit_key(&mut self, k: KeyEvent) {
        self.mode = Mode::Normal;
        if matches!(k.code, KeyCode::Char('y' | 'Y')) {
            self.quit = true;
        } else {
            let save = self.key_label(Action::Save).to_string();
            self.set_status(&format!("still here — {save} saves the design"), false);
        }
    }

    /// Performs one action of the key table.
    pub fn act(&mut self, a: Action) -> Vec<Request> {
        match a {
            Action::Quit => self.quit_or_ask(),
            Action::Help => self.mode = Mode::Help(0),
            Action::Zoom => self.screen.zoom = !self.screen.zoom,
            Action::FocusNext | Action::FocusPrev => self.focus = self.focus.cycle(a == Action::FocusNext),
            // The front view: ↑↓ walk along the front, Enter loads the selected design.
            Action::Up | Action::Down if self.front_shown() => self.front_walk(a == Action::Down),
            Action::Edit if self.front_shown() => return self.front_load(),
            Action::FrontView => self.toggle_front(),
            // The response curve focused: ←→ move the forcing frequency (the marker), ↑↓ select.
            Action::Decrease { fine } | Action::Increase { fine }
                if self.focus == Panel::Chart && self.screen.chart_view == ChartView::Response =>
            {
                return self.step_knob(Knob::FREQ, matches!(a, Action::Increase { .. }), fine)
            }
            Action::Up | Action::Down
                if self.focus == Panel::Chart && self.screen.chart_view != ChartView::Response =>
            {
                return self.chart_move(0, a == Action::Up)
            }
            Action::Up => {
                self.selected = (self.selected + Knob::ALL.len() - 1) % Knob::ALL.len();
                self.show_hint();
            }
            Action::Down => {
                self.selected = (self.selected + 1) % Knob::ALL.len();
                self.show_hint();
            }
            Action::Decrease { .. } | Action::Increase { .. } if self.focus == Panel::Chart => {
                return self.chart_move(1, matches!(a, Action::Increase { .. }))
            }
            Action::Decrease { fine } => return self.step(false, fine),
            Action::Increase { fine } => return self.step(true, fine),
            Action::Edit => {
                self.mode = Mode::Editing(self.param().display(&self.setup()));
                self.screen.line_selected = true;
            }
            Action::Presets => {
                let i = self.host.preset_list.iter().position(|p| p.name == self.preset).unwrap_or(0);
                self.mode = Mode::Presets(i);
            }
            Action::Pin => self.toggle_pin(),
            Action::Undo => return self.undo(),
            Action::ToggleChartView => return self.toggle_chart_view(),
            Action::Save => {
                self.mode = Mode::SaveAs(self.suggested_name());
                self.screen.line_selected = true;
            }
            Action::Load => self.open_saved(),
            Action::Export => self.mode = Mode::Export(0),
            Action::Tour => return self.start_tour(),
            Action::Best => return self.best(),
            Action::PulseView => self.toggle_pulse(),
            Action::ResponseView => return self.toggle_response(),
            Action::TourNext => {
                let next = self.tour.as_ref().map(|t| (t.step + 1, t.tour.steps.len()));
                match next {
                    Some((i, n)) if i < n => return self.tour_step(i),
                    Some(_) => self.leave_tour(true),
                    None => {}
                }
            }
            Action::TourPrev => {
                let prev = self.tour.as_ref().map(|t| t.step.saturating_sub(1));
                if let Some(i) = prev {
                    return self.tour_step(i);
                }
            }
            Action::TourLeave => self.leave_tour(false),
            Action::Find => self.mode = Mode::Find(String::new(), 0),
            Action::Field(f) => self.select_field(f),
            Action::Animate => self.toggle_anim(),
            Action::Table1 => self.toggle_table1(),
            Action::AnimPlay | Action::AnimStep { .. } | Action::AnimSpeed { .. } | Action::AnimRestart => {
                self.anim_key(a);
            }
        }
        vec![]
    }

    /// A key in the `/` filter: typing narrows the fields, ↑↓ choose among the matches, Enter
    /// selects the highlighted one, Esc cancels (the selection stays).
    fn find_key(&mut self, k: KeyEvent, buf: String, i: usize) {
        let n = fields::find(&buf).len().max(1);
        match k.code {
            KeyCode::Up => self.mode = Mode::Find(buf, (i + n - 1) % n),
            KeyCode::Down | KeyCode::Tab => self.mode = Mode::Find(buf, (i + 1) % n),
            _ => match line_key(k, buf, NAME_MAX, false) {
                Line::Typing(buf) => self.mode = Mode::Find(buf, 0),
                Line::Cancel => {
                    self.mode = Mode::Normal;
                    self.set_status("find cancelled", false);
                }
                Line::Submit(buf) => {
                    self.mode = Mode::Normal;
                    match fields::find(&buf).get(i) {
                        Some(&f) => self.select_field(f),
                        None => self.set_status(&format!("no field matches '{buf}'"), true),
                    }
                }
            },
        }
    }

    /// Selects field `f` (the parameters panel gets the focus) and explains it.
    pub(crate) fn select_field(&mut self, f: Knob) {
        if let Some(i) = Knob::ALL.iter().position(|k| *k == f) {
            self.selected = i;
            // (The tour keeps its step's panel in front.)
            if self.focus == Panel::Chart && self.tour.is_none() {
                self.focus = Panel::Params;
            }
            self.show_hint();
        }
    }

    /// A key in the value line of the selected field.
    fn edit_key(&mut self, k: KeyEvent, buf: String) -> Vec<Request> {
        let selected = std::mem::take(&mut self.screen.line_selected);
        match line_key(k, buf, VALUE_MAX, selected) {
            Line::Typing(buf) => self.mode = Mode::Editing(buf),
            Line::Cancel => {
                self.mode = Mode::Normal;
                self.set_status("input cancelled", false);
            }
            Line::Submit(buf) => {
                self.mode = Mode::Normal;
                // The value as shown, accepted: no change (it is rounded for display).
                if buf == self.param().display(&self.setup()) {
                    self.set_status(&format!("{} unchanged", self.param().label()), false);
                    return vec![];
                }
                return self.submit_text(&buf);
            }
        }
        vec![]
    }

    /// A key in the save line (the name to save under).
    fn save_key(&mut self, k: KeyEvent, buf: String) -> Vec<Request> {
        let selected = std::mem::take(&mut self.screen.line_selected);
        match line_key(k, buf, NAME_MAX, selected) {
            Line::Typing(buf) => self.mode = Mode::SaveAs(buf),
            Line::Cancel => {
                self.mode = Mode::Normal;
                self.set_status("save cancelled", false);
            }
            Line::Submit(name) => {
                self.mode = Mode::Normal;
                self.save_or_ask(name.trim());
            }
        }
        vec![]
    }

    /// The answer to "overwrite NAME?": only `y` overwrites; any other key keeps the file.
    fn confirm_key(&mut self, k: KeyEvent, name: &str) -> Vec<Request> {
        self.mode = Mode::Normal;
        if matches!(k.code, KeyCode::Char('y' | 'Y')) {
            self.save_as(name);
        } else {
            self.set_status(&format!("save cancelled: {name} kept as it was"), false);
        }
        vec![]
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
            KeyCode::Esc => {
                self.mode = Mode::Normal;
                return ListNav::Close;
            }
            KeyCode::Char('q') => {
                self.mode = Mode::Normal;
                self.quit_or_ask();
                return ListNav::Quit;
            }
            _ => {}
        }
        ListNav::Stay
    }

    /// A key in the preset list; Enter loads the preset (undoable).
    fn preset_key(&mut self, k: KeyEvent, i: usize) -> Vec<Request> {
        let ListNav::Choose(i) = self.list_nav(k, i, self.host.preset_list.len(), Mode::Presets) else { return vec![] };
        let Some(name) = self.host.preset_list.get(i).map(|p| p.name) else { return vec![] };
        let runs = self.runs;
        let checked = |d: crate::design::Design| {
            crate::tui::fields::check_loaded(&crate::tui::fields::Setup { design: d.clone(), runs }).map(|()| d)
        };
        match presets::preset(name).and_then(checked) {
            Ok(mut d) => {
                d.thresholds = self.host.settings.config.thresholds(d.thresholds);
                self.screen.pulse = PulseView::for_preset(name);
                let reqs = self.apply(d, Scope::All, format!("preset {name}"));
                self.preset = name.to_string();
                reqs
            }
            Err(e) => self.error(e),
        }
    }

    /// A key in the saved-designs list; Enter loads the design (undoable).
    fn saved_key(&mut self, k: KeyEvent, i: usize) -> Vec<Request> {
        let n = self.host.saved.designs.len() + self.host.saved.problems.len();
        let ListNav::Choose(i) = self.list_nav(k, i, n, Mode::Saved) else { return vec![] };
        self.load_saved(i)
    }

    /// A key in the export menu; Enter asks for that export.
    fn export_key(&mut self, k: KeyEvent, i: usize) -> Vec<Request> {
        let menu = self.export_menu();
        let ListNav::Choose(i) = self.list_nav(k, i, menu.len(), Mode::Export) else { return vec![] };
        let Some(&(kind, _)) = menu.get(i) else { return vec![] };
        self.export(kind).into_iter().collect()
    }

    /// A left click: a field under it is selected, a direction on the polar becomes the
    /// listener's θ, the chart cell under it becomes the live design.
    pub(crate) fn click(&mut self, x: u16, y: u16) -> Vec<Request> {
        if self.mode != Mode::Normal {
            return vec![];
        }
        let field = self.drawn.fields.iter().find(|(r, _)| r.contains(ratatui::layout::Position { x, y }));
        if let Some(&(_, i)) = field {
            if let Some(&f) = Knob::ALL.get(i) {
                self.select_field(f);
                self.focus = Panel::Params;
            }
            return vec![];
        }
        if self.drawn.polar.is_some_and(|p| p.theta_at(x, y).is_some()) {
            return self.drag(x, y);
        }
        let Some((m, g)) = self.drawn.geometry.as_ref().and_then(|geo| geo.hit(x, y)) else {
            return vec![];
        };
        self.focus = Panel::Chart;
        let grid = &self.chart.grids.fine;
        let (mass, gap) = (grid.masses_kg[m], grid.gaps_m[g]);
        self.select_design(mass, gap)
    }

    /// A left drag (or click) on the polar: the listener's θ follows the pointer (whole
    /// degrees, inside the source's range); θ becomes the selected field.
    pub(crate) fn drag(&mut self, x: u16, y: u16) -> Vec<Request> {
        let Some(deg) = self.drawn.polar.and_then(|p| p.theta_at(x, y)) else { return vec![] };
        if self.mode != Mode::Normal {
            return vec![];
        }
        self.select_field(Knob::THETA);
        if (self.design.observer.theta_rad.to_degrees() - deg).abs() < 1e-9 {
            return vec![];
        }
        self.submit_text(&format!("{deg}"))
    }
}
