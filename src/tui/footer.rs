//! The footer: the key table's hints, as many as fit, and how a key is shown.

use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;

use super::keys::{self, Keymap};
use super::theme::Palette;

/// The footer: the key table's hints (the tour's first while it runs) and, with the mouse on,
/// `mouse on`; as many whole ones as fit in `width`, chosen by importance
/// ([`keys::FOOTER_PRIORITY`]) and shown in table order.
pub(super) fn footer_line(
    keys: &Keymap,
    width: u16,
    (touring, animating): (bool, bool),
    mouse: bool,
    theme: &Palette,
) -> Paragraph<'static> {
    let mut hints = keys.footer_items_in(touring, animating);
    if mouse {
        hints.push(keys::mouse_hint());
    }
    let shown = |h: &keys::Hint| (format!(" {}", key_text(&h.label, theme)), format!(" {} ", h.hint));
    let cost = |h: &keys::Hint| {
        let (key, text) = shown(h);
        key.chars().count() + text.chars().count()
    };
    // The last item's trailing space may fall off the edge.
    let mut spans = Vec::new();
    for h in keys::fit_hints(hints, usize::from(width) + 1, cost) {
        let (key, text) = shown(&h);
        spans.push(Span::styled(key, Style::default().add_modifier(Modifier::BOLD | Modifier::REVERSED)));
        spans.push(Span::raw(text));
    }
    Paragraph::new(Line::from(spans))
}

/// A key as shown: with `--ascii` the arrows are spelled (`Left`, `Up/Down`).
pub(super) fn key_text(label: &str, theme: &Palette) -> String {
    if !theme.ascii {
        return label.to_string();
    }
    let spelled = label.replace("↑↓", "Up/Down").replace("←→", "Left/Right");
    let spelled = spelled.replace('↑', "Up").replace('↓', "Down").replace('←', "Left").replace('→', "Right");
    theme.text(&spelled).into_owned()
}
