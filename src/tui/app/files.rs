//! The explorer's file actions: save the live design under a name (asking before one is
//! overwritten), list and load saved designs (small TOML files in the data directory, read
//! on the UI thread), and ask the worker for exports (written on their own threads).

use std::path::Path;

use super::state::{App, ChartView, Mode};
use crate::export::{wav::WavOptions, Artifact, ExportOptions};
use crate::store::{self, DesignFile};
use crate::tui::compute::{default_band, response_design};
use crate::tui::fields::{Knob, Scope, Setup};
use crate::tui::files::{export_menu, export_name, unique_path};
use crate::tui::worker::{ExportJob, Request, WorkError};
use crate::units::sig;

/// Saving, loading and exporting.
impl App {
    /// The name offered when saving: the preset's or saved design's name, or the first free
    /// `design-N`.
    pub fn suggested_name(&self) -> String {
        if self.preset != "default" && store::check_design_name(&self.preset).is_ok() {
            return self.preset.clone();
        }
        (1..).map(|n| format!("design-{n}")).find(|n| !self.is_saved(n)).unwrap_or_else(|| "design-1".into())
    }

    /// True if something (a saved design, or anything else) is at `name`'s path in the data
    /// directory. A dangling link counts: saving would replace it.
    fn is_saved(&self, name: &str) -> bool {
        let path = self.host.data_dir.as_deref().and_then(|d| store::design_path(d, name).ok());
        path.is_some_and(|p| p.symlink_metadata().is_ok())
    }

    /// Saves the live design as `name`, but first asks if that would replace a saved design.
    pub(crate) fn save_or_ask(&mut self, name: &str) {
        if self.is_saved(name) {
            self.mode = Mode::ConfirmOverwrite(name.to_string());
        } else {
            self.write_design(name, false);
        }
    }

    /// Saves the live design as `name` in the data directory (a small file, written
    /// atomically on this thread), replacing any design of that name; the outcome goes to the
    /// status line. The keys ask first ([`Mode::ConfirmOverwrite`]) before replacing one.
    pub fn save_as(&mut self, name: &str) {
        self.write_design(name, true);
    }

    /// Writes the live design as `name`; an existing file is replaced only if `overwrite`
    /// (without it, one that appeared since the question is reported, not replaced).
    fn write_design(&mut self, name: &str, overwrite: bool) {
        if let Err(e) = store::check_design_name(name) {
            self.error(format_args!("cannot save: {e}"));
            return;
        }
        let Some(dir) = self.host.data_dir.clone() else {
            self.error("cannot save: no home directory, so no data directory");
            return;
        };
        let p = &self.design.damper;
        let description = format!(
            "saved from the explorer: m {} g, d {} cm (from {})",
            sig(p.impact_mass_kg * 1e3, 4),
            sig(p.gap_m * 1e2, 3),
            self.preset
        );
        let ensemble = (self.runs > 1).then_some(self.runs);
        let file = DesignFile {
            description,
            ensemble,
            uncertainty: std::collections::BTreeMap::default(),
            design: self.design.clone(),
        };
        match store::save_design(&dir, name, &file, overwrite) {
            Ok(path) => {
                self.preset = name.to_string();
                self.mark_unmodified();
                self.set_status(&format!("saved {name} to {}", path.display()), false);
            }
            Err(e) => {
                self.error(format_args!("cannot save {name}: {e}"));
            }
        }
    }

    /// Opens the list of saved designs (read from the data directory now: a few small files).
    pub(crate) fn open_saved(&mut self) {
        let Some(dir) = self.host.data_dir.clone() else {
            self.error("cannot load: no home directory, so no data directory");
            return;
        };
        match store::list_designs(&dir) {
            Ok(list) => {
                let i = list.designs.iter().position(|d| d.name == self.preset).unwrap_or(0);
                self.host.saved = list;
                self.host.load_error = None;
                self.mode = Mode::Saved(i);
            }
            Err(e) => {
                self.error(format_args!("cannot list saved designs: {e}"));
            }
        }
    }

