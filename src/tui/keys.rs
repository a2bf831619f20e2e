// Over 800 lines: the one key table (dispatch, help, footer) with its parsing, overrides and their tests.
//! The one key table. The `?` help overlay, the footer hints and the key dispatch all read
//! [`KEYS`] (the explorer) and [`TOUR_KEYS`] (what changes while the guided tour runs), so a
//! binding cannot exist without being documented.

use std::collections::BTreeMap;

use crossterm::event::{KeyCode, KeyEvent, KeyEventKind, KeyModifiers};

use super::fields::Knob;
use crate::config::{ActionName, KeyBinding, KeyCode as ConfigKey, KeySpec, NamedKey};

/// Everything a key (or a mouse click) can ask the app to do.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Action {
    Quit,
    Help,
    FocusNext,
    FocusPrev,
    /// Previous parameter (or gap row up in the chart).
    Up,
    /// Next parameter (or gap row down in the chart).
    Down,
    /// Decrease the selected value by a step (`fine`: a small step).
    Decrease {
        fine: bool,
    },
    /// Increase the selected value by a step (`fine`: a small step).
    Increase {
        fine: bool,
    },
    /// Open the input line to type a value with units.
    Edit,
    Presets,
    Pin,
    Undo,
    ToggleChartView,
    /// Save the design under a name in the data directory.
    Save,
    /// Choose a saved design to load.
    Load,
    /// Choose a file to export into the export directory.
    Export,
    /// Start the guided tour.
    Tour,
    /// Jump to the zone-3 design of the chart with the largest margin.
    Best,
    /// The pulse panel: the loudest impact of the run, or one impact on a plate.
    PulseView,
    /// The chart panel: the frequency response of the forced design (f marked) / the zones.
    ResponseView,
    /// The focused panel fills the screen, and back (the tour starts zoomed).
    Zoom,
    /// Tour: the next step (after the last: leave the tour).
    TourNext,
    /// Tour: the previous step.
    TourPrev,
    /// Tour: leave it, keeping the design to explore.
    TourLeave,
    /// Open the filter over the field list (`/`): type part of a name, Enter selects.
    Find,
    /// Select this field at once (the headline inputs: mass, gap, r, θ).
    Field(Knob),
    /// The animation view: the run played in slow motion (again: back to the panels).
    Animate,
    /// Animation: play or pause.
    AnimPlay,
    /// Animation: one frame forward (`back`: one frame back).
    AnimStep {
        back: bool,
    },
    /// Animation: faster (or slower) playback, 1/1000× to 1×.
    AnimSpeed {
        faster: bool,
    },
    /// Animation: back to the run's start.
    AnimRestart,
    /// The Table 1 view: the paper's measurements beside both models (again: back).
    Table1,
    /// The front view: the design front of `thud tui --front FILE`, ↑↓ walk along it, Enter
    /// loads the selected design (again: back).
    FrontView,
}

/// One binding: the key, its modifiers, the action, its name in `config.toml`'s `[keys]`, how
/// the key is written and what it does.
#[derive(Debug, Clone, Copy)]
pub struct Binding {
    pub code: KeyCode,
    pub mods: KeyModifiers,
    pub action: Action,
    /// The action's name in the `[keys]` table of `config.toml` (several keys may share one).
    pub name: &'static str,
    /// The key as shown to people ("Ctrl-C", "Shift-→").
    pub label: &'static str,
    /// What it does, for the help overlay.
    pub help: &'static str,
    /// Short hint for the footer; empty: not in the footer.
    pub hint: &'static str,
}

const NONE: KeyModifiers = KeyModifiers::NONE;
const SHIFT: KeyModifiers = KeyModifiers::SHIFT;
const CTRL: KeyModifiers = KeyModifiers::CONTROL;

const fn bind(
    code: KeyCode,
    mods: KeyModifiers,
    action: Action,
    name: &'static str,
    label: &'static str,
    help: &'static str,
    hint: &'static str,
) -> Binding {
    Binding { code, mods, action, name, label, help, hint }
}

