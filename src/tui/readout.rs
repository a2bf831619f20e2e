//! The readout: what the design is worth, live beside pinned. Tall (one row per number) where
//! there is room, compact (two numbers a row, the zone first) in the teaching layout at 80×24.
//! A forced design's compact readout pairs its steady figures instead (amplitude with and
//! without the damper, cut, Leq, impacts a period); an ensemble's gives e, e_fit and SPLmax
//! a row each, with their [p10–p90].
//!
//! Columns never run together: each value is cut to its column with one blank or more after
//! it, losing first the insides of its bracketed parts (`1.4000 m/s […]`), then them (`1.4000
//! m/s…`), then its end, each cut marked with `…` (`...` in ASCII); beside a pinned design the
//! live column is as wide as the longest forms that leave the pinned one room for its own.
//!
//! Its view-model is here too: the rows of the live and pinned designs, the note under them
//! and the title naming the design's orbit ([`readout_rows`], [`readout_title`]).

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph, Widget};

use ratatui::Frame;

use super::app::{App, Panel};
use super::compute::{ensemble_under, AcousticResult};
use super::theme::{self, Palette};
use super::titles::{self, panel_block, title_width};
use crate::design::{Design, Metrics, Zone, ZoneBy};
use crate::ensemble::{Ensemble, Percentiles};
use crate::units::sig;
use crate::verdict::Verdict;
use unicode_width::UnicodeWidthStr;

/// One readout row: label, live value, pinned value (if a design is pinned).
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    pub label: &'static str,
    pub live: String,
    pub pinned: Option<String>,
}

/// The readout's data.
pub struct ReadoutView<'a> {
    pub block: Block<'a>,
    pub rows: &'a [Row],
    /// A line under the rows (e.g. "no impacts" or an error), if any.
    pub note: Option<&'a str>,
    pub theme: Palette,
    /// Two numbers a row (the zone on its own row first).
    pub compact: bool,
}

/// The pinned column's least width where the live one wants more room than there is: its own
/// width or this, whichever is less (a third of the room where that is more).
pub const PINNED_MIN: usize = 8;

/// `text` cut to at most `room` columns: the first of its [`forms`] that fits, else its start
/// and `ell` (`…`, or `...` in ASCII) as every cut text ends ([`theme::cut_to`]). The forms
/// are the readout's own: its columns are the only cut text with bracketed parts to drop first.
pub fn cut(text: &str, room: usize, ell: &str) -> String {
    forms(text, ell)
        .into_iter()
        .find(|f| f.width() <= room)
        .unwrap_or_else(|| theme::cut_to(text, room, ell).into_owned())
}

/// A value's forms, longest first: itself; with the insides of its bracketed parts elided
/// (`1.4000 m/s […]`, `1 noisy, weak (…), 75%`); its head before them and `ell`
/// (`1.4000 m/s…`).
pub fn forms(text: &str, ell: &str) -> [String; 3] {
    let elided = elide_brackets(text, ell);
    let head = match [text.find(" ("), text.find(" [")].into_iter().flatten().min() {
        Some(i) => format!("{}{ell}", &text[..i]),
        None => elided.clone(),
    };
    [text.to_string(), elided, head]
}

/// `text` with the inside of each ` (…)` and ` […]` part replaced by `ell` where that is
/// shorter (a `(!)` stays).
fn elide_brackets(text: &str, ell: &str) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(i) = [rest.find(" ("), rest.find(" [")].into_iter().flatten().min() {
        let close = if rest[i + 1..].starts_with('(') { ')' } else { ']' };
        let Some(j) = rest[i + 2..].find(close) else { break };
        let inside = &rest[i + 2..i + 2 + j];
        out.push_str(&rest[..i + 2]);
        out.push_str(if inside.chars().count() > ell.chars().count() { ell } else { inside });
        out.push(close);
        rest = &rest[i + 3 + j..];
    }
    out.push_str(rest);
    out
}

/// `text` cut to `width − gap` columns (see [`cut`]) and padded to `width`: the next column
/// starts `gap` or more blanks after it.
fn fit(text: &str, width: usize, gap: usize, ell: &str) -> String {
    let t = cut(text, width.saturating_sub(gap), ell);
    format!("{t:<width$}")
}

/// The widths of the live and the pinned columns in `room` columns, given the widest of each
/// column's values in each of their [`forms`]: the live one as wide as its longest form that
/// leaves the pinned one room for its own (full values first, then elided, then heads), and two
/// blanks; the pinned one the rest. Where not even the heads fit, the pinned one gets its
/// width, or a third of the room (at least [`PINNED_MIN`]) where that is less.
pub fn split(room: usize, live: [usize; 3], pinned: [usize; 3]) -> (usize, usize) {
    for (a, b) in [(0, 0), (0, 1), (1, 1), (1, 2), (2, 2)] {
        if live[a] + 2 + pinned[b] <= room {
            return (live[a] + 2, room - live[a] - 2);
        }
    }
    let pin_min = pinned[2].min((room / 3).max(PINNED_MIN)).min(room);
    let live_w = (live[2] + 2).min(room - pin_min);
    (live_w, room - live_w)
}

