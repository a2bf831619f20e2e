//! `thud paper`: the paper's tables and figures, reproduced.

use std::path::PathBuf;

use clap::Args;

use super::format::print_str;
use super::{print_table, OutputArgs};
use crate::error::ThudError;
use crate::paper;

#[derive(Debug, Clone, Args)]
pub struct PaperArgs {
    /// Which table or figure (see --list), or `all` with --out DIR for every one as CSV/SVG plus REPORT.md.
    #[arg(value_name = "ID", required_unless_present = "list")]
    id: Option<String>,
    /// List every table and figure that can be reproduced.
    #[arg(long)]
    list: bool,
    /// Folder for `thud paper all` (created if missing).
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
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
    if id == "all" {
        return all(a.out.as_deref());
    }
    let table = paper::get(&id).ok_or_else(|| {
        let ids: Vec<&str> = paper::items().map(|i| i.id).collect();
        ThudError::invalid("paper item", format!("unknown '{id}'; one of: {}", ids.join(", ")))
    })??;
    print_table(&table, a.output.format());
    Ok(())
}

/// `thud paper all --out DIR`: every item as CSV (and SVG where plotted) plus REPORT.md.
fn all(out: Option<&std::path::Path>) -> Result<(), ThudError> {
    let dir = out.ok_or_else(|| ThudError::invalid("out", "`thud paper all` needs --out DIR"))?;
    let files = crate::export::report::paper_bundle();
    for f in &files {
        crate::export::write_file(&dir.join(&f.name), f.contents.as_bytes())?;
    }
    eprintln!("thud: wrote {} files to {}", files.len(), dir.display());
    Ok(())
}
