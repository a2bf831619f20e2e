//! `thud tui` (and `thud` alone): the interactive explorer.

use clap::Args;

use super::CliError;

/// Options of the explorer.
#[derive(Debug, Clone, Default, Args)]
pub struct TuiArgs {
    /// Starting design: default, paper-fig9, paper-table3.
    #[arg(long, default_value = "default")]
    pub preset: String,
    /// Pure ASCII: plain borders, plot glyphs and text (theta, us) for fonts without Braille.
    #[arg(long)]
    pub ascii: bool,
    /// Colours: default (dark background), light (light background), mono (none); overrides
    /// the theme of config.toml.
    #[arg(long, value_enum, value_name = "THEME")]
    pub theme: Option<crate::config::Theme>,
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
pub fn run_default() -> Result<(), CliError> {
    use std::io::IsTerminal;
    if std::io::stdin().is_terminal() && std::io::stdout().is_terminal() {
        run(&TuiArgs { preset: "default".into(), ..Default::default() })
    } else {
        use clap::CommandFactory;
        Ok(super::Cli::command().print_help().map_err(|e| CliError::Io(format!("cannot write the help: {e}")))?)
    }
}

/// Runs the explorer.
pub fn run(a: &TuiArgs) -> Result<(), CliError> {
    use crate::tui::tour::TourSource;
    let tour = a.tour.as_ref().map(|file| file.clone().map_or(TourSource::BuiltIn, TourSource::File));
    let opts = crate::tui::Options {
        preset: a.preset.clone(),
        ascii: a.ascii,
        mouse: a.mouse,
        export_dir: a.export_dir.clone(),
        tour,
        theme: a.theme,
    };
    crate::tui::run(&opts).map_err(CliError::Tui)
}
