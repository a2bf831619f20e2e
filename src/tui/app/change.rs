//! Changing the live design: apply a new design (undoable) and ask for the work it needs;
//! undo; step or type the selected field; move on the chart. Every change returns the
//! [`Request`]s for the worker; what a key or click does is in `input.rs`.

use std::sync::Arc;

use super::state::{App, ChartState, ChartView, UndoEntry};
use crate::design::{self, Design};
use crate::tui::cache_key::{ChartKey, ResponseKey, SimKey, SoundKey};
use crate::tui::compute::{default_band, nearest};
use crate::tui::fields::{Knob, Scope, Setup};
use crate::tui::worker::{ChartWork, Request};
use crate::units::sig;

/// Changing the live design, and the work each change needs.
impl App {
    /// Goes back to the design (and ensemble size and name) before the last change.
    pub(crate) fn undo(&mut self) -> Vec<Request> {
        if let Some(entry) = self.edits.undo.pop() {
            let then = Setup { design: entry.design, runs: entry.runs };
            let what = changes(&self.setup(), &self.preset, &then, &entry.preset);
            self.design = then.design;
            self.runs = then.runs;
            self.preset = entry.preset;
            self.set_status(&format!("undo: {what}"), false);
            self.requests(Scope::All)
        } else {
            self.set_status("nothing to undo", false);
            vec![]
        }
    }

    /// Makes `new` the live design (pushing the old one for undo) and asks for what it needs.
    pub(crate) fn apply(&mut self, new: Design, scope: Scope, message: String) -> Vec<Request> {
        self.apply_setup(Setup { design: new, runs: self.runs }, scope, message)
    }

    /// Makes `new` the live design and ensemble size (pushing the old ones for undo) and asks
    /// for what they need.
    pub(crate) fn apply_setup(&mut self, new: Setup, scope: Scope, message: String) -> Vec<Request> {
        if new.design == self.design && new.runs == self.runs {
            self.set_status(&message, false);
            return vec![];
        }
        let old = std::mem::replace(&mut self.design, new.design);
        let old_runs = std::mem::replace(&mut self.runs, new.runs);
        self.edits.undo.push(UndoEntry { design: old, runs: old_runs, preset: self.preset.clone() });
        self.results.error = None;
        self.set_status(&message, false);
        self.requests(scope)
    }

    /// The work a change of `scope` needs (the worker's caches make repeats cheap).
    fn requests(&mut self, scope: Scope) -> Vec<Request> {
        let mut out = Vec::new();
        let sim_fresh = self.results.sim_for.as_ref() == Some(&SimKey::of(&self.design));
        match (scope, &self.results.sim) {
            (Scope::Thresholds, _) => {}
            (Scope::Acoustics, Some(sim)) if sim_fresh => {
                out.push(Request::Acoustic(self.design.clone(), sim.clone(), self.runs));
            }
            _ => out.push(Request::Sim(self.design.clone())),
        }
        let key = ChartKey::with_runs(&self.design, &self.chart.grids, self.runs);
        if key != self.chart.key {
            self.chart = ChartState::empty(&self.design, &self.chart.grids, self.runs);
            self.chart.error = None;
            out.push(Request::Chart(self.design.clone(), ChartWork::Zones(self.chart.grids.clone(), self.runs)));
        } else if self.chart.levels_for != SoundKey::of(&self.design) {
            out.push(self.relevel());
        }
        out.extend(self.response_request());
        out.extend(self.bifurcation_request());
        out
    }

    /// The bifurcation diagram's job, if its view is shown, the design is forced and its fine
    /// pass (which does not depend on f) is neither in nor already asked for.
    pub(crate) fn bifurcation_request(&mut self) -> Option<Request> {
        if self.screen.chart_view != ChartView::Bifurcation || !self.design.damper.forced() {
            return None;
        }
        let [_, fine] = self.bifurcation_keys();
        let have = self.curves.bifurcation.fine.as_ref().is_some_and(|(k, _)| *k == fine);
        if have || self.curves.bifurcation.asked.as_ref() == Some(&fine) {
            return None;
        }
        self.curves.bifurcation.asked = Some(fine);
        self.curves.bifurcation.error = None;
        Some(Request::Chart(self.design.clone(), ChartWork::Bifurcation))
    }

    /// The response curve's job, if the response view is shown, the design is forced and its
    /// curve (which does not depend on f) is neither in nor already asked for.
    pub(crate) fn response_request(&mut self) -> Option<Request> {
        if self.screen.chart_view != ChartView::Response || !self.design.damper.forced() {
            return None;
        }
        let band = default_band(&self.design);
        let key = ResponseKey::of(&self.design, &band);
        if self.curves.response.curve_for.as_ref() == Some(&key) || self.curves.response.asked.as_ref() == Some(&key) {
            return None;
        }
        self.curves.response.asked = Some(key);
        self.curves.response.error = None;
        self.curves.response.progress = (0, band.points);
        Some(Request::Chart(self.design.clone(), ChartWork::Response(band)))
    }

    /// Asks for the chart's levels at the current observer (acoustics only).
    pub(crate) fn relevel(&self) -> Request {
        Request::Relevel(self.design.clone(), Arc::new(self.chart.passes()))
    }

    /// Steps the selected parameter once (`up`: increase; `fine`: a small step).
    pub(crate) fn step(&mut self, up: bool, fine: bool) -> Vec<Request> {
        self.step_knob(self.param(), up, fine)
    }