/// Every binding of the app (normal mode), in help order. The input line and the lists use
/// Enter/Esc/arrows as described in the help text of `Enter` and `P`. A `[keys]` override in
/// `config.toml` replaces the first key of the named action (see [`Keymap::with_overrides`]).
pub const KEYS: &[Binding] = &[
    bind(KeyCode::Char('q'), NONE, Action::Quit, "quit", "q", "quit (asks first if the design is not saved)", "quit"),
    bind(KeyCode::Char('c'), CTRL, Action::Quit, "quit", "Ctrl-C", "quit at once", ""),
    bind(KeyCode::Char('?'), NONE, Action::Help, "help", "?", "help: keys, then (→) what the numbers mean", "help"),
    bind(
        KeyCode::Char('T'),
        SHIFT,
        Action::Tour,
        "tour",
        "T",
        "guided tour of the paper's story (→ next, ← back, Esc leaves)",
        "tour",
    ),
    bind(KeyCode::Up, NONE, Action::Up, "up", "↑", "previous parameter (chart focused: larger gap)", ""),
    bind(KeyCode::Char('k'), NONE, Action::Up, "up", "k", "same as ↑", ""),
    bind(KeyCode::Down, NONE, Action::Down, "down", "↓", "next parameter (chart focused: smaller gap)", "select"),
    bind(KeyCode::Char('j'), NONE, Action::Down, "down", "j", "same as ↓", ""),
    bind(
        KeyCode::Left,
        NONE,
        Action::Decrease { fine: false },
        "decrease",
        "←",
        "decrease by a step (chart: lighter ball)",
        "",
    ),
    bind(
        KeyCode::Right,
        NONE,
        Action::Increase { fine: false },
        "increase",
        "→",
        "increase by a step (chart: heavier ball)",
        "change",
    ),
    bind(KeyCode::Char('-'), NONE, Action::Decrease { fine: false }, "decrease", "-", "decrease by a step", ""),
    bind(KeyCode::Char('+'), NONE, Action::Increase { fine: false }, "increase", "+", "increase by a step", ""),
    bind(KeyCode::Char('='), NONE, Action::Increase { fine: false }, "increase", "=", "increase by a step", ""),
    bind(
        KeyCode::Left,
        SHIFT,
        Action::Decrease { fine: true },
        "decrease-fine",
        "Shift-←",
        "decrease by a fine step",
        "",
    ),
    bind(
        KeyCode::Right,
        SHIFT,
        Action::Increase { fine: true },
        "increase-fine",
        "Shift-→",
        "increase by a fine step",
        "",
    ),
    bind(
        KeyCode::Char('_'),
        NONE,
        Action::Decrease { fine: true },
        "decrease-fine",
        "_",
        "decrease by a fine step",
        "",
    ),
    bind(
        KeyCode::Char('*'),
        NONE,
        Action::Increase { fine: true },
        "increase-fine",
        "*",
        "increase by a fine step",
        "",
    ),
    bind(
        KeyCode::Enter,
        NONE,
        Action::Edit,
        "edit",
        "Enter",
        "type a value with units, e.g. 40.5g, 3cm, 60deg (Enter accepts, Esc cancels)",
        "type",
    ),
    bind(
        KeyCode::Char('/'),
        NONE,
        Action::Find,
        "find",
        "/",
        "find a field: type part of its name (th → θ), ↑↓ choose, Enter selects, Esc cancels",
        "find",
    ),
    bind(KeyCode::Char('m'), NONE, Action::Field(Knob::MASS), "field-mass", "m", "select the ball's mass m", "fields"),
    bind(KeyCode::Char('g'), NONE, Action::Field(Knob::GAP), "field-gap", "g", "select the gap d", ""),
    bind(KeyCode::Char('r'), NONE, Action::Field(Knob::R), "field-r", "r", "select the listener's distance r", ""),
    bind(KeyCode::Char('t'), NONE, Action::Field(Knob::THETA), "field-theta", "t", "select the listener's angle θ", ""),
    bind(
        KeyCode::Char('a'),
        NONE,
        Action::Animate,
        "animate",
        "a",
        "animation: the run in slow motion (a again: back to the panels)",
        "",
    ),
    bind(KeyCode::Tab, NONE, Action::FocusNext, "next-panel", "Tab", "focus the next panel", "focus"),
    bind(
        KeyCode::Char('z'),
        NONE,
        Action::Zoom,
        "zoom",
        "z",
        "zoom: the focused panel fills the screen (Tab: the next one), z again: all panels",
        "zoom",
    ),
    bind(KeyCode::BackTab, SHIFT, Action::FocusPrev, "prev-panel", "Shift-Tab", "focus the previous panel", ""),
    bind(
        KeyCode::Char('P'),
        SHIFT,
        Action::Presets,
        "presets",
        "P",
        "choose a preset (↑↓, Enter applies, Esc closes)",
        "presets",
    ),
    bind(
        KeyCode::Char('p'),
        NONE,
        Action::Pin,
        "pin",
        "p",
        "pin this design: plots show it beside the live one",
        "pin",
    ),
    bind(KeyCode::Char('u'), NONE, Action::Undo, "undo", "u", "undo the last change", "undo"),
    bind(
        KeyCode::Char('v'),
        NONE,
        Action::ToggleChartView,
        "view",
        "v",
        "chart: zones (mass × gap) / e vs SPLmax / with a force, x(kT) over f (bifurcation)",
        "view",
    ),
    bind(
        KeyCode::Char('s'),
        NONE,
        Action::Save,
        "save",
        "s",
        "save this design under a name (Enter saves, Esc cancels)",
        "save",
    ),
    bind(
        KeyCode::Char('L'),
        SHIFT,
        Action::Load,
        "load",
        "L",
        "load a saved design (↑↓, Enter loads, Esc closes)",
        "load",
    ),
    bind(KeyCode::Char('o'), NONE, Action::Load, "load", "o", "same as L", ""),
    bind(
        KeyCode::Char('e'),
        NONE,
        Action::Export,
        "export",
        "e",
        "export a CSV, SVG or WAV file of this design to the export directory",
        "export",
    ),
    bind(
        KeyCode::Char('b'),
        NONE,
        Action::Best,
        "best",
        "b",
        "jump to the zone-3 design of the chart furthest inside both thresholds",
        "best",
    ),
    bind(
        KeyCode::Char('i'),
        NONE,
        Action::PulseView,
        "impact",
        "i",
        "pulse panel: the run's loudest impact / one impact at v0 on a plate (Fig 2)",
        "impact",
    ),
    bind(
        KeyCode::Char('M'),
        SHIFT,
        Action::Table1,
        "table1",
        "M",
        "Table 1: measured beside both models, paper and physical (M again: back)",
        "",
    ),
    bind(
        KeyCode::Char('f'),
        NONE,
        Action::ResponseView,
        "response",
        "f",
        "chart: frequency response (F0 > 0), f marked (chart focused: ←→ move f) / zones",
        "response",
    ),
    bind(
        KeyCode::Char('D'),
        SHIFT,
        Action::FrontView,
        "front",
        "D",
        "design front of thud tui --front FILE: ↑↓ walk, Enter loads (D again: back)",
        "",
    ),
];

