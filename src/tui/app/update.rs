//! The one transition function, [`App::update`]: a message in (a key, a click, a worker
//! result, a tick), the state changed, and the work to ask for out. A worker result is taken
//! if its key is the live design's and dropped as stale otherwise.

use std::fmt::Display;
use std::sync::Arc;

use crossterm::event::{Event, MouseButton, MouseEventKind};

use super::state::App;
use crate::design::Chart;
use crate::dynamics::Bifurcation;
use crate::response::Response;
use crate::tui::cache_key::{BifurcationKey, ReadoutKey, ResponseKey, SimKey, SoundKey};
use crate::tui::compute::{ChartPasses, Stage};
use crate::tui::worker::{ChartWork, Done, Request};

/// Everything the app reacts to.
#[derive(Debug)]
pub enum Msg {
    /// A terminal event (key, mouse, resize).
    Input(Event),
    /// A worker result.
    Work(Done),
    /// Spinner tick (only sent while work is in flight).
    Tick,
    /// The terminal hung up (see `tui::hangup`): the explorer ends.
    Hangup,
    /// A frame of the playing animation: this much real time (s) went by since the last one.
    Frame(f64),
    /// A bracketed paste without its end marker was dropped after its time ran out
    /// (`tui::input_parse`): `bytes` bytes after its start marker.
    PasteDropped { bytes: usize },
}

/// Messages, and the worker's results.
impl App {
    /// The work to start with: simulate the design and sweep the chart.
    pub fn initial_requests(&self) -> Vec<Request> {
        vec![
            Request::Sim(self.design.clone()),
            Request::Chart(self.design.clone(), ChartWork::Zones(self.chart.grids.clone(), self.runs)),
        ]
    }

    /// Handles one message; returns the work to ask the worker for.
    pub fn update(&mut self, msg: Msg) -> Vec<Request> {
        match msg {
            Msg::Input(Event::Key(k)) => self.key(k),
            Msg::Input(Event::Mouse(m)) if self.mouse => match m.kind {
                MouseEventKind::Down(MouseButton::Left) => self.click(m.column, m.row),
                MouseEventKind::Drag(MouseButton::Left) => self.drag(m.column, m.row),
                _ => vec![],
            },
            Msg::Input(_) => vec![],
            Msg::Work(done) => self.work(done),
            Msg::Tick => {
                self.screen.spinner = self.screen.spinner.wrapping_add(1);
                vec![]
            }
            Msg::Hangup => {
                self.quit = true;
                vec![]
            }
            Msg::Frame(real_s) => {
                self.anim_advance(real_s);
                vec![]
            }
            Msg::PasteDropped { bytes } => {
                let s = if bytes == 1 { "" } else { "s" };
                self.set_status(&format!("dropped a paste that never ended ({bytes} byte{s}); keys work again"), false);
                vec![]
            }
        }
    }

