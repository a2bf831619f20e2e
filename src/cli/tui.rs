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
    /// Folder the export key (e) writes files into (default: the current directory).
    #[arg(long, value_name = "DIR")]
    pub export_dir: Option<std::path::PathBuf>,
}

/// `thud` with no subcommand: the explorer on a terminal, the help text otherwise (pipes,
/// scripts, CI).
pub fn run_default() -> Result<(), String> {
    use std::io::IsTerminal;
    if std::io::stdin().is_terminal() && std::io::stdout().is_terminal() {
        run(&TuiArgs { preset: "default".into(), ..Default::default() })
    } else {
        use clap::CommandFactory;
        super::Cli::command().print_help().map_err(|e| e.to_string())
    }
}

/// Runs the explorer; the error is one line for stderr.
pub fn run(a: &TuiArgs) -> Result<(), String> {
    let opts = crate::tui::Options {
        preset: a.preset.clone(),
        ascii: a.ascii,
        mouse: a.mouse,
        export_dir: a.export_dir.clone(),
    };
    crate::tui::run(&opts).map_err(|e| e.to_string())
}
