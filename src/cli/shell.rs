//! Shell integration: `thud completions SHELL` prints a completion script (clap_complete) and
//! `thud man [COMMAND…]` a roff man page (clap_mangen), both generated from the very clap
//! definitions the command line parses with, so they never drift from it.

use clap::{Args, CommandFactory};
use clap_complete::Shell;

use super::{Cli, CliError, Out};
use crate::error::ThudError;

/// Options of `thud completions`.
#[derive(Debug, Clone, Copy, Args)]
pub struct CompletionsArgs {
    /// The shell to complete for.
    #[arg(value_enum)]
    shell: Shell,
}

/// Options of `thud man`.
#[derive(Debug, Clone, Args)]
pub struct ManArgs {
    /// The command whose page to print (`pulse`, `export csv`); none: the page of thud itself,
    /// thud(1), which lists the commands (thud-pulse(1), …).
    #[arg(value_name = "COMMAND")]
    command: Vec<String>,
}

/// `thud completions SHELL`: the completion script on stdout.
pub fn completions(a: &CompletionsArgs, out: &mut Out) -> Result<(), CliError> {
    let mut script = Vec::new();
    clap_complete::generate(a.shell, &mut Cli::command(), "thud", &mut script);
    out.raw(&script)
}

/// `thud man [COMMAND…]`: the man page of thud or of one of its commands, in roff.
pub fn man(a: &ManArgs, out: &mut Out) -> Result<(), CliError> {
    let mut cmd = Cli::command().disable_help_subcommand(true);
    cmd.build();
    for name in &a.command {
        let next = cmd.find_subcommand(name).cloned();
        cmd = next.ok_or_else(|| {
            let known: Vec<&str> = cmd.get_subcommands().map(clap::Command::get_name).collect();
            let what = if known.is_empty() {
                "it has no commands".to_string()
            } else {
                format!("one of: {}", known.join(", "))
            };
            ThudError::invalid("command", format!("'{name}' is not a command of `{}`; {what}", cmd_path(&cmd)))
        })?;
    }
    let mut page = Vec::new();
    clap_mangen::Man::new(cmd).render(&mut page)?;
    out.raw(&title_first(&page))
}

/// "thud export" for the command whose display name is "thud-export".
fn cmd_path(cmd: &clap::Command) -> String {
    cmd.get_display_name().unwrap_or_else(|| cmd.get_name()).replace('-', " ")
}

/// The page with its `.TH` line first: roff's apostrophe preamble (`.ie \n(.g .ds Aq \(aq` /
/// `.el .ds Aq '`, which defines the string the text uses for apostrophes) moves just after
/// it, where it still comes before any text. `man`, `whatis` and `lexgrog` look for `.TH` at
/// the top.
fn title_first(page: &[u8]) -> Vec<u8> {
    let text = String::from_utf8_lossy(page);
    let (preamble, rest): (Vec<&str>, Vec<&str>) =
        text.lines().partition(|l| l.starts_with(".ie \\n(.g .ds Aq") || l.starts_with(".el .ds Aq"));
    let mut lines: Vec<&str> = Vec::with_capacity(preamble.len() + rest.len());
    let th = rest.iter().position(|l| l.starts_with(".TH ")).unwrap_or(0);
    lines.extend(&rest[..=th.min(rest.len().saturating_sub(1))]);
    lines.extend(&preamble);
    lines.extend(rest.iter().skip(th + 1));
    let mut out = lines.join("\n");
    out.push('\n');
    out.into_bytes()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_title_comes_first_and_nothing_is_lost() {
        let page = b".ie \\n(.g .ds Aq \\(aq\n.el .ds Aq '\n.TH thud 1 \"thud 0.1.0\"\n.SH NAME\nthud\n";
        let out = String::from_utf8(title_first(page)).unwrap();
        assert_eq!(out, ".TH thud 1 \"thud 0.1.0\"\n.ie \\n(.g .ds Aq \\(aq\n.el .ds Aq '\n.SH NAME\nthud\n");
    }
}
