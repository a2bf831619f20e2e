//! Layout: turns the app state into panels sized for the terminal. Three size classes:
//!
//! - wide (≥ 110 × 34): parameters and a tall readout on the left; the pulse, the polar, the
//!   history and the chart on the right;
//! - teaching (≥ 60 × 15, e.g. 80×24): two plots side by side — the M-shaped pulse and the
//!   polar, or (Tab to them) the history and the chart — over a compact strip of the selected
//!   parameter with its neighbours and a compact readout;
//! - tiny: the selected parameter and the readout, down to a one-line message.
//!
//! The guided tour adds its caption box at the bottom and draws the panel its step talks about
//! with a heavy border. Here are [`draw`] and the layout; each area has its own module: the
//! header (`header`), the panels (`params`, `readout`, `waveform`, `polar`, `history`,
//! `chart`, each with its view-model), the status line (`status`), the footer (`footer`),
//! the tour's caption (`caption`) and the popups (`popups`: help's two pages, the lists).
//! With `--ascii` the frame gets a last pass that keeps it pure ASCII.

use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Modifier, Style};
use ratatui::widgets::Paragraph;
use ratatui::Frame;

use super::app::{App, Mode, Panel, PulseView};
use super::compute::{AcousticResult, SimResult};
use super::fields::Knob;
use super::history::{self, HistoryView};
use super::params::ParamsView;
use super::polar::PolarView;
use super::theme::fold_buffer;
use super::titles::{fit, panel_block, title_width};
pub use super::view::Drawn;
use super::waveform::{self, WaveformView};
use super::{caption, chart, footer, header, popups, readout, status};
use crate::units::sig;

/// The view-models the tests read, where they always were.
pub use super::chart::panel::chart_cells;
pub use super::readout::{design_verdict, readout_rows};

/// Rows of the wide layout's parameter panel: the design's fields. The forcing and ensemble
/// fields come last and scroll into view when selected (↑ from the first field reaches them).
const PARAMS_ROWS: u16 = 19;

/// Smallest terminal that gets more than the one-line message.
pub const MIN_W: u16 = 30;
pub const MIN_H: u16 = 8;

/// Draws the whole screen.
pub fn draw(f: &mut Frame, app: &App) -> Drawn {
    let area = f.area();
    if area.width == 0 || area.height == 0 {
        return Drawn::default();
    }
    if area.width < MIN_W || area.height < MIN_H {
        let msg = format!("thud: terminal {}×{} too small; need {MIN_W}×{MIN_H}", area.width, area.height);
        let msg = app.theme.text(&msg);
        f.render_widget(
            Paragraph::new(app.theme.fit(&msg, area.width.into()).into_owned()),
            Rect { height: 1, ..area },
        );
        fold(f, app);
        return Drawn::default();
    }
    let touring = app.tour.is_some();
    // While touring the caption box carries the tour's keys: no footer.
    let footer_h = u16::from(area.height >= 12 && !touring);
    let [header, body, status, footer] = Layout::vertical([
        Constraint::Length(1),
        Constraint::Min(1),
        Constraint::Length(1),
        Constraint::Length(footer_h),
    ])
    .areas(area);
    f.render_widget(Paragraph::new(app.theme.fit_line(header::header_line(app), header.width.into())), header);
    let caption_h = if touring && body.height >= 12 { 5 } else { 0 };
    let [panels, caption] = Layout::vertical([Constraint::Min(1), Constraint::Length(caption_h)]).areas(body);
    let drawn = body_panels(f, app, panels);
    if caption_h > 0 {
        caption::caption_box(f, app, caption);
    }
    f.render_widget(Paragraph::new(app.theme.fit_line(status::status_line(app), status.width.into())), status);
    if footer_h > 0 {
        f.render_widget(
            footer::footer_line(
                &app.host.settings.keys,
                footer.width,
                (touring, app.anim.is_some()),
                app.mouse,
                &app.theme,
            ),
            footer,
        );
    }
    match app.mode {
        Mode::Help(scroll) => popups::help_popup(f, &app.host.settings.keys, &app.theme, scroll, area),
        Mode::Glossary(scroll) => popups::glossary_popup(f, app, scroll, area),
        _ => {
            if let Some(list) = popups::list_view(app) {
                popups::list_popup(f, &list, &app.theme, area);
            }
        }
    }
    fold(f, app);
    drawn
}

