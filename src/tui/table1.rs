//! The Table 1 view (`M`, and the tour's Table 1 step): the paper's eight measurements (an
//! acrylic sphere dropped on a steel plate, cited from Akay & Hodgson) beside the paper's model
//! and the physical model, both differences, and their mean and rms.
//!
//! Every number is the engine's own: the table is [`crate::paper::table1`], the function
//! `thud paper table1 --json` prints, and this view only picks its columns by their keys and
//! rounds them (levels to 0.1 dB). Nothing is retyped here.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph, Widget};

use super::theme::Palette;
use super::tour::wrap;
use crate::paper::{Table, Value};
use crate::units::sig;

/// The columns the view shows, by their keys in the engine's table, with the view's headings:
/// a (mm), U0 (m/s), measured, the paper's model, the physical model, and both differences
/// (model − measured).
const COLUMNS: [(&str, &str); 7] = [
    ("radius_mm", "a (mm)"),
    ("u0_m_s", "U0 m/s"),
    ("spl_experiment_db", "measured"),
    ("spl_model_db", "paper"),
    ("spl_physical_db", "physical"),
    ("model_minus_experiment_db", "paper − meas."),
    ("physical_minus_experiment_db", "physical − meas."),
];

/// Blank columns between two columns of the view.
const GAP: usize = 2;

/// Table 1 as the view shows it: the engine's rows and summary rows, each cell formatted; or
/// why the engine could not make it (shown instead of the table).
#[derive(Debug, Clone, PartialEq)]
pub struct Table1 {
    /// One line per measurement: the cells of the columns shown (a, U0, measured, paper, physical,
    /// both differences), formatted.
    pub rows: Vec<[String; 7]>,
    /// The summary rows the engine gives (mean, rms, range of the differences): the row's
    /// name and the two differences' cells.
    pub summary: Vec<(String, String, String)>,
    /// The engine's notes on the models (what each assumes).
    pub notes: Vec<String>,
    /// Why there is no table (the engine's error), if there is none.
    pub error: Option<String>,
}

impl Table1 {
    /// The engine's Table 1 ([`crate::paper::table1`]), formatted for the view. It depends on
    /// no design, so it is computed once a process (about 20 ms, the first time the view or
    /// the tour's step opens) and copied after.
    pub fn compute() -> Self {
        static TABLE: std::sync::OnceLock<Table1> = std::sync::OnceLock::new();
        TABLE
            .get_or_init(|| match crate::paper::table1() {
                Ok(t) => Self::of(&t),
                Err(e) => Self::failed(e.to_string()),
            })
            .clone()
    }

    fn failed(error: String) -> Self {
        Table1 { rows: Vec::new(), summary: Vec::new(), notes: Vec::new(), error: Some(error) }
    }

    /// The view of the engine's table `t`: its cells picked by column key. A column the view
    /// needs and the table lacks is an error shown in place of the table, never a made-up cell.
    pub fn of(t: &Table) -> Self {
        let mut at = [0; 7];
        for (i, (key, _)) in COLUMNS.iter().enumerate() {
            match t.columns.iter().position(|c| c.key == *key) {
                Some(j) => at[i] = j,
                None => return Self::failed(format!("the engine's Table 1 has no column {key}")),
            }
        }
        let rows = t.rows.iter().map(|r| std::array::from_fn(|i| cell(r.get(at[i]), COLUMNS[i].0))).collect();
        let summary = t
            .summary
            .iter()
            .map(|r| {
                let name = match r.first() {
                    Some(Value::Text(s)) => s.clone(),
                    _ => String::new(),
                };
                // The rms is a magnitude: shown without a sign.
                let unsigned = |c: String| if name == "rms" { c.trim_start_matches('+').to_string() } else { c };
                let (paper, physical) = (cell(r.get(at[5]), COLUMNS[5].0), cell(r.get(at[6]), COLUMNS[6].0));
                (name.clone(), unsigned(paper), unsigned(physical))
            })
            .collect();
        Table1 { rows, summary, notes: t.notes.clone(), error: None }
    }

    /// The lines of the view as `th` draws them (folded to ASCII with `--ascii`): a heading,
    /// one line per measurement, the summary rows; each column as wide as its widest cell.
    fn lines(&self, th: &Palette) -> Vec<String> {
        let mut grid: Vec<[String; 7]> = vec![COLUMNS.map(|(_, h)| h.to_string())];
        grid.extend(self.rows.iter().cloned());
        for (name, paper, physical) in &self.summary {
            let blank = String::new;
            grid.push([name.clone(), blank(), blank(), blank(), blank(), paper.clone(), physical.clone()]);
        }
        let grid: Vec<[String; 7]> = grid.iter().map(|r| r.clone().map(|c| th.text(&c).into_owned())).collect();
        let widths: [usize; 7] = std::array::from_fn(|i| grid.iter().map(|r| r[i].chars().count()).max().unwrap_or(0));
        grid.iter()
            .map(|r| {
                let cells: Vec<String> = r.iter().zip(widths).map(|(c, w)| format!("{c:>w$}")).collect();
                cells.join(&" ".repeat(GAP))
            })
            .collect()
    }
}

