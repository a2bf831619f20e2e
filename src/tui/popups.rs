//! The popups over the screen: help's two pages (the keys, what the numbers mean) and the
//! lists (presets, saved designs, exports, find a field).

use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Clear, Paragraph};
use ratatui::Frame;

use std::path::PathBuf;

use super::app::{App, ChartView, Mode};
use super::explain;
use super::footer::key_text;
use super::keys::{Action, Keymap};
use super::theme::Palette;
use super::tour::wrap;
use crate::store;

/// A rectangle of at most `w × h` centred in `area`.
fn centered(area: Rect, w: u16, h: u16) -> Rect {
    let (w, h) = (w.min(area.width), h.min(area.height));
    Rect::new(area.x + (area.width - w) / 2, area.y + (area.height - h) / 2, w, h)
}

/// `text` wrapped at word boundaries to `width` columns, a word longer than a line broken
/// where the line ends (a path in an error message), so nothing is cut.
pub(super) fn wrap_all(text: &str, width: usize) -> Vec<String> {
    let width = width.max(1);
    wrap(text, width)
        .into_iter()
        .flat_map(|l| {
            let chars: Vec<char> = l.chars().collect();
            chars.chunks(width).map(|c| c.iter().collect::<String>()).collect::<Vec<_>>()
        })
        .collect()
}

/// Lines under a key's label in the help: the label and action name, then the help text
/// wrapped beside them (the continuation lines indented).
fn help_lines(keys: &Keymap, theme: &Palette, width: usize) -> Vec<Line<'static>> {
    let names = width >= 60;
    let head_w = if names { 24 } else { 10 };
    let text_w = width.saturating_sub(head_w).max(10);
    let mut lines = Vec::new();
    for b in &keys.keys {
        let label = key_text(&b.label, theme);
        let head = if names { format!("{label:<10}{:<14}", b.name) } else { format!("{label:<10}") };
        for (i, l) in wrap_all(&theme.text(b.help), text_w).into_iter().enumerate() {
            let h = if i == 0 { head.clone() } else { String::new() };
            lines.push(Line::from(format!("{h:<head_w$}{l}")));
        }
    }
    let plain = theme.label();
    lines.push(Line::from(""));
    let notes = [
        "Values are typed in the unit shown (45 = 45 g) or with units: 40.5g 3cm 0.7m 60deg 1.4m/s 2s 103dB",
        "The second column is the action's name for [keys] in config.toml, e.g. save = \"ctrl-s\"",
    ];
    for note in notes.iter().take(if names { 2 } else { 1 }) {
        lines.extend(wrap_all(&theme.text(note), width).into_iter().map(|l| Line::from(Span::styled(l, plain))));
    }
    lines
}

/// Scrolls `lines` in a bordered popup `popup` (cleared first) under `title`: at most to the
/// last screenful, with "more" marks on the bottom border while text is above or below.
fn scrolled_popup(f: &mut Frame, theme: &Palette, popup: Rect, title: &str, lines: Vec<Line<'static>>, scroll: u16) {
    f.render_widget(Clear, popup);
    let inner_h = popup.height.saturating_sub(2);
    let total = u16::try_from(lines.len()).unwrap_or(u16::MAX);
    let max_scroll = total.saturating_sub(inner_h);
    let scroll = scroll.min(max_scroll);
    let mut marks = Vec::new();
    if scroll > 0 {
        marks.push(format!("{} more above", theme.sym("↑", "^")));
    }
    if scroll < max_scroll {
        marks.push(format!("{} more below (PgDn)", theme.sym("↓", "v")));
    }
    let room = usize::from(popup.width.saturating_sub(2));
    let mut block = theme.block(theme.fit(&theme.text(title), room).into_owned(), false);
    if !marks.is_empty() {
        let marks = format!(" {} ", marks.join(", "));
        block = block.title_bottom(Line::from(theme.fit(&marks, room).into_owned()).right_aligned());
    }
    let inner = block.inner(popup);
    f.render_widget(block, popup);
    f.render_widget(Paragraph::new(lines).scroll((scroll, 0)), inner);
}

