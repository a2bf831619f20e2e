//! One meaning per flag name: walking every command's clap definition (`thud::cli::Cli`), a long
//! flag that appears on several commands takes the same kind of value (a switch, one value, a
//! repeatable value), under the same placeholder (its unit or type: `FILE`, `N`, `K/N`), with the
//! same choices, and says the same thing in its help.

use std::collections::BTreeMap;

use clap::{ArgAction, CommandFactory};

/// One appearance of a long flag on a command.
#[derive(Debug, Clone)]
struct Use {
    /// The command path (`thud fit damper`).
    command: String,
    hidden: bool,
    /// What it takes: `switch`, `value`, `values` (repeatable) or `count`.
    takes: &'static str,
    /// Placeholder(s) of the value (its type or unit).
    value_names: Vec<String>,
    /// The choices, if it has a fixed set.
    choices: Vec<String>,
    help: String,
}

fn takes(a: &clap::Arg) -> &'static str {
    match a.get_action() {
        ArgAction::SetTrue | ArgAction::SetFalse => "switch",
        ArgAction::Count => "count",
        ArgAction::Append => "values",
        ArgAction::Help | ArgAction::HelpShort | ArgAction::HelpLong | ArgAction::Version => "info",
        _ if a.get_num_args().is_some_and(|n| n.max_values() > 1) => "values",
        _ => "value",
    }
}

fn walk(cmd: &clap::Command, path: &str, uses: &mut BTreeMap<String, Vec<Use>>) {
    for a in cmd.get_arguments() {
        let Some(long) = a.get_long() else { continue };
        let help = a.get_long_help().or(a.get_help()).map(ToString::to_string).unwrap_or_default();
        uses.entry(long.to_string()).or_default().push(Use {
            command: path.to_string(),
            hidden: a.is_hide_set(),
            takes: takes(a),
            value_names: a.get_value_names().unwrap_or_default().iter().map(ToString::to_string).collect(),
            choices: a.get_possible_values().iter().map(|v| v.get_name().to_string()).collect(),
            help,
        });
    }
    for sub in cmd.get_subcommands() {
        walk(sub, &format!("{path} {}", sub.get_name()), uses);
    }
}

fn every_flag() -> BTreeMap<String, Vec<Use>> {
    let mut cmd = thud::cli::Cli::command();
    cmd.build();
    let mut uses = BTreeMap::new();
    walk(&cmd, "thud", &mut uses);
    uses
}

/// Flags whose help is worded for each command, with what every one of their helps says (the
/// meaning they share, case-insensitive) and why the wording may differ. Any other flag on
/// several commands has one help, word for word.
const WORDED: &[(&str, &[&str], &str)] = &[
    ("json", &["print one json"], "what the object holds is the command's result"),
    ("out", &["file", "standard output"], "the file the command's result is written to"),
    ("force", &["replace"], "what is replaced is the command's output (--out, --svg, --pdf, the pages)"),
    ("preset", &["`thud presets`"], "`pulse` takes the ball, observer and air of the preset"),
    ("main-mass", &["mass", "(kg"], "`pulse` names it as the movable target of Eq 8"),
    ("mass", &["mass", "(kg"], "`pulse` calls the ball a sphere"),
    ("sphere", &["material"], "`pulse` lists the materials, the design says what follows from one"),
    ("source", &["reflecting surfaces"], "`pulse` lists the choices"),
    ("theta", &["observer angle", "degrees"], "`pulse` says where it is measured from"),
    ("u0", &["u0", "(m/s)"], "`export` says which of its artifacts take it"),
    ("data", &["measure"], "a measured decay (CSV): one for the structure, repeated for the damper"),
    ("save", &["save", "name"], "what is saved is the command's fitted design"),
    ("shard", &["part k of n", "thud merge"], "the parts are the command's (grid cells, values)"),
    ("continuation", &["rising then falling"], "from the previous frequency (or value)"),
    ("ensemble", &["ball offsets spread evenly over the clearance"], "per run, cell or frequency"),
    ("points", &["points of"], "`export` draws a waveform or a time history"),
    (
        "vary",
        &["name=from:to:n"],
        "`sweep` varies several (repeatable), `bifurcation` one, `continue` over its range (N unused)",
    ),
    ("band", &["inclination bands"], "`merge` defaults to the parts' band"),
    ("freqs", &["forcing frequencies from:to:n"], "`export` says it is of a response"),
    ("gaps", &["gaps from:to:n"], "`export` says which artifacts take it"),
    ("masses", &["impact masses from:to:n"], "the default range is the command's"),
    // `pulse` has a table of its own (one impact of a sphere on a plate), worded for it: the
    // same quantities, in the same units, as the design's.
    ("density", &["density (kg/m³)"], "`pulse`: the sphere's"),
    ("k-hz", &["hertz stiffness k_hz (n/m^1.5)"], "`pulse` gives its default"),
    ("model", &["the model of the world"], "`pulse` says what its physical model measures"),
    ("plate", &["material"], "`pulse`: the plate struck; the design: the enclosure"),
    ("pulse", &["acceleration pulse", "half-sine"], "`pulse` gives its default"),
    ("quad-signs", &["quadrupole wall-image signs"], "`pulse` explains the choices"),
    ("r", &["observer distance", "(m)"], "`pulse` says where it is measured from"),
    ("radius", &["radius (m"], "`pulse`: the sphere's"),
];