/// One cell of column `key` as shown: the radius and speed as the paper prints them (U0 to
/// 0.01 m/s), levels
/// and differences to 0.1 dB (differences signed), a text cell as it is, "—" for none.
fn cell(v: Option<&Value>, key: &str) -> String {
    match v {
        Some(Value::Num(x)) if x.is_finite() => match key {
            "radius_mm" => sig(*x, 4),
            "u0_m_s" => format!("{x:.2}"),
            k if k.contains("minus") => format!("{x:+.1}").replace('-', "−"),
            _ => format!("{x:.1}"),
        },
        Some(Value::Text(s)) if key.contains("minus") => s.replace('-', "−"),
        Some(Value::Text(s)) => s.clone(),
        _ => "—".to_string(),
    }
}

/// The view's widget: the table in `block`, the engine's notes under it where they fit.
pub struct Table1View<'a> {
    pub block: Block<'a>,
    pub table: &'a Table1,
    pub theme: Palette,
}

impl Widget for Table1View<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let th = &self.theme;
        let inner = self.block.inner(area);
        self.block.render(area, buf);
        let width = usize::from(inner.width);
        let mut lines: Vec<Line<'static>> = if let Some(e) = &self.table.error {
            wrap(&format!("no Table 1: {e}"), width)
                .into_iter()
                .map(|l| Line::from(Span::styled(th.text(&l).into_owned(), th.error())))
                .collect()
        } else {
            let body = self.table.lines(th);
            let table_w = body.iter().map(|l| l.chars().count()).max().unwrap_or(0);
            let pad = " ".repeat(width.saturating_sub(table_w) / 2);
            let n_rows = self.table.rows.len();
            body.iter()
                .enumerate()
                .map(|(i, l)| {
                    let text = th.fit(&format!("{pad}{l}"), width).into_owned();
                    // The heading and the summary in the label's weight, the rows plain.
                    if i == 0 || i > n_rows {
                        Line::from(Span::styled(text, th.label()))
                    } else {
                        Line::from(text)
                    }
                })
                .collect()
        };
        // The engine's notes (what each model assumes) where the height leaves room for all.
        let notes: Vec<String> = self.table.notes.iter().flat_map(|n| wrap(n, width)).collect();
        if !notes.is_empty() && lines.len() + 1 + notes.len() <= usize::from(inner.height) {
            lines.push(Line::from(""));
            lines.extend(notes.iter().map(|n| Line::from(Span::styled(th.text(n).into_owned(), th.label()))));
        }
        Paragraph::new(lines).render(inner, buf);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The view shows the engine's Table 1: eight rows, each cell the engine's value rounded
    /// as shown, and the mean and rms of both differences the engine computes.
    #[test]
    fn the_view_is_the_engine_s_table1_rounded() {
        let t = crate::paper::table1().unwrap();
        let v = Table1::of(&t);
        assert_eq!(v.error, None);
        assert_eq!(v.rows.len(), 8);
        let key = |k: &str| t.columns.iter().position(|c| c.key == k).unwrap();
        for (row, shown) in t.rows.iter().zip(&v.rows) {
            let Value::Num(measured) = row[key("spl_experiment_db")] else { panic!() };
            assert_eq!(shown[2], format!("{measured:.1}"));
            let Value::Num(d) = row[key("physical_minus_experiment_db")] else { panic!() };
            let back: f64 = shown[6].replace('−', "-").parse().unwrap();
            assert!((back - d).abs() <= 0.05 + 1e-12, "{back} vs {d}");
        }
        let names: Vec<&str> = v.summary.iter().map(|(n, _, _)| n.as_str()).collect();
        assert!(names.starts_with(&["mean", "rms"]), "{names:?}");
        for th in [Palette::default(), Palette { ascii: true, ..Palette::default() }] {
            let lines = v.lines(&th);
            assert!(lines.iter().all(|l| l.chars().count() <= 78), "fits 80 columns:\n{}", lines.join("\n"));
            let width = lines[0].chars().count();
            assert!(lines.iter().all(|l| l.chars().count() == width), "aligned:\n{}", lines.join("\n"));
        }
    }

    #[test]
    fn a_table_without_a_column_the_view_needs_says_so() {
        let mut t = crate::paper::table1().unwrap();
        t.columns.retain(|c| c.key != "spl_physical_db");
        let v = Table1::of(&t);
        assert!(v.error.as_deref().is_some_and(|e| e.contains("spl_physical_db")), "{v:?}");
        assert!(v.rows.is_empty());
    }
}