/// The footer's hints by importance, by action name (`mouse` for [`mouse_hint`]):
/// when the footer cannot show every hint, it keeps the first of this list that fit and shows
/// them in table order. Every action with a hint is listed (a test checks it).
pub const FOOTER_PRIORITY: &[&str] = &[
    "tour-next",
    "tour-back",
    "tour-leave",
    "anim-play",
    "anim-faster",
    "anim-step",
    "anim-restart",
    "quit",
    "help",
    "down",
    "increase",
    "edit",
    "find",
    "field-mass",
    // Above the tour: at 80 columns the footer has room for one of them, and the status line
    // names `T` when the explorer starts.
    "mouse",
    "zoom",
    "next-panel",
    "tour",
    "view",
    "save",
    "undo",
    "pin",
    "presets",
    "best",
    "load",
    "export",
    "impact",
    "response",
];

/// One hint of the footer: its action's name (its rank in [`FOOTER_PRIORITY`]), the key as
/// shown and what it does.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Hint {
    pub name: &'static str,
    pub label: String,
    pub hint: &'static str,
}

/// The footer's word that the mouse is on (a click on a chart cell selects that design),
/// shown after the keys while mouse reporting is on.
pub fn mouse_hint() -> Hint {
    Hint { name: "mouse", label: "mouse".into(), hint: "on" }
}

