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
//! with a heavy border. One function per area: header, body panels, status line (with the
//! input lines and the overwrite question), footer, the tour's caption and the popups (help's
//! two pages, the lists). With `--ascii` the frame gets a last pass that keeps it pure ASCII.

use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Clear, Paragraph};
use ratatui::Frame;

use std::path::PathBuf;

use super::app::{App, ChartView, Mode, Panel, PulseView};
use super::bifurcation::{BifurcationState, BifurcationView};
use super::chart::{self, CellView, Geometry, ScatterView, ZoneGridView};
use super::compute::{default_band, ensemble_under, nearest, AcousticResult, SimResult, AGREEMENT_SURE};
use super::explain;
use super::fields::Knob;
use super::history::{self, HistoryView};
use super::keys::Keymap;
use super::keys::{self, Action};
use super::params::ParamsView;
use super::polar::{PolarHit, PolarView};
use super::readout::{verdict_words, ReadoutView, Row};
use super::response::{ResponseState, ResponseView};
use super::theme::{fold_buffer, Palette};
use super::tour::wrap;
use super::waveform::{self, WaveformView};
use crate::design::{Chart, Design, Metrics, Zone, ZoneBy};
use crate::ensemble::{Ensemble, Percentiles};
use crate::store;
use crate::units::sig;
use crate::verdict::Verdict;

/// Rows of the wide layout's parameter panel: the design's fields. The forcing and ensemble
/// fields come last and scroll into view when selected (↑ from the first field reaches them).
const PARAMS_ROWS: u16 = 19;

/// Smallest terminal that gets more than the one-line message.
pub const MIN_W: u16 = 30;
pub const MIN_H: u16 = 8;

/// What a frame drew that the app needs to know: where the chart's cells are (for mouse
/// clicks) and whether the chart was on screen at all.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Drawn {
    pub geometry: Option<Geometry>,
    pub chart_shown: bool,
    /// Where each shown field of the parameters panel is (its line, its index in `Knob::ALL`).
    pub fields: Vec<(Rect, usize)>,
    /// Where the polar's canvas is (a click or drag there sets θ).
    pub polar: Option<PolarHit>,
}

impl Drawn {
    /// This and `other` together (each area is drawn once a frame).
    fn and(mut self, other: Drawn) -> Drawn {
        self.geometry = self.geometry.or(other.geometry);
        self.chart_shown |= other.chart_shown;
        self.fields.extend(other.fields);
        self.polar = self.polar.or(other.polar);
        self
    }
}

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
    f.render_widget(Paragraph::new(app.theme.fit_line(header_line(app), header.width.into())), header);
    let caption_h = if touring && body.height >= 12 { 5 } else { 0 };
    let [panels, caption] = Layout::vertical([Constraint::Min(1), Constraint::Length(caption_h)]).areas(body);
    let drawn = body_panels(f, app, panels);
    if caption_h > 0 {
        caption_box(f, app, caption);
    }
    f.render_widget(Paragraph::new(app.theme.fit_line(status_line(app), status.width.into())), status);
    if footer_h > 0 {
        f.render_widget(
            footer_line(&app.settings.keys, footer.width, (touring, app.anim.is_some()), app.mouse, &app.theme),
            footer,
        );
    }
    match app.mode {
        Mode::Help(scroll) => help_popup(f, &app.settings.keys, &app.theme, scroll, area),
        Mode::Glossary(scroll) => glossary_popup(f, app, scroll, area),
        _ => {
            if let Some(list) = list_view(app) {
                list_popup(f, &list, &app.theme, area);
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
    if app.zoom && body.width >= 30 && body.height >= 6 {
        return zoomed(f, app, body);
    }
    if body.width >= 110 && body.height >= params_h + 10 {
        let [left, right] = Layout::horizontal([Constraint::Length(40), Constraint::Min(1)]).areas(body);
        let [params, readout] = Layout::vertical([Constraint::Length(params_h), Constraint::Min(1)]).areas(left);
        let drawn = params_widget(f, app, params);
        readout_widget(f, app, readout, false);
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
            readout_widget(f, app, readout, true);
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
            readout_widget(f, app, readout, true);
            drawn.and(plot(f, app, Panel::Chart, chart))
        }
    } else {
        let [sel, readout] = Layout::vertical([Constraint::Length(1), Constraint::Min(0)]).areas(body);
        let fld = app.param();
        let line = format!("{}{} {}", app.theme.pointer(), fld.label(), fld.display(&app.design));
        let line = app.theme.text(&line).into_owned();
        f.render_widget(Paragraph::new(line).style(Style::default().add_modifier(Modifier::REVERSED)), sel);
        readout_widget(f, app, readout, false);
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
            readout_widget(f, app, body, false);
            Drawn::default()
        }
        which => plot(f, app, which, body),
    }
}

