//! Layout: turns the app state into panels sized for the terminal. From 80×24 up every panel
//! is reachable (the plots share one slot in the compact layout; Tab picks it); smaller
//! terminals get fewer panels, down to a one-line message; nothing is drawn on 0×0. One
//! function per area: header, body panels, status line (with the input lines and the
//! overwrite question), footer, and the popups (help, the lists and their text).

use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Clear, Paragraph, Widget};
use ratatui::Frame;

use std::path::PathBuf;

use super::app::{App, ChartView, Mode, Panel};
use super::chart::{self, CellView, Geometry, ScatterView, ZoneGridView};
use super::compute::nearest;
use super::fields::Param;
use super::files::EXPORTS;
use super::history::HistoryView;
use super::keys::Action;
use super::keys::Keymap;
use super::params::ParamsView;
use super::polar::PolarView;
use super::readout::{ReadoutView, Row};
use super::waveform::WaveformView;
use crate::design::{Chart, Design, Metrics, Zone};
use crate::store;
use crate::units::sig;

/// Smallest terminal that gets more than the one-line message.
pub const MIN_W: u16 = 30;
pub const MIN_H: u16 = 8;

/// Draws the whole screen; returns where the chart cells are (for mouse clicks), if shown.
pub fn draw(f: &mut Frame, app: &App) -> Option<Geometry> {
    let area = f.area();
    if area.width == 0 || area.height == 0 {
        return None;
    }
    if area.width < MIN_W || area.height < MIN_H {
        let msg = format!("thud: terminal {}×{} too small; need {MIN_W}×{MIN_H}", area.width, area.height);
        f.render_widget(Paragraph::new(msg), Rect { height: 1, ..area });
        return None;
    }
    let footer_h = u16::from(area.height >= 12);
    let [header, body, status, footer] = Layout::vertical([
        Constraint::Length(1),
        Constraint::Min(1),
        Constraint::Length(1),
        Constraint::Length(footer_h),
    ])
    .areas(area);
    f.render_widget(header_line(app), header);
    let geometry = body_panels(f, app, body);
    f.render_widget(status_line(app), status);
    if footer_h > 0 {
        f.render_widget(footer_line(&app.keys, footer.width), footer);
    }
    if app.mode == Mode::Help {
        help_popup(f, &app.keys, area);
    } else if let Some(list) = list_view(app) {
        list_popup(f, &list, area);
    }
    geometry
}

/// Lays out the body by size class.
fn body_panels(f: &mut Frame, app: &App, body: Rect) -> Option<Geometry> {
    let pinned = app.pinned.is_some();
    let readout_h = 11 + u16::from(pinned);
    if body.width >= 110 && body.height >= 20 + readout_h {
        let [left, right] = Layout::horizontal([Constraint::Length(40), Constraint::Min(1)]).areas(body);
        let [params, readout] =
            Layout::vertical([Constraint::Length(Param::ALL.len() as u16 + 2), Constraint::Min(1)]).areas(left);
        f.render_widget(params_view(app), params);
        readout_widget(f, app, readout);
        let [top, bottom] = Layout::vertical([Constraint::Percentage(45), Constraint::Percentage(55)]).areas(right);
        let [wave, polar] = Layout::horizontal([Constraint::Percentage(55), Constraint::Percentage(45)]).areas(top);
        let [hist, chart] = Layout::horizontal([Constraint::Percentage(45), Constraint::Percentage(55)]).areas(bottom);
        plot(f, app, Panel::Waveform, wave);
        plot(f, app, Panel::Polar, polar);
        plot(f, app, Panel::History, hist);
        plot(f, app, Panel::Chart, chart)
    } else if body.width >= 60 && body.height >= 12 {
        let [left, right] = Layout::horizontal([Constraint::Length(30), Constraint::Min(1)]).areas(body);
        f.render_widget(params_view(app), left);
        let readout_h = readout_h.min(body.height.saturating_sub(8)).max(6);
        let [readout, slot] = Layout::vertical([Constraint::Length(readout_h), Constraint::Min(0)]).areas(right);
        readout_widget(f, app, readout);
        if slot.height >= 5 {
            return plot(f, app, app.plot, slot);
        }
        None
    } else {
        let [sel, readout] = Layout::vertical([Constraint::Length(1), Constraint::Min(0)]).areas(body);
        let fld = app.param();
        let line = format!("{}{} {}", app.theme.pointer(), fld.label(), fld.display(&app.design));
        f.render_widget(Paragraph::new(line).style(Style::default().add_modifier(Modifier::REVERSED)), sel);
        readout_widget(f, app, readout);
        None
    }
}

