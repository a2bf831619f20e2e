//! The guided tour's caption box at the bottom of the body.

use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Clear, Paragraph};
use ratatui::Frame;

use super::app::App;
use super::popups::wrap_all;

/// The tour's caption: which step, its title and the caption wrapped to the box.
pub(super) fn caption_box(f: &mut Frame, app: &App, area: Rect) {
    let Some(state) = &app.tour else { return };
    let Some(step) = state.tour.steps.get(state.step) else { return };
    let th = &app.theme;
    let n = state.tour.steps.len();
    let title = th.text(&format!(" tour {}/{n}: {} ", state.step + 1, step.title)).into_owned();
    let title = th.fit(&title, area.width.saturating_sub(2).into()).into_owned();
    let keys = if state.step + 1 < n {
        " → next  ← back  z all panels  Esc explore from here "
    } else {
        " → finish  ← back  z all panels  Esc explore "
    };
    // The field the step talks about (selected), with its value: the keys change it.
    let fld = app.param();
    let field = th.text(&format!(" {}{} = {} ", th.pointer(), fld.label(), fld.display(&app.setup()))).into_owned();
    let room = usize::from(area.width.saturating_sub(4)).saturating_sub(th.text(keys).chars().count());
    let mut block =
        th.block(Line::from(Span::styled(title, Style::default().add_modifier(Modifier::BOLD))), true).title_bottom(
            Line::from(th.fit(&th.text(keys), area.width.saturating_sub(2).into()).into_owned()).right_aligned(),
        );
    if field.chars().count() <= room {
        block = block.title_bottom(Line::from(Span::styled(field, th.label())).left_aligned());
    }
    let inner = block.inner(area);
    f.render_widget(Clear, area);
    f.render_widget(block, area);
    let caption = th.text(&step.caption).into_owned();
    let (w, h) = (usize::from(inner.width), usize::from(inner.height));
    let lines: Vec<Line> = th.fit_lines(wrap_all(&caption, w), h, w).into_iter().map(Line::from).collect();
    f.render_widget(Paragraph::new(lines), inner);
}