/// Placeholders that differ from the flag's elsewhere, with why.
const PLACEHOLDERS: &[(&str, &str, &str, &str)] = &[
    ("out", "thud paper", "DIR|FILE", "`paper all` writes its set of files into a folder; one ID, a file"),
    ("save", "thud design", "DIR", "`design` saves each front design as a design file in a folder"),
];

/// Hidden flags: an old name kept only to answer with the new one, or an old switch kept for
/// scripts. They are refused (tests/it/forced_cli.rs, tests/it/pdf.rs) or do what the default does.
const HIDDEN: &[(&str, &[&str], &str)] = &[
    (
        "force",
        &["thud simulate", "thud response", "thud restitution", "thud fit damper"],
        "the force amplitude's old name, refused with a line naming --force-amplitude",
    ),
    ("pdf", &["thud paper"], "the old name of --with-pdf, refused with a line naming it"),
    ("mouse", &["thud tui"], "the mouse is on by default; the switch of when it was off"),
];

#[test]
fn a_flag_name_means_one_thing_on_every_command() {
    let flags = every_flag();
    assert!(flags.len() > 50, "{} flags: the walk missed commands", flags.len());
    assert!(flags["force-amplitude"].len() >= 12, "{:?}", flags["force-amplitude"]);
    let mut problems = Vec::new();
    for (long, uses) in &flags {
        for u in uses.iter().filter(|u| u.hidden) {
            let known = HIDDEN.iter().any(|(f, cmds, _)| f == long && cmds.contains(&u.command.as_str()));
            if !known {
                problems.push(format!("--{long} is hidden on `{}`: give it a reason in HIDDEN", u.command));
            }
        }
        let shown: Vec<&Use> = uses.iter().filter(|u| !u.hidden && u.takes != "info").collect();
        let Some(first) = shown.first() else { continue };
        for u in &shown[1..] {
            // A value given once or repeatable is one kind of value; a switch is another.
            let kind = |t: &str| if t == "values" { "value" } else { t }.to_string();
            if kind(u.takes) != kind(first.takes) {
                problems.push(format!(
                    "--{long}: a {} on `{}`, a {} on `{}`",
                    u.takes, first.command, first.takes, u.command
                ));
            }
            let excused =
                |u: &Use| PLACEHOLDERS.iter().any(|(f, c, v, _)| f == long && *c == u.command && u.value_names == [*v]);
            if u.value_names != first.value_names && !excused(u) && !excused(first) {
                problems.push(format!(
                    "--{long}: <{}> on `{}`, <{}> on `{}`",
                    first.value_names.join(" "),
                    first.command,
                    u.value_names.join(" "),
                    u.command
                ));
            }
            if u.choices != first.choices {
                problems.push(format!("--{long}: other choices on `{}` than on `{}`", u.command, first.command));
            }
        }
        if shown.iter().all(|u| u.help == first.help) {
            continue;
        }
        match WORDED.iter().find(|(f, _, _)| f == long) {
            None => problems.push(format!(
                "--{long}: its help differs between `{}` and the others: one wording, or a reason in WORDED",
                first.command
            )),
            Some((_, phrases, _)) => {
                for u in &shown {
                    let help = u.help.to_lowercase();
                    for p in phrases.iter().filter(|p| !help.contains(*p)) {
                        problems.push(format!("--{long} on `{}` does not say {p:?}: {}", u.command, u.help));
                    }
                }
            }
        }
    }
    // Every reason is for a flag that still exists (a stale entry would excuse nothing).
    for (f, _, _) in WORDED.iter().chain(HIDDEN.iter()) {
        assert!(flags.contains_key(*f), "--{f} is in an allow-list but on no command");
    }
    assert!(problems.is_empty(), "{} flag(s) with two meanings:\n{}", problems.len(), problems.join("\n"));
}

#[test]
fn the_force_amplitude_and_replace_are_two_names_everywhere() {
    let flags = every_flag();
    // `--force` replaces a file wherever it is shown; the amplitude is `--force-amplitude`.
    for u in flags["force"].iter().filter(|u| !u.hidden) {
        assert_eq!(u.takes, "switch", "{u:?}");
        assert!(u.help.starts_with("Replace") || u.help.contains(": replace"), "{u:?}");
    }
    for u in &flags["force-amplitude"] {
        assert_eq!((u.takes, u.value_names.as_slice()), ("value", &["F0".to_string()][..]), "{u:?}");
    }
    // Every command with a design takes the amplitude under the one name.
    for u in &flags["preset"] {
        // (`fit damper` fits a free decay: no force is a flag of it; the pulse, `thud pulse` and
        // `thud export svg|pdf|wav pulse`, is one impact, with no structure to force.)
        let pulse = u.command.ends_with(" pulse");
        if !pulse && u.command != "thud tui" && u.command != "thud fit damper" {
            assert!(flags["force-amplitude"].iter().any(|a| a.command == u.command), "{}", u.command);
        }
    }
}
