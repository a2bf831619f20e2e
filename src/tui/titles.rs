//! A panel's frame: its block (the tour's panel heavy and pointed at, the focused one
//! coloured) and its title, the longest of its forms that fits.

use ratatui::layout::Rect;
use ratatui::widgets::Block;

use super::app::{App, Panel};
use super::theme::Palette;

/// A panel's block: the tour's panel with a heavy border and a pointer, the focused one
/// coloured, the title folded to ASCII with `--ascii`.
pub(super) fn panel_block(app: &App, which: Panel, title: &str) -> Block<'static> {
    let th = &app.theme;
    if app.tour_panel() == Some(which) {
        let t = format!(" {} {}", th.sym("▶", ">"), title.trim_start());
        th.highlight_block(th.text(&t).into_owned())
    } else {
        th.block(th.text(title).into_owned(), app.focus == which)
    }
}

/// The longest of `options` that fits a panel `width` wide (its borders taken off), as drawn
/// (folded to ASCII with `--ascii`); the shortest cut with an ellipsis when none fits.
pub(super) fn fit(theme: &Palette, options: &[String], width: u16) -> String {
    let w = usize::from(width).saturating_sub(2);
    let last = theme.text(&options[options.len() - 1]).into_owned();
    options
        .iter()
        .find(|t| theme.text(t).chars().count() <= w)
        .cloned()
        .unwrap_or_else(|| theme.fit(&last, w).into_owned())
}

/// The width a panel's title may use: the panel's, less the tour's pointer when it has one.
pub(super) fn title_width(app: &App, which: Panel, area: Rect) -> u16 {
    if app.tour_panel() == Some(which) {
        area.width.saturating_sub(2)
    } else {
        area.width
    }
}