/// The hints of `hints` (in their order) that fit in `width` columns when each takes
/// `cost(hint)` columns, chosen by [`FOOTER_PRIORITY`]: a hint is dropped only for a more
/// important one (hints of names not in the list come last).
pub fn fit_hints(hints: Vec<Hint>, width: usize, cost: impl Fn(&Hint) -> usize) -> Vec<Hint> {
    let rank = |h: &Hint| FOOTER_PRIORITY.iter().position(|n| *n == h.name).unwrap_or(FOOTER_PRIORITY.len());
    let mut order: Vec<usize> = (0..hints.len()).collect();
    order.sort_by_key(|&i| rank(&hints[i]));
    let mut keep = vec![false; hints.len()];
    let mut used = 0;
    for i in order {
        let w = cost(&hints[i]);
        if used + w <= width {
            used += w;
            keep[i] = true;
        }
    }
    hints.into_iter().zip(keep).filter_map(|(h, k)| k.then_some(h)).collect()
}

/// The bindings that change while the guided tour runs (looked up before [`KEYS`]; every
/// other key works as usual).
pub const TOUR_KEYS: &[Binding] = &[
    bind(KeyCode::Right, NONE, Action::TourNext, "tour-next", "→", "tour: next step", "next"),
    bind(KeyCode::Left, NONE, Action::TourPrev, "tour-back", "←", "tour: previous step", "back"),
    bind(KeyCode::Esc, NONE, Action::TourLeave, "tour-leave", "Esc", "tour: leave it and explore from here", "leave"),
];

/// The bindings that change while the animation shows (looked up before [`KEYS`]; `a`
/// leaves it, every other key works as usual).
pub const ANIM_KEYS: &[Binding] = &[
    bind(KeyCode::Char(' '), NONE, Action::AnimPlay, "anim-play", "Space", "animation: play or pause", "play/pause"),
    bind(
        KeyCode::Char('.'),
        NONE,
        Action::AnimStep { back: false },
        "anim-step",
        ".",
        "animation: one frame on",
        "frame",
    ),
    bind(KeyCode::Char(','), NONE, Action::AnimStep { back: true }, "anim-back", ",", "animation: one frame back", ""),
    bind(
        KeyCode::Char('['),
        NONE,
        Action::AnimSpeed { faster: false },
        "anim-slower",
        "[",
        "animation: slower (down to 1/1000×)",
        "",
    ),
    bind(
        KeyCode::Char(']'),
        NONE,
        Action::AnimSpeed { faster: true },
        "anim-faster",
        "]",
        "animation: faster (up to 1×)",
        "speed",
    ),
    bind(KeyCode::Home, NONE, Action::AnimRestart, "anim-restart", "Home", "animation: back to the start", "restart"),
];

/// One binding in effect: the table's row with its key, possibly overridden by the config.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Key {
    pub code: KeyCode,
    pub mods: KeyModifiers,
    pub action: Action,
    pub name: &'static str,
    /// The key as shown (the table's label, or the override's).
    pub label: String,
    pub help: &'static str,
    pub hint: &'static str,
    /// True if the config replaced the table's key.
    pub overridden: bool,
    /// A tour key ([`TOUR_KEYS`]): it acts only while the tour runs.
    pub tour: bool,
    /// An animation key ([`ANIM_KEYS`]): it acts only while the animation shows.
    pub anim: bool,
}

/// The bindings in effect: [`KEYS`] with the config's overrides. Dispatch, help overlay and
/// footer all read it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Keymap {
    pub keys: Vec<Key>,
}

impl Default for Keymap {
    fn default() -> Self {
        let key = |b: &Binding, tour: bool, anim: bool| Key {
            code: b.code,
            mods: b.mods,
            action: b.action,
            name: b.name,
            label: b.label.to_string(),
            help: b.help,
            hint: b.hint,
            overridden: false,
            tour,
            anim,
        };
        let keys = KEYS
            .iter()
            .map(|b| key(b, false, false))
            .chain(TOUR_KEYS.iter().map(|b| key(b, true, false)))
            .chain(ANIM_KEYS.iter().map(|b| key(b, false, true)))
            .collect();
        Self { keys }
    }
}

