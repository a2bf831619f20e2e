//! The status line: the input lines (save as, find, a field being typed) with their hints,
//! the overwrite and quit questions, or the last message.

use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};

use super::app::{App, Mode};
use super::keys::Action;

/// The input line's text: reversed while selected (typing replaces it).
fn typed(app: &App) -> Style {
    if app.screen.line_selected {
        Style::default().add_modifier(Modifier::REVERSED)
    } else {
        Style::default()
    }
}

pub(super) fn status_line(app: &App) -> Line<'static> {
    let th = &app.theme;
    let cursor = th.sym("█", "_");
    // The hints are read, not skimmed: plain text, never dim.
    let plain = th.label();
    if let Mode::SaveAs(buf) = &app.mode {
        let dir =
            app.host.data_dir.as_deref().map_or_else(|| "(no data directory)".into(), |d| d.display().to_string());
        return Line::from(vec![
            Span::styled(" save as: ", Style::default().add_modifier(Modifier::BOLD)),
            Span::styled(buf.clone(), typed(app)),
            Span::raw(cursor),
            Span::styled(format!("  (letters, digits, - or _; Enter saves in {dir}, Esc cancels)"), plain),
        ]);
    }
    if let Mode::ConfirmOverwrite(name) = &app.mode {
        return Line::from(vec![
            Span::styled(format!(" overwrite {name}? y/n"), Style::default().add_modifier(Modifier::BOLD)),
            Span::styled("  (y replaces the saved design of that name; any other key keeps it)", plain),
        ]);
    }
    if app.mode == Mode::ConfirmQuit {
        return Line::from(vec![
            Span::styled(" quit without saving? y/n", Style::default().add_modifier(Modifier::BOLD)),
            Span::styled(
                format!("  (y quits; any other key stays, then {} saves)", app.key_label(Action::Save)),
                plain,
            ),
        ]);
    }
    if let Mode::Find(buf, _) = &app.mode {
        return Line::from(vec![
            Span::styled(" find: ", Style::default().add_modifier(Modifier::BOLD)),
            Span::styled(th.text(buf).into_owned(), typed(app)),
            Span::raw(cursor),
            Span::styled("  (part of a field's name; ↑↓ choose, Enter selects, Esc cancels)", plain),
        ]);
    }
    if let Mode::Editing(buf) = &app.mode {
        let f = app.param();
        let hint = match (f.display_unit(), f.display_range(&app.design)) {
            (Some((unit, _)), Some((lo, hi))) => format!(
                "  (plain number: {unit}, {}–{}; or with a unit; Enter accepts, Esc cancels, Ctrl-U clears)",
                crate::limits::short(lo),
                crate::limits::short(hi)
            ),
            _ => "  (Enter accepts, Esc cancels, Ctrl-U clears)".to_string(),
        };
        return Line::from(vec![
            Span::styled(
                th.text(&format!(" {} = ", f.label())).into_owned(),
                Style::default().add_modifier(Modifier::BOLD),
            ),
            Span::styled(th.text(buf).into_owned(), typed(app)),
            Span::raw(cursor),
            Span::styled(th.text(&hint).into_owned(), plain),
        ]);
    }
    match &app.screen.status {
        Some(s) if s.error => Line::from(Span::styled(th.text(&format!(" {}", s.text)).into_owned(), th.error())),
        Some(s) => Line::from(th.text(&format!(" {}", s.text)).into_owned()),
        None => Line::from(""),
    }
}
