//! Shell integration: `thud completions SHELL` prints a completion script (clap_complete) and
//! `thud man [COMMAND…]` a roff man page (clap_mangen), `thud man --all DIR` every page, all
//! generated from the very clap definitions the command line parses with, so they never drift
//! from it. [`with_hints`] adds the names the shell can offer (presets, materials, paper items,
//! commands) to a copy of those definitions; [`extra_sections`] appends the sections clap_mangen
//! does not write (EXIT STATUS, ENVIRONMENT, FILES, UNITS, EXAMPLES, SEE ALSO).

use std::path::{Path, PathBuf};

use clap::builder::PossibleValuesParser;
use clap::{Arg, Args, Command, CommandFactory};
use clap_complete::Shell;

use super::{Cli, CliError, Out};
use crate::error::ThudError;
use crate::fsio::{self, Overwrite};

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
    #[arg(value_name = "COMMAND", conflicts_with = "all")]
    command: Vec<String>,
    /// Write every page (thud.1, thud-pulse.1, …, thud-export-csv.1, thud-man.1) into DIR,
    /// created if missing; pages already there are kept unless --force (nothing is written then).
    #[arg(long, value_name = "DIR", value_hint = clap::ValueHint::DirPath)]
    all: Option<PathBuf>,
    /// With --all: replace pages of the same names (atomically; never a device or folder).
    #[arg(long, requires = "all")]
    force: bool,
    /// Write every page where man(1) finds it for this thud: `share/man/man1` beside the folder
    /// of the `thud` run (~/.cargo/bin/thud → ~/.cargo/share/man/man1, ~/.local/bin/thud →
    /// ~/.local/share/man/man1; a symbolic link's own folder), or the first folder of MANPATH
    /// when it is set, replacing the pages of an earlier install; then `man thud`.
    #[arg(long, conflicts_with_all = ["all", "command", "force"])]
    install: bool,
}

/// The command line's definitions with the names a shell can offer: preset names for
/// `--preset`, materials for `--sphere`/`--plate`, the items of `thud paper ID` and the commands
/// of `thud man COMMAND`. Only completions and man pages use this copy; the parser keeps its
/// own (which accepts aliases such as `pmma` too).
pub fn with_hints(cmd: Command) -> Command {
    let presets: Vec<&'static str> = crate::presets::names().collect();
    let materials: Vec<&'static str> = crate::contact::MATERIALS.iter().map(|m| m.name).collect();
    let items: Vec<&'static str> = crate::paper::items().map(|i| i.id).chain(std::iter::once("all")).collect();
    let commands: Vec<String> = cmd.get_subcommands().map(|c| c.get_name().to_string()).collect();
    hint(cmd, &|path: &[&str], arg: Arg| match (path, arg.get_id().as_str()) {
        (_, "preset") => arg.value_parser(PossibleValuesParser::new(presets.clone())),
        (_, "sphere" | "plate") => arg.value_parser(PossibleValuesParser::new(materials.clone())),
        (["paper"], "id") => arg.value_parser(PossibleValuesParser::new(items.clone())),
        (["man"], "command") => arg.value_parser(PossibleValuesParser::new(commands.clone())),
        _ => arg,
    })
}

/// `cmd` with `f(path, arg)` applied to every argument of it and of its subcommands (`path`:
/// the subcommand names below the top, e.g. `["export", "csv"]`).
fn hint(cmd: Command, f: &dyn Fn(&[&str], Arg) -> Arg) -> Command {
    fn walk(mut cmd: Command, path: &mut Vec<String>, f: &dyn Fn(&[&str], Arg) -> Arg) -> Command {
        let ids: Vec<String> = cmd.get_arguments().map(|a| a.get_id().to_string()).collect();
        {
            let here: Vec<&str> = path.iter().map(String::as_str).collect();
            for id in ids {
                cmd = cmd.mut_arg(id, |a| f(&here, a));
            }
        }
        let names: Vec<String> = cmd.get_subcommands().map(|c| c.get_name().to_string()).collect();
        for name in names {
            path.push(name.clone());
            let sub = cmd.find_subcommand(&name).cloned();
            if let Some(sub) = sub {
                let sub = walk(sub, path, f);
                cmd = cmd.mut_subcommand(&name, |_| sub);
            }
            path.pop();
        }
        cmd
    }
    walk(cmd, &mut Vec::new(), f)
}

/// The command line's definitions for pages: hinted, built, without the `help` subcommand.
fn page_root() -> Command {
    let mut cmd = with_hints(Cli::command()).disable_help_subcommand(true);
    cmd.build();
    cmd
}