    /// Takes a worker result if it is for the current parameters; drops stale ones. A failed
    /// job (refused by the physics, or crashed) is an error in the status line.
    // Over 80 lines: one match arm per kind of worker result, each short.
    fn work(&mut self, done: Done) -> Vec<Request> {
        match done {
            Done::Sim { key, result } => {
                if key != SimKey::of(&self.design) {
                    return vec![];
                }
                match result {
                    Ok(sim) => {
                        if let Some(why) = sim.eval.run.truncated {
                            self.error(format_args!(
                                "run cut short: {} at t = {} s of {} s; the numbers cover only that time",
                                why.describe(),
                                crate::limits::short(sim.eval.run.final_time_s),
                                crate::limits::short(self.design.damper.duration_s)
                            ));
                        }
                        self.results.sim = Some(sim.clone());
                        self.results.sim_for = Some(key);
                        return vec![Request::Acoustic(self.design.clone(), sim, self.runs)];
                    }
                    Err(e) => self.fail(e),
                }
            }
            Done::Acoustic { key, result } => {
                if key != ReadoutKey::of(&self.design, self.runs) {
                    return vec![];
                }
                match result {
                    Ok(a) => {
                        self.results.acoustic = Some(a);
                        self.results.acoustic_for = Some(key);
                    }
                    Err(e) => self.fail(e),
                }
            }
            Done::ChartCell { key, sound, stage, index, cell, ensemble } if key == self.chart.key => {
                if let Some(slot) = self.stage_chart(stage).and_then(|c| c.cells.get_mut(index)) {
                    *slot = Some(cell);
                }
                if let (Stage::Fine, Some(e)) = (stage, ensemble) {
                    if let Some(slot) = self.chart.ensembles.get_mut(index) {
                        *slot = Some(e);
                    }
                }
                if sound != SoundKey::of(&self.design) {
                    self.chart.levels_for = sound;
                }
            }
            Done::Chart { key, sound, stage, result, ensembles } if key == self.chart.key => match result {
                Ok(chart) => {
                    if let Some(c) = self.stage_chart(stage) {
                        *c = (*chart).clone();
                    }
                    if let (Stage::Fine, Some(e)) = (stage, ensembles) {
                        self.chart.ensembles =
                            e.cells.iter().map(|c| c.as_ref().map(|c| Arc::new(c.ensemble.clone()))).collect();
                    }
                    if sound != SoundKey::of(&self.design) {
                        self.chart.levels_for = sound;
                        return vec![self.relevel()];
                    }
                }
                Err(e) => self.chart_failed(e),
            },
            Done::Relevel { key, sound, result } if key == self.chart.key && sound == SoundKey::of(&self.design) => {
                match result {
                    Ok(passes) => {
                        self.merge_levels(&passes);
                        self.chart.levels_for = sound;
                    }
                    Err(e) => self.chart_failed(e),
                }
            }
            Done::ChartCell { .. } | Done::Chart { .. } | Done::Relevel { .. } => {}
            Done::Response { key, result } => self.response_done(key, result),
            Done::ResponseProgress { key, done, total } => {
                if self.curves.response.asked.as_ref() == Some(&key) {
                    self.curves.response.progress = (done, total);
                }
            }
            Done::Bifurcation { key, stage, result } => self.bifurcation_pass(key, stage, result),
            Done::Branches { key, result } => {
                if key == self.bifurcation_keys()[1] {
                    match result {
                        Ok(b) => self.curves.bifurcation.branches = Some((key, b)),
                        Err(e) => {
                            self.error(format_args!("orbit branches: {e}"));
                        }
                    }
                }
            }
            Done::Export { kind, path, result } => self.export_finished(kind, &path, result),
        }
        if self.screen.pending_best && !self.chart_busy() {
            self.screen.pending_best = false;
            return self.best();
        }
        vec![]
    }

    /// Takes the response curve if it is the one last asked for.
    fn response_done(&mut self, key: ResponseKey, result: Result<Arc<Response>, crate::tui::worker::WorkError>) {
        if self.curves.response.asked.as_ref() != Some(&key) {
            return;
        }
        match result {
            Ok(r) => {
                self.curves.response.curve = Some(r);
                self.curves.response.curve_for = Some(key);
            }
            Err(e) => {
                self.curves.response.error = Some(e.to_string());
                self.error(format_args!("response curve: {e}"));
            }
        }
    }

    /// Takes a pass of the bifurcation diagram if it is the live design's; drops stale ones.
    fn bifurcation_pass(
        &mut self,
        key: BifurcationKey,
        stage: Stage,
        result: Result<Arc<Bifurcation>, crate::tui::worker::WorkError>,
    ) {
        let [coarse, fine] = self.bifurcation_keys();
        if key != if stage == Stage::Coarse { coarse } else { fine } {
            return;
        }
        match result {
            Ok(b) if stage == Stage::Coarse => self.curves.bifurcation.coarse = Some((key, b)),
            Ok(b) => self.curves.bifurcation.fine = Some((key, b)),
            Err(e) => {
                self.curves.bifurcation.error = Some(e.to_string());
                self.error(format_args!("bifurcation diagram: {e}"));
            }
        }
    }

    /// Takes the relevelled cells (cells that arrived since the request keep theirs).
    fn merge_levels(&mut self, p: &ChartPasses) {
        let merge = |into: &mut Chart, from: &Chart| {
            for (a, b) in into.cells.iter_mut().zip(&from.cells) {
                if b.is_some() {
                    *a = *b;
                }
            }
        };
        if let (Some(c), Some(from)) = (self.chart.coarse.as_mut(), p.coarse.as_ref()) {
            merge(c, from);
        }
        merge(&mut self.chart.fine, &p.fine);
    }

    /// The chart of a pass.
    fn stage_chart(&mut self, stage: Stage) -> Option<&mut Chart> {
        match stage {
            Stage::Coarse => self.chart.coarse.as_mut(),
            Stage::Fine => Some(&mut self.chart.fine),
        }
    }

    /// The live design's work failed: its readout shows the error until the design changes.
    fn fail(&mut self, e: impl Display) {
        self.results.error = Some(e.to_string());
        self.error(e);
    }

    /// The chart's work failed: the chart stops filling in and the error is shown.
    fn chart_failed(&mut self, e: impl Display) {
        self.chart.error = Some(e.to_string());
        self.error(e);
    }
}