fn params_view(app: &App) -> impl Widget + '_ {
    struct Owned<'a> {
        rows: Vec<(String, String)>,
        app: &'a App,
    }
    impl Widget for Owned<'_> {
        fn render(self, area: Rect, buf: &mut ratatui::buffer::Buffer) {
            ParamsView {
                rows: &self.rows,
                selected: self.app.selected,
                focused: self.app.focus == Panel::Params,
                theme: self.app.theme,
            }
            .render(area, buf);
        }
    }
    let rows = Param::ALL.iter().map(|f| (f.label().to_string(), f.display(&app.design))).collect();
    Owned { rows, app }
}

/// Formats one readout value from a design's metrics.
type Format<'a> = &'a dyn Fn(&Metrics, &Design) -> String;

/// The readout rows of the live (and pinned) design.
pub fn readout_rows(app: &App) -> (Vec<Row>, Option<String>) {
    let live = app.metrics().filter(|_| !app.design_busy());
    let pinned = app.pinned.as_ref().and_then(|p| p.acoustic.as_ref().map(|a| (a.metrics, p.design.clone())));
    let cols = |f: Format| {
        let l = live.map_or_else(|| "…".to_string(), |m| f(m, &app.design));
        let p = pinned.as_ref().map(|(m, d)| f(m, d));
        (l, p)
    };
    let opt = |v: Option<f64>, digits: usize, unit: &str| {
        v.map_or("—".to_string(), |v| format!("{} {unit}", sig(v, digits)))
    };
    let spec: [(&'static str, Format); 8] = [
        ("U0max", &|m, _| format!("{} m/s", sig(m.u0_max_m_s, 4))),
        ("e", &|m, _| opt(m.inclination_cm_s, 3, "cm/s")),
        ("e_fit", &|m, _| opt(m.inclination_fit_cm_s, 3, "cm/s")),
        ("SPLmax", &|m, _| opt(m.spl_max_db, 4, "dB")),
        ("zone", &|m, d| {
            m.zone(&d.thresholds)
                .map_or("— (no e or no sound)".into(), |z: Zone| format!("{} {}", z.number(), z.describe()))
        }),
        ("impacts", &|m, _| m.n_impacts.to_string()),
        ("τ@U0max", &|m, _| opt(m.contact_duration_s.map(|t| t * 1e6), 4, "µs")),
        ("R mean", &|m, _| opt(m.restitution_mean, 3, "")),
    ];
    let rows = spec
        .iter()
        .map(|(label, f)| {
            let (live, pinned) = cols(*f);
            Row { label, live: live.trim_end().to_string(), pinned: pinned.map(|p| p.trim_end().to_string()) }
        })
        .collect();
    let note = if let Some(e) = &app.work_error {
        format!("error: {e}")
    } else if app.design_busy() {
        "computing…".to_string()
    } else {
        format!(
            "SPL: rms over τ at r {} m, θ {}°",
            sig(app.design.observer.r_m, 3),
            sig(app.design.observer.theta_rad.to_degrees(), 3)
        )
    };
    (rows, Some(note))
}

fn readout_widget(f: &mut Frame, app: &App, area: Rect) {
    let (rows, note) = readout_rows(app);
    f.render_widget(ReadoutView { rows: &rows, note: note.as_deref(), theme: app.theme, focused: false }, area);
}

/// Draws one plot panel; returns the chart geometry if it drew the zone grid.
fn plot(f: &mut Frame, app: &App, which: Panel, area: Rect) -> Option<Geometry> {
    let focused = app.focus == which;
    let theme = app.theme;
    let pinned = app.pinned.as_ref();
    match which {
        Panel::Waveform | Panel::Params => {
            let live = app.acoustic.as_ref().map_or(&[][..], |a| &a.waveform);
            let pin = pinned.and_then(|p| p.acoustic.as_ref()).map(|a| &a.waveform[..]);
            f.render_widget(WaveformView { live, pinned: pin, focused, theme }, area);
        }
        Panel::Polar => {
            let live = app.acoustic.as_ref().map_or(&[][..], |a| &a.polar);
            let pin = pinned.and_then(|p| p.acoustic.as_ref()).map(|a| &a.polar[..]);
            let d = &app.design;
            let view = PolarView {
                live,
                pinned: pin,
                theta_deg: d.observer.theta_rad.to_degrees(),
                range_deg: d.radiation.source.theta_range_deg(),
                r_m: d.observer.r_m,
                focused,
                theme,
            };
            f.render_widget(view, area);
        }
        Panel::History => {
            let (with, without) = app.sim.as_ref().map_or((&[][..], &[][..]), |s| (&s.history_cm[..], &s.free_cm[..]));
            let pin = pinned.and_then(|p| p.sim.as_ref()).map(|s| &s.history_cm[..]);
            f.render_widget(HistoryView { with_damper: with, without, pinned: pin, focused, theme }, area);
        }
        Panel::Chart => return chart_panel(f, app, area, focused),
    }
    None
}

fn chart_title(app: &App) -> String {
    let t = &app.design.thresholds;
    let (done, total) = app.chart.progress();
    let progress = if done < total { format!(" {done}/{total}") } else { String::new() };
    let view = match app.chart_view {
        ChartView::Zones => "zones m×d",
        ChartView::Scatter => "e vs SPLmax",
    };
    format!(" {view}  L* {} dB  e* {} cm/s{progress} ", t.spl_db, t.inclination_cm_s)
}

fn chart_panel(f: &mut Frame, app: &App, area: Rect, focused: bool) -> Option<Geometry> {
    let title = chart_title(app);
    let fine = &app.chart.fine;
    match app.chart_view {
        ChartView::Zones => {
            let cells = chart_cells(app);
            let masses_g: Vec<f64> = fine.masses_kg.iter().map(|m| m * 1e3).collect();
            let gaps_cm: Vec<f64> = fine.gaps_m.iter().map(|g| g * 1e2).collect();
            let view = ZoneGridView {
                masses_g: &masses_g,
                gaps_cm: &gaps_cm,
                cells: &cells,
                current: current_cell(app),
                title: &title,
                focused,
                theme: app.theme,
            };
            f.render_widget(view, area);
            Geometry::new(chart::block("", false, &app.theme).inner(area), masses_g.len(), gaps_cm.len())
        }
        ChartView::Scatter => {
            let pts = scatter_points(app);
            let current =
                app.metrics().filter(|_| !app.design_busy()).and_then(|m| Some((m.inclination_cm_s?, m.spl_max_db?)));
            let t = &app.design.thresholds;
            let view = ScatterView {
                points: &pts,
                current,
                l_star_db: t.spl_db,
                e_star_cm_s: t.inclination_cm_s,
                title: &title,
                focused,
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
        .map(|(i, c)| match c {
            Some(c) => CellView::Exact(app.zone(&c.metrics)),
            None => coarse_zone(app.chart.coarse.as_ref(), fine.masses_kg[i % nm], fine.gaps_m[i / nm], app),
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

/// The fine-grid cell of the live design, if it lies inside the grid.
fn current_cell(app: &App) -> Option<(usize, usize)> {
    let g = &app.chart.fine;
    let p = &app.design.damper;
    let inside = |v: &[f64], x: f64| {
        let half = if v.len() > 1 { 0.5 * (v[1] - v[0]) } else { f64::INFINITY };
        !v.is_empty() && x >= v[0] - half && x <= v[v.len() - 1] + half
    };
    (inside(&g.masses_kg, p.impact_mass_kg) && inside(&g.gaps_m, p.gap_m))
        .then(|| (nearest(&g.masses_kg, p.impact_mass_kg), nearest(&g.gaps_m, p.gap_m)))
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

fn header_line(app: &App) -> Paragraph<'static> {
    let bold = Style::default().add_modifier(Modifier::BOLD);
    let p = &app.design.damper;
    let mut spans = vec![
        Span::styled(" thud ", bold.add_modifier(Modifier::REVERSED)),
        Span::raw(format!(
            " preset {} │ m {} g, d {} cm ",
            app.preset,
            sig(p.impact_mass_kg * 1e3, 4),
            sig(p.gap_m * 1e2, 3)
        )),
    ];
    if app.busy() {
        let frames = app.theme.spinner();
        let frame = frames[app.spinner % frames.len()];
        let (done, total) = app.chart.progress();
        let text = if !app.exports.is_empty() && !app.design_busy() {
            format!("│ {frame} exporting {} ", app.exports.len())
        } else {
            let what = if app.design_busy() { "computing design" } else { "filling chart" };
            format!("│ {frame} {what} {done}/{total} ")
        };
        spans.push(Span::styled(text, bold));
    }
    if app.pinned.is_some() {
        spans.push(Span::styled("│ pinned ", app.theme.pinned()));
    }
    if app.focus != Panel::Params {
        spans.push(Span::raw(format!("│ focus: {:?} ", app.focus).to_lowercase()));
    }
    Paragraph::new(Line::from(spans))
}

fn status_line(app: &App) -> Paragraph<'static> {
    let cursor = if app.theme.ascii { "_" } else { "█" };
    if let Mode::SaveAs(buf) = &app.mode {
        let dir = app.data_dir.as_deref().map_or_else(|| "(no data directory)".into(), |d| d.display().to_string());
        return Paragraph::new(Line::from(vec![
            Span::styled(" save as: ", Style::default().add_modifier(Modifier::BOLD)),
            Span::raw(format!("{buf}{cursor}")),
            Span::styled(
                format!("  (letters, digits, - or _; Enter saves in {dir}, Esc cancels)"),
                Style::default().add_modifier(Modifier::DIM),
            ),
        ]));
    }
    if let Mode::ConfirmOverwrite(name) = &app.mode {
        return Paragraph::new(Line::from(vec![
            Span::styled(format!(" overwrite {name}? y/n"), Style::default().add_modifier(Modifier::BOLD)),
            Span::styled(
                "  (y replaces the saved design of that name; any other key keeps it)",
                Style::default().add_modifier(Modifier::DIM),
            ),
        ]));
    }
    if let Mode::Editing(buf) = &app.mode {
        let f = app.param();
        let unit = f.kind().map(|k| k.plain_unit()).unwrap_or("");
        let hint = if unit.is_empty() {
            String::new()
        } else {
            format!("  (plain number: {unit}; Enter accepts, Esc cancels)")
        };
        return Paragraph::new(Line::from(vec![
            Span::styled(format!(" {} = ", f.label()), Style::default().add_modifier(Modifier::BOLD)),
            Span::raw(format!("{buf}{cursor}")),
            Span::styled(hint, Style::default().add_modifier(Modifier::DIM)),
        ]));
    }
    match &app.status {
        Some(s) if s.error => Paragraph::new(Span::styled(format!(" {}", s.text), app.theme.error())),
        Some(s) => Paragraph::new(format!(" {}", s.text)),
        None => Paragraph::new(""),
    }
}

/// The footer: the key table's hints, as many whole ones as fit in `width`, in table order.
fn footer_line(keys: &Keymap, width: u16) -> Paragraph<'static> {
    let mut spans = Vec::new();
    let mut used = 0;
    for (k, h) in keys.footer_hints() {
        let (key, text) = (format!(" {k}"), format!(" {h} "));
        let w = key.chars().count() + text.chars().count();
        // The last item's trailing space may fall off the edge.
        if used + w - 1 > width as usize {
            continue;
        }
        used += w;
        spans.push(Span::styled(key, Style::default().add_modifier(Modifier::BOLD | Modifier::REVERSED)));
        spans.push(Span::raw(text));
    }
    Paragraph::new(Line::from(spans))
}

/// A rectangle of at most `w × h` centred in `area`.
fn centered(area: Rect, w: u16, h: u16) -> Rect {
    let (w, h) = (w.min(area.width), h.min(area.height));
    Rect::new(area.x + (area.width - w) / 2, area.y + (area.height - h) / 2, w, h)
}

/// The help overlay: every binding in effect (with its `[keys]` action name), in one to three
/// columns.
fn help_popup(f: &mut Frame, keys: &Keymap, area: Rect) {
    let keys = &keys.keys;
    let rows_avail = area.height.saturating_sub(5).max(1) as usize;
    let cols = keys.len().div_ceil(rows_avail).clamp(1, 3);
    let per_col = keys.len().div_ceil(cols);
    let col_w = (area.width.saturating_sub(2) as usize / cols).max(10);
    let lines: Vec<Line> = (0..per_col)
        .map(|r| {
            let spans: Vec<Span> = (0..cols)
                .filter_map(|c| keys.get(c * per_col + r))
                .flat_map(|b| {
                    let text = if cols == 1 {
                        format!("{:<10}{:<14}{}", b.label, b.name, b.help)
                    } else {
                        format!("{:<10}{}", b.label, b.help)
                    };
                    let text: String = text.chars().take(col_w.saturating_sub(1)).collect();
                    [Span::raw(format!("{text:<col_w$}"))]
                })
                .collect();
            Line::from(spans)
        })
        .collect();
    let h = per_col as u16 + 4;
    let w = if cols == 1 { 112 } else { area.width };
    let popup = centered(area, w, h);
    f.render_widget(Clear, popup);
    let block = Block::bordered().title(" keys (? or Esc closes) ");
    let inner = block.inner(popup);
    f.render_widget(block, popup);
    let mut all = lines;
    let dim = Style::default().add_modifier(Modifier::DIM);
    all.push(Line::from(Span::styled("Values are typed with units: 40.5g 3cm 0.7m 60deg 1.4m/s 2s 103dB", dim)));
    let note = if cols == 1 {
        "The second column is the action's name for [keys] in config.toml, e.g. save = \"ctrl-s\""
    } else {
        "Rebind in config.toml [keys], e.g. save = \"ctrl-s\" (names: ? on a wider screen)"
    };
    all.push(Line::from(Span::styled(note, dim)));
    f.render_widget(Paragraph::new(all), inner);
}

/// A list popup (presets, saved designs, exports): the rows around the highlighted one, then
/// the highlighted row's detail. Rows that cannot be chosen are drawn in the error style.
fn list_popup(f: &mut Frame, list: &ListView, area: Rect) {
    let n = list.items.len();
    let popup = centered(area, 76, (n.max(1) as u16).saturating_add(7));
    f.render_widget(Clear, popup);
    let block = Block::bordered().title(list.title.clone());
    let inner = block.inner(popup);
    f.render_widget(block, popup);
    if n == 0 {
        f.render_widget(Paragraph::new(list.empty.clone()).wrap(ratatui::widgets::Wrap { trim: true }), inner);
        return;
    }
    let sel = list.selected.min(n - 1);
    let detail_h = 3.min(inner.height.saturating_sub(1));
    let rows_h = (inner.height - detail_h).max(1) as usize;
    let first = (sel + 1).saturating_sub(rows_h);
    let mut lines: Vec<Line> = list
        .items
        .iter()
        .enumerate()
        .skip(first)
        .take(rows_h)
        .map(|(i, item)| {
            let mut style = if item.problem { Style::default().add_modifier(Modifier::DIM) } else { Style::default() };
            if i == sel {
                style = style.add_modifier(Modifier::REVERSED);
            }
            Line::from(Span::styled(format!("{} {}", if i == sel { ">" } else { " " }, item.label), style))
        })
        .collect();
    lines.push(Line::from(""));
    lines.push(Line::from(list.items[sel].detail.clone()));
    f.render_widget(Paragraph::new(lines).wrap(ratatui::widgets::Wrap { trim: false }), inner);
}

/// One row of a list popup (presets, saved designs, exports).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ListItem {
    pub label: String,
    /// Shown under the list for the highlighted row.
    pub detail: String,
    /// A row that cannot be chosen (e.g. a corrupt saved file).
    pub problem: bool,
}

/// A list popup to draw: title, rows, highlighted row, and a line for an empty list.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ListView {
    pub title: String,
    pub items: Vec<ListItem>,
    pub selected: usize,
    pub empty: String,
}

/// The list popup of the app's mode, if it shows one.
pub fn list_view(app: &App) -> Option<ListView> {
    let (title, items, selected, empty) = match &app.mode {
        Mode::Presets(i) => (
            " presets (↑↓, Enter applies, Esc closes) ".to_string(),
            app.preset_list
                .iter()
                .map(|p| ListItem { label: p.name.to_string(), detail: p.description.clone(), problem: false })
                .collect(),
            *i,
            String::new(),
        ),
        Mode::Saved(i) => {
            let good = app.saved.designs.iter().map(|d| ListItem {
                label: d.name.clone(),
                detail: d.description.clone(),
                problem: false,
            });
            let bad = app.saved.problems.iter().map(|p| ListItem {
                label: format!(
                    "✗ {} (cannot be loaded)",
                    p.path.file_name().map_or_else(|| p.path.display().to_string(), |n| n.to_string_lossy().into())
                ),
                detail: p.to_string(),
                problem: true,
            });
            let dir = app.data_dir.as_deref().map_or_else(PathBuf::new, store::designs_dir);
            (
                " saved designs (↑↓, Enter loads, Esc closes) ".to_string(),
                good.chain(bad).collect(),
                *i,
                format!("No saved designs in {}; press {} to save one.", dir.display(), app.key_label(Action::Save)),
            )
        }
        Mode::Export(i) => (
            " export (↑↓, Enter writes the file, Esc closes) ".to_string(),
            EXPORTS
                .iter()
                .map(|(k, label)| ListItem {
                    label: label.to_string(),
                    detail: format!("{} in {}", k.default_file_name(), app.export_dir_name()),
                    problem: false,
                })
                .collect(),
            *i,
            String::new(),
        ),
        _ => return None,
    };
    Some(ListView { title, items, selected, empty })
}