/// The `--ascii` frame's last pass.
fn fold(f: &mut Frame, app: &App) {
    if app.theme.ascii {
        fold_buffer(f.buffer_mut());
    }
}

/// The plots shown side by side in the teaching layout: the pulse and the polar, or, once
/// Tab reaches them, the history and the chart.
pub fn teaching_pair(focus: Panel) -> (Panel, Panel) {
    match focus {
        Panel::History | Panel::Chart => (Panel::History, Panel::Chart),
        _ => (Panel::Waveform, Panel::Polar),
    }
}

/// Lays out the body by size class.
fn body_panels(f: &mut Frame, app: &App, body: Rect) -> Drawn {
    let params_h = PARAMS_ROWS.min(Knob::ALL.len() as u16) + 2;
    if let Some(anim) = &app.anim {
        if body.width >= 30 && body.height >= 6 {
            anim_panel(f, app, anim, body);
            return Drawn::default();
        }
    }
    if let Some(table) = &app.table1 {
        if body.width >= 30 && body.height >= 6 {
            table1_panel(f, app, table, body);
            return Drawn::default();
        }
    }
    if let (Some(k), Some(front)) = (app.screen.front, app.host.front.as_deref()) {
        if body.width >= 30 && body.height >= 10 {
            front_panel(f, app, front, k, body);
            return Drawn::default();
        }
    }
    if app.screen.zoom && body.width >= 30 && body.height >= 6 {
        return zoomed(f, app, body);
    }
    if body.width >= 110 && body.height >= params_h + 10 {
        let [left, right] = Layout::horizontal([Constraint::Length(40), Constraint::Min(1)]).areas(body);
        let [params, readout] = Layout::vertical([Constraint::Length(params_h), Constraint::Min(1)]).areas(left);
        let drawn = params_widget(f, app, params);
        readout::readout_widget(f, app, readout, false);
        let [top, bottom] = Layout::vertical([Constraint::Percentage(45), Constraint::Percentage(55)]).areas(right);
        let [wave, polar] = Layout::horizontal([Constraint::Percentage(55), Constraint::Percentage(45)]).areas(top);
        let [hist, chart] = Layout::horizontal([Constraint::Percentage(45), Constraint::Percentage(55)]).areas(bottom);
        plot(f, app, Panel::Waveform, wave);
        let drawn = drawn.and(plot(f, app, Panel::Polar, polar));
        plot(f, app, Panel::History, hist);
        drawn.and(plot(f, app, Panel::Chart, chart))
    } else if body.width >= 60 && body.height >= 12 {
        let strip_h = if body.height >= 19 { 7 } else { 6 };
        if teaching_pair(app.focus).0 == Panel::Waveform {
            // The sound: pulse and polar over the parameters and the readout.
            let [top, strip] = Layout::vertical([Constraint::Min(1), Constraint::Length(strip_h)]).areas(body);
            let [params, readout] = Layout::horizontal([Constraint::Length(30), Constraint::Min(1)]).areas(strip);
            let drawn = params_widget(f, app, params);
            readout::readout_widget(f, app, readout, true);
            let [left, right] = Layout::horizontal([Constraint::Percentage(55), Constraint::Percentage(45)]).areas(top);
            plot(f, app, Panel::Waveform, left);
            drawn.and(plot(f, app, Panel::Polar, right))
        } else {
            // The design: the chart the full height (every gap row at 80×24), the history,
            // parameters and readout beside it.
            let [left, chart] =
                Layout::horizontal([Constraint::Percentage(50), Constraint::Percentage(50)]).areas(body);
            let params_h = if body.height >= 19 { 5 } else { 4 };
            let [hist, params, readout] =
                Layout::vertical([Constraint::Min(1), Constraint::Length(params_h), Constraint::Length(strip_h)])
                    .areas(left);
            plot(f, app, Panel::History, hist);
            let drawn = params_widget(f, app, params);
            readout::readout_widget(f, app, readout, true);
            drawn.and(plot(f, app, Panel::Chart, chart))
        }
    } else {
        let [sel, readout] = Layout::vertical([Constraint::Length(1), Constraint::Min(0)]).areas(body);
        let fld = app.param();
        let line = format!("{}{} {}", app.theme.pointer(), fld.label(), fld.display(&app.design));
        let line = app.theme.text(&line).into_owned();
        f.render_widget(Paragraph::new(line).style(Style::default().add_modifier(Modifier::REVERSED)), sel);
        readout::readout_widget(f, app, readout, false);
        Drawn::default()
    }
}

