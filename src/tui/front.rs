//! The front view: the Pareto front of a `thud design --json` report (`thud tui --front FILE`),
//! objective against objective with the selected design highlighted; ↑↓ walk along it and
//! Enter makes the selected design the live one.
//!
//! Each front design is rebuilt from the report's starting design and its variables by the
//! search's own function ([`Problem::design_at`]), so the design the explorer runs is the one
//! the search ran: its readout gives exactly the report's objectives, which the view shows
//! beside the report's, every digit.

use std::path::Path;

use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Modifier, Style};
use ratatui::widgets::{Block, Paragraph, Widget};
use serde::Deserialize;

use super::plot::{fit_bounds, Curve, LinePlot};
use super::theme::{Palette, Role};
use crate::design::search::{Column, Problem, Sense, Value, Variable};
use crate::design::Design;
use crate::error::ThudError;
use crate::params::{DesignDraft, Param, Spelling};
use crate::study;

/// Largest report read (bytes): a front of thousands of designs is far below it.
pub const FRONT_MAX_BYTES: u64 = 64 << 20;

/// Why a front file cannot be shown. The message is one line naming the file.
#[derive(Debug, thiserror::Error)]
#[error("--front {file}: {why}")]
pub struct FrontError {
    pub file: String,
    pub why: String,
}

/// One design of the front.
#[derive(Debug, Clone)]
pub struct FrontPoint {
    /// Its place in the search's order of evaluation (the report's `index`).
    pub index: usize,
    /// One value per variable, as the report gives it.
    pub values: Vec<Value>,
    /// One value per objective, as the report gives it.
    pub objectives: Vec<Option<f64>>,
    /// The design the search ran for it.
    pub design: Design,
}

/// A front read from a report.
#[derive(Debug, Clone)]
pub struct Front {
    /// The file as shown.
    pub file: String,
    /// The objectives' columns and senses, in the report's order.
    pub objectives: Vec<(Column, Sense)>,
    /// The variables' columns (`mass_kg`, `sphere`).
    pub variables: Vec<String>,
    /// The search's starting design.
    pub base: Design,
    pub points: Vec<FrontPoint>,
    /// The search was stopped: the front found so far.
    pub partial: bool,
}

#[derive(Deserialize)]
struct ReportJson {
    design: Design,
    variables: Vec<VariableJson>,
    objectives: Vec<ObjectiveJson>,
    #[serde(default)]
    band_hz: Vec<f64>,
    #[serde(default)]
    ensemble: Option<crate::design::search::Robust>,
    #[serde(default)]
    partial: bool,
    front: Vec<RowJson>,
}

#[derive(Deserialize)]
struct VariableJson {
    name: String,
    column: String,
    from: Option<f64>,
    to: Option<f64>,
    options: Option<Vec<String>>,
}

#[derive(Deserialize)]
struct ObjectiveJson {
    column: String,
    sense: Sense,
}

#[derive(Deserialize)]
struct RowJson {
    index: usize,
    variables: serde_json::Map<String, serde_json::Value>,
    objectives: serde_json::Map<String, serde_json::Value>,
}

impl Front {
    /// Reads the report `thud design --json` wrote to `path` (a regular file, at most
    /// [`FRONT_MAX_BYTES`]).
    pub fn load(path: &Path) -> Result<Front, FrontError> {
        let file = crate::fsio::shown(path);
        let text = crate::fsio::read_to_string(path, FRONT_MAX_BYTES)
            .map_err(|e| FrontError { file: file.clone(), why: e.reason() })?;
        Front::parse(&text, &file)
    }