/// Terminals disagree about reporting SHIFT with characters and with Shift-Tab: ignore it there.
fn strip(code: KeyCode, m: KeyModifiers) -> KeyModifiers {
    if matches!(code, KeyCode::Char(_) | KeyCode::BackTab) {
        m - KeyModifiers::SHIFT
    } else {
        m
    }
}

/// The action names of the table, each once, in table order.
pub fn action_names() -> Vec<&'static str> {
    let mut out: Vec<&'static str> = Vec::new();
    for b in KEYS.iter().chain(TOUR_KEYS).chain(ANIM_KEYS) {
        if !out.contains(&b.name) {
            out.push(b.name);
        }
    }
    out
}

/// A config key as a crossterm key and modifiers, with its label.
pub fn from_spec(spec: KeySpec) -> (KeyCode, KeyModifiers, String) {
    let mut mods = KeyModifiers::NONE;
    if spec.ctrl {
        mods |= KeyModifiers::CONTROL;
    }
    if spec.alt {
        mods |= KeyModifiers::ALT;
    }
    let (code, name) = match spec.code {
        ConfigKey::Char(c) => {
            // Shift with a letter is the capital letter (what terminals send).
            let c = if spec.shift { c.to_uppercase().next().unwrap_or(c) } else { c };
            // Shown like the table's "Ctrl-C": a capital letter after Ctrl- or Alt-.
            let shown = if spec.ctrl || spec.alt { c.to_ascii_uppercase() } else { c };
            (KeyCode::Char(c), shown.to_string())
        }
        ConfigKey::F(n) => {
            if spec.shift {
                mods |= KeyModifiers::SHIFT;
            }
            (KeyCode::F(n), format!("F{n}"))
        }
        ConfigKey::Named(k) => {
            if spec.shift {
                mods |= KeyModifiers::SHIFT;
            }
            named(k)
        }
    };
    let mut label = String::new();
    if spec.ctrl {
        label.push_str("Ctrl-");
    }
    if spec.alt {
        label.push_str("Alt-");
    }
    if mods.contains(KeyModifiers::SHIFT) {
        label.push_str("Shift-");
    }
    label.push_str(&name);
    (code, mods, label)
}

fn named(k: NamedKey) -> (KeyCode, String) {
    let (code, label) = match k {
        NamedKey::Enter => (KeyCode::Enter, "Enter"),
        NamedKey::Esc => (KeyCode::Esc, "Esc"),
        NamedKey::Tab => (KeyCode::Tab, "Tab"),
        NamedKey::BackTab => (KeyCode::BackTab, "BackTab"),
        NamedKey::Backspace => (KeyCode::Backspace, "Backspace"),
        NamedKey::Delete => (KeyCode::Delete, "Delete"),
        NamedKey::Insert => (KeyCode::Insert, "Insert"),
        NamedKey::Space => (KeyCode::Char(' '), "Space"),
        NamedKey::Up => (KeyCode::Up, "↑"),
        NamedKey::Down => (KeyCode::Down, "↓"),
        NamedKey::Left => (KeyCode::Left, "←"),
        NamedKey::Right => (KeyCode::Right, "→"),
        NamedKey::Home => (KeyCode::Home, "Home"),
        NamedKey::End => (KeyCode::End, "End"),
        NamedKey::PageUp => (KeyCode::PageUp, "PageUp"),
        NamedKey::PageDown => (KeyCode::PageDown, "PageDown"),
    };
    (code, label.to_string())
}