/// A panel's block: the tour's panel with a heavy border and a pointer, the focused one
/// coloured, the title folded to ASCII with `--ascii`.
fn panel_block(app: &App, which: Panel, title: &str) -> Block<'static> {
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
fn fit(theme: &Palette, options: &[String], width: u16) -> String {
    let w = usize::from(width).saturating_sub(2);
    let last = theme.text(&options[options.len() - 1]).into_owned();
    options
        .iter()
        .find(|t| theme.text(t).chars().count() <= w)
        .cloned()
        .unwrap_or_else(|| theme.fit(&last, w).into_owned())
}

/// The width a panel's title may use: the panel's, less the tour's pointer when it has one.
fn title_width(app: &App, which: Panel, area: Rect) -> u16 {
    if app.tour_panel() == Some(which) {
        area.width.saturating_sub(2)
    } else {
        area.width
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

/// Formats one readout value from a design's metrics.
type Format<'a> = &'a dyn Fn(&Metrics, &Design) -> String;

/// The marker put after a negative e: the glossary (help page 2) explains it.
pub const NEGATIVE_E: &str = "(!)";

/// "0.597 cm/s [0.512–0.702]": a median with its p10–p90 (the engine's nearest-rank
/// percentiles of the ensemble), each to `digits` significant digits.
pub fn spread(p: &Percentiles, digits: usize, unit: &str) -> String {
    let v = |x: Option<f64>| x.map_or("—".to_string(), |x| sig(x, digits));
    match p.median {
        None => "—".to_string(),
        Some(_) => format!("{} {unit} [{}–{}]", v(p.median), v(p.p10), v(p.p90)),
    }
}

/// The readout's extra rows of a forced design: its steady state over the last N periods
/// (the engine's [`crate::response::Steady`]), in the units people read.
fn steady_rows(a: &AcousticResult) -> Vec<(&'static str, String)> {
    let Some(s) = &a.steady else { return vec![] };
    let opt = |v: Option<f64>, digits: usize, unit: &str| {
        v.map_or("—".to_string(), |v| format!("{} {unit}", sig(v, digits)))
    };
    if let Some(e) = &a.forced_ensemble {
        // N > 1: the N runs' settled states, median [p10–p90] (the line without the ball is
        // the same for every run).
        let p = &e.spread;
        let mm = |p: &Percentiles| Percentiles {
            p10: p.p10.map(|x| x * 1e3),
            median: p.median.map(|x| x * 1e3),
            p90: p.p90.map(|x| x * 1e3),
        };
        return vec![
            ("amp", spread(&mm(&p.amplitude_m), 4, "mm")),
            ("alone", opt(e.amplitude_linear_m.map(|x| x * 1e3), 4, "mm")),
            ("cut", spread(&p.reduction_db, 3, "dB")),
            ("Leq", spread(&p.leq_db, 4, "dB")),
            ("imp/T", spread(&p.impacts_per_period, 3, "")),
        ];
    }
    vec![
        ("amp", format!("{} mm", sig(s.amplitude_m * 1e3, 4))),
        ("alone", opt(s.amplitude_linear_m.map(|x| x * 1e3), 4, "mm")),
        ("cut", opt(s.reduction_db, 3, "dB")),
        ("Leq", opt(s.leq_db, 4, "dB")),
        ("imp/T", sig(s.impacts_per_period, 3)),
    ]
}

/// Where a design's run starts, as the readout's forced note says it: "after the 2 m/s
/// strike" (the main mass's v0), "after the ball's 0.5 m/s start" (w0 alone), or "from rest".
pub fn start_words(d: &Design) -> String {
    let p = &d.damper;
    if p.v0_m_s != 0.0 {
        format!("after the {} m/s strike", crate::units::short(p.v0_m_s))
    } else if p.ball_velocity_m_s != 0.0 {
        format!("after the ball's {} m/s start", crate::units::short(p.ball_velocity_m_s))
    } else {
        "from rest".to_string()
    }
}

/// The note of a forced design: whether its steady state settled, the start it ran from
/// (the response view's curve runs from rest), whether it is periodic, and its window's end
/// (after settling, as `thud simulate --settle`); with N > 1 the share of runs that settled.
/// The most important words first: the compact readout cuts the note at its edge.
fn steady_note(a: &AcousticResult, d: &Design) -> Option<String> {
    let s = a.steady.as_ref()?;
    let start = start_words(d);
    if let Some(e) = &a.forced_ensemble {
        let cut = if e.truncated { ", TRUNCATED" } else { "" };
        return Some(format!(
            "{} runs: {:.0}% settled, {start}, {:.0}% periodic{cut}",
            e.ensemble.len(),
            100.0 * e.settled_fraction,
            100.0 * e.periodic_fraction
        ));
    }
    // The design's one verdict, as the readout's title names it ([`readout_title`]); first,
    // as the note is cut at the readout's edge at 80×24 and 120×40.
    let v = design_verdict(a)?;
    Some(format!("{}, {start}, by t {} s", verdict_words(&v), sig(s.window_end_s, 3)))
}

/// The verdict on the live design's motion ([`crate::verdict::of_design`]): its settled
/// run's and its orbit's at f, as one. The readout's title and note, and the bifurcation
/// view's line at f, all name this one.
pub fn design_verdict(a: &AcousticResult) -> Option<Verdict> {
    crate::verdict::of_design(a.steady.as_ref().map(|s| s.verdict), a.orbit.as_ref().map(|o| o.run.orbit))
}

/// The ensemble of a readout under the design's thresholds (reclassified on draw as zones are).
fn ensemble_of(a: &AcousticResult, d: &Design) -> Option<Ensemble> {
    a.ensemble.as_ref().map(|e| ensemble_under(e, &d.thresholds))
}

/// The readout values of one design: (label, value) per row.
fn readout_values(a: &AcousticResult, d: &Design) -> Vec<(&'static str, String)> {
    let m = &a.metrics;
    let opt = |v: Option<f64>, digits: usize, unit: &str| {
        v.map_or("—".to_string(), |v| format!("{} {unit}", sig(v, digits)))
    };
    let by = match d.thresholds.zone_by {
        ZoneBy::Paper => "by e",
        ZoneBy::Fit => "by e_fit",
    };
    let zone = |m: &Metrics| {
        m.zone(&d.thresholds)
            .map_or("— (no e or no sound)".into(), |z: Zone| format!("{} {} ({by})", z.number(), z.describe()))
    };
    let negative = |e: Option<f64>, v: String| if e.is_some_and(|e| e < 0.0) { format!("{v} {NEGATIVE_E}") } else { v };
    let mut rows = if let Some(e) = ensemble_of(a, d) {
        let s = &e.spread;
        let mm = &e.metrics;
        vec![
            ("U0max", spread(&s.u0_max_m_s, 5, "m/s")),
            ("e", negative(s.inclination_cm_s.median, spread(&s.inclination_cm_s, 3, "cm/s"))),
            ("e_fit", spread(&s.inclination_fit_cm_s, 3, "cm/s")),
            ("SPLmax", spread(&s.spl_max_db, 4, "dB")),
            ("zone", format!("{}, {:.0}%", zone(mm), 100.0 * e.agreement)),
            ("impacts", mm.n_impacts.to_string()),
            ("τ@U0max", opt(mm.contact_duration_s.map(|t| t * 1e6), 4, "µs")),
            ("R mean", opt(mm.restitution_mean, 3, "")),
        ]
    } else {
        let spec: [(&'static str, Format); 8] = [
            ("U0max", &|m, _| format!("{} m/s", sig(m.u0_max_m_s, 5))),
            ("e", &|m, _| negative(m.inclination_cm_s, opt(m.inclination_cm_s, 3, "cm/s"))),
            ("e_fit", &|m, _| opt(m.inclination_fit_cm_s, 3, "cm/s")),
            ("SPLmax", &|m, _| opt(m.spl_max_db, 4, "dB")),
            ("zone", &|m, _| zone(m)),
            ("impacts", &|m, _| m.n_impacts.to_string()),
            ("τ@U0max", &|m, _| opt(m.contact_duration_s.map(|t| t * 1e6), 4, "µs")),
            ("R mean", &|m, _| opt(m.restitution_mean, 3, "")),
        ];
        spec.iter().map(|(label, f)| (*label, f(m, d))).collect()
    };
    rows.extend(steady_rows(a));
    rows
}

/// The readout rows of the live (and pinned) design, and the note under them.
pub fn readout_rows(app: &App) -> (Vec<Row>, Option<String>) {
    let live_a = app.acoustic().filter(|_| !app.design_busy());
    let live = live_a.map(|a| readout_values(a, &app.design));
    let pinned = app.pinned.as_ref().and_then(|p| p.acoustic.as_ref().map(|a| readout_values(a, &p.design)));
    // The rows the live design has (its last results' while it computes; the plain eight at first).
    let labels: Vec<&'static str> = match (&live, app.acoustic()) {
        (Some(v), _) => v.iter().map(|r| r.0).collect(),
        (None, Some(a)) if app.design.damper.forced() == a.steady.is_some() => {
            readout_values(a, &app.design).iter().map(|r| r.0).collect()
        }
        _ => ["U0max", "e", "e_fit", "SPLmax", "zone", "impacts", "τ@U0max", "R mean"].to_vec(),
    };
    let find = |v: &Option<Vec<(&'static str, String)>>, label: &str| {
        v.as_ref().map(|v| v.iter().find(|r| r.0 == label).map_or(String::new(), |r| r.1.clone()))
    };
    let rows = labels
        .iter()
        .map(|label| Row {
            label,
            live: find(&live, label).unwrap_or_else(|| "…".to_string()).trim_end().to_string(),
            pinned: find(&pinned, label).map(|p| p.trim_end().to_string()),
        })
        .collect();
    let negative = live_a.is_some_and(|a| match ensemble_of(a, &app.design) {
        Some(e) => e.spread.inclination_cm_s.median.is_some_and(|e| e < 0.0),
        None => a.metrics.inclination_cm_s.is_some_and(|e| e < 0.0),
    });
    let note = if let Some(e) = &app.results.error {
        format!("error: {e}")
    } else if app.design_busy() {
        "computing…".to_string()
    } else if let Some(n) = live_a.and_then(|a| steady_note(a, &app.design)) {
        // A forced design's note first, settled or not: it says which start the figures are
        // from (the response view's curve runs from rest).
        if negative {
            format!("{n}; {NEGATIVE_E} e < 0")
        } else {
            n
        }
    } else if negative {
        format!("{NEGATIVE_E} e < 0: see ? page 2")
    } else if let Some(e) = live_a.and_then(|a| a.ensemble.as_ref()) {
        format!("median [p10–p90] of {} runs; % agree", e.runs)
    } else {
        format!(
            "SPL: {} at r {} m, θ {}°",
            app.design.model.level_name(),
            sig(app.design.observer.r_m, 3),
            sig(app.design.observer.theta_rad.to_degrees(), 3)
        )
    };
    (rows, Some(note))
}

/// The readout's title, `width` columns for it: with a force on, the live design's orbit at
/// its f as the engine classified it with the readout (`a.orbit`, as `thud bifurcation --vary
/// f=f:f:1`): `readout: orbit 2/1 sym`. The title, not a row or the note: at 80×24 the compact
/// readout has no row to spare and cuts its one-line note at its edge, and at 120×40 a row
/// more would push the note (which start the figures are from) off the tall one. With N > 1
/// runs the rows are the runs' medians over spread ball offsets, the orbit the design's own
/// start's: it says so (`from y0`). Always named `readout`; plain ` readout ` where the orbit
/// does not fit whole, while the design computes (no stale orbit), without a force, and with
/// the Newmark solver (orbits are sampled with the event solver only).
pub fn readout_title(app: &App, width: u16) -> String {
    let plain = " readout ".to_string();
    let live = app.acoustic().filter(|_| !app.design_busy());
    let Some((a, v)) = live.and_then(|a| Some((a, design_verdict(a)?))) else { return plain };
    let words = verdict_words(&v);
    let options = if a.ensemble.is_some() || a.forced_ensemble.is_some() {
        vec![format!(" readout: {words} from y0 "), plain]
    } else if matches!(v, Verdict::Periodic { .. }) {
        vec![format!(" readout: {words} (impacts/periods) "), format!(" readout: {words} "), plain]
    } else {
        vec![format!(" readout: {words} "), plain]
    };
    fit(&app.theme, &options, width)
}

fn readout_widget(f: &mut Frame, app: &App, area: Rect, compact: bool) {
    let (rows, note) = readout_rows(app);
    let title = readout_title(app, title_width(app, Panel::Readout, area));
    let view = ReadoutView {
        block: panel_block(app, Panel::Readout, &title),
        rows: &rows,
        note: note.as_deref(),
        theme: app.theme,
        compact,
    };
    f.render_widget(view, area);
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
            let Sound { pulse: live, peaks, empty, .. } = sound_of(app.results.acoustic.as_deref(), app.pulse);
            let pin = pin_sound.map(|a| sound_of(Some(a), app.pulse).pulse);
            let u0 = match app.pulse {
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
            let live = sound_of(app.results.acoustic.as_deref(), app.pulse).polar;
            let pin = pin_sound.map(|a| sound_of(Some(a), app.pulse).polar);
            let d = &app.design;
            let r = sig(d.observer.r_m, 3);
            let what = if app.pulse == PulseView::Single { "one impact" } else { "loudest impact" };
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
        Panel::Chart => return Drawn { geometry: chart_panel(f, app, area), chart_shown: true, ..Drawn::default() },
    }
    Drawn::default()
}

fn chart_title(app: &App, width: u16) -> String {
    let th = &app.theme;
    let t = &app.design.thresholds;
    let (done, total) = app.chart.progress();
    let progress = if done < total { format!(" {done}/{total}") } else { String::new() };
    let by = match t.zone_by {
        ZoneBy::Paper => "e",
        ZoneBy::Fit => "e_fit",
    };
    let (l, e) = (format!("L* {} dB", t.spl_db), format!("e* {} cm/s", t.inclination_cm_s));
    match app.chart_view {
        ChartView::Zones => fit(
            th,
            &[
                format!(" zones over mass × gap  {l}  {e} (by {by}){progress} "),
                format!(" zones m×d  {l}  {e}{progress} "),
                format!(" zones  {l}  {e} "),
                " zones ".into(),
            ],
            width,
        ),
        ChartView::Scatter => fit(
            th,
            &[
                format!(" e vs SPLmax (Fig 17)  {l}  {e}{progress} "),
                format!(" e vs SPLmax  {l}  {e} "),
                " e vs SPLmax ".into(),
            ],
            width,
        ),
        ChartView::Response => {
            let p = &app.design.damper;
            let (f0, f) = (sig(p.force_n, 3), sig(p.freq_hz, 4));
            fit(
                th,
                &[
                    format!(" frequency response: F0 {f0} N, from rest, settled; f {f} Hz "),
                    format!(" response: F0 {f0} N, f {f} Hz "),
                    format!(" response F0 {f0} N "),
                    " response ".into(),
                ],
                width,
            )
        }
        ChartView::Bifurcation => {
            let p = &app.design.damper;
            let (f0, f) = (sig(p.force_n, 3), sig(p.freq_hz, 4));
            let refining = if app.bifurcation_busy() { ", refining…" } else { "" };
            fit(
                th,
                &[
                    format!(" bifurcation: x(kT) over f, F0 {f0} N, from its start; f {f} Hz{refining} "),
                    format!(" bifurcation: x(kT) over f, f {f} Hz{refining} "),
                    format!(" bifurcation{refining} "),
                    " bifurcation ".into(),
                ],
                width,
            )
        }
    }
}

fn chart_panel(f: &mut Frame, app: &App, area: Rect) -> Option<Geometry> {
    let title = chart_title(app, title_width(app, Panel::Chart, area));
    let block = panel_block(app, Panel::Chart, &title);
    let inner = block.inner(area);
    let fine = &app.chart.fine;
    match app.chart_view {
        ChartView::Response => {
            let band = default_band(&app.design);
            let state = if !app.design.damper.forced() {
                ResponseState::NoForce
            } else if let Some(r) = app.response() {
                ResponseState::Ready(r)
            } else if let Some(e) = app.response.error.as_deref() {
                ResponseState::Failed(e)
            } else {
                ResponseState::Computing(app.response.progress.0, app.response.progress.1)
            };
            let at_f = app.acoustic().filter(|_| !app.design_busy()).and_then(|a| a.rest_at_f.as_ref());
            let view = ResponseView { block, state, band, freq_hz: app.design.damper.freq_hz, at_f, theme: app.theme };
            f.render_widget(view, area);
            None
        }
        ChartView::Bifurcation => {
            let state = if !app.design.damper.forced() {
                BifurcationState::NoForce
            } else if let Some((b, fine)) = app.bifurcation() {
                BifurcationState::Ready(b, fine)
            } else if let Some(e) = app.bifurcation.error.as_deref() {
                BifurcationState::Failed(e)
            } else {
                BifurcationState::Computing
            };
            let band = default_band(&app.design);
            let live = app.acoustic().filter(|_| !app.design_busy());
            let at_f = live.and_then(|a| a.orbit.as_ref());
            let view = BifurcationView {
                block,
                state,
                band_hz: [band.from_hz, band.to_hz],
                freq_hz: app.design.damper.freq_hz,
                at_f,
                verdict: live.and_then(design_verdict),
                theme: app.theme,
            };
            f.render_widget(view, area);
            None
        }
        ChartView::Zones => {
            let cells = chart_cells(app);
            let masses_g: Vec<f64> = fine.masses_kg.iter().map(|m| m * 1e3).collect();
            let gaps_cm: Vec<f64> = fine.gaps_m.iter().map(|g| g * 1e2).collect();
            let p = &app.design.damper;
            let view = ZoneGridView {
                block,
                masses_g: &masses_g,
                gaps_cm: &gaps_cm,
                cells: &cells,
                design: (p.impact_mass_kg * 1e3, p.gap_m * 1e2),
                zone: app.design_zone(),
                theme: app.theme,
            };
            f.render_widget(view, area);
            chart::layout(inner, &masses_g, &gaps_cm, &app.theme, chart::pending(&cells), chart::unsure(&cells))
                .map(|l| l.geometry)
        }
        ChartView::Scatter => {
            let pts = scatter_points(app);
            let current =
                app.metrics().filter(|_| !app.design_busy()).and_then(|m| Some((m.inclination_cm_s?, m.spl_max_db?)));
            let t = &app.design.thresholds;
            let view = ScatterView {
                block,
                points: &pts,
                current,
                l_star_db: t.spl_db,
                e_star_cm_s: t.inclination_cm_s,
                theme: app.theme,
            };
            f.render_widget(view, area);
            None
        }
    }
}

/// The fine grid's cells: computed ones exact, the rest borrowed from the nearest coarse cell.
pub fn chart_cells(app: &App) -> Vec<CellView> {
    let fine = &app.chart.fine;
    let nm = fine.masses_kg.len();
    fine.cells
        .iter()
        .enumerate()
        .map(|(i, c)| match (c, app.chart.ensembles.get(i).and_then(Option::as_ref)) {
            (Some(_), Some(e)) => {
                let (zone, agreement) = e.zone_under(&app.design.thresholds);
                if agreement < AGREEMENT_SURE {
                    CellView::Unsure(zone)
                } else {
                    CellView::Exact(zone)
                }
            }
            (Some(c), None) => CellView::Exact(app.zone(&c.metrics)),
            (None, _) => coarse_zone(app.chart.coarse.as_ref(), fine.masses_kg[i % nm], fine.gaps_m[i / nm], app),
        })
        .collect()
}

fn coarse_zone(coarse: Option<&Chart>, m: f64, g: f64, app: &App) -> CellView {
    let Some(c) = coarse else { return CellView::Empty };
    match c.cell(nearest(&c.masses_kg, m), nearest(&c.gaps_m, g)) {
        Some(cell) => CellView::Approx(app.zone(&cell.metrics)),
        None => CellView::Empty,
    }
}

/// (e, SPLmax, zone) of every computed cell (fine pass, or coarse while the fine one is empty).
pub fn scatter_points(app: &App) -> Vec<(f64, f64, Zone)> {
    let fine = &app.chart.fine;
    let src = if fine.done() > 0 { Some(fine) } else { app.chart.coarse.as_ref() };
    src.map_or_else(Vec::new, |c| {
        c.cells
            .iter()
            .flatten()
            .filter_map(|c| {
                let m = &c.metrics;
                Some((m.inclination_cm_s?, m.spl_max_db?, app.zone(m)?))
            })
            .collect()
    })
}

fn header_line(app: &App) -> Line<'static> {
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
        let frame = frames[app.spinner % frames.len()];
        let (done, total) = app.chart.progress();
        let text = if !app.exports.is_empty() && !app.design_busy() {
            format!("{bar} {frame} exporting {} ", app.exports.len())
        } else {
            let what = if app.design_busy() { "computing design" } else { "filling chart" };
            format!("{bar} {frame} {what} {done}/{total} ")
        };
        spans.push(Span::styled(text, bold));
    }
    if app.pinned.is_some() {
        spans.push(Span::styled(format!("{bar} pinned "), th.pinned()));
    }
    if app.pulse == PulseView::Single {
        spans.push(Span::raw(format!("{bar} pulse: one impact ")));
    }
    if app.zoom {
        spans.push(Span::raw(format!("{bar} zoom: {:?} ", app.zoomed_panel()).to_lowercase()));
    } else if app.focus != Panel::Params {
        spans.push(Span::raw(format!("{bar} focus: {:?} ", app.focus).to_lowercase()));
    }
    Line::from(spans)
}

