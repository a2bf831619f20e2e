//! What the explorer shows: its panels and which impact the pulse panel is about. Shared by the
//! app's state and the guided tour's steps, which name panels and views (kept apart from
//! `app.rs` so that the tour does not import the app that runs it).

use ratatui::layout::Rect;

use super::chart::Geometry;
use super::polar::PolarHit;

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
    pub(crate) fn and(mut self, other: Drawn) -> Drawn {
        self.geometry = self.geometry.or(other.geometry);
        self.chart_shown |= other.chart_shown;
        self.fields.extend(other.fields);
        self.polar = self.polar.or(other.polar);
        self
    }
}

/// The panels; Tab cycles through them (not the readout, which a tour step may point at).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Panel {
    Params,
    Waveform,
    Polar,
    History,
    Chart,
    Readout,
}

impl Panel {
    pub const ALL: [Panel; 5] = [Panel::Params, Panel::Waveform, Panel::Polar, Panel::History, Panel::Chart];

    pub(crate) fn cycle(self, forward: bool) -> Panel {
        let i = Self::ALL.iter().position(|p| *p == self).unwrap_or(0);
        let n = Self::ALL.len();
        Self::ALL[if forward { (i + 1) % n } else { (i + n - 1) % n }]
    }
}

/// Which impact the pulse panel and the polar show.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PulseView {
    /// The loudest impact of the run (at U0max, against the main mass).
    #[default]
    Loudest,
    /// One impact at U0 = v0 on a fixed plate: what `thud pulse` computes (Fig 2, Table 1).
    Single,
}

impl PulseView {
    /// The view a preset opens on: the single-impact presets (the paper's Fig 2 and Table 1)
    /// show their one impact, every other preset the run's loudest.
    pub fn for_preset(name: &str) -> Self {
        match name {
            "paper-fig2" | "paper-table1" => PulseView::Single,
            _ => PulseView::Loudest,
        }
    }
}
