//! A table of the paper (and `restitution`'s) as JSON: the one writer of `thud paper ID --json`,
//! `thud restitution --json` and Python's `thud.paper(ID)`.

use crate::paper::{Table, Value};

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
