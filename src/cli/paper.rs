//! `thud paper`: the paper's tables and figures, reproduced.

use clap::Args;

use super::format::print_str;
use super::{print_table, OutputArgs};
use crate::error::ThudError;
use crate::paper;

#[derive(Debug, Clone, Args)]
pub struct PaperArgs {
    /// Which table or figure (see --list).
    #[arg(value_name = "ID", required_unless_present = "list")]
    id: Option<String>,
    /// List every table and figure that can be reproduced.
    #[arg(long)]
    list: bool,
    #[command(flatten)]
    output: OutputArgs,
}

pub fn run(a: &PaperArgs) -> Result<(), ThudError> {
    if a.list {
        let mut s = String::new();
        for item in paper::items() {
            s += &format!("{:<8} {}\n", item.id, item.description);
        }
        print_str(&s);
        return Ok(());
    }
    let id = a.id.as_deref().unwrap_or_default().to_ascii_lowercase();
    let table = paper::get(&id).ok_or_else(|| {
        let ids: Vec<&str> = paper::items().map(|i| i.id).collect();
        ThudError::invalid("paper item", format!("unknown '{id}'; one of: {}", ids.join(", ")))
    })??;
    print_table(&table, a.output.format());
    Ok(())
}