/// `thud completions SHELL`: the completion script on stdout.
pub fn completions(a: &CompletionsArgs, out: &mut Out) -> Result<(), CliError> {
    let mut script = Vec::new();
    clap_complete::generate(a.shell, &mut with_hints(Cli::command()), "thud", &mut script);
    if a.shell == Shell::Zsh {
        script = zsh_value_names(&String::from_utf8_lossy(&script)).into_bytes();
    }
    out.raw(&script)
}

/// The zsh script with the colons of value names escaped: `_arguments` reads
/// `--vary=[help]:MESSAGE:ACTION`, so an unescaped `NAME=FROM:TO:N` made `TO` the action and
/// zsh ran it as a command ("command not found: TO"). clap_complete escapes the help's colons
/// but not the value name's.
fn zsh_value_names(script: &str) -> String {
    fn names(cmd: &Command, into: &mut Vec<String>) {
        for arg in cmd.get_arguments() {
            for n in arg.get_value_names().unwrap_or_default() {
                if n.contains(':') && !into.iter().any(|m| m == n.as_str()) {
                    into.push(n.to_string());
                }
            }
        }
        for sub in cmd.get_subcommands() {
            names(sub, into);
        }
    }
    let mut found = Vec::new();
    names(&with_hints(Cli::command()), &mut found);
    let mut out = script.to_string();
    for n in found {
        out = out.replace(&format!("]:{n}:"), &format!("]:{}:", n.replace(':', "\\:")));
    }
    out
}

/// `thud man [COMMAND…]`: the man page of thud or of one of its commands, in roff; `thud man
/// --all DIR`: every page into DIR.
pub fn man(a: &ManArgs, out: &mut Out) -> Result<(), CliError> {
    if let Some(dir) = &a.all {
        return write_all(dir, Overwrite::from_force(a.force), "--all");
    }
    if a.install {
        return write_all(&install_dir()?, Overwrite::Replace, "--install");
    }
    let mut cmd = page_root();
    let mut path: Vec<String> = Vec::new();
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
        path.push(name.clone());
    }
    out.raw(&page(&cmd, &path)?)
}

/// Where `--install` writes: the first folder of `MANPATH` if it is set (man then searches it),
/// else `share/man/man1` beside the folder of the `thud` that was run, as it was run (a symbolic
/// link's own folder, not its target's: man-db's manpath adds `DIR/../share/man` for every `DIR`
/// of `PATH`, so the pages are found for the `thud` on `PATH`, a link to a binary elsewhere too).
fn install_dir() -> Result<PathBuf, CliError> {
    if let Some(first) =
        std::env::var_os("MANPATH").and_then(|m| std::env::split_paths(&m).find(|p| !p.as_os_str().is_empty()))
    {
        return Ok(first.join("man1"));
    }
    let bin = invoked_dir().map_or_else(
        || {
            let exe = std::env::current_exe()
                .map_err(|e| ThudError::invalid("--install", format!("cannot find the running thud binary: {e}")))?;
            exe.parent().map(Path::to_path_buf).ok_or_else(|| {
                ThudError::invalid("--install", format!("{} has no folder above its own", fsio::shown(&exe)))
            })
        },
        Ok,
    )?;
    let prefix = bin
        .parent()
        .ok_or_else(|| ThudError::invalid("--install", format!("{} has no folder above its own", fsio::shown(&bin))))?;
    Ok(prefix.join("share").join("man").join("man1"))
}

/// The folder of the `thud` that was run, as the shell found it: the path it was run by (made
/// absolute, links kept), or the first folder of `PATH` holding a file of its name.
fn invoked_dir() -> Option<PathBuf> {
    let argv0 = PathBuf::from(std::env::args_os().next()?);
    let found = if argv0.components().count() > 1 {
        std::env::current_dir().ok()?.join(&argv0)
    } else {
        let path = std::env::var_os("PATH")?;
        std::env::split_paths(&path).map(|dir| dir.join(&argv0)).find(|p| p.is_file() && p.is_absolute())?
    };
    found.parent().map(Path::to_path_buf)
}

/// Every page: (file name, the command's path below `thud`, the command), thud(1) first, each
/// command before its subcommands.
fn all_pages() -> Vec<(String, Vec<String>, Command)> {
    fn walk(cmd: &Command, path: &mut Vec<String>, pages: &mut Vec<(String, Vec<String>, Command)>) {
        let name = if path.is_empty() { "thud".to_string() } else { format!("thud-{}", path.join("-")) };
        pages.push((format!("{name}.1"), path.clone(), cmd.clone()));
        for sub in cmd.get_subcommands() {
            path.push(sub.get_name().to_string());
            walk(sub, path, pages);
            path.pop();
        }
    }
    let mut pages = Vec::new();
    walk(&page_root(), &mut Vec::new(), &mut pages);
    pages
}

