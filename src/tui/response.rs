//! The response view of the chart panel: the frequency response of the forced
//! design as the engine computes it ([`crate::response::response`], every frequency from rest
//! and settled, as `thud response`): the steady amplitude with the damper and without it
//! against the forcing frequency f, and the level Leq of the rattle below, with the current f
//! marked. The curve does not depend on f, so changing f moves the marker only.
//!
//! The amplitudes span decades (a few mm with the damper, hundreds without it at resonance),
//! so they are drawn in dB re 1 mm, 20·log10(x/1 mm); the line under the plots gives the
//! engine's numbers at f itself, from rest (computed for exactly f with the readout, as `thud
//! response --freqs f:f:1`), in mm.

use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Modifier, Style};
use ratatui::widgets::{Block, Paragraph, Widget};

use super::compute::FreqBand;
use super::plot::{fit_bounds, Curve, LinePlot};
use super::theme::{Palette, Role};
use crate::response::{Response, ResponsePoint};
use crate::units::sig;

/// What the view shows: the curve, or why there is none.
pub enum ResponseState<'a> {
    /// The design has no force: nothing to respond to.
    NoForce,
    /// Being computed: (frequencies done, all).
    Computing(usize, usize),
    /// The engine (or a work cap) refused it.
    Failed(&'a str),
    Ready(&'a Response),
}

/// The response view's data.
pub struct ResponseView<'a> {
    pub block: Block<'a>,
    pub state: ResponseState<'a>,
    /// The band the curve spans (Hz).
    pub band: FreqBand,
    /// The forcing frequency f of the live design (Hz), marked on the curve.
    pub freq_hz: f64,
    /// The engine's point at exactly f from rest (None while it computes).
    pub at_f: Option<&'a ResponsePoint>,
    pub theme: Palette,
}

/// `x` (m) in dB re 1 mm.
fn db_mm(x_m: f64) -> Option<f64> {
    (x_m > 0.0 && x_m.is_finite()).then(|| 20.0 * (x_m * 1e3).log10())
}

/// The points of every sweep of `r` (one, from rest).
fn points(r: &Response) -> Vec<&ResponsePoint> {
    r.sweeps.iter().flat_map(|s| &s.points).collect()
}

/// The line under the plots, the longest of its wordings that fits `width` columns: the
/// engine's steady figures at f itself from rest (`at_f`, computed for exactly f, never the
/// nearest band point's), and where f lies off the band.
pub fn marker_line(at_f: Option<&ResponsePoint>, band: &FreqBand, f: f64, width: usize) -> String {
    let fs = sig(f, 4);
    let side = (!band.contains(f)).then_some(if f < band.from_hz { "below" } else { "above" });
    let off = side.map_or(String::new(), |s| format!(" ({s} the band, arrow at the edge)"));
    let options = match at_f {
        Some(p) => {
            let s = &p.steady;
            let mm = |x: f64| sig(x * 1e3, 3);
            let alone = s.amplitude_linear_m.map_or("—".to_string(), mm);
            let cut = s.reduction_db.map_or("—".to_string(), |c| format!("{} dB", sig(c, 3)));
            let leq = s.leq_db.map_or("—".to_string(), |l| format!("{} dB", sig(l, 4)));
            let x = mm(s.amplitude_m);
            // A point at f that is not a steady state says so first.
            let x = if s.verdict.is_marked() { format!("{x} ({})", s.verdict.label().to_uppercase()) } else { x };
            vec![
                format!(
                    "f {fs} Hz from rest: {x} mm (alone {alone} mm), cut {cut}, Leq {leq}, {} impacts/T{off}",
                    sig(s.impacts_per_period, 3)
                ),
                format!("f {fs} Hz from rest: {x} mm (alone {alone} mm), cut {cut}, Leq {leq}"),
                format!("f {fs} Hz from rest: {x} mm, alone {alone}, Leq {leq}"),
                format!("f {fs} Hz from rest: {x} mm, alone {alone}"),
                format!("f {fs} Hz from rest: {x} mm"),
                format!("{fs} Hz, rest: {x} mm"),
            ]
        }
        None => vec![format!("f {fs} Hz from rest: computing…{off}"), format!("f {fs} Hz: computing…")],
    };
    options.iter().find(|o| o.chars().count() <= width).unwrap_or(&options[options.len() - 1]).clone()
}

impl ResponseView<'_> {
    /// The marker: a vertical line at f over `yb`, or nothing off the band.
    fn marker(&self, yb: [f64; 2]) -> Vec<(f64, f64)> {
        if self.band.contains(self.freq_hz) {
            vec![(self.freq_hz, yb[0]), (self.freq_hz, yb[1])]
        } else {
            vec![]
        }
    }

    /// An arrow at the edge of `area` (first plot row) when f is off the band.
    fn arrow(&self, buf: &mut Buffer, area: Rect) {
        if self.band.contains(self.freq_hz) || area.width < 2 || area.height < 2 {
            return;
        }
        let th = &self.theme;
        let (x, a) = if self.freq_hz < self.band.from_hz {
            (area.x, th.sym("←", "<"))
        } else {
            (area.right() - 1, th.sym("→", ">"))
        };
        buf.set_stringn(x, area.y + 1, a, 1, Style::default().add_modifier(Modifier::BOLD | Modifier::REVERSED));
    }
}