impl Keymap {
    /// The table with `overrides` (action name → key) applied: each one replaces the first key
    /// of its action (other keys of the action, like `o` for load, stay). An unknown action
    /// name, or a key that another binding still uses, is refused: the problems come back as
    /// messages and the table's key stays.
    pub fn with_overrides(overrides: &BTreeMap<ActionName, KeyBinding>) -> (Keymap, Vec<String>) {
        let mut map = Keymap::default();
        let mut problems = Vec::new();
        let mut applied: Vec<(usize, &ActionName, &KeyBinding)> = Vec::new();
        for (name, binding) in overrides {
            let Some(i) = map.keys.iter().position(|k| k.name == name.as_str()) else {
                problems.push(format!(
                    "unknown action '{}' in [keys]; one of: {}",
                    name.as_str(),
                    action_names().join(", ")
                ));
                continue;
            };
            let (code, mods, label) = from_spec(binding.spec());
            let k = &mut map.keys[i];
            (k.code, k.mods, k.label, k.overridden) = (code, mods, label, true);
            applied.push((i, name, binding));
        }
        // Refuse overrides whose key is still taken by another binding (checked after all are
        // applied, so keys can be swapped between actions; a refusal may free or take a key, so
        // repeat until none is left).
        let default = Keymap::default();
        loop {
            let clash = applied.iter().enumerate().find_map(|(n, &(i, name, binding))| {
                let k = &map.keys[i];
                map.keys
                    .iter()
                    .enumerate()
                    .find(|(j, o)| {
                        *j != i
                            && o.tour == k.tour
                            && o.anim == k.anim
                            && o.code == k.code
                            && strip(o.code, o.mods) == strip(k.code, k.mods)
                    })
                    .map(|(_, o)| (n, i, name, binding, o.name))
            });
            let Some((n, i, name, binding, other)) = clash else { break };
            problems.push(format!(
                "[keys] {} = \"{binding}\": that key is already {other}; kept {}",
                name.as_str(),
                default.keys[i].label
            ));
            map.keys[i] = default.keys[i].clone();
            applied.remove(n);
        }
        (map, problems)
    }

    /// The action bound to a key press in the explorer, if any. Key releases are ignored;
    /// SHIFT is ignored for characters and Shift-Tab.
    pub fn action_for(&self, key: &KeyEvent) -> Option<Action> {
        self.action_in(key, false)
    }

    /// The action bound to a key press; while the tour runs (`touring`) its keys come first.
    pub fn action_in(&self, key: &KeyEvent, touring: bool) -> Option<Action> {
        self.action_mode(key, touring, false)
    }

    /// The action bound to a key press; while the animation shows (`animating`) its keys
    /// come first, then the tour's while it runs.
    pub fn action_mode(&self, key: &KeyEvent, touring: bool, animating: bool) -> Option<Action> {
        if key.kind == KeyEventKind::Release {
            return None;
        }
        let mods = strip(key.code, key.modifiers);
        let hit = |tour: bool, anim: bool| {
            self.keys
                .iter()
                .find(|b| b.tour == tour && b.anim == anim && b.code == key.code && strip(b.code, b.mods) == mods)
        };
        animating
            .then(|| hit(false, true))
            .flatten()
            .or_else(|| touring.then(|| hit(true, false)).flatten())
            .or_else(|| hit(false, false))
            .map(|b| b.action)
    }

    /// The first key of `action` as shown (e.g. "s"), if any.
    pub fn label_of(&self, action: Action) -> Option<&str> {
        self.keys.iter().find(|k| k.action == action).map(|k| k.label.as_str())
    }

    /// The footer: the hints of the explorer's table, in table order, as (key label, hint).
    pub fn footer_hints(&self) -> Vec<(String, &'static str)> {
        self.footer_hints_in(false)
    }

    /// The footer while the tour runs (`touring`: its keys first) or not.
    pub fn footer_hints_in(&self, touring: bool) -> Vec<(String, &'static str)> {
        self.footer_items(touring).into_iter().map(|h| (h.label, h.hint)).collect()
    }

    /// The footer's hints with their action names, in table order (the tour's first while it
    /// runs); [`fit_hints`] chooses the ones that fit.
    pub fn footer_items(&self, touring: bool) -> Vec<Hint> {
        self.footer_items_in(touring, false)
    }