/// `thud man --all DIR`: every page into `dir` through [`fsio::write`]. Every target is checked
/// first, so a refused page leaves the folder as it was.
fn write_all(dir: &Path, overwrite: Overwrite, flag: &str) -> Result<(), CliError> {
    let pages = all_pages();
    for (file, _, _) in &pages {
        let target = dir.join(file);
        fsio::check_target(&target, overwrite).map_err(|e| page_error(&target, &e, flag))?;
    }
    for (file, path, cmd) in &pages {
        let target = dir.join(file);
        fsio::write(&target, &page(cmd, path)?, overwrite).map_err(|e| page_error(&target, &e, flag))?;
    }
    super::warn(&format!("wrote {} man pages to {}", pages.len(), dir.display()));
    Ok(())
}

/// A refused or failed page as the one-line error of `--out` writes, naming `flag` (`--all`,
/// `--install`).
fn page_error(target: &Path, e: &fsio::FsError, flag: &str) -> ThudError {
    super::export::out_error(target, e).renamed(flag)
}

/// The page of `cmd` (at `path` below thud): clap_mangen's sections, then [`extra_sections`].
fn page(cmd: &Command, path: &[String]) -> Result<Vec<u8>, CliError> {
    let mut page = Vec::new();
    clap_mangen::Man::new(cmd.clone()).render(&mut page)?;
    let mut page = title_first(&page);
    page.extend_from_slice(extra_sections(cmd, path).as_bytes());
    Ok(page)
}

/// Text for roff: backslashes and hyphens escaped, no line starting with a control character.
fn roff(text: &str) -> String {
    let t = text.replace('\\', "\\e").replace('-', "\\-");
    if t.starts_with('.') || t.starts_with('\'') {
        format!("\\&{t}")
    } else {
        t
    }
}

/// Examples of the command at `path` (a command line each, then what it does).
fn examples(path: &[String]) -> Vec<(&'static str, &'static str)> {
    let p: Vec<&str> = path.iter().map(String::as_str).collect();
    match p.as_slice() {
        [] => vec![
            ("thud", "open the explorer"),
            ("thud simulate --preset paper-fig9 --json", "one design, every impact, as JSON"),
            ("thud sweep --csv > chart.csv", "the design chart, one row per mass and gap"),
            ("thud paper all --out paper/", "every table and figure of the paper"),
        ],
        ["pulse"] => vec![("thud pulse --radius 19.05mm --mass 40.5g --u0 1.4 --json", "the paper's Fig 2 impact")],
        ["simulate"] => vec![
            ("thud simulate --preset paper-fig9", "the Fig 9 free vibration, summarised"),
            ("thud simulate --mass 50g --gap 3cm --csv --samples 501", "the time history as CSV"),
            ("thud simulate --ensemble 16 --json", "16 runs from spread ball offsets"),
        ],
        ["sweep"] => vec![
            ("thud sweep --masses 30g:100g:20 --gaps 2cm:5cm:20", "the zone map and Table 5"),
            ("thud sweep --shard 0/8 --out part0.jsonl", "part 0 of 8 for `thud merge`"),
            ("thud sweep --vary v0=1:3:5 --vary c1=10:60:6 --csv", "a study over any parameters, one row per cell"),
        ],
        ["bifurcation"] => vec![(
            "thud bifurcation --preset forced-rattle --vary f=3Hz:8Hz:200 --csv --out bif.csv --svg bif.svg",
            "x(kT) and the impacts against f, each value's orbit",
        )],
        ["impact-map"] => vec![("thud impact-map --preset forced-rattle --svg map.svg", "phase against impact speed")],
        ["basins"] => vec![("thud basins --preset forced-rattle --grid 20 --svg basins.svg", "which start reaches which orbit")],
        ["merge"] => vec![("thud merge part*.jsonl --json", "the whole chart from its parts")],
        ["response"] => vec![("thud response --force-amplitude 1N --freqs 3Hz:8Hz:101 --csv", "amplitude and Leq against frequency")],
        ["restitution"] => vec![("thud restitution --json", "restitution against impact mass (Fig 13)")],
        ["paper"] => vec![
            ("thud paper table3", "Table 3 beside the paper's numbers"),
            ("thud paper --list", "every item"),
            ("thud paper all --with-pdf --out paper/", "every item as CSV, its figure as SVG and PDF"),
        ],
        ["export"] | ["export", "wav"] => vec![
            ("thud export wav --preset steel-ball --out steel.wav", "the rattle, 16-bit PCM, 20 Pa full scale"),
            ("thud export wav --format float --out s.wav", "32-bit float, not clipped"),
        ],
        ["export", "csv"] => vec![("thud export csv impacts --preset paper-fig9 --out impacts.csv", "every impact")],
        ["export", "svg"] => vec![("thud export svg chart --out chart.svg", "the zone chart as a figure")],
        ["export", "pdf"] => vec![(
            "thud export pdf chart --no-title --size 1200x800 --out chart.pdf",
            "the zone chart as a PDF for a paper, font embedded",
        )],
        ["presets"] => vec![("thud presets", "the named starting designs")],
        ["tui"] => vec![("thud tui --preset paper-fig9", "the explorer on a preset")],
        ["limits"] => vec![("thud limits --json", "every range and work cap")],
        ["completions"] => vec![(
            "mkdir -p ~/.local/share/bash-completion/completions && thud completions bash > ~/.local/share/bash-completion/completions/thud",
            "bash completion",
        )],
        ["man", ..] => vec![
            ("thud man --install", "every page where man(1) finds it; then man thud"),
            ("thud man --all ~/.local/share/man/man1", "every page into a folder"),
        ],
        _ => vec![],
    }
}

