//! The header line: the preset (marked `*` when modified), the model, the mass and gap, and
//! what runs (the spinner, the exports), the pin, the pulse view, the zoom and the focus.

use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};

use super::app::{App, Panel, PulseView};
use crate::units::sig;

/// The header line of `app`.
pub(super) fn header_line(app: &App) -> Line<'static> {
    let th = &app.theme;
    let bold = Style::default().add_modifier(Modifier::BOLD);
    let p = &app.design.damper;
    let bar = th.sym("│", "|");
    let mut spans = vec![
        Span::styled(" thud ", bold.add_modifier(Modifier::REVERSED)),
        Span::raw(format!(
            " preset {}{} {bar} {} model {bar} m {} g, d {} cm ",
            app.preset,
            if app.modified() { "*" } else { "" },
            app.design.model.name(),
            sig(p.impact_mass_kg * 1e3, 4),
            sig(p.gap_m * 1e2, 3)
        )),
    ];
    if app.busy() {
        let frames = th.spinner();
        let frame = frames[app.screen.spinner % frames.len()];
        let (done, total) = app.chart.progress();
        let text = if !app.host.exports.is_empty() && !app.design_busy() {
            format!("{bar} {frame} exporting {} ", app.host.exports.len())
        } else {
            let what = if app.design_busy() { "computing design" } else { "filling chart" };
            format!("{bar} {frame} {what} {done}/{total} ")
        };
        spans.push(Span::styled(text, bold));
    }
    if app.pinned.is_some() {
        spans.push(Span::styled(format!("{bar} pinned "), th.pinned()));
    }
    if app.screen.pulse == PulseView::Single {
        spans.push(Span::raw(format!("{bar} pulse: one impact ")));
    }
    if app.screen.zoom {
        spans.push(Span::raw(format!("{bar} zoom: {:?} ", app.zoomed_panel()).to_lowercase()));
    } else if app.focus != Panel::Params {
        spans.push(Span::raw(format!("{bar} focus: {:?} ", app.focus).to_lowercase()));
    }
    Line::from(spans)
}