    /// The front of a report's text; `file` names it in errors.
    pub fn parse(text: &str, file: &str) -> Result<Front, FrontError> {
        let bad = |why: String| FrontError { file: file.to_string(), why };
        let r: ReportJson = serde_json::from_str(text).map_err(|e| {
            bad(format!("not a report of thud design --json ({e}); write one with thud design … --json --out FILE"))
        })?;
        if !r.band_hz.is_empty() {
            return Err(bad("its objectives are the worst over a band of frequencies (--over); the explorer runs \
                 one frequency, so its readout could not show them"
                .into()));
        }
        if r.ensemble.is_some_and(|e| e.runs > 1) {
            return Err(bad("its objectives are quantiles over ball starts (--ensemble); the explorer's readout \
                 shows one run's, so it could not show them"
                .into()));
        }
        let variables =
            r.variables.iter().map(|v| variable(v).map_err(|e| bad(e.to_string()))).collect::<Result<Vec<_>, _>>()?;
        let objectives = r
            .objectives
            .iter()
            .map(|o| {
                Column::named(&o.column)
                    .map(|c| (c, o.sense))
                    .ok_or_else(|| bad(format!("'{}' is not a result column", o.column)))
            })
            .collect::<Result<Vec<_>, _>>()?;
        if objectives.is_empty() {
            return Err(bad("no objective".into()));
        }
        let base = r.design.clone().check().map_err(|e| bad(format!("its design: {e}")))?;
        let problem = Problem {
            base,
            variables,
            objectives: Vec::new(),
            constraints: Vec::new(),
            band_hz: Vec::new(),
            robust: None,
        };
        let mut points = Vec::with_capacity(r.front.len());
        for (k, row) in r.front.iter().enumerate() {
            let at = |why: String| bad(format!("front design {}: {why}", k + 1));
            let values = problem
                .variables
                .iter()
                .zip(&r.variables)
                .map(|(v, j)| {
                    let x = row.variables.get(&j.column).ok_or_else(|| at(format!("no value of {}", j.column)))?;
                    match (v, x) {
                        (Variable::Range { .. }, serde_json::Value::Number(n)) => {
                            n.as_f64().map(Value::Number).ok_or_else(|| at(format!("{} is not a number", j.column)))
                        }
                        (Variable::Choice { .. }, serde_json::Value::String(s)) => Ok(Value::Choice(s.clone())),
                        _ => Err(at(format!("{} = {x} is not a value of that variable", j.column))),
                    }
                })
                .collect::<Result<Vec<_>, _>>()?;
            let objectives = r
                .objectives
                .iter()
                .map(|o| match row.objectives.get(&o.column) {
                    Some(serde_json::Value::Number(n)) => Ok(n.as_f64()),
                    Some(serde_json::Value::Null) => Ok(None),
                    _ => Err(at(format!("no value of {}", o.column))),
                })
                .collect::<Result<Vec<_>, _>>()?;
            let design = problem.design_at(&values).map_err(|e| at(e.to_string()))?.into_design();
            points.push(FrontPoint { index: row.index, values, objectives, design });
        }
        if points.is_empty() {
            return Err(bad("its front is empty (no design met every constraint)".into()));
        }
        Ok(Front {
            file: file.to_string(),
            objectives,
            variables: r.variables.iter().map(|v| v.column.clone()).collect(),
            base: r.design,
            points,
            partial: r.partial,
        })
    }

    /// The front design whose design is `d`, if any.
    #[must_use]
    pub fn position(&self, d: &Design) -> Option<usize> {
        // Thresholds aside: the explorer applies the user's own.
        let mut d = d.clone();
        d.thresholds = self.base.thresholds;
        self.points.iter().position(|p| p.design == d)
    }
}

/// The variable a report's entry describes, checked as `--vary`/`--choose` check theirs.
fn variable(v: &VariableJson) -> Result<Variable, ThudError> {
    match (&v.options, v.from, v.to) {
        (Some(options), _, _) => Variable::parse_choice(&format!("{}={}", v.name, options.join(","))),
        (None, Some(lo), Some(hi)) if lo < hi => {
            let row: &'static Param<DesignDraft> = study::numeric_row(&v.name, Spelling::Flag)?;
            Ok(Variable::Range { row, lo, hi })
        }
        _ => Err(ThudError::invalid(format!("variable {}", v.name), "neither a range (from < to) nor options")),
    }
}

/// A value as the report writes it: every digit.
pub fn value_text(v: &Value) -> String {
    match v {
        Value::Number(x) => x.to_string(),
        Value::Choice(s) => s.clone(),
    }
}

/// What the view shows: the front, the selected design, and the live design's values of the
/// objectives when its readout is computed.
pub struct FrontView<'a> {
    pub block: Block<'a>,
    pub front: &'a Front,
    pub selected: usize,
    /// The live design's objectives (its readout's), None while it computes.
    pub live: Option<Vec<Option<f64>>>,
    /// The front design the live one is, if any.
    pub live_is: Option<usize>,
    /// The keys: walk, load, close.
    pub keys: [String; 3],
    pub theme: Palette,
}

