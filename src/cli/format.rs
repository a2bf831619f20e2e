//! Tables as aligned text, JSON or CSV (written through [`super::Out`]).

use std::io::Write;

use crate::paper::Table;
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

pub use thud_render::json::table_json;
