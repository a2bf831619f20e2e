//! What the screen shows beside the design: the pin, the chart panel's picture (zones,
//! scatter, response curve), the pulse panel's impact, the selected field's hint.

use super::state::{App, ChartView, Pinned};
use crate::tui::compute::default_band;
use crate::tui::explain;
use crate::tui::fields::Knob;
use crate::tui::keys::Action;
use crate::tui::view::PulseView;
use crate::tui::worker::Request;
use crate::units::sig;

/// The views and the hint.
impl App {
    /// Pins the live design with its results (drawn dim beside it), or unpins it.
    pub(crate) fn toggle_pin(&mut self) {
        if self.pinned.take().is_some() {
            self.set_status("unpinned", false);
        } else {
            self.pinned = Some(Pinned {
                design: self.design.clone(),
                sim: self.results.sim.clone(),
                acoustic: self.results.acoustic.clone(),
            });
            self.set_status("pinned this design: it stays on the plots (dim) while you change the live one", false);
        }
    }

    /// Cycles the chart panel: the zones, the scatter, and with a force on the bifurcation
    /// diagram over f (from the response: zones); returns the work the diagram needs.
    pub(crate) fn toggle_chart_view(&mut self) -> Vec<Request> {
        self.screen.chart_view = match self.screen.chart_view {
            ChartView::Zones => ChartView::Scatter,
            ChartView::Scatter if self.design.damper.forced() => ChartView::Bifurcation,
            ChartView::Scatter | ChartView::Response | ChartView::Bifurcation => ChartView::Zones,
        };
        self.say_chart_view();
        self.bifurcation_request().into_iter().collect()
    }

    /// Switches the chart panel to the response curve and back to the zones; returns the work
    /// the curve needs (none if it is cached, or without a force).
    pub(crate) fn toggle_response(&mut self) -> Vec<Request> {
        self.screen.chart_view = match self.screen.chart_view {
            ChartView::Response => ChartView::Zones,
            ChartView::Zones | ChartView::Scatter | ChartView::Bifurcation => ChartView::Response,
        };
        self.say_chart_view();
        self.response_request().into_iter().collect()
    }

    /// Says which picture the chart panel shows (and how to bring it on screen).
    fn say_chart_view(&mut self) {
        let view = match self.screen.chart_view {
            ChartView::Zones => "zones over mass × gap".to_string(),
            ChartView::Scatter => "e vs SPLmax (Fig 17)".to_string(),
            ChartView::Response if self.design.damper.forced() => {
                let b = default_band(&self.design);
                format!(
                    "response over {}–{} Hz (0.6–1.6 × the natural frequency), f marked",
                    sig(b.from_hz, 3),
                    sig(b.to_hz, 3)
                )
            }
            ChartView::Response => {
                format!("frequency response: no force; set {} > 0 (↑ from mass m) to draw it", Knob::FORCE.label())
            }
            ChartView::Bifurcation => {
                let b = default_band(&self.design);
                format!(
                    "bifurcation diagram: x(kT) over f {}–{} Hz, coarse first, f marked",
                    sig(b.from_hz, 3),
                    sig(b.to_hz, 3)
                )
            }
        };
        let text = if self.drawn.chart_shown {
            format!("chart view: {view}")
        } else {
            format!("chart view: {view}; not on screen: press {} to show the chart", self.key_label(Action::FocusNext))
        };
        self.set_status(&text, false);
    }

    /// Switches the pulse panel between the run's loudest impact and one impact on a plate.
    pub(crate) fn toggle_pulse(&mut self) {
        self.screen.pulse = match self.screen.pulse {
            PulseView::Loudest => PulseView::Single,
            PulseView::Single => PulseView::Loudest,
        };
        let text = match self.screen.pulse {
            PulseView::Loudest => "pulse: the loudest impact of the run (at U0max, against the main mass)".to_string(),
            PulseView::Single => format!(
                "pulse: one impact at U0 = v0 = {} m/s on a fixed plate (as thud pulse; the paper's Fig 2)",
                sig(self.design.damper.v0_m_s, 3)
            ),
        };
        self.set_status(&text, false);
    }

    /// The status line's hint for the selected field (what it is, unit, range).
    pub(crate) fn show_hint(&mut self) {
        let h = explain::field_hint(self.param(), &self.design);
        self.set_status(&h, false);
    }
}

/// The Table 1 view.
impl App {
    /// `M`: shows Table 1 (the paper's measurements beside both models, the engine's
    /// [`crate::paper::table1`]), or leaves it.
    pub(crate) fn toggle_table1(&mut self) {
        if self.table1.take().is_some() {
            self.set_status("Table 1 closed", false);
            return;
        }
        self.anim = None;
        self.screen.front = None;
        self.table1 = Some(crate::tui::table1::Table1::compute());
        let key = self.key_label(Action::Table1).to_string();
        self.set_status(
            &format!("Table 1: the measurements beside both models, as thud paper table1 prints them ({key} closes)"),
            false,
        );
    }
}

/// The animation view.
impl App {
    /// The end of the runs the animation plays (s): the live design's, and a pinned design's
    /// if longer; None until the live run is computed.
    fn anim_end_s(&self) -> Option<f64> {
        let pinned = self.pinned.as_ref().and_then(|p| p.sim.as_ref()).map_or(0.0, |s| s.eval.run.final_time_s);
        self.results.sim.as_ref().map(|s| s.eval.run.final_time_s.max(pinned))
    }

