//! The one key table. The `?` help overlay, the footer hints and the key dispatch all read
//! [`KEYS`], so a binding cannot exist without being documented.

use crossterm::event::{KeyCode, KeyEvent, KeyEventKind, KeyModifiers};

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
}

/// One binding: the key, its modifiers, the action, how the key is written and what it does.
#[derive(Debug, Clone, Copy)]
pub struct Binding {
    pub code: KeyCode,
    pub mods: KeyModifiers,
    pub action: Action,
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
    label: &'static str,
    help: &'static str,
    hint: &'static str,
) -> Binding {
    Binding { code, mods, action, label, help, hint }
}

/// Every binding of the app (normal mode). The input line and the lists use Enter/Esc/arrows
/// as described in the help text of `Enter` and `P`.
pub const KEYS: &[Binding] = &[
    bind(KeyCode::Char('q'), NONE, Action::Quit, "q", "quit", "quit"),
    bind(KeyCode::Esc, NONE, Action::Quit, "Esc", "quit (or close a popup / cancel the input line)", ""),
    bind(KeyCode::Char('c'), CTRL, Action::Quit, "Ctrl-C", "quit", ""),
    bind(KeyCode::Char('?'), NONE, Action::Help, "?", "show or hide this help", "help"),
    bind(KeyCode::Up, NONE, Action::Up, "↑", "previous parameter (chart focused: larger gap)", ""),
    bind(KeyCode::Char('k'), NONE, Action::Up, "k", "same as ↑", ""),
    bind(KeyCode::Down, NONE, Action::Down, "↓", "next parameter (chart focused: smaller gap)", "select"),
    bind(KeyCode::Char('j'), NONE, Action::Down, "j", "same as ↓", ""),
    bind(KeyCode::Left, NONE, Action::Decrease { fine: false }, "←", "decrease by a step (chart: lighter ball)", ""),
    bind(
        KeyCode::Right,
        NONE,
        Action::Increase { fine: false },
        "→",
        "increase by a step (chart: heavier ball)",
        "change",
    ),
    bind(KeyCode::Char('-'), NONE, Action::Decrease { fine: false }, "-", "decrease by a step", ""),
    bind(KeyCode::Char('+'), NONE, Action::Increase { fine: false }, "+", "increase by a step", ""),
    bind(KeyCode::Char('='), NONE, Action::Increase { fine: false }, "=", "increase by a step", ""),
    bind(KeyCode::Left, SHIFT, Action::Decrease { fine: true }, "Shift-←", "decrease by a fine step", ""),
    bind(KeyCode::Right, SHIFT, Action::Increase { fine: true }, "Shift-→", "increase by a fine step", ""),
    bind(KeyCode::Char('_'), NONE, Action::Decrease { fine: true }, "_", "decrease by a fine step", ""),
    bind(KeyCode::Char('*'), NONE, Action::Increase { fine: true }, "*", "increase by a fine step", "fine"),
    bind(
        KeyCode::Enter,
        NONE,
        Action::Edit,
        "Enter",
        "type a value with units, e.g. 40.5g, 3cm, 60deg (Enter accepts, Esc cancels)",
        "type",
    ),
    bind(KeyCode::Tab, NONE, Action::FocusNext, "Tab", "focus the next panel", "focus"),
    bind(KeyCode::BackTab, SHIFT, Action::FocusPrev, "Shift-Tab", "focus the previous panel", ""),
    bind(KeyCode::Char('P'), SHIFT, Action::Presets, "P", "choose a preset (↑↓, Enter applies, Esc closes)", "presets"),
    bind(KeyCode::Char('p'), NONE, Action::Pin, "p", "pin this design: plots show it beside the live one", "pin"),
    bind(KeyCode::Char('u'), NONE, Action::Undo, "u", "undo the last change", "undo"),
    bind(KeyCode::Char('v'), NONE, Action::ToggleChartView, "v", "chart: zones (mass × gap) / e vs SPLmax", "view"),
];

/// The action bound to a key press, if any. Key releases are ignored; SHIFT is ignored for
/// characters and Shift-Tab.
pub fn action_for(key: &KeyEvent) -> Option<Action> {
    if key.kind == KeyEventKind::Release {
        return None;
    }
    // Terminals disagree about reporting SHIFT with characters and with Shift-Tab.
    let shift_free = |code: KeyCode| matches!(code, KeyCode::Char(_) | KeyCode::BackTab);
    let strip = |code: KeyCode, m: KeyModifiers| if shift_free(code) { m - KeyModifiers::SHIFT } else { m };
    let mods = strip(key.code, key.modifiers);
    KEYS.iter().find(|b| b.code == key.code && strip(b.code, b.mods) == mods).map(|b| b.action)
}

/// The footer: the hints of the table, in table order, as (key label, hint) pairs.
pub fn footer_hints() -> Vec<(&'static str, &'static str)> {
    let mut out: Vec<(&str, &str)> = Vec::new();
    for b in KEYS.iter().filter(|b| !b.hint.is_empty()) {
        let label = match b.action {
            Action::Down => "↑↓",
            Action::Increase { fine: false } => "←→",
            Action::Increase { fine: true } => "Shift-←→",
            _ => b.label,
        };
        out.push((label, b.hint));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(code: KeyCode, mods: KeyModifiers) -> KeyEvent {
        KeyEvent::new(code, mods)
    }

    #[test]
    fn quit_keys() {
        for (c, m) in [(KeyCode::Char('q'), NONE), (KeyCode::Esc, NONE), (KeyCode::Char('c'), CTRL)] {
            assert_eq!(action_for(&key(c, m)), Some(Action::Quit));
        }
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

    #[test]
    fn footer_comes_from_the_table() {
        let hints = footer_hints();
        assert!(hints.contains(&("q", "quit")));
        assert!(hints.contains(&("?", "help")));
        assert!(hints.len() >= 8);
    }
}