    /// The footer's hints; while the animation shows (`animating`) its keys first.
    pub fn footer_items_in(&self, touring: bool, animating: bool) -> Vec<Hint> {
        let first = |a: Action| self.keys.iter().find(|k| k.action == a);
        let pair = |a: Action, b: Action, both: &str| match (first(a), first(b)) {
            (Some(x), Some(y)) if x.overridden || y.overridden => format!("{}{}", x.label, y.label),
            _ => both.to_string(),
        };
        let plain = || self.keys.iter().filter(|k| !k.tour && !k.anim);
        let anim = self.keys.iter().filter(|k| k.anim && animating);
        let tour_first: Vec<&Key> = if touring {
            anim.chain(self.keys.iter().filter(|k| k.tour)).chain(plain()).collect()
        } else {
            anim.chain(plain()).collect()
        };
        tour_first
            .into_iter()
            .filter(|k| !k.hint.is_empty())
            // While touring ← and → move through the steps.
            .filter(|k| !(touring && !k.tour && matches!(k.action, Action::Increase { .. })))
            .map(|k| {
                let label = match k.action {
                    Action::Down => pair(Action::Up, Action::Down, "↑↓"),
                    Action::Increase { fine: false } => {
                        pair(Action::Decrease { fine: false }, Action::Increase { fine: false }, "←→")
                    }
                    // The four field keys as one hint: "mgrt fields".
                    Action::Field(_) => [Knob::MASS, Knob::GAP, Knob::R, Knob::THETA]
                        .into_iter()
                        .filter_map(|f| first(Action::Field(f)).map(|k| k.label.clone()))
                        .collect::<String>(),
                    _ => k.label.clone(),
                };
                Hint { name: k.name, label, hint: k.hint }
            })
            .collect()
    }
}

/// The action bound to a key press by the table without overrides.
pub fn action_for(key: &KeyEvent) -> Option<Action> {
    Keymap::default().action_for(key)
}