/// The help's first page: every binding in effect (with its `[keys]` action name where the
/// width allows), wrapped, scrolled by `scroll` lines.
pub(super) fn help_popup(f: &mut Frame, keys: &Keymap, theme: &Palette, scroll: u16, area: Rect) {
    let width = 112.min(area.width);
    let lines = help_lines(keys, theme, usize::from(width.saturating_sub(2)));
    let popup = centered(area, width, u16::try_from(lines.len()).unwrap_or(u16::MAX).saturating_add(2));
    scrolled_popup(
        f,
        theme,
        popup,
        " help 1/2: keys — ↑↓ PgUp/PgDn scroll, → what the numbers mean, Esc closes ",
        lines,
        scroll,
    );
}

/// The help's second page, "What the numbers mean": the glossary, wrapped, scrolled by
/// `scroll` lines.
pub(super) fn glossary_popup(f: &mut Frame, app: &App, scroll: u16, area: Rect) {
    let th = &app.theme;
    let width = 100.min(area.width);
    let bold = Style::default().add_modifier(Modifier::BOLD);
    let mut lines: Vec<Line> = Vec::new();
    let cx = explain::OnScreen {
        forced: app.design.damper.forced(),
        runs: app.runs,
        response_view: app.screen.chart_view == ChartView::Response,
    };
    let glossary = explain::glossary_for(app.design.thresholds.zone_by, cx);
    // The term column: a blank after the longest term shown (at least 8 wide).
    let term_w = glossary.iter().map(|(t, _)| th.text(t).chars().count() + 1).max().unwrap_or(0).max(8);
    let text_w = (width as usize).saturating_sub(term_w + 3).max(10);
    for (term, text) in glossary {
        let text = th.text(&text).into_owned();
        for (i, l) in wrap(&text, text_w).into_iter().enumerate() {
            let head = if i == 0 { th.text(term).into_owned() } else { String::new() };
            lines.push(Line::from(vec![Span::styled(format!("{head:<term_w$}"), bold), Span::raw(l)]));
        }
    }
    let popup = centered(area, width, u16::try_from(lines.len()).unwrap_or(u16::MAX).saturating_add(2));
    let title = format!(" help 2/2: {} — ↑↓ PgUp/PgDn scroll, ← keys, Esc closes ", explain::GLOSSARY_TITLE);
    scrolled_popup(f, th, popup, &title, lines, scroll);
}

/// A list popup (presets, saved designs, exports): the rows around the highlighted one, then
/// the highlighted row's detail. Rows that cannot be chosen are drawn in the error style.
pub(super) fn list_popup(f: &mut Frame, list: &ListView, theme: &Palette, area: Rect) {
    let n = list.items.len();
    let error: Vec<String> = list
        .error
        .as_deref()
        .map(|e| wrap_all(&theme.text(e), usize::from(76.min(area.width).saturating_sub(2))))
        .unwrap_or_default();
    let error_h = u16::try_from(error.len()).unwrap_or(u16::MAX);
    let popup = centered(area, 76, (n.max(1) as u16).saturating_add(7).saturating_add(error_h));
    f.render_widget(Clear, popup);
    let block =
        theme.block(theme.fit(&theme.text(&list.title), popup.width.saturating_sub(2).into()).into_owned(), false);
    let inner = block.inner(popup);
    f.render_widget(block, popup);
    if n == 0 {
        let empty = theme.text(&list.empty).into_owned();
        f.render_widget(Paragraph::new(empty).wrap(ratatui::widgets::Wrap { trim: true }), inner);
        return;
    }
    // The error first: it is what the user must read, whole, before the rows.
    let error_h = error_h.min(inner.height.saturating_sub(1));
    let [err_area, inner] = Layout::vertical([Constraint::Length(error_h), Constraint::Min(0)]).areas(inner);
    let err_lines: Vec<Line> = error.into_iter().map(|l| Line::from(Span::styled(l, theme.error()))).collect();
    f.render_widget(Paragraph::new(err_lines), err_area);
    let sel = list.selected.min(n - 1);
    let detail_h = 3.min(inner.height.saturating_sub(1));
    let rows_h = (inner.height - detail_h).max(1) as usize;
    let first = (sel + 1).saturating_sub(rows_h);
    let mut lines: Vec<Line> = list
        .items
        .iter()
        .enumerate()
        .skip(first)
        .take(rows_h)
        .map(|(i, item)| {
            let mut style = if item.problem { theme.error() } else { Style::default() };
            if i == sel {
                style = style.add_modifier(Modifier::REVERSED);
            }
            let label = theme.text(&item.label).into_owned();
            Line::from(Span::styled(format!("{} {label}", if i == sel { ">" } else { " " }), style))
        })
        .collect();
    lines.push(Line::from(""));
    lines.push(Line::from(theme.text(&list.items[sel].detail).into_owned()));
    f.render_widget(Paragraph::new(lines).wrap(ratatui::widgets::Wrap { trim: false }), inner);
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
    /// Why the last choice failed, shown whole under the list (which stays open).
    pub error: Option<String>,
}