/// The widest of `texts` in each of their [`forms`] (at least `min`).
fn widest<'a>(texts: impl Iterator<Item = &'a str>, ell: &str, min: usize) -> [usize; 3] {
    let mut w = [min; 3];
    for t in texts {
        for (k, f) in forms(t, ell).iter().enumerate() {
            w[k] = w[k].max(f.chars().count());
        }
    }
    w
}

impl ReadoutView<'_> {
    fn ell(&self) -> &'static str {
        self.theme.sym("…", "...")
    }

    fn tall(&self, w: usize) -> Vec<Line<'static>> {
        let th = &self.theme;
        let ell = self.ell();
        let any_pinned = self.rows.iter().any(|r| r.pinned.is_some());
        // The labels' column: 8 wide, or wider for a label spelled out in ASCII (tau@U0max).
        let lw = self.rows.iter().map(|r| th.text(r.label).chars().count() + 1).max().unwrap_or(0).max(8);
        let room = w.saturating_sub(lw);
        let (live_w, pin_w) = if any_pinned && w >= 30 {
            let live: Vec<String> = self.rows.iter().map(|r| th.text(&r.live).into_owned()).collect();
            let pinned: Vec<String> =
                self.rows.iter().map(|r| th.text(r.pinned.as_deref().unwrap_or_default()).into_owned()).collect();
            let (live, pinned) =
                (widest(live.iter().map(String::as_str), ell, 4), widest(pinned.iter().map(String::as_str), ell, 6));
            split(room, live, pinned)
        } else {
            (room, 0)
        };
        let mut lines: Vec<Line> = Vec::new();
        if pin_w > 0 {
            let head = format!("{:<lw$}{}{}", "", fit("live", live_w, 1, ell), fit("pinned", pin_w, 0, ell));
            lines.push(Line::from(Span::styled(head, Style::default().add_modifier(Modifier::UNDERLINED))));
        }
        for r in self.rows {
            let gap = usize::from(pin_w > 0);
            let mut spans = vec![
                Span::styled(format!("{:<lw$}", th.text(r.label)), Style::default().add_modifier(Modifier::BOLD)),
                Span::raw(fit(&th.text(&r.live), live_w, gap, ell)),
            ];
            if pin_w > 0 {
                let pinned = th.text(r.pinned.as_deref().unwrap_or_default()).into_owned();
                spans.push(Span::styled(fit(&pinned, pin_w, 0, ell), th.pinned()));
            }
            lines.push(Line::from(spans));
        }
        lines
    }

    /// Zone first on its own row, then pairs: e | e_fit, SPLmax | U0max, τ | R mean, impacts.
    /// With a pinned design: zone, e and SPLmax as live | pinned. Every value is cut to its
    /// column (see [`cut`]), one blank or more before the next.
    fn compact(&self, w: usize) -> Vec<Line<'static>> {
        let th = &self.theme;
        let ell = self.ell();
        let get = |label: &str| self.rows.iter().find(|r| r.label == label);
        let bold = Style::default().add_modifier(Modifier::BOLD);
        // A label and its value in `width` columns, `gap` of them left blank at the end.
        let cell = |r: Option<&Row>, width: usize, gap: usize| -> Vec<Span<'static>> {
            let Some(r) = r else { return vec![] };
            let label = th.text(r.label).into_owned();
            let value = th.text(&r.live).into_owned();
            let lw = label.chars().count().max(6) + 1;
            vec![
                Span::styled(format!("{label:<lw$}"), bold),
                Span::raw(fit(&value, width.saturating_sub(lw), gap, ell)),
            ]
        };
        let mut lines = Vec::new();
        if self.rows.iter().any(|r| r.pinned.is_some()) {
            let shown: Vec<&Row> = ["zone", "e", "SPLmax"].iter().filter_map(|l| get(l)).collect();
            let live: Vec<String> = shown.iter().map(|r| th.text(&r.live).into_owned()).collect();
            let pinned: Vec<String> =
                shown.iter().map(|r| th.text(r.pinned.as_deref().unwrap_or_default()).into_owned()).collect();
            let (live, pinned) =
                (widest(live.iter().map(String::as_str), ell, 4), widest(pinned.iter().map(String::as_str), ell, 6));
            let (live_w, pin_w) = split(w.saturating_sub(7), live, pinned);
            let head = format!("{:<7}{}{}", "", fit("live", live_w, 1, ell), fit("pinned", pin_w, 0, ell));
            lines.push(Line::from(Span::styled(head, Style::default().add_modifier(Modifier::UNDERLINED))));
            for r in shown {
                let pinned = th.text(r.pinned.as_deref().unwrap_or("")).into_owned();
                lines.push(Line::from(vec![
                    Span::styled(format!("{:<7}", th.text(r.label)), bold),
                    Span::raw(fit(&th.text(&r.live), live_w, 1, ell)),
                    Span::styled(fit(&pinned, pin_w, 0, ell), th.pinned()),
                ]));
            }
            return lines;
        }
        lines.push(Line::from(cell(get("zone"), w, 0)));
        if get("amp").is_none() && self.rows.iter().any(|r| r.live.contains(" [")) {
            for label in ["e", "e_fit", "SPLmax"] {
                lines.push(Line::from(cell(get(label), w, 0)));
            }
            return lines;
        }
        let pairs = if get("amp").is_some() {
            [("amp", "alone"), ("cut", "Leq"), ("imp/T", "SPLmax")]
        } else {
            [("e", "e_fit"), ("SPLmax", "U0max"), ("τ@U0max", "R mean")]
        };
        // The left column as wide as its widest entry (a negative e carries its marker).
        let width = |r: Option<&Row>| {
            r.map_or(0, |r| th.text(r.label).chars().count().max(6) + 1 + th.text(&r.live).chars().count())
        };
        let left = pairs.iter().map(|(a, _)| width(get(a))).max().unwrap_or(0) + 2;
        let left = left.max(w / 2).min(w.saturating_sub(12));
        for (a, b) in pairs {
            let mut spans = cell(get(a), left, 1);
            spans.extend(cell(get(b), w - left, 0));
            lines.push(Line::from(spans));
        }
        lines
    }
}