/// EXIT STATUS, ENVIRONMENT, FILES, UNITS, EXAMPLES and SEE ALSO of the page of `cmd` (at
/// `path` below thud), in roff.
fn extra_sections(cmd: &Command, path: &[String]) -> String {
    let mut s = String::new();
    let item = |s: &mut String, tag: &str, text: &str| {
        *s += &format!(".TP\n{}\n{}\n", roff(tag), roff(text));
    };
    s += ".SH \"EXIT STATUS\"\n";
    item(&mut s, "0", "Success (also when standard output is closed early, as by head).");
    item(&mut s, "1", "An I/O failure, an internal error or a non-finite result.");
    item(
        &mut s,
        "2",
        "Bad input: a value outside its range, an unknown flag, a file that exists without --force. One line on standard error names what was typed.",
    );
    item(
        &mut s,
        "128+N",
        "Stopped by signal N (130 SIGINT, 143 SIGTERM, 129 SIGHUP); the terminal is restored and no partial file is left.",
    );
    s += ".SH ENVIRONMENT\n";
    item(&mut s, "NO_COLOR", "When set to anything non-empty, the explorer draws without colour.");
    item(
        &mut s,
        "TERM, COLORTERM",
        "Unless COLORTERM is set or TERM names 256 colours (xterm-256color, tmux-256color, *-direct), the explorer sends only the classic 16-colour codes.",
    );
    item(
        &mut s,
        "RAYON_NUM_THREADS",
        "Worker threads for sweeps, ensembles and responses when --threads is not given (else one per CPU).",
    );
    item(&mut s, "XDG_CONFIG_HOME", "Where thud/config.toml is read from (default ~/.config).");
    item(&mut s, "XDG_DATA_HOME", "Where saved designs are kept, in thud/designs/ (default ~/.local/share).");
    s += ".SH FILES\n";
    item(
        &mut s,
        "$XDG_CONFIG_HOME/thud/config.toml",
        "Settings: theme, markers, zone thresholds, key overrides. A file that fails to parse is reported and never overwritten.",
    );
    item(
        &mut s,
        "$XDG_DATA_HOME/thud/designs/NAME.toml",
        "Designs saved from the explorer, in the format of the presets.",
    );
    s += &format!(
        ".PP\n{}\n",
        roff("Every file thud writes is written whole or not at all; an existing file is kept unless --force.")
    );
    s += ".SH UNITS\n";
    s += &format!(
        ".PP\n{}\n",
        roff("A plain number is SI (kg, m, s, N, Pa, m/s, N/m^1.5); angles are degrees, L* is in dB, e* in cm/s. A number may carry its unit: 40.5g, 19.05mm, 4cm, 45deg, 250ms, 5Hz, 1N. Every CSV column and JSON key names its unit (mass_kg, gap_m, spl_max_db; dB re 20 uPa); zones are numbers 1 to 4.")
    );
    let ex = examples(path);
    if !ex.is_empty() {
        s += ".SH EXAMPLES\n";
        for (line, what) in ex {
            s += &format!(".TP\n\\fB{}\\fR\n{}\n", roff(line), roff(what));
        }
    }
    s += ".SH \"SEE ALSO\"\n";
    let mut refs: Vec<String> = Vec::new();
    if !path.is_empty() {
        refs.push("thud(1)".into());
    }
    if path.len() > 1 {
        refs.push(format!("thud-{}(1)", path[..path.len() - 1].join("-")));
    }
    let here = if path.is_empty() { "thud".to_string() } else { format!("thud-{}", path.join("-")) };
    refs.extend(cmd.get_subcommands().map(|c| format!("{here}-{}(1)", c.get_name())));
    if refs.is_empty() {
        refs.push("thud(1)".into());
    }
    s += &format!(".PP\n{}\n", roff(&refs.join(", ")));
    s += &format!(".PP\n{}\n", roff("README.md, the guide (docs/guide, a book with mdbook build docs) and docs/model.md in the source distribution."));
    s
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