/// The list popup of the app's mode, if it shows one.
pub fn list_view(app: &App) -> Option<ListView> {
    let (title, items, selected, empty) = match &app.mode {
        Mode::Presets(i) => (
            " presets (↑↓, Enter applies, Esc closes) ".to_string(),
            app.host
                .preset_list
                .iter()
                .map(|p| ListItem { label: p.name.to_string(), detail: p.description.clone(), problem: false })
                .collect(),
            *i,
            String::new(),
        ),
        Mode::Saved(i) => {
            let good = app.host.saved.designs.iter().map(|d| ListItem {
                label: d.name.clone(),
                detail: d.description.clone(),
                problem: false,
            });
            let bad = app.host.saved.problems.iter().map(|p| ListItem {
                label: format!(
                    "✗ {} (cannot be loaded)",
                    p.path.file_name().map_or_else(|| p.path.display().to_string(), |n| n.to_string_lossy().into())
                ),
                detail: p.to_string(),
                problem: true,
            });
            let dir = app.host.data_dir.as_deref().map_or_else(PathBuf::new, store::designs_dir);
            (
                " saved designs (↑↓, Enter loads, Esc closes) ".to_string(),
                good.chain(bad).collect(),
                *i,
                format!("No saved designs in {}; press {} to save one.", dir.display(), app.key_label(Action::Save)),
            )
        }
        Mode::Export(i) => (
            " export (↑↓, Enter writes the file, Esc closes) ".to_string(),
            app.export_menu()
                .iter()
                .map(|(k, label)| ListItem {
                    label: format!("{label}  [{}]", k.default_file_name()),
                    detail: format!("{} in {}", k.default_file_name(), app.export_dir_name()),
                    problem: false,
                })
                .collect(),
            *i,
            String::new(),
        ),
        Mode::Find(buf, i) => {
            let setup = app.setup();
            (
                format!(" find a field: {buf} (↑↓ choose, Enter selects, Esc cancels) "),
                super::fields::find(buf)
                    .into_iter()
                    .map(|k| ListItem {
                        label: format!("{:<12} {}", k.label(), k.display(&setup)),
                        detail: format!("{} ({}): {}", k.label(), k.param(), explain::field_hint(k, &app.design)),
                        problem: false,
                    })
                    .collect(),
                *i,
                format!("no field matches '{buf}' — Backspace, or Esc to cancel"),
            )
        }
        _ => return None,
    };
    let error = if matches!(app.mode, Mode::Saved(_)) { app.host.load_error.clone() } else { None };
    Some(ListView { title, items, selected, empty, error })
}