impl Widget for ReadoutView<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let inner = self.block.inner(area);
        (&self.block).render(area, buf);
        let w = inner.width as usize;
        let mut lines = if self.compact { self.compact(w) } else { self.tall(w) };
        if let Some(n) = self.note {
            let n = self.theme.text(n).into_owned();
            // Tall: the whole note, wrapped (its rows are free); compact: one line, cut.
            let parts = if self.compact { vec![n] } else { super::tour::wrap(&n, w.max(1)) };
            for part in parts {
                lines.push(Line::from(Span::styled(part, Style::default().add_modifier(Modifier::ITALIC))));
            }
        }
        let lines: Vec<Line> = lines.into_iter().map(|l| self.theme.fit_line(l, w)).collect();
        Paragraph::new(lines).render(inner, buf);
    }
}

/// A verdict as the explorer words it, in the readout's title and note and the bifurcation
/// view's line: `orbit 3/1`, `orbit settled`, `orbit NOT SETTLED`, `orbit TRUNCATED`
/// (capitals where the figures are not a steady state's).
pub fn verdict_words(v: &Verdict) -> String {
    if v.is_marked() {
        format!("orbit {}", v.label().to_uppercase())
    } else {
        format!("orbit {}", v.label())
    }
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
    titles::fit(&app.theme, &options, width)
}

pub(super) fn readout_widget(f: &mut Frame, app: &App, area: Rect, compact: bool) {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cut_drops_the_bracketed_insides_first_then_the_end() {
        assert_eq!(cut("1.4000 m/s [1.4000–1.4498]", 26, "…"), "1.4000 m/s [1.4000–1.4498]");
        assert_eq!(cut("1.4000 m/s [1.4000–1.4498]", 20, "…"), "1.4000 m/s […]");
        assert_eq!(cut("4 quiet, weak (by e), 75%", 22, "…"), "4 quiet, weak (…), 75%");
        assert_eq!(cut("4 quiet, weak (by e), 75%", 14, "…"), "4 quiet, weak…");
        assert_eq!(cut("4 quiet, weak (by e), 75%", 10, "…"), "4 quiet,…");
        assert_eq!(cut("-0.33 cm/s [-0.5–0.1] (!)", 19, "…"), "-0.33 cm/s […] (!)");
        assert_eq!(cut("104.2 dB [103.1–104.9]", 11, "..."), "104.2 dB...");
        assert_eq!(cut("104.2 dB [103.1–104.9]", 8, "..."), "104.2...");
        assert_eq!(cut("abc", 0, "…"), "");
    }

    #[test]
    fn the_pinned_column_keeps_room_beside_a_wide_live_one() {
        assert_eq!(split(40, [10; 3], [10; 3]), (12, 28));
        // Whole live values, the pinned ones elided; then both elided; then both heads.
        assert_eq!(split(40, [20, 14, 10], [20, 14, 10]), (22, 18));
        assert_eq!(split(30, [20, 14, 10], [20, 14, 10]), (16, 14));
        assert_eq!(split(24, [20, 14, 10], [20, 14, 10]), (12, 12));
        let (live, pinned) = split(21, [25, 22, 14], [25, 22, 14]);
        assert_eq!(live + pinned, 21);
        assert!(pinned >= PINNED_MIN && live > pinned, "{live} {pinned}");
        assert_eq!(split(5, [25; 3], [25; 3]), (0, 5));
    }
}
