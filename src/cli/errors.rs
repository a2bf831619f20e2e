//! The command line's error contract: every error is ONE line on stderr, `thud: …`, naming the
//! flag the user typed; bad input exits 2, an internal error (a non-finite number in a result, a
//! failed write to stdout) exits 1, a closed stdout pipe (`| head`) exits 0 quietly.
//!
//! Long values echoed back are cut to [`MAX_VALUE_CHARS`] characters with "…", and control
//! characters are shown escaped so a value cannot start a second line.

use std::io;

use crate::error::ThudError;

/// Longest value (in characters) echoed back in a message.
pub const MAX_VALUE_CHARS: usize = 60;

/// Longest message (in characters) printed, after the values have been cut.
const MAX_MESSAGE_CHARS: usize = 400;

/// The long flag of the force amplitude on every command (`--force` replaces a file).
pub const FORCE_AMPLITUDE: &str = "force-amplitude";

/// The long flag (without dashes) of an engine parameter named bare (`force` → `force-amplitude`;
/// every other name is its flag).
pub fn flag_of(param: &str) -> &str {
    if param == "force" {
        FORCE_AMPLITUDE
    } else {
        param
    }
}

/// What can go wrong in a command.
#[derive(Debug)]
pub enum CliError {
    /// Bad input (a value, a flag, a combination): exit 2.
    Input(ThudError),
    /// A run refused before it starts (a work cap), already worded: exit 2.
    Refused(String),
    /// A NaN or ∞ in a result, caught before it was printed: exit 1.
    NonFinite(String),
    /// Writing the output failed: exit 1, or 0 quietly for a closed pipe.
    Output(io::Error),
    /// Writing a file failed (the disk, the file system), already worded: exit 1.
    Io(String),
    /// The explorer could not start or run: a bad preset or tour (exit 2), no terminal or a
    /// failed draw (exit 1; [`crate::tui::TuiError::exit_code`]).
    Tui(crate::tui::TuiError),
}

impl From<ThudError> for CliError {
    fn from(e: ThudError) -> Self {
        CliError::Input(e)
    }
}

impl From<io::Error> for CliError {
    fn from(e: io::Error) -> Self {
        CliError::Output(e)
    }
}

impl CliError {
    /// The exit code and the line for stderr (None: exit quietly).
    pub fn report(&self, flags: &[String]) -> (i32, Option<String>) {
        match self {
            // Not bad input: a run stopped by an interrupt (the signal's own exit code is set
            // by the handler) or by the program itself.
            CliError::Input(e @ ThudError::Cancelled) => (1, Some(e.to_string())),
            CliError::Input(e) => (2, Some(name_flag(e, flags))),
            CliError::Io(m) => (1, Some(m.clone())),
            CliError::Tui(crate::tui::TuiError::Preset(e)) => (2, Some(name_flag(e, flags))),
            CliError::Tui(e) => (e.exit_code(), Some(e.to_string())),
            CliError::Refused(m) => (2, Some(m.clone())),
            CliError::NonFinite(what) => (
                1,
                Some(format!(
                    "internal error: a result came out as {what}, which is not a number; nothing was printed. \
                     This is a bug in thud: please report it with the command line"
                )),
            ),
            CliError::Output(e) if e.kind() == io::ErrorKind::BrokenPipe => (0, None),
            CliError::Output(e) => (1, Some(format!("cannot write the output: {e}"))),
        }
    }
}

/// The error's line, naming its parameter as the flag the user types (`invalid --mass: …`)
/// when the engine named it bare (`mass`) and it is one of thud's long flags. The parameter is
/// the error's own ([`ThudError::param`]); no message is parsed back.
pub fn name_flag(e: &ThudError, flags: &[String]) -> String {
    let param = e.param();
    if param.is_empty() || !flags.iter().any(|f| f == param) {
        return e.to_string();
    }
    // The flag's name: the engine's `force` is `--force-amplitude` (`--force` replaces a file).
    let flag = format!("--{}", flag_of(param));
    match e.clone().renamed(flag.clone()) {
        renamed if renamed.param() != param => renamed.to_string(),
        // A variant with a fixed parameter (no impact: `u0`) keeps its words under the flag.
        _ => ThudError::invalid(flag, e.detail()).to_string(),
    }
}