/// The input line's text: reversed while selected (typing replaces it).
fn typed(app: &App) -> Style {
    if app.line_selected {
        Style::default().add_modifier(Modifier::REVERSED)
    } else {
        Style::default()
    }
}

fn status_line(app: &App) -> Line<'static> {
    let th = &app.theme;
    let cursor = th.sym("█", "_");
    // The hints are read, not skimmed: plain text, never dim.
    let plain = th.label();
    if let Mode::SaveAs(buf) = &app.mode {
        let dir = app.data_dir.as_deref().map_or_else(|| "(no data directory)".into(), |d| d.display().to_string());
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
    match &app.status {
        Some(s) if s.error => Line::from(Span::styled(th.text(&format!(" {}", s.text)).into_owned(), th.error())),
        Some(s) => Line::from(th.text(&format!(" {}", s.text)).into_owned()),
        None => Line::from(""),
    }
}

/// The footer: the key table's hints (the tour's first while it runs) and, with the mouse on,
/// `mouse on`; as many whole ones as fit in `width`, chosen by importance
/// ([`keys::FOOTER_PRIORITY`]) and shown in table order.
fn footer_line(
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
fn key_text(label: &str, theme: &Palette) -> String {
    if !theme.ascii {
        return label.to_string();
    }
    let spelled = label.replace("↑↓", "Up/Down").replace("←→", "Left/Right");
    let spelled = spelled.replace('↑', "Up").replace('↓', "Down").replace('←', "Left").replace('→', "Right");
    theme.text(&spelled).into_owned()
}

/// The tour's caption: which step, its title and the caption wrapped to the box.
fn caption_box(f: &mut Frame, app: &App, area: Rect) {
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

/// A rectangle of at most `w × h` centred in `area`.
fn centered(area: Rect, w: u16, h: u16) -> Rect {
    let (w, h) = (w.min(area.width), h.min(area.height));
    Rect::new(area.x + (area.width - w) / 2, area.y + (area.height - h) / 2, w, h)
}

/// `text` wrapped at word boundaries to `width` columns, a word longer than a line broken
/// where the line ends (a path in an error message), so nothing is cut.
fn wrap_all(text: &str, width: usize) -> Vec<String> {
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
fn help_popup(f: &mut Frame, keys: &Keymap, theme: &Palette, scroll: u16, area: Rect) {
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
fn glossary_popup(f: &mut Frame, app: &App, scroll: u16, area: Rect) {
    let th = &app.theme;
    let width = 100.min(area.width);
    let bold = Style::default().add_modifier(Modifier::BOLD);
    let mut lines: Vec<Line> = Vec::new();
    let cx = explain::OnScreen {
        forced: app.design.damper.forced(),
        runs: app.runs,
        response_view: app.chart_view == ChartView::Response,
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
fn list_popup(f: &mut Frame, list: &ListView, theme: &Palette, area: Rect) {
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
            app.preset_list
                .iter()
                .map(|p| ListItem { label: p.name.to_string(), detail: p.description.clone(), problem: false })
                .collect(),
            *i,
            String::new(),
        ),
        Mode::Saved(i) => {
            let good = app.saved.designs.iter().map(|d| ListItem {
                label: d.name.clone(),
                detail: d.description.clone(),
                problem: false,
            });
            let bad = app.saved.problems.iter().map(|p| ListItem {
                label: format!(
                    "✗ {} (cannot be loaded)",
                    p.path.file_name().map_or_else(|| p.path.display().to_string(), |n| n.to_string_lossy().into())
                ),
                detail: p.to_string(),
                problem: true,
            });
            let dir = app.data_dir.as_deref().map_or_else(PathBuf::new, store::designs_dir);
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
    let error = if matches!(app.mode, Mode::Saved(_)) { app.load_error.clone() } else { None };
    Some(ListView { title, items, selected, empty, error })
}