impl Widget for ResponseView<'_> {
    // Over 80 lines: the view drawn top to bottom: axes, curves, the f marker, the legend.
    fn render(self, area: Rect, buf: &mut Buffer) {
        let inner = self.block.inner(area);
        (&self.block).render(area, buf);
        let th = self.theme;
        let r = match self.state {
            ResponseState::Ready(r) => r,
            ResponseState::NoForce => {
                let text = "No force: the design rings down freely (F0 = 0). Set F0 > 0 (the force field, \
                            ↑ from mass m) to see how much the damper cuts the resonance.";
                let text = th.text(text).into_owned();
                Paragraph::new(text).wrap(ratatui::widgets::Wrap { trim: true }).render(inner, buf);
                return;
            }
            ResponseState::Computing(done, total) => {
                let text = format!(
                    "computing the response: {done}/{total} frequencies, {}–{} Hz, each from rest and settled…",
                    sig(self.band.from_hz, 3),
                    sig(self.band.to_hz, 3)
                );
                let text = th.text(&text).into_owned();
                Paragraph::new(text).wrap(ratatui::widgets::Wrap { trim: true }).render(inner, buf);
                return;
            }
            ResponseState::Failed(e) => {
                let text = th.text(&format!("no response curve: {e}")).into_owned();
                Paragraph::new(text).style(th.error()).wrap(ratatui::widgets::Wrap { trim: true }).render(inner, buf);
                return;
            }
        };
        let pts = points(r);
        let with: Vec<(f64, f64)> =
            pts.iter().filter_map(|p| Some((p.freq_hz, db_mm(p.steady.amplitude_m)?))).collect();
        let without: Vec<(f64, f64)> =
            pts.iter().filter_map(|p| Some((p.freq_hz, db_mm(p.steady.amplitude_linear_m?)?))).collect();
        let leq: Vec<(f64, f64)> = pts.iter().filter_map(|p| Some((p.freq_hz, p.steady.leq_db?))).collect();
        // Points that are not a steady state (not settled, or cut short by a work cap) are
        // marked over the curve, with a legend entry of their own.
        let apart = |truncated: bool| -> Vec<(f64, f64)> {
            pts.iter()
                .filter(|p| p.steady.verdict.is_marked() && p.steady.verdict.is_truncated() == truncated)
                .filter_map(|p| Some((p.freq_hz, db_mm(p.steady.amplitude_m)?)))
                .collect()
        };
        let (unsettled, truncated) = (apart(false), apart(true));
        let xb = [self.band.from_hz, self.band.to_hz];
        let leq_h = if inner.height >= 16 { inner.height * 2 / 5 } else { 0 };
        let [top, bottom, info] =
            Layout::vertical([Constraint::Min(1), Constraint::Length(leq_h), Constraint::Length(1)]).areas(inner);
        let yb = fit_bounds(with.iter().chain(&without).map(|p| p.1), 0.05);
        let mark = self.marker(yb);
        let marker_style = Style::default().add_modifier(Modifier::BOLD | Modifier::REVERSED);
        let mut series = vec![
            Curve::line("none", &without, th.behind(th.ink(Role::Alone)), th.mark('○', 'o')),
            Curve::line("damper", &with, th.style(Role::Damper), th.mark('●', '#')),
            Curve::line("f", &mark, marker_style, th.mark('│', '|')),
        ];
        if !unsettled.is_empty() {
            series.push(Curve::points("not settled", &unsettled, th.style(Role::Error), th.mark('?', '?')));
        }
        if !truncated.is_empty() {
            series.push(Curve::points("truncated", &truncated, th.style(Role::Error), th.mark('!', '!')));
        }
        LinePlot {
            block: Block::default(),
            x_title: "f (Hz)",
            y_title: "x (dB re 1 mm)",
            series,
            empty: "no steady amplitude",
            theme: th,
            y_zero: false,
            x_bounds: Some(xb),
            y_bounds: Some(yb),
            legend: true,
        }
        .render(top, buf);
        self.arrow(buf, top);
        if leq_h > 0 {
            let lb = fit_bounds(leq.iter().map(|p| p.1), 0.05);
            let lmark = self.marker(lb);
            LinePlot {
                block: Block::default(),
                x_title: "f (Hz)",
                y_title: "Leq (dB)",
                series: vec![
                    Curve::line("Leq", &leq, th.style(Role::Live), th.mark('•', '*')),
                    Curve::line("", &lmark, marker_style, th.mark('│', '|')),
                ],
                empty: "no impact in any window: no Leq",
                theme: th,
                y_zero: false,
                x_bounds: Some(xb),
                y_bounds: Some(lb),
                legend: true,
            }
            .render(bottom, buf);
        }
        let line = th.text(&marker_line(self.at_f, &self.band, self.freq_hz, info.width as usize)).into_owned();
        let line = th.fit(&line, info.width.into()).into_owned();
        buf.set_stringn(info.x, info.y, &line, info.width as usize, Style::default());
    }
}
