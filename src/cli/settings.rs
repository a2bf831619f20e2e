//! The user's settings as the CLI uses them, and `thud config check`.
//!
//! The config is loaded once per run from the config directory; a problem with the file is a
//! warning, kept apart from errors: a command that succeeds prints it after its output (one
//! line, the run went on with the defaults and the file is left as it is), a command that fails
//! prints only its own error line, and `thud config check` lists every problem.

use std::sync::OnceLock;

use clap::{Args, Subcommand};

use super::{CliError, Out};
use crate::config::{self, Config};

static CONFIG: OnceLock<(Config, Option<String>)> = OnceLock::new();

/// Loads the user's config (once); a problem with the file is kept for [`warning`].
pub fn load() -> &'static Config {
    &CONFIG
        .get_or_init(|| {
            let loaded = config::load_user_config();
            let warning = loaded.warning();
            (loaded.config, warning)
        })
        .0
}

/// The warning about the user's config file, if it was loaded and had a problem.
pub fn warning() -> Option<&'static str> {
    CONFIG.get().and_then(|(_, w)| w.as_deref())
}

/// Options of `thud config`.
#[derive(Debug, Clone, Args)]
pub struct ConfigArgs {
    #[command(subcommand)]
    pub action: ConfigAction,
}

/// What `thud config` does.
#[derive(Debug, Clone, Copy, Subcommand)]
pub enum ConfigAction {
    /// Check config.toml: print every problem as FILE:LINE:COL: problem; exit 2 if there is any.
    Check,
}

/// What `thud config check` reads and what it leaves to the commands, said after "no problems".
const CHECKED: &str = "checked: the TOML syntax, every key and value, and [design] on the default preset \
     against `thud limits`; not checked: [design] on another --preset, or with a command's own \
     flags (each command checks those when it runs)";

/// `thud config check`: every problem of the user's `config.toml` on standard output, then one
/// line on stderr and exit 2 if there was any.
pub fn run(a: &ConfigArgs, out: &mut Out) -> Result<(), CliError> {
    let ConfigAction::Check = a.action;
    let Some(check) = config::check_user_config() else {
        return out.text("no home directory: no settings file; the defaults are used\n");
    };
    let path = check.path.display();
    if !check.exists {
        return out.text(&format!("{path}: no such file; the defaults are used\n"));
    }
    if check.problems.is_empty() {
        return out.text(&format!("{path}: no problems; {CHECKED}\n"));
    }
    // The file's own text echoed (a `nan` it holds is no result of thud's): written as it is.
    let max = config::MAX_LISTED_PROBLEMS;
    let mut lines: String =
        check.problems.iter().take(max).map(|p| format!("{}\n", p.to_string().replace(['\n', '\r'], " "))).collect();
    if check.problems.len() > max {
        lines += &format!("{path}: … and {} more problems (the first {max} are listed)\n", check.problems.len() - max);
    }
    out.raw(lines.as_bytes())?;
    out.flush()?;
    let n = check.problems.len();
    Err(CliError::Refused(format!(
        "{path}: {n} problem{} (listed above); until fixed, thud uses the default settings",
        if n == 1 { "" } else { "s" }
    )))
}
