//! Tables as aligned text, JSON or CSV (written through [`super::Out`]).

use std::io::Write;

use crate::paper::{Table, Value};
pub use crate::units::num;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OutputFormat {
    Text,
    Json,
    Csv,
}

/// Writes `table` as CSV: a header of column keys, then the rows (the one CSV writer,
/// [`crate::export::csv::write_table`]).
pub fn write_csv(out: &mut impl Write, table: &Table) -> std::io::Result<()> {
    crate::export::csv::write_table(out, table).map_err(crate::export::csv::into_io)
}

/// Writes `table` as aligned text with its title and notes.
pub fn write_text(out: &mut impl Write, table: &Table) -> std::io::Result<()> {
    writeln!(out, "{}", table.title)?;
    let cells: Vec<Vec<String>> = table
        .rows
        .iter()
        .chain(&table.summary)
        .map(|r| r.iter().zip(&table.columns).map(|(v, c)| c.text(v, num)).collect())
        .collect();
    let widths: Vec<usize> = table
        .columns
        .iter()
        .enumerate()
        .map(|(i, c)| cells.iter().map(|r| r[i].chars().count()).chain([c.label.chars().count()]).max().unwrap_or(0))
        .collect();
    let line = |items: Vec<String>| -> String {
        items.iter().zip(&widths).map(|(s, w)| format!("{s:>w$}")).collect::<Vec<_>>().join("  ")
    };
    writeln!(out, "{}", line(table.columns.iter().map(|c| c.label.to_string()).collect()))?;
    for row in cells {
        writeln!(out, "{}", line(row))?;
    }
    for n in &table.notes {
        writeln!(out, "note: {n}")?;
    }
    Ok(())
}

/// A table as JSON: id, title, notes, columns, and rows as objects keyed by column (and its
/// summary rows, if it has any, under `summary`, keyed by the row's name and then by column).
pub fn table_json(table: &Table) -> serde_json::Value {
    let object = |r: &Vec<Value>| {
        let map: serde_json::Map<String, serde_json::Value> = table
            .columns
            .iter()
            .zip(r)
            .map(|(c, v)| (c.key.to_string(), serde_json::to_value(v).unwrap_or_default()))
            .collect();
        serde_json::Value::Object(map)
    };
    let rows: Vec<serde_json::Value> = table.rows.iter().map(object).collect();
    let mut json = serde_json::json!({
        "id": table.id,
        "title": table.title,
        "notes": table.notes,
        "columns": table.columns,
        "rows": rows,
    });
    if !table.summary.is_empty() {
        let summary: serde_json::Map<String, serde_json::Value> = table
            .summary
            .iter()
            .map(|r| {
                let name = match r.first() {
                    Some(Value::Text(t)) => t.clone(),
                    _ => String::new(),
                };
                let cells: serde_json::Map<String, serde_json::Value> = table
                    .columns
                    .iter()
                    .zip(r)
                    .skip(1)
                    .filter(|(_, v)| !matches!(v, Value::Missing))
                    .map(|(c, v)| (c.key.to_string(), serde_json::to_value(v).unwrap_or_default()))
                    .collect();
                (name, serde_json::Value::Object(cells))
            })
            .collect();
        json["summary"] = serde_json::Value::Object(summary);
    }
    json
}