/// The animation view in the whole body: the live design's run in slow motion.
fn anim_panel<'a>(f: &mut Frame, app: &'a App, anim: &'a super::anim::Anim, area: Rect) {
    let th = &app.theme;
    let title = fit(
        th,
        &[
            " animation: the run in slow motion, to scale; ghost: without the ball ".to_string(),
            " animation, to scale; ghost: without the ball ".to_string(),
            " animation ".to_string(),
        ],
        area.width,
    );
    // In the tour the animation is the step's panel: marked as the others are.
    let title = if app.tour.is_some() { format!(" {} {}", th.sym("▶", ">"), title.trim_start()) } else { title };
    let block = th.highlight_block(th.text(&title).into_owned());
    let track = |sim: &'a SimResult, d: &crate::design::Design, sound: Option<&'a AcousticResult>| super::anim::Track {
        history: &sim.eval.run.history,
        impacts: &sim.eval.run.impacts,
        history_cm: &sim.history_cm,
        gap_m: d.damper.gap_m,
        ball_radius_m: d.ball_radius_m(),
        levels_db: sound.map_or(&[], |a| &a.impact_spl_db),
    };
    let Some(sim) = app.results.sim.as_deref() else {
        f.render_widget(Paragraph::new(th.text("no run to play yet").into_owned()).block(block), area);
        return;
    };
    // The levels only while the readout is the live design's (else they may be another run's).
    let sound = app.results.acoustic.as_deref().filter(|_| !app.design_busy());
    let pinned = app.pinned.as_ref().and_then(|p| Some(track(p.sim.as_deref()?, &p.design, p.acoustic.as_deref())));
    let pinned_end = app.pinned.as_ref().and_then(|p| p.sim.as_ref()).map_or(0.0, |s| s.eval.run.final_time_s);
    let end_s = sim.eval.run.final_time_s.max(pinned_end);
    let view = super::anim::AnimView {
        block,
        anim,
        live: track(sim, &app.design, sound),
        free_cm: &sim.free_cm,
        pinned,
        end_s,
        theme: app.theme,
    };
    f.render_widget(view, area);
}