    /// Steps field `f` once (`up`: increase; `fine`: a small step).
    pub(crate) fn step_knob(&mut self, f: Knob, up: bool, fine: bool) -> Vec<Request> {
        match f.stepped(&self.setup(), up, fine) {
            Ok(s) => {
                let message = self.change_message(f, &s, "");
                self.apply_setup(s, f.scope(), message)
            }
            Err(e) => self.error(e),
        }
    }

    /// Sets the selected parameter from typed text (a plain number in the unit the field
    /// shows); a bad value is refused with a message naming the field, and a value off the
    /// chart's range is accepted with a word saying so.
    pub fn submit_text(&mut self, text: &str) -> Vec<Request> {
        let f = self.param();
        match f.parsed(&self.setup(), text) {
            Ok(s) => {
                let off = self.off_chart(f, &s.design);
                let message = self.change_message(f, &s, &off);
                self.apply_setup(s, f.scope(), message)
            }
            Err(e) => self.error(e),
        }
    }

    /// The status line after field `f` changed to give `s`: "label value", with f when a force
    /// was switched on with it, and where f falls on the response curve's band.
    fn change_message(&self, f: Knob, s: &Setup, extra: &str) -> String {
        let mut m = format!("{} {}{extra}", f.label(), f.display(s));
        if let Some(why) = f.idle(&s.design) {
            m += &format!(" — {why}");
        }
        let (was, now) = (&self.design.damper, &s.design.damper);
        if f == Knob::FORCE && now.freq_hz != was.freq_hz {
            m += &format!("; {} {} (the natural frequency)", Knob::FREQ.label(), Knob::FREQ.display(s));
        }
        if f == Knob::FREQ && self.screen.chart_view == ChartView::Response {
            let band = default_band(&s.design);
            if !band.contains(now.freq_hz) {
                m += &format!(
                    " — off the response curve's band ({}–{} Hz): its marker is an arrow at the edge",
                    sig(band.from_hz, 3),
                    sig(band.to_hz, 3)
                );
            }
        }
        m
    }

    /// " — off the chart (…)" if field `f` of `d` (mass or gap) lies outside the chart's grid.
    fn off_chart(&self, f: Knob, d: &Design) -> String {
        let g = &self.chart.grids.fine;
        let (values, v, unit, k) = match f {
            Knob::MASS => (&g.masses_kg, d.damper.impact_mass_kg, "g", 1e3),
            Knob::GAP => (&g.gaps_m, d.damper.gap_m, "cm", 1e2),
            _ => return String::new(),
        };
        let (Some(lo), Some(hi)) = (values.first(), values.last()) else { return String::new() };
        let half = if values.len() > 1 { 0.5 * (hi - lo) / (values.len() - 1) as f64 } else { 0.0 };
        if v < lo - half || v > hi + half {
            format!(
                " — off the chart ({}–{} {unit}): the chart marks it with an arrow at its edge",
                sig(lo * k, 3),
                sig(hi * k, 3)
            )
        } else {
            String::new()
        }
    }

    /// Moves the design to the neighbouring chart cell along mass (`axis` 1) or gap (0).
    pub(crate) fn chart_move(&mut self, axis: usize, up: bool) -> Vec<Request> {
        let g = &self.chart.grids.fine;
        let (values, now) = if axis == 1 {
            (&g.masses_kg, self.design.damper.impact_mass_kg)
        } else {
            (&g.gaps_m, self.design.damper.gap_m)
        };
        let i = nearest(values, now);
        let j = if up { (i + 1).min(values.len() - 1) } else { i.saturating_sub(1) };
        let j = if values[i] != now && ((up && values[i] > now) || (!up && values[i] < now)) { i } else { j };
        let (m, d) = if axis == 1 {
            (values[j], self.design.damper.gap_m)
        } else {
            (self.design.damper.impact_mass_kg, values[j])
        };
        self.select_design(m, d)
    }

    /// Makes (mass, gap) the live design.
    pub fn select_design(&mut self, mass_kg: f64, gap_m: f64) -> Vec<Request> {
        let d = design::variant(&self.design, mass_kg, gap_m);
        let msg = format!(
            "m {} g, d {} cm",
            Knob::MASS.display(&d).trim_end_matches(" g"),
            Knob::GAP.display(&d).trim_end_matches(" cm")
        );
        self.apply(d, Scope::Design, msg)
    }
}

/// What differs between the live design (`now`, from preset `now_preset`) and `then`, as
/// "mass 45.50 g → 40.50 g" (at most three fields, then how many more).
pub fn changes(now: &Setup, now_preset: &str, then: &Setup, then_preset: &str) -> String {
    let mut parts = Vec::new();
    if now_preset != then_preset {
        parts.push(format!("preset {now_preset} → {then_preset}"));
    }
    let fields: Vec<String> = Knob::ALL
        .iter()
        .filter_map(|p| {
            let (a, b) = (p.display(now), p.display(then));
            (a != b).then(|| format!("{} {a} → {b}", p.param()))
        })
        .collect();
    let more = fields.len().saturating_sub(3);
    parts.extend(fields.into_iter().take(3));
    if more > 0 {
        parts.push(format!("and {more} more"));
    }
    if parts.is_empty() {
        "the design is as it was".into()
    } else {
        parts.join(", ")
    }
}
