//! `thud tui` (and `thud` alone): the interactive explorer.

use clap::Args;

use super::CliError;

/// Options of the explorer.
#[derive(Debug, Clone, Default, Args)]
pub struct TuiArgs {
    /// Starting design (`thud presets` lists them: default, paper-fig9, paper-table3, quiet-nylon, …).
    #[arg(long, value_name = "P", default_value = "default")]
    pub preset: String,
    #[command(flatten)]
    pub ascii: super::AsciiArgs,
    /// Colours: default (dark background), light (light background), mono (none); overrides
    /// the theme of config.toml.
    #[arg(long, value_enum, value_name = "THEME")]
    pub theme: Option<crate::config::Theme>,
    /// Do not capture the mouse (by default it is on where the terminal reports it: a click on
    /// a chart cell selects that design, and the terminal's own selection needs Shift). The
    /// config key `mouse = false` does the same.
    #[arg(long, overrides_with = "mouse")]
    pub no_mouse: bool,
    /// Capture the mouse (the default; kept for scripts written when it was off by default).
    #[arg(long, hide = true, overrides_with = "no_mouse")]
    pub mouse: bool,
    /// Folder the export key (e) writes files into (default: the current directory).
    #[arg(long, value_name = "DIR")]
    pub export_dir: Option<std::path::PathBuf>,
    /// Start with the guided tour: the built-in one, or the steps of FILE (TOML, see
    /// assets/tour.toml). T starts it from inside the explorer.
    #[arg(long, value_name = "FILE", num_args = 0..=1)]
    #[allow(clippy::option_option)]
    pub tour: Option<Option<std::path::PathBuf>>,
    /// Open the front view on the design front of FILE, the report `thud design … --json`
    /// writes: ↑↓ walk along it, Enter loads the selected design (D shows and hides the view).
    /// The explorer starts on the search's starting design.
    #[arg(long, value_name = "FILE")]
    pub front: Option<std::path::PathBuf>,
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

impl TuiArgs {
    /// The explorer's options: the mouse is on unless `--no-mouse` (the last of `--mouse` and
    /// `--no-mouse` wins).
    pub fn options(&self) -> crate::tui::Options {
        use crate::tui::tour::TourSource;
        let tour = self.tour.as_ref().map(|file| file.clone().map_or(TourSource::BuiltIn, TourSource::File));
        crate::tui::Options {
            preset: self.preset.clone(),
            ascii: self.ascii.ascii,
            mouse: !self.no_mouse,
            export_dir: self.export_dir.clone(),
            tour,
            theme: self.theme,
            front: self.front.clone(),
        }
    }
}

/// Runs the explorer.
pub fn run(a: &TuiArgs) -> Result<(), CliError> {
    crate::tui::run(&a.options()).map_err(CliError::Tui)
}

#[cfg(test)]
mod tests {
    use clap::Parser;

    use super::super::{Cli, Command};

    fn mouse(args: &[&str]) -> bool {
        let cli = Cli::try_parse_from(["thud", "tui"].iter().chain(args)).unwrap();
        let Some(Command::Tui(a)) = cli.command else { panic!("not the tui command: {args:?}") };
        a.options().mouse
    }

    #[test]
    fn the_mouse_is_on_by_default_and_no_mouse_turns_it_off() {
        assert!(mouse(&[]));
        assert!(!mouse(&["--no-mouse"]));
        assert!(mouse(&["--mouse"]), "the old flag still parses");
        assert!(mouse(&["--no-mouse", "--mouse"]) && !mouse(&["--mouse", "--no-mouse"]), "the last one wins");
        assert!(super::TuiArgs::default().options().mouse, "`thud` alone has the mouse on");
    }
}