/// The front view in the whole body: the front beside the readout (under it on a narrow
/// screen), so a loaded design's readout shows beside the front's numbers.
fn front_panel(f: &mut Frame, app: &App, front: &super::front::Front, k: usize, area: Rect) {
    use super::keys::Action;
    let th = &app.theme;
    let (plot, readout, compact) = if area.width >= 100 {
        let [readout, plot] = Layout::horizontal([Constraint::Length(40), Constraint::Min(1)]).areas(area);
        (plot, readout, false)
    } else {
        let h = if area.height >= 19 { 7 } else { 6 };
        let [plot, readout] = Layout::vertical([Constraint::Min(1), Constraint::Length(h)]).areas(area);
        (plot, readout, true)
    };
    readout::readout_widget(f, app, readout, compact);
    let title = fit(
        th,
        &[
            format!(" design front of {}: {} designs, the selected one highlighted ", front.file, front.points.len()),
            format!(" design front: {} designs ", front.points.len()),
            " front ".to_string(),
        ],
        plot.width,
    );
    let live_is = front.position(&app.design);
    // The live design's objectives: its readout's, once computed for it.
    let live = app
        .acoustic()
        .filter(|_| !app.design_busy())
        .map(|a| front.objectives.iter().map(|(c, _)| c.value(&a.metrics, a.steady.as_ref())).collect());
    let key = |a: Action| app.key_label(a).to_string();
    let view = super::front::FrontView {
        block: th.highlight_block(th.text(&title).into_owned()),
        front,
        selected: k,
        live,
        live_is,
        keys: [format!("{}{}", key(Action::Up), key(Action::Down)), key(Action::Edit), key(Action::FrontView)],
        theme: *th,
    };
    f.render_widget(view, plot);
}

/// The Table 1 view in the whole body: the measurements beside both models (the engine's table).
fn table1_panel(f: &mut Frame, app: &App, table: &super::table1::Table1, area: Rect) {
    let th = &app.theme;
    let title = fit(
        th,
        &[
            " Table 1 (dB): acrylic sphere on a steel plate, dipole at r 28.28 cm, θ 45°: measured and both models "
                .to_string(),
            " Table 1 (dB): measured and both models ".to_string(),
            " Table 1 (dB) ".to_string(),
        ],
        area.width.saturating_sub(2),
    );
    // In the tour the table is the step's panel: marked as the others are.
    let block = if app.tour.is_some() {
        th.highlight_block(th.text(&format!(" {} {}", th.sym("▶", ">"), title.trim_start())).into_owned())
    } else {
        th.block(th.text(&title).into_owned(), true)
    };
    f.render_widget(super::table1::Table1View { block, table, theme: app.theme }, area);
}

/// The zoomed panel alone in the whole body.
fn zoomed(f: &mut Frame, app: &App, body: Rect) -> Drawn {
    match app.zoomed_panel() {
        Panel::Params => params_widget(f, app, body),
        Panel::Readout => {
            readout::readout_widget(f, app, body, false);
            Drawn::default()
        }
        which => plot(f, app, which, body),
    }
}

fn params_widget(f: &mut Frame, app: &App, area: Rect) -> Drawn {
    let setup = app.setup();
    let rows: Vec<(String, String)> = Knob::ALL.iter().map(|p| (p.label().to_string(), p.shown(&setup))).collect();
    let groups: Vec<&'static str> = Knob::ALL.iter().map(|p| p.group().title()).collect();
    let view = ParamsView {
        block: panel_block(app, Panel::Params, " parameters "),
        rows: &rows,
        groups: &groups,
        selected: app.selected,
        focused: app.focus == Panel::Params,
        theme: app.theme,
    };
    let fields = view.field_lines(area);
    f.render_widget(view, area);
    Drawn { fields, ..Drawn::default() }
}

/// What the pulse and polar panels draw of one design's sound in the current pulse view.
struct Sound<'a> {
    /// (ms after the direct arrival, Pa).
    pulse: &'a [(f64, f64)],
    /// (θ in deg, SPL in dB).
    polar: &'a [(f64, f64)],
    /// The pulse's humps (ms, Pa), for the single impact.
    peaks: &'a [(f64, f64)],
    /// The message shown when there is nothing to draw.
    empty: String,
}

