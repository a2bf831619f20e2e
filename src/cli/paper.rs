//! `thud paper`: the paper's tables and figures, reproduced.

use std::path::PathBuf;

use clap::Args;

use super::export::out_error;
use super::{budget, CliError, Out, OutputArgs};
use crate::error::ThudError;
use crate::export::report;
use crate::fsio::{self, FsError, Overwrite};
use crate::paper;

#[derive(Debug, Clone, Args)]
pub struct PaperArgs {
    /// Which table or figure (see --list), or `all` with --out DIR for every one as CSV/SVG plus REPORT.md.
    #[arg(value_name = "ID", required_unless_present = "list")]
    id: Option<String>,
    /// List every table and figure that can be reproduced.
    #[arg(long)]
    list: bool,
    /// Folder for `thud paper all` (created if missing); files in it are kept unless --force.
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// With `all`: replace files of the same names in --out (atomically; never a device or folder).
    #[arg(long, requires = "out")]
    force: bool,
    #[command(flatten)]
    output: OutputArgs,
}

pub fn run(a: &PaperArgs, out: &mut Out) -> Result<(), CliError> {
    if a.list {
        let mut s = String::new();
        for item in paper::items() {
            s += &format!("{:<8} {}\n", item.id, item.description);
        }
        return out.text(&s);
    }
    let id = a.id.as_deref().unwrap_or_default().to_ascii_lowercase();
    if id == "all" {
        return all(a.out.as_deref(), Overwrite::from_force(a.force));
    }
    let table = paper::get(&id).ok_or_else(|| {
        let ids: Vec<&str> = paper::items().map(|i| i.id).collect();
        ThudError::invalid("paper item", format!("unknown '{id}'; one of: {}", ids.join(", ")))
    })??;
    out.table(&table, a.output.format())
}

/// `thud paper all --out DIR`: every item as CSV (and SVG where plotted) plus REPORT.md. Every
/// target is checked before the work starts (an existing file is kept unless `--force`), and
/// every number in every file before the first file is written.
fn all(out: Option<&std::path::Path>, overwrite: Overwrite) -> Result<(), CliError> {
    let dir = out.ok_or_else(|| ThudError::invalid("out", "`thud paper all` needs --out DIR"))?;
    if fsio::is_stdout(dir) {
        return Err(ThudError::invalid("out", "-: `thud paper all` writes a folder of files; give --out DIR").into());
    }
    let refused = |e: FsError| out_error(e.path(), &e);
    let expected = report::expected_files();
    report::check_bundle_targets(dir, expected.iter().map(String::as_str), overwrite).map_err(refused)?;
    let spinner = budget::spinner("reproducing the paper", true);
    let files = report::paper_bundle();
    spinner.finish_and_clear();
    for f in &files {
        super::output::check_text(&f.contents).map_err(|e| {
            if let CliError::NonFinite(w) = e {
                CliError::NonFinite(format!("{w} in {}", f.name))
            } else {
                e
            }
        })?;
    }
    report::write_bundle(dir, &files, overwrite).map_err(refused)?;
    super::warn(&format!("wrote {} files to {}", files.len(), dir.display()));
    Ok(())
}
