//! The bifurcation view of the chart panel (`v` with a force on): the
//! stroboscopic samples x(kT) of the forced design's orbit against the forcing frequency f, as
//! `thud bifurcation --vary f=FROM:TO:N` computes them ([`crate::dynamics::bifurcation`], each
//! value from the design's own start, the engine's default transient and sampled periods), over
//! the response view's band. A coarse pass is drawn first, then the fine one replaces it; the
//! current f is marked, with its own orbit's samples (computed for exactly f with the readout,
//! as `thud bifurcation --vary f=f:f:1`), and the line under the plot names that orbit's type.
//! After the fine pass, the periodic orbits' branches continued over the band (as `thud
//! bifurcation --branches 12` draws them) are drawn over the samples: stable ones as lines,
//! unstable ones dotted.

use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Modifier, Style};
use ratatui::widgets::{Block, Paragraph, Widget};

use super::plot::{fit_bounds, Curve, LinePlot};
use super::theme::{Palette, Role};
use crate::continuation::Branch;
use crate::dynamics::{Bifurcation, BifurcationPoint};
use crate::units::sig;

/// What the view shows: the diagram, or why there is none.
pub enum BifurcationState<'a> {
    /// The design has no force: no orbit to sample.
    NoForce,
    /// The first pass is being computed.
    Computing,
    /// The engine (or a work cap) refused it.
    Failed(&'a str),
    /// A pass: the fine one (`true`) or the coarse one while the fine computes.
    Ready(&'a Bifurcation, bool),
}

/// The view's data.
pub struct BifurcationView<'a> {
    pub block: Block<'a>,
    pub state: BifurcationState<'a>,
    /// The band's ends (Hz).
    pub band_hz: [f64; 2],
    /// The live design's forcing frequency (Hz), marked.
    pub freq_hz: f64,
    /// The orbit at exactly f (None while the readout computes it).
    pub at_f: Option<&'a BifurcationPoint>,
    /// The periodic orbits' branches over the band, drawn over the samples (None until
    /// computed, after the fine pass).
    pub branches: Option<&'a [Branch]>,
    /// The live design's verdict, as the readout names it.
    pub verdict: Option<crate::verdict::Verdict>,
    pub theme: Palette,
}

/// The (f in Hz, x(kT) in mm) samples of `points`.
pub fn samples_mm(points: &[BifurcationPoint]) -> Vec<(f64, f64)> {
    points.iter().flat_map(|p| p.run.samples.iter().map(move |s| (p.value, 1e3 * s.x_m))).collect()
}

/// The line under the plot: the orbit at f, named by the design's one verdict (`verdict`, as
/// the readout names it; the orbit's own where there is none).
pub fn orbit_line(at_f: Option<&BifurcationPoint>, verdict: Option<crate::verdict::Verdict>, f: f64) -> String {
    match at_f {
        Some(p) => format!(
            "f {} Hz: {}, |x| ≤ {} mm over {} periods",
            sig(f, 4),
            super::readout::verdict_words(&verdict.unwrap_or(p.run.orbit)),
            sig(1e3 * p.run.amplitude_m, 3),
            p.run.samples.len()
        ),
        None => format!("f {} Hz: computing its orbit…", sig(f, 4)),
    }
}

impl Widget for BifurcationView<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let th = self.theme;
        let inner = self.block.inner(area);
        (&self.block).render(area, buf);
        let message = |buf: &mut Buffer, text: &str| {
            Paragraph::new(th.text(text).into_owned()).style(th.label()).render(inner, buf);
        };
        let (b, fine) = match self.state {
            BifurcationState::NoForce => {
                return message(buf, "no force: set F0 > 0 to sample its orbits over f");
            }
            BifurcationState::Computing => return message(buf, "computing the coarse pass over f…"),
            BifurcationState::Failed(e) => return message(buf, &format!("no diagram: {e}")),
            BifurcationState::Ready(b, fine) => (b, fine),
        };
        let [plot, note] = Layout::vertical([Constraint::Min(1), Constraint::Length(1)]).areas(inner);
        let pts = samples_mm(&b.points);
        let here: Vec<(f64, f64)> = self.at_f.map_or_else(Vec::new, |p| samples_mm(std::slice::from_ref(p)));
        let (stable, unstable) = self.branches.map_or_else(Default::default, crate::export::continuation::strobe_lines);
        let yb = fit_bounds(pts.iter().chain(&here).chain(&stable).chain(&unstable).map(|p| p.1), 0.05);
        let f = self.freq_hz;
        let marker = [(f, yb[0]), (f, yb[1])];
        let bold = Style::default().add_modifier(Modifier::BOLD);
        let name = if fine { "x(kT)" } else { "x(kT), coarse" };
        let mut series = vec![
            Curve::line("f", &marker, th.behind(th.ink(Role::Grid)), th.mark('│', '|')),
            Curve::points(name, &pts, th.style(Role::Damper), th.marker()),
        ];
        // The continued branches over the samples (stable a line, unstable dotted), under the
        // orbit at f.
        if !stable.is_empty() {
            series.push(Curve::line("stable orbit", &stable, th.style(Role::Fit), th.marker()));
        }
        if !unstable.is_empty() {
            series.push(Curve::line("unstable orbit", &unstable, th.style(Role::Alone), th.mark('·', '.')));
        }
        series.push(Curve::points("at f", &here, bold.patch(th.style(Role::Live)), th.mark('●', 'o')));
        LinePlot {
            block: Block::default(),
            x_title: "f (Hz)",
            y_title: "x(kT) (mm)",
            series,
            empty: "no samples",
            theme: th,
            y_zero: true,
            x_bounds: Some(self.band_hz),
            y_bounds: Some(yb),
            legend: true,
        }
        .render(plot, buf);
        let text = orbit_line(self.at_f, self.verdict, f);
        buf.set_stringn(note.x, note.y, th.fit(&th.text(&text), note.width.into()), note.width.into(), th.label());
    }
}
