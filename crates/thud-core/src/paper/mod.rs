//! The paper's tables and figures, recomputed by the model, with the paper's printed numbers
//! beside them. Pure data in, tables out; the CLI only formats them.

mod acoustic;
mod damper;

use serde::Serialize;

use crate::error::ThudError;

pub use acoustic::*;
pub use damper::*;

/// One cell of a reproduced table.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Value {
    Num(f64),
    Text(String),
    /// The paper prints nothing here.
    Missing,
}

impl From<f64> for Value {
    fn from(v: f64) -> Self {
        Value::Num(v)
    }
}

impl From<Option<f64>> for Value {
    fn from(v: Option<f64>) -> Self {
        v.map_or(Value::Missing, Value::Num)
    }
}

/// A column: a machine key (used in JSON/CSV, unit in the name) and a label for people.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Column {
    pub key: &'static str,
    pub label: &'static str,
}

impl Column {
    /// Whether the column counts things (designs, impacts): its numbers are whole.
    #[must_use]
    pub fn counts(&self) -> bool {
        self.key == "count" || self.key.starts_with("n_")
    }

    /// A cell of this column as text: a count whole (`5`, not `5.0000`), other numbers by
    /// `num`, nothing as "—".
    pub fn text(&self, v: &Value, num: impl Fn(f64) -> String) -> String {
        match v {
            Value::Num(x) if self.counts() && x.fract() == 0.0 && x.abs() < 1e15 => format!("{x:.0}"),
            Value::Num(x) => num(*x),
            Value::Text(s) => s.clone(),
            Value::Missing => "—".into(),
        }
    }
}

/// A reproduced table or figure: columns, rows and notes on conventions and deviations.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Table {
    pub id: &'static str,
    pub title: String,
    pub notes: Vec<String>,
    pub columns: Vec<Column>,
    pub rows: Vec<Vec<Value>>,
    /// Rows that summarise `rows` (Table 1's mean, rms and range of the differences), shown
    /// under them; the first cell names the row. Empty for most tables.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub summary: Vec<Vec<Value>>,
}

/// A column with machine `key` and human `label`.
#[must_use]
pub const fn col(key: &'static str, label: &'static str) -> Column {
    Column { key, label }
}

/// One reproducible item: id, what it is.
pub struct Item {
    pub id: &'static str,
    pub description: &'static str,
}

/// Every reproducible item, in the order `thud paper --list` shows them.
pub fn items() -> impl Iterator<Item = &'static Item> {
    ACOUSTIC_ITEMS.iter().chain(DAMPER_ITEMS.iter())
}

/// The table or figure with this id, or `None` if there is no such item.
pub fn get(id: &str) -> Option<Result<Table, ThudError>> {
    acoustic(id).or_else(|| damper(id))
}