    /// `a`: shows the animation (from the start, at its default speed, playing), or leaves it.
    pub(crate) fn toggle_anim(&mut self) {
        if self.anim.take().is_some() {
            self.set_status("animation closed", false);
            return;
        }
        self.table1 = None;
        self.screen.front = None;
        self.anim = Some(crate::tui::anim::Anim::default());
        self.set_status(
            "animation: Space plays/pauses, . , one frame, [ ] slower/faster, Home restarts, a closes",
            false,
        );
    }

    /// The animation's own keys.
    pub(crate) fn anim_key(&mut self, a: Action) {
        let end = self.anim_end_s().unwrap_or(0.0);
        let Some(anim) = self.anim.as_mut() else { return };
        match a {
            Action::AnimPlay => {
                if !anim.playing && anim.t_s >= end {
                    anim.t_s = 0.0;
                }
                anim.playing = !anim.playing;
            }
            Action::AnimStep { back } => anim.step(back, end),
            Action::AnimSpeed { faster } => {
                let n = crate::tui::anim::SPEEDS.len();
                anim.speed = if faster { (anim.speed + 1).min(n - 1) } else { anim.speed.saturating_sub(1) };
            }
            Action::AnimRestart => anim.t_s = 0.0,
            _ => {}
        }
        self.anim_name_flash(None);
    }

    /// True while the animation plays (the event loop then draws 30 frames a second).
    pub fn anim_playing(&self) -> bool {
        self.anim.as_ref().is_some_and(|a| a.playing) && self.anim_end_s().is_some()
    }

    /// A frame: `real_s` of real time on.
    pub(crate) fn anim_advance(&mut self, real_s: f64) {
        let Some(end) = self.anim_end_s() else { return };
        if let Some(a) = self.anim.as_mut().filter(|a| a.playing) {
            a.advance(real_s, end);
        }
        self.anim_name_flash(Some(real_s));
    }

    /// The impact the flash line names ([`crate::tui::anim::Anim::name_flash`]); its level is
    /// the worker's, computed with the readout (no field is computed here).
    fn anim_name_flash(&mut self, played_s: Option<f64>) {
        let Some(sim) = self.results.sim.as_ref() else { return };
        if let Some(anim) = self.anim.as_mut() {
            anim.name_flash(&sim.eval.run.impacts, played_s);
        }
    }
}

/// The front view.
impl App {
    /// True while the front view shows (a front is loaded and `D` opened it).
    pub fn front_shown(&self) -> bool {
        self.screen.front.is_some() && self.host.front.is_some()
    }

    /// `D`: shows the front of `--front FILE` (the live design selected if it is one of its
    /// designs, else the first), or leaves it; without a front, says how to give one.
    pub(crate) fn toggle_front(&mut self) {
        if self.screen.front.take().is_some() {
            self.set_status("front view closed", false);
            return;
        }
        let Some(front) = self.host.front.clone() else {
            self.set_status(
                "no design front: start the explorer with thud tui --front FILE (the report thud design --json writes)",
                false,
            );
            return;
        };
        self.anim = None;
        self.table1 = None;
        self.screen.front = Some(front.position(&self.design).unwrap_or(0));
        self.front_hint();
    }

    /// The status line of the front view: its keys.
    pub(crate) fn front_hint(&mut self) {
        let Some(front) = self.host.front.clone() else { return };
        let (up, down, load, close) = (
            self.key_label(Action::Up).to_string(),
            self.key_label(Action::Down).to_string(),
            self.key_label(Action::Edit).to_string(),
            self.key_label(Action::FrontView).to_string(),
        );
        self.set_status(
            &format!(
                "front of {} ({} designs): {up}{down} walk along it, {load} loads the selected design, {close} closes",
                front.file,
                front.points.len()
            ),
            false,
        );
    }

    /// ↑↓ in the front view: the previous or next design along the front (in the order of the
    /// first objective), stopping at the ends.
    pub(crate) fn front_walk(&mut self, next: bool) {
        let n = self.host.front.as_ref().map_or(0, |f| f.points.len());
        if let Some(k) = self.screen.front.as_mut() {
            *k = if next { (*k + 1).min(n.saturating_sub(1)) } else { k.saturating_sub(1) };
        }
    }

    /// Enter in the front view: the selected design becomes the live one (one run, the user's
    /// thresholds; undoable); its readout then gives the front's objectives.
    pub(crate) fn front_load(&mut self) -> Vec<Request> {
        let (Some(front), Some(k)) = (self.host.front.clone(), self.screen.front) else { return vec![] };
        let Some(p) = front.points.get(k) else { return vec![] };
        let mut design = p.design.clone();
        design.thresholds = self.host.settings.config.thresholds(design.thresholds);
        let setup = crate::tui::fields::Setup { design, runs: 1 };
        if let Err(e) = crate::tui::fields::check_loaded(&setup) {
            return self.error(format!("front design {}: {e}", k + 1));
        }
        let name = format!("front-{}", k + 1);
        let reqs = self.apply_setup(
            setup,
            crate::tui::fields::Scope::All,
            format!("front design {} of {} loaded (u undoes)", k + 1, front.points.len()),
        );
        self.preset = name;
        self.mark_unmodified();
        reqs
    }
}
