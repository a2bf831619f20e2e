//! Work budgets on the command line: each command estimates its run's work with the engine's
//! [`crate::limits`] functions before it starts and refuses an estimate over its cap (exit 2,
//! one line naming the flag, the estimate, the cap and what to change) unless `--no-limit` is
//! given. Long runs show an `indicatif` progress bar on stderr when stderr is a terminal.

use std::io::IsTerminal;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use indicatif::{ProgressBar, ProgressStyle};

use super::errors::{cut_chars, CliError, MAX_VALUE_CHARS};
use crate::limits::Estimate;

/// What every command is told besides its own flags.
#[derive(Debug, Clone, Copy, Default)]
pub struct Ctx {
    /// `--no-limit`: run whatever the estimates say.
    pub no_limit: bool,
}

impl Ctx {
    /// Refuses `e` if it is over its cap: "`flag value`: estimate exceeds the limit; `hint`".
    pub fn enforce(&self, e: Estimate, flag: &str, value: &str, hint: &str) -> Result<(), CliError> {
        if self.no_limit || !e.exceeded() {
            return Ok(());
        }
        Err(CliError::Refused(format!(
            "{flag} {}: {}; {hint}, or add --no-limit",
            cut_chars(value, MAX_VALUE_CHARS),
            e.describe()
        )))
    }
}

/// `--no-limit` for this process: the designs the command line builds run without the
/// solvers' work caps too ([`crate::damper::SOLVER_CAPS`]), not only past the estimates.
static NO_LIMIT: AtomicBool = AtomicBool::new(false);

/// Sets `--no-limit` for the process (once, from the command line).
pub fn set_no_limit(on: bool) {
    NO_LIMIT.store(on, Ordering::Relaxed);
}

/// Whether `--no-limit` was given.
pub fn no_limit() -> bool {
    NO_LIMIT.load(Ordering::Relaxed)
}

/// A progress bar of `len` steps on stderr, hidden when stderr is not a terminal.
pub fn bar(len: u64, what: &str) -> ProgressBar {
    if !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let pb = ProgressBar::new(len);
    if let Ok(style) = ProgressStyle::with_template("{msg} {wide_bar} {pos}/{len} ({eta})") {
        pb.set_style(style);
    }
    pb.set_message(what.to_string());
    pb
}

/// A spinner with elapsed time on stderr for a run expected to take over about a second
/// (`expected_long`), hidden otherwise or when stderr is not a terminal.
pub fn spinner(what: &str, expected_long: bool) -> ProgressBar {
    if !expected_long || !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let pb = ProgressBar::new_spinner();
    if let Ok(style) = ProgressStyle::with_template("{spinner} {msg} {elapsed}") {
        pb.set_style(style);
    }
    pb.set_message(what.to_string());
    pb.enable_steady_tick(Duration::from_millis(120));
    pb
}