impl FrontView<'_> {
    /// The lines under the plot, each fitted to `width` by the caller.
    pub fn lines(&self) -> Vec<String> {
        let f = self.front;
        let k = self.selected.min(f.points.len() - 1);
        let p = &f.points[k];
        let [walk, load, close] = &self.keys;
        let partial = if f.partial { " (partial: the search was stopped)" } else { "" };
        let mut out = vec![format!(
            "design {} of {}{partial}, evaluation {} · {walk} walk · {load} loads it · {close} closes",
            k + 1,
            f.points.len(),
            p.index
        )];
        out.push(
            f.variables
                .iter()
                .zip(&p.values)
                .map(|(c, v)| format!("{c} {}", value_text(v)))
                .collect::<Vec<_>>()
                .join("  "),
        );
        let here = self.live_is == Some(k);
        for (i, (c, _)) in f.objectives.iter().enumerate() {
            let front = p.objectives[i].map_or("—".to_string(), |x| x.to_string());
            let live = match (&self.live, here) {
                (Some(l), true) => {
                    let v = l.get(i).copied().flatten();
                    let same = v.map(f64::to_bits) == p.objectives[i].map(f64::to_bits);
                    let mark = if same { "= the front's" } else { "≠ the front's" };
                    format!("live {} {mark}", v.map_or("—".to_string(), |x| x.to_string()))
                }
                (None, true) => "live: computing…".to_string(),
                (_, false) => "not loaded".to_string(),
            };
            out.push(format!("{} {front}  ({live})", c.name()));
        }
        out
    }
}

impl Widget for FrontView<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let inner = self.block.inner(area);
        (&self.block).render(area, buf);
        let th = self.theme;
        let f = self.front;
        let lines = self.lines();
        let text_h = (lines.len() as u16).min(inner.height.saturating_sub(6));
        let [plot, info] = Layout::vertical([Constraint::Min(1), Constraint::Length(text_h)]).areas(inner);
        // Objective 1 across, objective 2 up (one objective: against the design's number).
        let xy = |i: usize, o: &[Option<f64>]| -> Option<(f64, f64)> {
            if f.objectives.len() >= 2 {
                Some((o[0]?, o[1]?))
            } else {
                Some(((i + 1) as f64, o[0]?))
            }
        };
        let all: Vec<(f64, f64)> = f.points.iter().enumerate().filter_map(|(i, p)| xy(i, &p.objectives)).collect();
        let k = self.selected.min(f.points.len() - 1);
        let sel: Vec<(f64, f64)> = xy(k, &f.points[k].objectives).into_iter().collect();
        let live: Vec<(f64, f64)> =
            self.live.as_ref().and_then(|l| xy(self.live_is.unwrap_or(k), l)).into_iter().collect();
        let (x_title, y_title) = if f.objectives.len() >= 2 {
            (title(f.objectives[0]), title(f.objectives[1]))
        } else {
            ("front design".to_string(), title(f.objectives[0]))
        };
        let xb = fit_bounds(all.iter().chain(&live).map(|p| p.0), 0.05);
        let yb = fit_bounds(all.iter().chain(&live).map(|p| p.1), 0.05);
        let selected = Style::default().add_modifier(Modifier::BOLD | Modifier::REVERSED);
        LinePlot {
            block: Block::default(),
            x_title: &x_title,
            y_title: &y_title,
            series: vec![
                Curve::points("front", &all, th.style(Role::Damper), th.mark('•', '*')),
                Curve::points("live", &live, th.style(Role::Live), th.mark('+', '+')).ranked(1),
                Curve::points("selected", &sel, selected, th.mark('◆', '@')).ranked(2),
            ],
            empty: "no front design has both objectives",
            theme: th,
            y_zero: false,
            x_bounds: Some(xb),
            y_bounds: Some(yb),
            legend: true,
        }
        .render(plot, buf);
        let width = info.width as usize;
        let text: Vec<String> = lines.iter().map(|l| th.fit(&th.text(l), width).into_owned()).collect();
        Paragraph::new(text.join("\n")).render(info, buf);
    }
}

/// An axis title: the column and which way is better.
fn title((c, s): (Column, Sense)) -> String {
    let way = match s {
        Sense::Minimize => "min",
        Sense::Maximize => "max",
    };
    format!("{} ({way})", c.name())
}