    /// Loads row `i` of the saved-designs list (the good designs, then the problem files).
    /// A failure keeps the list open on that row with the whole error under it.
    pub(crate) fn load_saved(&mut self, i: usize) -> Vec<Request> {
        if let Some(entry) = self.host.saved.designs.get(i) {
            let name = entry.name.clone();
            let Some(dir) = self.host.data_dir.clone() else { return vec![] };
            let loaded = store::load_design(&dir, &name).map_err(|e| e.to_string()).and_then(|f| {
                // N goes through the field's own check (its range and the work caps).
                let mut setup = Setup { design: f.design, runs: 1 };
                if let Some(n) = f.ensemble {
                    setup = Knob::RUNS.parsed(&setup, &n.to_string()).map_err(|e| format!("ensemble N {n}: {e}"))?;
                }
                crate::tui::fields::check_loaded(&setup).map(|()| setup).map_err(|e| e.to_string())
            });
            return match loaded {
                Ok(setup) => {
                    let reqs = self.apply_setup(setup, Scope::All, format!("loaded {name} (u undoes)"));
                    self.preset.clone_from(&name);
                    self.mark_unmodified();
                    reqs
                }
                Err(e) => self.load_failed(i, format!("cannot load {name}: {e}")),
            };
        }
        let problem = i.checked_sub(self.host.saved.designs.len()).and_then(|j| self.host.saved.problems.get(j));
        match problem.map(ToString::to_string) {
            Some(p) => self.load_failed(i, format!("cannot load {p}")),
            None => vec![],
        }
    }

    /// A load of row `i` failed with `why`: the list stays open on it and shows `why` whole.
    fn load_failed(&mut self, i: usize, why: String) -> Vec<Request> {
        self.mode = Mode::Saved(i);
        self.error(&why);
        self.host.load_error = Some(why);
        vec![]
    }

    /// Asks the worker to write an export of `kind` into the export directory, under its
    /// default name (with -1, -2 … added if that file exists or is being written).
    pub fn export(&mut self, kind: Artifact) -> Option<Request> {
        if kind == Artifact::Wav {
            let e =
                crate::limits::wav_samples(self.design.damper.duration_s, f64::from(WavOptions::default().sample_rate));
            if e.exceeded() {
                self.error(format_args!("cannot export {}: {}; shorten the duration", export_name(kind), e.describe()));
                return None;
            }
        }
        let path = unique_path(&self.host.export_dir, kind.default_file_name(), &self.host.exports);
        self.host.exports.push(path.clone());
        // Sweeps use the chart's grid and its N runs a cell, and a response the curve's band
        // and design (from rest, as the view runs it), so the file shows what the screen does
        // (the curve's band is the engine's default, so it is `thud export … response`'s too).
        let g = &self.chart.grids.fine;
        let (design, options) = if kind.needs_sweep() {
            let options = ExportOptions {
                masses_kg: Some(g.masses_kg.clone()),
                gaps_m: Some(g.gaps_m.clone()),
                ensemble_runs: self.runs,
                ..ExportOptions::default()
            };
            (self.design.clone(), options)
        } else if kind.is_response() {
            let freqs = default_band(&self.design).freqs();
            // The curve's design keeps f (a forced design is checked with it); each point sets its own.
            let mut design = response_design(&self.design);
            design.damper.freq_hz = self.design.damper.freq_hz;
            (design, ExportOptions { freqs_hz: Some(freqs), ..ExportOptions::default() })
        } else {
            (self.design.clone(), ExportOptions::default())
        };
        self.set_status(&format!("exporting {} to {} …", export_name(kind), self.shown_path(&path)), false);
        Some(Request::Export(Box::new(ExportJob { kind, design, options, path, ascii: self.theme.ascii })))
    }

    /// The export menu's rows: the frequency response's too while it is on screen.
    pub fn export_menu(&self) -> Vec<(Artifact, &'static str)> {
        export_menu(self.screen.chart_view == ChartView::Response && self.design.damper.forced())
    }

    /// An export ended: the file is no longer pending and the status line says how it went.
    pub(crate) fn export_finished(&mut self, kind: Artifact, path: &Path, result: Result<(), WorkError>) {
        self.host.exports.retain(|p| p != path);
        let shown = self.shown_path(path);
        match result {
            Ok(()) => self.set_status(&format!("exported {} to {shown}", export_name(kind)), false),
            Err(e) => {
                self.error(format_args!("export of {} failed: {e}", export_name(kind)));
            }
        }
    }

    /// The export directory as shown.
    pub(crate) fn export_dir_name(&self) -> String {
        if self.host.export_dir == Path::new(".") {
            "the current directory".into()
        } else {
            self.host.export_dir.display().to_string()
        }
    }

    /// An export path as shown: the file name alone in the current directory.
    fn shown_path(&self, path: &Path) -> String {
        if self.host.export_dir == Path::new(".") {
            path.file_name().map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned())
        } else {
            path.display().to_string()
        }
    }
}
