//! The chart panel's view-model: its title and, by view, what the zones grid, the scatter,
//! the response curve and the bifurcation diagram draw of the app's state.

use ratatui::layout::Rect;
use ratatui::widgets::Block;
use ratatui::Frame;

use super::{CellView, Geometry, ScatterView, ZoneGridView};
use crate::design::{Chart, Zone, ZoneBy};
use crate::tui::app::{App, ChartView, Panel};
use crate::tui::bifurcation::{BifurcationState, BifurcationView};
use crate::tui::compute::{default_band, nearest, AGREEMENT_SURE};
use crate::tui::readout::design_verdict;
use crate::tui::response::{ResponseState, ResponseView};
use crate::tui::titles::{fit, panel_block, title_width};
use crate::units::sig;

/// The chart panel's title in its current view, `width` columns for it.
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
    match app.screen.chart_view {
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

/// The response view: the live design's curve over f, or why there is none yet.
fn response_panel(f: &mut Frame, app: &App, block: Block<'static>, area: Rect) {
    let band = default_band(&app.design);
    let state = if !app.design.damper.forced() {
        ResponseState::NoForce
    } else if let Some(r) = app.response() {
        ResponseState::Ready(r)
    } else if let Some(e) = app.curves.response.error.as_deref() {
        ResponseState::Failed(e)
    } else {
        ResponseState::Computing(app.curves.response.progress.0, app.curves.response.progress.1)
    };
    let at_f = app.acoustic().filter(|_| !app.design_busy()).and_then(|a| a.rest_at_f.as_ref());
    let view = ResponseView { block, state, band, freq_hz: app.design.damper.freq_hz, at_f, theme: app.theme };
    f.render_widget(view, area);
}

/// The bifurcation view: the live design's diagram over f, or why there is none yet.
fn bifurcation_panel(f: &mut Frame, app: &App, block: Block<'static>, area: Rect) {
    let state = if !app.design.damper.forced() {
        BifurcationState::NoForce
    } else if let Some((b, fine)) = app.bifurcation() {
        BifurcationState::Ready(b, fine)
    } else if let Some(e) = app.curves.bifurcation.error.as_deref() {
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
        branches: app.branches(),
        verdict: live.and_then(design_verdict),
        theme: app.theme,
    };
    f.render_widget(view, area);
}

/// The chart panel in its current view; returns where the zones grid's cells are (for clicks).
pub(crate) fn chart_panel(f: &mut Frame, app: &App, area: Rect) -> Option<Geometry> {
    let title = chart_title(app, title_width(app, Panel::Chart, area));
    let block = panel_block(app, Panel::Chart, &title);
    let inner = block.inner(area);
    let fine = &app.chart.fine;
    match app.screen.chart_view {
        ChartView::Response => {
            response_panel(f, app, block, area);
            None
        }
        ChartView::Bifurcation => {
            bifurcation_panel(f, app, block, area);
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
            super::layout(inner, &masses_g, &gaps_cm, &app.theme, super::pending(&cells), super::unsure(&cells))
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