/// The message as one printable line: control characters escaped, quoted values longer than
/// [`MAX_VALUE_CHARS`] cut with "…", and the whole line bounded.
pub fn one_line(message: &str) -> String {
    let escaped: String = message
        .chars()
        .flat_map(|c| match c {
            '\n' => "\\n".chars().collect::<Vec<_>>(),
            '\r' => "\\r".chars().collect(),
            '\t' => vec![' '],
            c if c.is_control() => c.escape_unicode().collect(),
            c => vec![c],
        })
        .collect();
    let cut = cut_quoted(&escaped);
    cut_chars(&cut, MAX_MESSAGE_CHARS)
}

/// `s` cut to `max` characters with "…" when longer.
pub fn cut_chars(s: &str, max: usize) -> String {
    if s.chars().count() <= max {
        s.to_string()
    } else {
        s.chars().take(max - 1).chain(['…']).collect()
    }
}

/// Cuts every quoted value ('…' opened after a space or bracket, closed before a space,
/// punctuation or the end) longer than [`MAX_VALUE_CHARS`] characters. An apostrophe inside
/// a word (the ball's) is not a quote.
fn cut_quoted(s: &str) -> String {
    let chars: Vec<char> = s.chars().collect();
    let opens = |i: usize| chars[i] == '\'' && (i == 0 || matches!(chars[i - 1], ' ' | '(' | '[' | ':' | '='));
    let closes = |i: usize| chars[i] == '\'' && chars.get(i + 1).is_none_or(|c| !c.is_alphanumeric());
    let mut out = String::with_capacity(s.len().min(4 * MAX_MESSAGE_CHARS));
    let mut i = 0;
    while i < chars.len() {
        if opens(i) {
            if let Some(end) = (i + 1..chars.len()).find(|&j| closes(j)) {
                let value: String = chars[i + 1..end].iter().collect();
                out.push('\'');
                out.push_str(&cut_chars(&value, MAX_VALUE_CHARS));
                out.push('\'');
                i = end + 1;
                continue;
            }
        }
        out.push(chars[i]);
        i += 1;
    }
    out
}

/// A clap error as one line (help and version are not errors: the caller prints them).
pub fn clap_line(e: &clap::Error, missing_subcommand: Option<(String, Vec<String>)>) -> String {
    if e.kind() == clap::error::ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand {
        if let Some((path, subs)) = missing_subcommand {
            return format!("`{path}` needs one of: {} (see `{path} --help`)", subs.join(", "));
        }
    }
    let rendered = e.render().to_string();
    let mut parts: Vec<String> = Vec::new();
    for line in rendered.lines().map(str::trim) {
        if line.starts_with("Usage:") || line.starts_with("For more information") {
            break;
        }
        if line.is_empty() {
            continue;
        }
        let line = line.strip_prefix("error: ").unwrap_or(line);
        match line.strip_prefix("tip: ") {
            Some(tip) => parts.push(format!("({tip})")),
            None => parts.push(line.to_string()),
        }
    }
    if parts.is_empty() {
        "invalid command line (see `thud --help`)".to_string()
    } else {
        parts.join(" ")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_quoted_values_are_cut() {
        let long = "x".repeat(100_000);
        let m = one_line(&format!("invalid mass: '{long}' is not a number (expected e.g. 40.5g)"));
        assert!(m.chars().count() < 150, "{}", m.len());
        assert!(m.contains("…'") && m.ends_with("(expected e.g. 40.5g)"), "{m}");
    }

    #[test]
    fn apostrophes_are_not_quotes() {
        let m = format!("invalid --mass: the ball's radius 1.3 m reaches the observer at r 0.7 m; {}", "y".repeat(80));
        assert_eq!(one_line(&m), m);
    }

    #[test]
    fn newlines_cannot_start_a_second_line() {
        assert_eq!(one_line("invalid preset: unknown 'a\nb'"), "invalid preset: unknown 'a\\nb'");
    }

    #[test]
    fn engine_names_become_flags() {
        let flags = vec!["mass".to_string(), "r".to_string(), "u0".to_string()];
        assert_eq!(name_flag(&ThudError::invalid("r", "0.7 m puts…"), &flags), "invalid --r: 0.7 m puts…");
        assert_eq!(name_flag(&ThudError::invalid("paper item", "x"), &flags), "invalid paper item: x");
        let range = crate::limits::MASS.check(1e308).unwrap_err();
        assert!(name_flag(&range, &flags).starts_with("invalid --mass: 1e308 kg is out of range"));
        assert!(name_flag(&ThudError::NoImpact, &flags).starts_with("invalid --u0: the design has no impact"));
        assert_eq!(name_flag(&ThudError::Cancelled, &flags), ThudError::Cancelled.to_string());
    }
}
