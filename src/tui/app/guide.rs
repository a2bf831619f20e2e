//! The guided tour (start, step, leave) and the jump to the chart's best zone-3 design, which
//! a tour step may ask for.

use std::sync::Arc;

use super::state::{best_zone3, App, Mode, TourState};
use crate::design;
use crate::tui::fields::{Scope, Setup};
use crate::tui::tour::{Tour, TourSource};
use crate::tui::view::Panel;
use crate::tui::worker::Request;
use crate::units::sig;

/// The tour and the best design.
impl App {
    /// Starts the guided tour (`tour_def`, else the built-in one) at its first step; returns
    /// the work that step needs. A tour that cannot be loaded is an error in the status line.
    pub fn start_tour(&mut self) -> Vec<Request> {
        let tour = match &self.host.tour_def {
            Some(t) => t.clone(),
            None => match Tour::load(&TourSource::BuiltIn) {
                Ok(t) => {
                    let t = Arc::new(t);
                    self.host.tour_def = Some(t.clone());
                    t
                }
                Err(e) => return self.error(e),
            },
        };
        self.tour = Some(TourState { tour, step: 0 });
        self.screen.tour_over = false;
        self.tour_step(0)
    }

    /// Shows step `i` of the running tour: its design (undoable), pulse view and panel.
    pub(crate) fn tour_step(&mut self, i: usize) -> Vec<Request> {
        let Some(state) = self.tour.as_mut() else { return vec![] };
        let Some(step) = state.tour.steps.get(i).cloned() else { return vec![] };
        state.step = i;
        let n = state.tour.steps.len();
        let mut d = step.design.clone();
        if !step.sets_thresholds {
            d.thresholds = self.host.settings.config.thresholds(d.thresholds);
        }
        self.screen.pulse = step.pulse;
        self.anim = step.animate.then(|| crate::tui::anim::Anim::at_speed(step.speed));
        self.table1 = step.table1.then(crate::tui::table1::Table1::compute);
        if let Some(i) = crate::tui::fields::Knob::ALL.iter().position(|k| *k == step.select) {
            self.selected = i;
        }
        self.focus = if Panel::ALL.contains(&step.panel) { step.panel } else { Panel::Params };
        // The step's panel fills the screen, so its plot is shown whole at any size (z: all).
        self.screen.zoom = true;
        self.mode = Mode::Normal;
        let mut reqs = self.apply_setup(Setup { design: d, runs: step.runs }, Scope::All, String::new());
        self.preset.clone_from(&step.preset);
        self.mark_unmodified();
        self.set_status(&format!("tour {}/{n}: {} — → next, ← back, Esc explores from here", i + 1, step.title), false);
        self.screen.pending_best = step.best;
        if step.best && !self.chart_busy() {
            reqs.extend(self.best());
        }
        reqs
    }

    /// Leaves the tour, keeping the design on screen to explore.
    pub(crate) fn leave_tour(&mut self, finished: bool) {
        self.tour = None;
        self.screen.tour_over = finished;
        self.screen.zoom = false;
        // Finishing lets the last step's jump to the best design happen; Esc keeps the state.
        if !finished {
            self.screen.pending_best = false;
        }
        let text = if finished {
            "tour finished — explore from here (T starts it again)"
        } else {
            "left the tour — explore from here (T starts it again)"
        };
        self.set_status(text, false);
    }

    /// Jumps to the zone-3 design of the chart with the largest margin (see [`best_zone3`]),
    /// saying why in the status line; "none in zone 3" if there is none.
    pub fn best(&mut self) -> Vec<Request> {
        let fine = &self.chart.fine;
        let chart = if fine.done() > 0 { Some(fine) } else { self.chart.coarse.as_ref() };
        let (done, total) = self.chart.progress();
        let filling = if done < total { format!(" (chart still filling: {done}/{total})") } else { String::new() };
        let Some(b) = chart.and_then(|c| best_zone3(c, &self.design.thresholds)) else {
            self.set_status(
                &format!("none in zone 3 on this chart{filling}: no design is both quiet and strong"),
                false,
            );
            return vec![];
        };
        let reqs = self.select_design(b.mass_kg, b.gap_m);
        let by = match self.design.thresholds.zone_by {
            design::ZoneBy::Paper => "e",
            design::ZoneBy::Fit => "e_fit",
        };
        let strong = if b.strong.is_finite() {
            format!("{by} {:.0} % over e*", 100.0 * b.strong)
        } else {
            format!("{by} > e* = 0")
        };
        self.set_status(
            &format!(
                "best zone 3: m {} g, d {} cm; margin {:.0} % = min(sound pressure {:.0} % under L* ({} dB), {strong}), best of {} zone-3 cells{filling}",
                sig(b.mass_kg * 1e3, 3),
                sig(b.gap_m * 1e2, 3),
                100.0 * b.margin,
                100.0 * b.quiet,
                sig(b.db_under, 2),
                b.count
            ),
            false,
        );
        reqs
    }
}
