//! `thud presets`: the named starting designs.

use clap::Args;

use super::{CliError, Out};
use crate::presets;

#[derive(Debug, Clone, Args)]
pub struct PresetsArgs {
    /// Print one JSON array of {name, description}.
    #[arg(long)]
    json: bool,
}

pub fn run(a: &PresetsArgs, out: &mut Out) -> Result<(), CliError> {
    let list = presets::list()?;
    if a.json {
        let v: Vec<serde_json::Value> =
            list.iter().map(|p| serde_json::json!({ "name": p.name, "description": p.description })).collect();
        return out.json(&v);
    }
    let width = list.iter().map(|p| p.name.len()).max().unwrap_or(0);
    let mut s = String::new();
    for p in &list {
        s += &format!("{:<width$}  {}\n", p.name, p.description);
    }
    s += "\nUse one with --preset NAME (simulate, sweep, export); flags override its values.\n";
    out.text(&s)
}
