//! `thud tui` (and `thud` alone): the interactive explorer.

use clap::Args;

/// Options of the explorer.
#[derive(Debug, Clone, Default, Args)]
pub struct TuiArgs {
    /// Starting design: default, paper-fig9, paper-table3.
    #[arg(long, default_value = "default")]
    pub preset: String,
    /// Pure ASCII: plain borders, plot glyphs and text (theta, us) for fonts without Braille.
    #[arg(long)]
    pub ascii: bool,
    /// Capture the mouse: a click on the chart selects that design.
    #[arg(long)]
    pub mouse: bool,
    /// Folder the export key (e) writes files into (default: the current directory).
    #[arg(long, value_name = "DIR")]
    pub export_dir: Option<std::path::PathBuf>,
    /// Start with the guided tour: the built-in one, or the steps of FILE (TOML, see
    /// assets/tour.toml). T starts it from inside the explorer.
    #[arg(long, value_name = "FILE", num_args = 0..=1)]
    #[allow(clippy::option_option)]
    pub tour: Option<Option<std::path::PathBuf>>,
}

/// `thud` with no subcommand: the explorer on a terminal, the help text otherwise (pipes,
/// scripts, CI).
pub fn run_default() -> Result<(), (i32, String)> {
    use std::io::IsTerminal;
    if std::io::stdin().is_terminal() && std::io::stdout().is_terminal() {
        run(&TuiArgs { preset: "default".into(), ..Default::default() })
    } else {
        use clap::CommandFactory;
        super::Cli::command().print_help().map_err(|e| (1, format!("cannot write the help: {e}")))
    }
}

/// Runs the explorer; the error is its exit code and one line for stderr.
pub fn run(a: &TuiArgs) -> Result<(), (i32, String)> {
    use crate::tui::tour::TourSource;
    let tour = a.tour.as_ref().map(|file| file.clone().map_or(TourSource::BuiltIn, TourSource::File));
    let opts = crate::tui::Options {
        preset: a.preset.clone(),
        ascii: a.ascii,
        mouse: a.mouse,
        export_dir: a.export_dir.clone(),
        tour,
    };
    crate::tui::run(&opts).map_err(|e| (e.exit_code(), e.to_string()))
}
