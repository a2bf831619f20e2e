//! `thud tui` (and `thud` alone): the interactive explorer.

use clap::Args;

/// Options of the explorer.
#[derive(Debug, Clone, Default, Args)]
pub struct TuiArgs {
    /// Starting design: default, paper-fig9, paper-table3.
    #[arg(long, default_value = "default")]
    pub preset: String,
    /// Plain dots instead of Braille (for fonts without Braille).
    #[arg(long)]
    pub ascii: bool,
    /// Capture the mouse: a click on the chart selects that design.
    #[arg(long)]
    pub mouse: bool,
}

/// Runs the explorer; the error is one line for stderr.
pub fn run(a: &TuiArgs) -> Result<(), String> {
    let opts = crate::tui::Options { preset: a.preset.clone(), ascii: a.ascii, mouse: a.mouse };
    crate::tui::run(&opts).map_err(|e| e.to_string())
}