/// The sound of a design in the current pulse view.
fn sound_of(a: Option<&super::compute::AcousticResult>, view: PulseView) -> Sound<'_> {
    let none = |empty: String| Sound { pulse: &[], polar: &[], peaks: &[], empty };
    match (a, view) {
        (None, _) => none("computing…".into()),
        (Some(a), PulseView::Loudest) => {
            Sound { pulse: &a.waveform, polar: &a.polar, peaks: &[], empty: "no impact: no sound".into() }
        }
        (Some(a), PulseView::Single) => match &a.single {
            Ok(s) => Sound { pulse: &s.waveform, polar: &s.polar, peaks: &s.peaks, empty: String::new() },
            Err(e) => none(format!("no single impact: {e}")),
        },
    }
}

/// Draws one plot panel; returns where its chart or polar is (for clicks).
fn plot(f: &mut Frame, app: &App, which: Panel, area: Rect) -> Drawn {
    let theme = app.theme;
    let pinned = app.pinned.as_ref();
    let pin_sound = pinned.and_then(|p| p.acoustic.as_deref());
    match which {
        Panel::Waveform | Panel::Params | Panel::Readout => {
            let Sound { pulse: live, peaks, empty, .. } = sound_of(app.results.acoustic.as_deref(), app.screen.pulse);
            let pin = pin_sound.map(|a| sound_of(Some(a), app.screen.pulse).pulse);
            let u0 = match app.screen.pulse {
                PulseView::Single => Some(app.design.damper.v0_m_s),
                PulseView::Loudest => None,
            };
            let width = title_width(app, Panel::Waveform, area);
            let loudest =
                app.metrics().filter(|_| !app.design_busy()).and_then(|m| Some((m.u0_max_m_s, m.spl_max_db?)));
            let title = fit(&theme, &[waveform::title(u0, loudest, width)], width);
            let view = WaveformView {
                block: panel_block(app, Panel::Waveform, &title),
                live,
                pinned: pin,
                peaks,
                empty: &empty,
                theme,
            };
            f.render_widget(view, area);
        }
        Panel::Polar => {
            let live = sound_of(app.results.acoustic.as_deref(), app.screen.pulse).polar;
            let pin = pin_sound.map(|a| sound_of(Some(a), app.screen.pulse).polar);
            let d = &app.design;
            let r = sig(d.observer.r_m, 3);
            let what = if app.screen.pulse == PulseView::Single { "one impact" } else { "loudest impact" };
            let title = fit(
                &theme,
                &[
                    format!(" directivity SPL(θ) of the {what}, r {r} m "),
                    format!(" directivity SPL(θ), r {r} m "),
                    format!(" SPL(θ), r {r} m "),
                    " SPL(θ) ".into(),
                ],
                title_width(app, Panel::Polar, area),
            );
            let view = PolarView {
                block: panel_block(app, Panel::Polar, &title),
                live,
                pinned: pin,
                theta_deg: super::compute::listener_deg(d),
                range_deg: d.radiation.source.theta_range_deg(),
                theme,
            };
            let polar = view.hit_area(area);
            f.render_widget(view, area);
            return Drawn { polar, ..Drawn::default() };
        }
        Panel::History => {
            let empty: &[(f64, f64)] = &[];
            let s = app.results.sim.as_deref();
            let view = HistoryView {
                block: panel_block(app, Panel::History, &{
                    let width = title_width(app, Panel::History, area);
                    fit(&theme, &[history::title(width).to_string()], width)
                }),
                with_damper: s.map_or(empty, |s| &s.history_cm),
                without: s.map_or(empty, |s| &s.free_cm),
                maxima: s.map_or(empty, |s| &s.maxima_cm),
                free_maxima: s.map_or(empty, |s| &s.free_maxima_cm),
                pinned: pinned.and_then(|p| p.sim.as_deref()).map(|s| &s.maxima_cm[..]),
                theme,
            };
            f.render_widget(view, area);
        }
        Panel::Chart => {
            return Drawn { geometry: chart::panel::chart_panel(f, app, area), chart_shown: true, ..Drawn::default() }
        }
    }
    Drawn::default()
}