/// The footer hints of the table without overrides.
pub fn footer_hints() -> Vec<(String, &'static str)> {
    Keymap::default().footer_hints()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(code: KeyCode, mods: KeyModifiers) -> KeyEvent {
        KeyEvent::new(code, mods)
    }

    #[test]
    fn quit_keys() {
        for (c, m) in [(KeyCode::Char('q'), NONE), (KeyCode::Char('c'), CTRL)] {
            assert_eq!(action_for(&key(c, m)), Some(Action::Quit));
        }
        assert_eq!(action_for(&key(KeyCode::Esc, NONE)), None, "Esc never quits the main view");
        assert_eq!(action_for(&key(KeyCode::Char('c'), NONE)), None);
    }

    #[test]
    fn shift_gives_fine_steps_and_capital_p_presets() {
        assert_eq!(action_for(&key(KeyCode::Right, SHIFT)), Some(Action::Increase { fine: true }));
        assert_eq!(action_for(&key(KeyCode::Right, NONE)), Some(Action::Increase { fine: false }));
        assert_eq!(action_for(&key(KeyCode::Char('P'), SHIFT)), Some(Action::Presets));
        assert_eq!(action_for(&key(KeyCode::Char('P'), NONE)), Some(Action::Presets));
        assert_eq!(action_for(&key(KeyCode::Char('p'), NONE)), Some(Action::Pin));
        assert_eq!(action_for(&key(KeyCode::BackTab, NONE)), Some(Action::FocusPrev));
        assert_eq!(action_for(&key(KeyCode::BackTab, SHIFT)), Some(Action::FocusPrev));
    }

    #[test]
    fn no_key_is_bound_twice() {
        for (i, a) in KEYS.iter().enumerate() {
            for b in &KEYS[i + 1..] {
                assert!(!(a.code == b.code && a.mods == b.mods), "{} bound twice", a.label);
            }
        }
    }

    fn overrides(pairs: &[(&str, &str)]) -> BTreeMap<ActionName, KeyBinding> {
        pairs.iter().map(|(a, k)| (ActionName::new(a).unwrap(), KeyBinding::new(k).unwrap())).collect()
    }

    #[test]
    fn an_override_replaces_the_first_key_of_its_action() {
        let (map, problems) = Keymap::with_overrides(&overrides(&[("save", "ctrl-s"), ("load", "F3")]));
        assert!(problems.is_empty(), "{problems:?}");
        assert_eq!(map.action_for(&key(KeyCode::Char('s'), CTRL)), Some(Action::Save));
        assert_eq!(map.action_for(&key(KeyCode::Char('s'), NONE)), None);
        assert_eq!(map.action_for(&key(KeyCode::F(3), NONE)), Some(Action::Load));
        assert_eq!(map.action_for(&key(KeyCode::Char('o'), NONE)), Some(Action::Load), "alternates stay");
        assert_eq!(map.label_of(Action::Save), Some("Ctrl-S"));
        assert!(map.footer_hints().contains(&("Ctrl-S".to_string(), "save")));
    }

    #[test]
    fn bad_overrides_are_reported_and_the_table_key_stays() {
        let (map, problems) = Keymap::with_overrides(&overrides(&[("sav", "w"), ("pin", "q")]));
        assert_eq!(problems.len(), 2, "{problems:?}");
        assert!(problems[0].contains("unknown action 'sav'"), "{}", problems[0]);
        assert!(problems[1].contains("already quit"), "{}", problems[1]);
        assert_eq!(map.action_for(&key(KeyCode::Char('p'), NONE)), Some(Action::Pin));
        assert_eq!(map.action_for(&key(KeyCode::Char('q'), NONE)), Some(Action::Quit));
    }

    #[test]
    fn keys_can_be_swapped() {
        let (map, problems) = Keymap::with_overrides(&overrides(&[("pin", "s"), ("save", "p")]));
        assert!(problems.is_empty(), "{problems:?}");
        assert_eq!(map.action_for(&key(KeyCode::Char('s'), NONE)), Some(Action::Pin));
        assert_eq!(map.action_for(&key(KeyCode::Char('p'), NONE)), Some(Action::Save));
    }

    #[test]
    fn tour_keys_act_only_while_touring_and_are_unique() {
        for (i, a) in TOUR_KEYS.iter().enumerate() {
            for b in &TOUR_KEYS[i + 1..] {
                assert!(!(a.code == b.code && a.mods == b.mods), "{} bound twice", a.label);
            }
        }
        let map = Keymap::default();
        let right = key(KeyCode::Right, NONE);
        assert_eq!(map.action_in(&right, true), Some(Action::TourNext));
        assert_eq!(map.action_in(&right, false), Some(Action::Increase { fine: false }));
        assert_eq!(map.action_in(&key(KeyCode::Char('q'), NONE), true), Some(Action::Quit), "others still work");
        assert_eq!(map.action_in(&key(KeyCode::Esc, NONE), true), Some(Action::TourLeave));
        assert_eq!(map.footer_hints_in(true)[0], ("→".to_string(), "next"));
        assert!(!map.footer_hints().iter().any(|(_, h)| *h == "next"));
        assert_eq!(action_for(&key(KeyCode::Char('T'), SHIFT)), Some(Action::Tour));
        assert_eq!(action_for(&key(KeyCode::Char('b'), NONE)), Some(Action::Best));
    }

    #[test]
    fn every_hint_has_a_rank_and_every_rank_a_hint() {
        let hinted: Vec<&str> =
            KEYS.iter().chain(TOUR_KEYS).chain(ANIM_KEYS).filter(|b| !b.hint.is_empty()).map(|b| b.name).collect();
        for name in &hinted {
            assert!(FOOTER_PRIORITY.contains(name), "{name} has a footer hint but no rank in FOOTER_PRIORITY");
        }
        for name in FOOTER_PRIORITY {
            assert!(hinted.contains(name) || *name == mouse_hint().name, "{name} is ranked but has no hint");
        }
    }

    #[test]
    fn fit_hints_drops_the_least_important_and_keeps_the_order() {
        let hint = |name: &'static str| Hint { name, label: name.into(), hint: "" };
        let hints = vec![hint("best"), hint("quit"), hint("view"), hint("help")];
        let names = |w| fit_hints(hints.clone(), w, |_| 10).into_iter().map(|h| h.name).collect::<Vec<_>>();
        assert_eq!(names(25), ["quit", "help"]);
        assert_eq!(names(30), ["quit", "view", "help"]);
        assert_eq!(names(40), ["best", "quit", "view", "help"]);
        // A smaller hint further down still fills the room a large one left.
        let cost = |h: &Hint| if h.name == "view" { 20 } else { 5 };
        let kept: Vec<_> = fit_hints(hints.clone(), 20, cost).into_iter().map(|h| h.name).collect();
        assert_eq!(kept, ["best", "quit", "help"]);
    }

    #[test]
    fn footer_comes_from_the_table() {
        let hints = footer_hints();
        assert!(hints.contains(&("q".to_string(), "quit")));
        assert!(hints.contains(&("?".to_string(), "help")));
        assert!(hints.contains(&("s".to_string(), "save")));
        assert!(hints.len() >= 8);
    }
}
