//! `thud presets`: the named starting designs.

use clap::Args;

use super::format::print_str;
use crate::error::ThudError;
use crate::presets;

#[derive(Debug, Clone, Args)]
pub struct PresetsArgs {
    /// Print one JSON array of {name, description}.
    #[arg(long)]
    json: bool,
}

pub fn run(a: &PresetsArgs) -> Result<(), ThudError> {
    let list = presets::list()?;
    if a.json {
        let v: Vec<serde_json::Value> =
            list.iter().map(|p| serde_json::json!({ "name": p.name, "description": p.description })).collect();
        print_str(&(serde_json::to_string_pretty(&v).unwrap_or_default() + "\n"));
        return Ok(());
    }
    let width = list.iter().map(|p| p.name.len()).max().unwrap_or(0);
    let mut s = String::new();
    for p in &list {
        s += &format!("{:<width$}  {}\n", p.name, p.description);
    }
    s += "\nUse one with --preset NAME (simulate, sweep, export); flags override its values.\n";
    print_str(&s);
    Ok(())
}
