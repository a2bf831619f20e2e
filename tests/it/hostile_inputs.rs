#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test or benchmark fails
//! Hostile and careless input: every numeric flag is range
//! checked, every run is budgeted before it starts, no NaN/∞ is ever printed as a result, and
//! every error is one line on stderr naming the flag the user typed. Process runs of the built
//! binary with HOME and the XDG folders in a temporary folder; each run is killed after 40 s of
//! its own CPU time (a failure): a budget of work that a loaded machine does not stretch, as a
//! wall-clock bound would.

use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Duration;

use proptest::prelude::*;

use crate::support::stranger::Stranger;
use crate::support::wait;
use wait::wait_within_cpu;

/// What one run of thud did.
#[derive(Debug)]
struct Ran {
    code: i32,
    stdout: String,
    stderr: String,
}

/// A thud command with HOME and the XDG folders inside `home`.
fn command(home: &Path, args: &[&str]) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_thud"));
    c.args(args)
        .env("HOME", home)
        .env("XDG_CONFIG_HOME", home.join("config"))
        .env("XDG_DATA_HOME", home.join("data"))
        .env_remove("XDG_CONFIG_DIRS")
        .stdin(Stdio::null());
    c
}

/// The CPU time (user and system, all threads) one run may use. Every run here is a quick
/// command (a few designs, three frequencies) or a refusal; the budget that keeps it quick is
/// the command's own work estimate, checked before it starts, and this bound catches a run
/// that escaped it. It is CPU time, not wall time, so a machine shared by other builds does not
/// fail the test; performance is measured by the benchmarks. 40 s: the 20 s of wall time this
/// bound replaces, on the two cores a run's threads share.
const CPU_BUDGET: Duration = Duration::from_secs(40);

/// The wall-time guard of one run, for a run that blocks without computing (which no CPU bound
/// sees). Ten minutes: on two cores shared by a dozen compilers a 20 s CPU run can take several.
const HANG_GUARD: Duration = Duration::from_secs(600);

/// Runs thud in `home`; panics (a test failure) if it uses more than [`CPU_BUDGET`] of CPU time
/// or blocks past [`HANG_GUARD`].
fn thud_in(home: &Path, args: &[&str]) -> Ran {
    let child = command(home, args).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().expect("run thud");
    let out = wait_within_cpu(child, CPU_BUDGET, HANG_GUARD, &format!("{args:?}"));
    Ran {
        code: out.status.code().unwrap_or(-1),
        stdout: String::from_utf8_lossy(&out.stdout).into(),
        stderr: String::from_utf8_lossy(&out.stderr).into(),
    }
}

fn thud(args: &[&str]) -> Ran {
    let home = tempfile::tempdir().unwrap();
    thud_in(home.path(), args)
}

/// Asserts a refusal: exit 2, exactly one stderr line, no stdout, and the line contains every
/// one of `needles` (the flag first).
fn assert_refused(args: &[&str], needles: &[&str]) {
    let r = thud(args);
    assert_eq!(r.code, 2, "{args:?}: exit {} stderr {}", r.code, r.stderr);
    assert_eq!(r.stderr.lines().count(), 1, "{args:?}: {}", r.stderr);
    assert!(r.stdout.is_empty(), "{args:?} printed: {}", r.stdout);
    assert!(r.stderr.starts_with("thud: "), "{args:?}: {}", r.stderr);
    for n in needles {
        assert!(r.stderr.contains(n), "{args:?}: '{n}' not in: {}", r.stderr);
    }
}

/// The first word of `text` that is how Rust prints NaN or ∞.
fn non_finite_word(text: &str) -> Option<&str> {
    text.split(|c: char| !c.is_ascii_alphanumeric()).find(|w| *w == "NaN" || *w == "inf")
}

// ---- What was found 2: work and memory are unbounded -------------------------------------

#[test]
fn newmark_steps_are_budgeted_before_the_run() {
    // Used to run for hours.
    assert_refused(
        &["simulate", "--solver", "newmark", "--dt", "1e-12"],
        &["--dt 1e-12", "2e12 Newmark steps exceed the limit of 1e9", "--dt ≥ 2e-9", "--no-limit"],
    );
    // Used to hang.
    assert_refused(&["simulate", "--solver", "newmark", "--dt", "1e-308"], &["--dt", "1e-308", "1e-14 to 0.001 s"]);
    assert_refused(&["simulate", "--solver", "newmark", "--duration", "1000"], &["--duration 1000", "Newmark steps"]);
}

#[test]
fn no_limit_lifts_the_caps() {
    // 1e6 steps is small, but over no cap either way: the refusal above needs the cap, and
    // --no-limit must let a capped run through. A short --duration keeps it quick.
    let r = thud(&["simulate", "--solver", "newmark", "--dt", "1e-12", "--duration", "2e-6", "--no-limit", "--json"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let v: serde_json::Value = serde_json::from_str(&r.stdout).unwrap();
    assert_eq!(v["design"]["solver"]["newmark"]["dt_s"].as_f64(), Some(1e-12));
    let refused = thud(&["simulate", "--solver", "newmark", "--dt", "1e-12", "--duration", "2e-2"]);
    assert_eq!(refused.code, 2, "{}", refused.stderr);
}

#[test]
fn wav_length_is_budgeted() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("p.wav");
    let out = out.to_str().unwrap();
    // Used to panic with "capacity overflow".
    assert_refused(&["export", "wav", "--duration", "1e308", "--out", out], &["--duration", "1e308"]);
    // Used to abort out of memory.
    assert_refused(
        &["export", "wav", "--duration", "1e4", "--out", out],
        &["--duration 1e4", "4.8e8 WAV samples exceed the limit of 4.8e7"],
    );
    assert!(!Path::new(out).exists());
}

#[test]
fn history_samples_are_budgeted() {
    // Used to abort after allocating 3.5 GB.
    assert_refused(
        &["simulate", "--csv", "--samples", "100000000"],
        &["--samples 100000000", "1e8 history samples exceed the limit of 1e7"],
    );
    assert_refused(&["pulse", "--points", "1e9"], &["--points 1e9", "waveform points exceed the limit"]);
}

#[test]
fn sweeps_are_budgeted() {
    // Used to hang.
    assert_refused(&["sweep", "--band", "1e-308"], &["--band", "1e-308", "0.001 to 1000 cm/s"]);
    // Used to run ~10 minutes with no progress shown.
    assert_refused(
        &["sweep", "--masses", "30g:100g:1000", "--gaps", "2cm:5cm:1000"],
        &["--masses/--gaps 1000 × 1000", "sweep cells exceed the limit"],
    );
    assert_refused(&["sweep", "--duration", "1000"], &["--duration 1000", "cell-seconds exceed the limit"]);
    assert_refused(&["sweep", "--solver", "newmark"], &["--dt", "Newmark steps exceed the limit"]);
}

#[test]
fn main_mass_cycles_are_budgeted() {
    // 5e11 cycles of a 500 kHz structure: would hang and then run out of memory.
    assert_refused(
        &["simulate", "--duration", "1e6", "--c", "0", "--k", "1e10", "--main-mass", "1e-3"],
        &["--duration 1e6", "main-mass cycles exceed the limit of 1e7"],
    );
}

#[test]
fn a_run_cut_short_by_its_work_cap_says_so() {
    // The issue's case: a v0 of 200 m/s is outside the physical range, so it is refused...
    assert_refused(&["simulate", "--duration", "1e6", "--v0", "200", "--json"], &["--v0", "200 m/s", "-100 to 100"]);
    // ... and an in-range design that still hits the solver's cap (a 10 µm gap rattles) says it.
    let r = thud(&["simulate", "--duration", "100", "--gap", "10um", "--json"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let v: serde_json::Value = serde_json::from_str(&r.stdout).unwrap();
    let t = v["final_time_s"].as_f64().unwrap();
    assert!(t < 100.0, "final time {t}");
    assert_eq!(v["truncated"], serde_json::Value::Bool(true));
    let why = v["truncation_reason"].as_str().unwrap();
    assert!(why.contains("work cap") && why.contains("100 s"), "{why}");
    let text = thud(&["simulate", "--duration", "100", "--gap", "10um"]);
    assert_eq!(text.code, 0);
    assert!(text.stdout.lines().any(|l| l.starts_with("TRUNCATED") && l.contains("work cap")), "{}", text.stdout);
    // A run that reaches its duration is not truncated.
    let full: serde_json::Value = serde_json::from_str(&thud(&["simulate", "--json"]).stdout).unwrap();
    assert_eq!(full["truncated"], serde_json::Value::Bool(false));
    assert!(full["truncation_reason"].is_null());
}

#[test]
fn progress_is_silent_when_stderr_is_not_a_terminal() {
    let r = thud(&["sweep", "--masses", "30g:60g:3", "--gaps", "2cm:3cm:2", "--csv"]);
    assert_eq!(r.code, 0);
    assert!(r.stderr.is_empty(), "{}", r.stderr);
}

// ---- What was found 3: wrong numbers printed as results -----------------------------------

#[test]
fn non_finite_results_are_refused_as_out_of_range_inputs() {
    let dir = tempfile::tempdir().unwrap();
    let f = |name: &str| dir.path().join(name).to_str().unwrap().to_string();
    let (csv, wav) = (f("e.csv"), f("p.wav"));
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["pulse", "--sound-speed", "1e308"], "--sound-speed"),
        (vec!["pulse", "--sound-speed", "1e-308"], "--sound-speed"),
        (vec!["pulse", "--rho-c", "1e308"], "--rho-c"),
        (vec!["pulse", "--k-hz", "1e-308"], "--k-hz"),
        (vec!["pulse", "--u0", "1e308"], "--u0"),
        (vec!["simulate", "--r", "1e308"], "--r"),
        (vec!["simulate", "--v0", "1e308"], "--v0"),
        (vec!["simulate", "--k", "1e308"], "--k"),
        (vec!["simulate", "--main-mass", "1e-308"], "--main-mass"),
        (vec!["export", "csv", "history", "--k", "1e308", "--out", &csv], "--k"),
        (vec!["export", "wav", "--full-scale", "1e-308", "--out", &wav], "--full-scale"),
        (vec!["export", "wav", "--radius", "1e-308", "--out", &wav], "--radius"),
    ];
    for (args, flag) in &cases {
        assert_refused(args, &[&format!("invalid {flag}: ")]);
    }
    assert!(!Path::new(&csv).exists() && !Path::new(&wav).exists(), "a file was written");
}

// ---- What was found 4: errors that name the wrong thing ------------------------------------

#[test]
fn errors_name_the_flag_the_user_typed() {
    // Used to say "invalid r: … sphere's radius inf m" and "invalid radius: 0 m".
    assert_refused(&["simulate", "--mass", "1e308"], &["invalid --mass: 1e308 kg is out of range", "0.0001 to 100 kg"]);
    assert_refused(&["simulate", "--density", "1e308"], &["invalid --density: 1e308 kg/m^3"]);
    // A ball grown into the observer is the ball's flag, not r.
    assert_refused(&["simulate", "--mass", "100", "--density", "10"], &["invalid --mass: ", "reaches the observer"]);
    assert_refused(&["pulse", "--sphere", "tungsten-carbide", "--radius", "2"], &["invalid --radius: ", "100 kg"]);
    // Engine errors are named by flag too.
    assert_refused(&["simulate", "--r", "1cm"], &["invalid --r: ", "inside the sphere"]);
}

#[test]
fn count_flags_give_one_line_not_clap_s_three() {
    for (args, flag) in [
        (vec!["pulse", "--points", "abc"], "--points"),
        (vec!["pulse", "--points", "-5"], "--points"),
        (vec!["simulate", "--csv", "--samples", "-1"], "--samples"),
        (vec!["simulate", "--csv", "--samples", "2.5"], "--samples"),
        (vec!["simulate", "--samples", "-1"], "--samples"),
        (vec!["simulate", "--show", "x"], "--show"),
        (vec!["simulate", "--show", "1e308"], "--show"),
        (vec!["export", "csv", "waveform", "--points", "lots", "--out", "x.csv"], "--points"),
    ] {
        assert_refused(&args, &[flag]);
    }
}

#[test]
fn clap_s_own_errors_are_one_line() {
    assert_refused(&["simulate", "--mas", "3"], &["'--mas'", "--mass"]);
    assert_refused(&["simulate", "--solver", "rk4"], &["rk4", "--solver"]);
    assert_refused(&["export"], &["thud export", "csv, svg, pdf, wav"]);
    assert_refused(&["paper"], &["<ID>"]);
    assert_refused(&["nonesuch"], &["nonesuch"]);
}

#[test]
fn long_values_are_cut_and_stay_on_one_line() {
    let long = "x".repeat(100_000);
    assert_refused(&["simulate", "--mass", &long], &["invalid --mass: ", "…"]);
    let r = thud(&["simulate", "--mass", &long]);
    assert!(r.stderr.chars().count() < 200, "{} characters", r.stderr.chars().count());
    let r = thud(&["simulate", "--preset", &long]);
    assert_eq!(r.stderr.lines().count(), 1);
    assert!(r.stderr.chars().count() < 600, "{} characters", r.stderr.chars().count());
    assert_refused(&["simulate", "--preset", "a\nsecond line"], &["--preset", "a\\nsecond line"]);
}

#[test]
fn config_thresholds_out_of_range_fall_back_with_a_warning() {
    for (key, value) in [("e_star_cm_s", "-5"), ("l_star_db", "1e308")] {
        let home = tempfile::tempdir().unwrap();
        let dir = home.path().join("config").join("thud");
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("config.toml"), format!("[thresholds]\n{key} = {value}\n")).unwrap();
        let r = thud_in(home.path(), &["simulate", "--json"]);
        assert_eq!(r.code, 0, "{}", r.stderr);
        assert_eq!(r.stderr.lines().count(), 1, "{}", r.stderr);
        assert!(r.stderr.contains("warning") && r.stderr.contains(key), "{}", r.stderr);
        let v: serde_json::Value = serde_json::from_str(&r.stdout).unwrap();
        let t = &v["design"]["thresholds"];
        assert_eq!((t["spl_db"].as_f64(), t["inclination_cm_s"].as_f64()), (Some(103.0), Some(0.9)), "{key}");
    }
}

// ---- Output: a closed pipe is quiet, another write error is reported -----------------------

#[test]
fn a_closed_pipe_ends_quietly() {
    for args in [
        &["simulate", "--csv", "--samples", "1000000"][..],
        &["pulse", "--json", "--points", "1000000"][..],
        &["paper", "table1"][..],
    ] {
        let home = tempfile::tempdir().unwrap();
        let mut child =
            command(home.path(), args).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().expect("run thud");
        let mut first = String::new();
        BufReader::new(child.stdout.take().unwrap()).read_line(&mut first).unwrap();
        assert!(!first.is_empty());
        // The reader is gone: like `| head -1`.
        let out = child.wait_with_output().unwrap();
        let code = out.status.code();
        assert!(code == Some(0) || code == Some(141) || code.is_none(), "{args:?}: {code:?}");
        assert!(out.stderr.is_empty(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    }
}

#[test]
fn a_failed_write_to_stdout_is_reported() {
    let Ok(full) = std::fs::OpenOptions::new().write(true).open("/dev/full") else {
        crate::support::skip::skip("/dev/full cannot be opened here");
        return;
    };
    let home = tempfile::tempdir().unwrap();
    let out = command(home.path(), &["simulate", "--csv"]).stdout(full).stderr(Stdio::piped()).output().unwrap();
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("cannot write the output"), "{err}");
}

// ---- The ranges: every bound of every flag gives finite numbers or a one-line refusal -------

/// The numeric flags of each command, with a unit suffix of the wrong kind for each. A flag
/// whose value is more than a number (`--vary f=3Hz:4Hz:N`) takes the hostile value in its
/// `template`, at `{}`; `wrong_unit` is then a whole value with one part of the wrong kind.
#[derive(Clone, Copy)]
struct Flag {
    name: &'static str,
    range: Option<thud::limits::Range>,
    wrong_unit: &'static str,
    template: &'static str,
}

const fn flag(name: &'static str, range: Option<thud::limits::Range>, wrong_unit: &'static str) -> Flag {
    Flag { name, range, wrong_unit, template: "{}" }
}

/// A flag whose hostile value is one part of a whole value (see [`Flag`]).
const fn part(name: &'static str, template: &'static str, wrong_unit: &'static str) -> Flag {
    Flag { name, range: None, wrong_unit, template }
}

impl Flag {
    /// The flag's whole value around `value`.
    fn value(&self, value: &str) -> String {
        self.template.replacen("{}", value, 1)
    }
}

use thud::limits as L;

/// The design flags: every row of the engine's table ([`thud::params::DESIGN`]) that takes a
/// number, with its range, so a new row is tested without being listed here; a unit of the
/// wrong kind for each (a length for a mass or a count, a mass otherwise). The force is in each
/// command's own list instead, spelled as that command spells it (`--force-amplitude` where
/// `--force` means overwrite).
fn design_flags() -> Vec<Flag> {
    use thud::params::{Accepts, DESIGN};
    DESIGN
        .iter()
        .filter(|p| p.name != "force")
        .filter_map(|p| {
            let wrong_unit = match p.accepts {
                Accepts::Quantity { kind: thud::units::Kind::Mass, .. } | Accepts::Count { .. } => "3cm",
                _ => "3kg",
            };
            Some(flag(p.name, Some(*p.range()?), wrong_unit))
        })
        .collect()
}

const PULSE_FLAGS: &[Flag] = &[
    flag("radius", Some(L::RADIUS), "3g"),
    flag("mass", Some(L::MASS), "3cm"),
    flag("u0", Some(L::U0), "3kg"),
    flag("k-hz", Some(L::K_HZ), "3kg"),
    flag("main-mass", Some(L::MAIN_MASS), "3m"),
    flag("r", Some(L::R), "3g"),
    flag("theta", Some(L::THETA), "3m"),
    flag("rho-c", Some(L::RHO_C), "3kg"),
    flag("sound-speed", Some(L::C_SOUND), "3kg"),
    flag("points", Some(L::POINTS), "3cm"),
];

/// `export wav pulse` takes the pulse's flags but `--points`, and the sound's.
fn pulse_sound_flags() -> Vec<Flag> {
    let pulse = PULSE_FLAGS.iter().filter(|f| f.name != "points").copied();
    pulse.chain([flag("full-scale", Some(L::FULL_SCALE), "3kg")]).collect()
}

/// A command under test: its base arguments, its own numeric flags, whether the design flags
/// apply, and its output modes.
type Cmd = (Vec<&'static str>, Vec<Flag>, bool, Vec<&'static str>);

/// The search's own flags of `thud design`, each one part of its value hostile.
const DESIGN_SEARCH_FLAGS: &[Flag] = &[
    part("evaluations", "{}", "3cm"),
    part("vary", "mass=20g:{}", "mass=20g:3cm"),
    part("require", "spl_max_db<={}", "mass<=3cm"),
    part("require", "mass>={}", "spl_max_db>=3kg"),
    part("choose", "sphere=steel,{}", "sphere=steel,3kg"),
    part("over", "freqs=4Hz:6Hz:{}", "freqs=4Hz:6kg:3"),
    part("ensemble", "{}", "3cm"),
    part("quantile", "{}", "3cm"),
    part("reference", "{},0", "3kg,0"),
];

/// The commands under test.
fn commands() -> Vec<Cmd> {
    vec![
        (vec!["pulse"], PULSE_FLAGS.to_vec(), false, vec!["", "--json", "--csv"]),
        (
            vec!["simulate"],
            vec![
                flag("samples", Some(L::SAMPLES), "3cm"),
                flag("show", Some(L::SHOW), "3cm"),
                flag("force", Some(L::FORCE), "3m"),
                flag("ensemble", Some(L::ENSEMBLE), "3cm"),
            ],
            true,
            vec!["", "--json", "--csv"],
        ),
        (
            vec!["sweep"],
            vec![
                flag("masses", None, "30g:60g:3cm"),
                flag("gaps", None, "2cm:3g:2"),
                flag("band", Some(L::BAND), "3kg"),
                flag("force-amplitude", Some(L::FORCE), "3m"),
                flag("ensemble", Some(L::ENSEMBLE), "3cm"),
            ],
            true,
            vec!["", "--json", "--csv"],
        ),
        (
            vec!["response"],
            vec![
                flag("freqs", None, "4Hz:6kg:3"),
                flag("force", Some(L::FORCE), "3m"),
                flag("ensemble", Some(L::ENSEMBLE), "3cm"),
            ],
            true,
            vec!["", "--json", "--csv"],
        ),
        (
            vec!["restitution"],
            vec![
                flag("u0", Some(L::U0), "3kg"),
                flag("masses", None, "5g:100cm:4"),
                flag("target", Some(L::TARGET), "3kg"),
            ],
            true,
            vec!["", "--json", "--csv"],
        ),
        (
            vec!["export", "csv", "history"],
            vec![
                flag("points", Some(L::POINTS), "3cm"),
                flag("u0", Some(L::U0), "3kg"),
                flag("force-amplitude", Some(L::FORCE), "3m"),
            ],
            true,
            vec![""],
        ),
        (
            vec!["export", "svg", "waveform"],
            vec![flag("points", Some(L::POINTS), "3cm"), flag("u0", Some(L::U0), "3kg")],
            true,
            vec![""],
        ),
        (
            vec!["export", "wav"],
            vec![flag("full-scale", Some(L::FULL_SCALE), "3kg"), flag("u0", Some(L::U0), "3kg")],
            true,
            vec![""],
        ),
        (
            vec!["continue"],
            vec![part("vary", "f=3Hz:4Hz:{}", "f=3Hz:4kg:3"), part("vary", "f={}:4Hz:3", "f=3kg:4Hz:3")],
            false,
            vec!["", "--json"],
        ),
        (
            vec!["orbit"],
            vec![
                part("period", "{}", "3cm"),
                part("guess", "{},0,0,0", "3kg,0,0,0"),
                part("guess", "0,{},0,0", "0,3cm,0,0"),
            ],
            false,
            vec!["", "--json"],
        ),
        (vec!["design"], DESIGN_SEARCH_FLAGS.to_vec(), false, vec!["", "--json", "--csv"]),
        (vec!["export", "svg", "pulse"], PULSE_FLAGS.to_vec(), false, vec![""]),
        (vec!["export", "pdf", "pulse"], PULSE_FLAGS.to_vec(), false, vec![""]),
        (vec!["export", "wav", "pulse"], pulse_sound_flags(), false, vec![""]),
    ]
}

/// Arguments that keep each command quick when it is not the flag under test.
fn quick(base: &[&str]) -> Vec<String> {
    match base[0] {
        "sweep" => ["--masses", "30g:60g:3", "--gaps", "2cm:3cm:2"].map(String::from).to_vec(),
        "restitution" => ["--masses", "10g:100g:4"].map(String::from).to_vec(),
        // A forced design (the response needs one) over three frequencies.
        "response" => ["--force-amplitude", "1N", "--freqs", "4Hz:6Hz:3"].map(String::from).to_vec(),
        // Float samples: the format where a non-finite value could show (PCM codes are integers).
        "export" if base.get(1) == Some(&"wav") => ["--format", "float"].map(String::from).to_vec(),
        // Two seed values of a forced design.
        "continue" => ["--vary", "f=3Hz:4Hz:2", "--force-amplitude", "1"].map(String::from).to_vec(),
        "orbit" => ["--force-amplitude", "1", "--freq", "5Hz"].map(String::from).to_vec(),
        // Four designs of a forced design (--over needs a force).
        "design" => {
            let search = ["--vary", "mass=20g:120g", "--minimize", "spl_max_db", "--evaluations", "4"];
            search.into_iter().chain(["--force-amplitude", "1", "--freq", "5Hz"]).map(String::from).collect()
        }
        _ => vec![],
    }
}

/// Runs one command with `--{flag} value` and checks the contract: exit 0 with only finite
/// numbers in the output (and the file), or exit 2 with one stderr line naming a flag the user
/// typed. Never a panic; never more than [`CPU_BUDGET`] of CPU time.
fn check_contract(base: &[&str], flag: &str, value: &str, mode: &str) {
    let home = tempfile::tempdir().unwrap();
    let file = home.path().join(if base[0] == "export" && base[1] == "wav" { "out.wav" } else { "out.txt" });
    let mut args: Vec<String> = base.iter().map(std::string::ToString::to_string).collect();
    let own = quick(base);
    let replaced = own.iter().any(|a| a == &format!("--{flag}"));
    let mut i = 0;
    while i < own.len() {
        if replaced && own[i] == format!("--{flag}") {
            i += 2;
            continue;
        }
        args.push(own[i].clone());
        i += 1;
    }
    if flag == "dt" {
        args.extend(["--solver".into(), "newmark".into()]);
    }
    // A row that needs another gets it (the ball's Poisson ratio needs the ball's material).
    if let Some(needed) = thud::params::design_param(flag).and_then(|p| p.requires) {
        args.extend([format!("--{needed}"), "steel".into()]);
    }
    // A force needs a frequency (`response` sets its own from --freqs).
    if flag.starts_with("force") && base[0] != "response" {
        args.extend(["--freq".into(), "5Hz".into()]);
    }
    // --samples only matters with --csv.
    let mode = if flag == "samples" { "--csv" } else { mode };
    if !mode.is_empty() {
        args.push(mode.into());
    }
    if base[0] == "export" {
        args.extend(["--out".into(), file.to_str().unwrap().into()]);
    }
    args.extend([format!("--{flag}"), value.to_string()]);
    let argv: Vec<&str> = args.iter().map(String::as_str).collect();
    let r = thud_in(home.path(), &argv);
    let shown: Vec<String> = argv.iter().map(|a| a.chars().take(40).collect()).collect();
    assert!(!r.stderr.contains("panicked") && r.code != 101, "{shown:?}: {}", r.stderr);
    match r.code {
        0 => {
            assert!(non_finite_word(&r.stdout).is_none(), "{shown:?} printed a non-finite number:\n{}", r.stdout);
            if mode == "--json" {
                assert!(serde_json::from_str::<serde_json::Value>(&r.stdout).is_ok(), "{shown:?}: bad JSON");
            }
            if base[0] == "export" {
                let bytes = std::fs::read(&file).unwrap_or_else(|e| panic!("{shown:?}: no file: {e}"));
                if base[1] == "pdf" {
                    assert!(bytes.starts_with(b"%PDF"), "{shown:?}: not a PDF");
                } else if base[1] == "wav" {
                    let data = bytes.windows(4).position(|w| w == b"data").expect("a data chunk") + 8;
                    let bad = bytes[data..]
                        .chunks_exact(4)
                        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
                        .find(|x| !x.is_finite());
                    assert!(bad.is_none(), "{shown:?}: WAV sample {bad:?}");
                } else {
                    let text = String::from_utf8_lossy(&bytes);
                    assert!(non_finite_word(&text).is_none(), "{shown:?} wrote a non-finite number");
                }
            }
        }
        2 => {
            assert_eq!(r.stderr.lines().count(), 1, "{shown:?}: {}", r.stderr);
            // Table 5's band count is known only once the chart is computed (it spans the
            // chart's e): a sweep whose e spans too many bands is refused naming --band, the
            // knob to turn, and says when it is the default.
            let table5 = base[0] == "sweep" && r.stderr.contains("Table 5 bands") && r.stderr.contains("--band ");
            assert!(
                r.stderr.contains(&format!("--{flag}")) || table5,
                "{shown:?}: does not name --{flag}: {}",
                r.stderr
            );
            assert!(r.stderr.chars().count() < 400, "{shown:?}: {} characters", r.stderr.chars().count());
        }
        c => panic!("{shown:?}: exit {c}: {}", r.stderr),
    }
}

/// Every range bound of every flag of every command, in every output mode: finite numbers or
/// a one-line refusal. This is where a NaN at an extreme but valid value would show.
#[test]
fn every_bound_of_every_flag_keeps_the_contract() {
    for (base, own, design, modes) in commands() {
        let design_flags = if design { design_flags() } else { vec![] };
        let flags: Vec<&Flag> = own.iter().chain(&design_flags).collect();
        for f in flags {
            let Some(range) = f.range else { continue };
            for v in [range.min, range.max] {
                let text = format!("{v:e}");
                // Sweeps and exports are the slow ones: one output mode is enough there.
                let slow = matches!(base[0], "sweep" | "export" | "response");
                let modes: &[&str] = if slow { &modes[..1] } else { &modes };
                for mode in modes {
                    check_contract(&base, f.name, &f.value(&text), mode);
                }
            }
        }
    }
}

/// Hostile values for any numeric flag.
fn hostile() -> impl Strategy<Value = String> {
    prop_oneof![
        Just("NaN".to_string()),
        Just("nan".to_string()),
        Just("inf".to_string()),
        Just("-inf".to_string()),
        Just("0".to_string()),
        Just("1e-308".to_string()),
        Just("-1e-308".to_string()),
        Just("1e308".to_string()),
        Just("-1e308".to_string()),
        Just("-1".to_string()),
        Just("-0.5".to_string()),
        Just("1e400".to_string()),
        Just("9".repeat(100_000)),
        Just("x".repeat(100_000)),
        Just(String::new()),
        Just("1 2".to_string()),
        Just("1e3e3".to_string()),
        Just("3furlongs".to_string()),
        Just("\u{1b}[31m1".to_string()),
        Just("1\n2".to_string()),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 84, failure_persistence: None, ..ProptestConfig::default() })]

    /// Every numeric flag of every command, fed a hostile value (or a unit of the wrong kind),
    /// keeps the contract.
    #[test]
    fn hostile_values_keep_the_contract(
        cmd in 0usize..64,
        pick in 0usize..64,
        value in hostile(),
        wrong_unit in any::<bool>(),
        mode_pick in 0usize..3,
    ) {
        let all = commands();
        let (base, own, design, modes) = &all[cmd % all.len()];
        let design_flags = if *design { design_flags() } else { vec![] };
        let flags: Vec<&Flag> = own.iter().chain(&design_flags).collect();
        let f = flags[pick % flags.len()];
        let value = if wrong_unit { f.wrong_unit.to_string() } else { f.value(&value) };
        check_contract(base, f.name, &value, modes[mode_pick % modes.len()]);
    }
}

/// The explorer's typed values use the same table: out of range is refused by the field's name.
#[test]
fn explorer_fields_use_the_same_ranges() {
    use thud::design::Design;
    use thud::tui::fields::Knob;
    let d = Design::default();
    for (field, text, name) in [
        (Knob::MASS, "1e308", "mass"),
        (Knob::GAP, "1e-308", "gap"),
        (Knob::K, "1e308", "k"),
        (Knob::R, "2km", "r"),
        (Knob::E_STAR, "-5", "e*"),
        (Knob::L_STAR, "1e308", "L*"),
        (Knob::SOLVER, "1e-308", "dt"),
    ] {
        let e = field.parsed(&d, text).unwrap_err().to_string();
        assert!(e.starts_with(&format!("invalid {name}: ")), "{text}: {e}");
    }
    assert!(Knob::MASS.parsed(&d, "100kg").is_ok());
    // The forcing and the ball's start: the same ranges and the same whole-design checks.
    for (field, text) in [
        (Knob::FORCE, "1e9"),
        (Knob::FORCE, "-1"),
        (Knob::FREQ, "1e9"),
        (Knob::FREQ, "nan"),
        (Knob::BALL_POSITION, "3cm"),
        (Knob::BALL_POSITION, "1e308"),
        (Knob::RUNS, "0"),
        (Knob::RUNS, "1e9"),
    ] {
        let e = field.parsed(&d, text).expect_err(text).to_string();
        assert!(e.starts_with("invalid "), "{text}: {e}");
        assert!(!e.contains('\n'), "{text}: {e}");
    }
    assert!(Knob::BALL_POSITION.parsed(&d, "1cm").is_ok(), "inside d/2 = 2 cm");
    // Stepping past a bound is refused too.
    let mut big = d.clone();
    big.damper.stiffness_n_m = 1e10;
    assert!(Knob::K.stepped(&big, true, false).is_err());
}

/// The explorer refuses a duration or a Newmark step whose runs exceed the command line's work
/// caps (the live design or the chart's fine grid), naming the field and the estimate, and
/// refuses a WAV export over its cap instead of running out of memory.
#[test]
fn explorer_refuses_runs_over_the_work_caps() {
    use thud::design::Design;
    use thud::tui::fields::Knob;
    let d = Design::default();
    // 1e6 s is inside the duration's range, but the chart's 192 cells × 1e6 s exceed the
    // sweep's cell-seconds cap.
    let e = Knob::DURATION.parsed(&d, "1e6").unwrap_err().to_string();
    assert!(e.starts_with("invalid duration: ") && e.contains("exceed the limit"), "{e}");
    // A Newmark step of 1e-12 s over 2 s is 2e12 steps.
    let e = Knob::SOLVER.parsed(&d, "1e-12").unwrap_err().to_string();
    assert!(e.starts_with("invalid dt: ") && e.contains("Newmark steps exceed the limit"), "{e}");
    // An ordinary duration is fine.
    assert!(Knob::DURATION.parsed(&d, "5").is_ok());
    // A WAV of 1000 s of a 1000-s design is over the 4.8e7-sample cap only past 1000 s; the
    // chart's cap (192 cells × duration ≤ 2e5 s) already refuses durations past ~1041 s, so
    // the export check is reached with a design built directly.
    let dir = tempfile::tempdir().unwrap();
    let mut long = d.clone();
    long.damper.duration_s = 2000.0;
    let mut app = thud::tui::App::new(long, "default", thud::tui::Palette::default());
    app.host.export_dir = dir.path().to_path_buf();
    assert!(app.export(thud::export::Artifact::Wav).is_none());
    let status = app.status().map(|s| s.text.clone()).unwrap_or_default();
    assert!(status.contains("WAV samples exceed the limit"), "{status}");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

/// The new flags of the exports and of `thud man`: `export wav --format` takes only pcm16,
/// pcm24 or float; `export svg --size` only WxH within 480–4000 × 320–4000 px; `--no-title` takes
/// no value; `man --all` refuses a path that is a file and takes no COMMAND beside it. Each is
/// refused with exit 2, one line naming the flag and what was typed, and no file.
#[test]
fn new_export_and_man_flags_are_checked_and_named() {
    let dir = tempfile::tempdir().unwrap();
    let f = |n: &str| dir.path().join(n).to_string_lossy().into_owned();
    let (wav, svg) = (f("s.wav"), f("s.svg"));
    for bad in ["pcm8", "PCM", "", "float64", "1e308"] {
        assert_refused(&["export", "wav", "--format", bad, "--out", &wav], &["--format", "pcm16"]);
    }
    for bad in
        ["479x320", "480x319", "4001x800", "800x4001", "-800x600", "1e308x600", "NaNxNaN", "800x", "x600", "800*600"]
    {
        assert_refused(&["export", "svg", "chart", "--size", bad, "--out", &svg], &["--size", bad, "480 to 4000"]);
    }
    assert_refused(&["export", "svg", "chart", "--no-title=yes", "--out", &svg], &["--no-title"]);
    let file = f("a-file");
    std::fs::write(&file, "x").unwrap();
    assert_refused(&["man", "--all", &file], &["a-file"]);
    assert_refused(&["man", "pulse", "--all", &f("m")], &["--all"]);
    assert_refused(&["man", "--force"], &["--all"]);
    assert!(!Path::new(&wav).exists() && !Path::new(&svg).exists() && !Path::new(&f("m")).exists());
    // The bounds themselves are taken.
    let r = thud(&["export", "svg", "waveform", "--size", "480x320", "--no-title", "--out", &svg]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let r = thud(&["export", "wav", "--format", "pcm24", "--duration", "0.05", "--out", &wav]);
    assert_eq!(r.code, 0, "{}", r.stderr);
}

// Round 2 (thread pools, dead terminals, config problems, loaded files, huge
// terminals, help to a full disk).

/// Item 4: `RAYON_NUM_THREADS` far past what the system gives is held to the thread range with
/// one warning; the run completes (it used to try 100000 threads and never finish in time).
#[test]
fn a_huge_rayon_num_threads_is_held_to_the_range_with_one_warning() {
    let home = tempfile::tempdir().unwrap();
    let mut c = command(home.path(), &["sweep", "--masses", "10g:50g:6", "--gaps", "1cm:3cm:4"]);
    let out = c.env("RAYON_NUM_THREADS", "100000").output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("RAYON_NUM_THREADS=100000") && err.contains("using 1024"), "{err}");
    assert!(String::from_utf8_lossy(&out.stdout).contains("zone"));
    // --threads is range-checked like every count.
    assert_refused(&["sweep", "--threads", "0"], &["--threads", "1 to 1024"]);
    assert_refused(&["--threads", "2000", "sweep"], &["--threads", "2000"]);
}

/// Item 4: under a pids limit every parallel command runs on the threads it gets (down to the
/// calling thread alone) with one warning, instead of panicking with ThreadPoolBuildError.
/// Root ignores RLIMIT_NPROC, so the runs are made as a user with no other process, on a copy
/// of the binary it can reach ([`Stranger`]; skipped, with the reason printed, where that is
/// not possible).
#[test]
fn thread_pools_fall_back_under_a_pids_limit() {
    let Some(stranger) = Stranger::new(0) else { return };
    let dir = &stranger.dir;
    let bin = &stranger.bin;
    let part = dir.path().join("part1.json");
    let part = part.to_str().unwrap();
    let grid = ["--masses", "10g:50g:6", "--gaps", "1cm:3cm:4"];
    let commands: Vec<Vec<&str>> = vec![
        [&["sweep"][..], &grid].concat(),
        vec!["response", "--force-amplitude", "5", "--freqs", "4:6:5"],
        vec!["simulate", "--ensemble", "8"],
        vec!["paper", "table3"],
        [&["sweep"][..], &grid, &["--shard", "1/2", "--out", part]].concat(),
    ];
    // `exec` leaves one process: with -u 1 no other thread at all; with -u 4 three more, one of
    // them left for the signal thread.
    for (limit, threads, expect) in [("1", "4", "calling thread alone"), ("4", "8", "only 2 of 8")] {
        for args in &commands {
            let _ = std::fs::remove_file(part);
            let out = Command::new("timeout")
                .args(["20", "setpriv"])
                .args(stranger.setpriv())
                .args(["bash", "-c"])
                .arg(format!("ulimit -u {limit} && exec \"$0\" \"$@\""))
                .arg(bin)
                .args(args)
                .env("HOME", dir.path())
                .env("XDG_CONFIG_HOME", dir.path().join("config"))
                .env("RAYON_NUM_THREADS", threads)
                .current_dir(dir.path())
                .output()
                .unwrap();
            let err = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(0), "ulimit -u {limit}, {args:?}: {err}");
            // Printed beside the success, after the command's own lines.
            let warning = err.lines().find(|l| l.starts_with("thud: warning: ")).unwrap_or("");
            assert!(warning.starts_with("thud: warning: ") && warning.contains(expect), "{args:?}: {err}");
            assert!(!err.contains("panicked"), "{args:?}: {err}");
            assert!(!out.stdout.is_empty() || std::path::Path::new(part).exists(), "{args:?} gave no result");
        }
    }
}

/// Item 14: help and version to a full disk fail with exit 1 and one line; to a closed pipe
/// they end quietly.
#[test]
fn help_and_version_to_a_full_disk_exit_1_with_one_line() {
    for args in [&["--help"][..], &["--version"], &["sweep", "--help"]] {
        let full = std::fs::OpenOptions::new().write(true).open("/dev/full").unwrap();
        let home = tempfile::tempdir().unwrap();
        let out = command(home.path(), args).stdout(full).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(err.starts_with("thud: cannot write the ") && err.contains("No space left"), "{args:?}: {err}");
    }
}

/// Item 14: an unknown preset for the explorer names `--preset`, as for every other command.
#[test]
fn the_explorer_s_unknown_preset_names_the_flag() {
    assert_refused(&["tui", "--preset", "bogus"], &["invalid --preset: ", "'bogus'"]);
}

/// Item 5: a pty whose master side closes without a SIGHUP (a new session, no controlling
/// terminal), as with `setsid` + `openpty`. Prints "exit CODE" or "STILL RUNNING".
const DEAD_PTY: &str = r#"
import fcntl, os, pty, select, struct, subprocess, sys, termios, time
m, s = pty.openpty()
fcntl.ioctl(s, termios.TIOCSWINSZ, struct.pack("HHHH", 30, 100, 0, 0))
p = subprocess.Popen([sys.argv[1], "tui"], stdin=s, stdout=s, stderr=s, start_new_session=True,
                     env=dict(os.environ, TERM="xterm-256color"))
os.close(s)
seen, last, start = b"", time.time(), time.time()
while time.time() - last < 1.0 and time.time() - start < 15:
    if select.select([m], [], [], 0.1)[0]:
        try:
            chunk = os.read(m, 65536)
        except OSError:
            break
        seen += chunk
        last = time.time()
if b"parameters" not in seen or p.poll() is not None:
    print("NO SCREEN", p.poll(), seen[-200:])
    sys.exit(0)
os.close(m)
try:
    print("exit", p.wait(timeout=1.5))
except subprocess.TimeoutExpired:
    p.kill()
    p.wait()
    print("STILL RUNNING")
"#;

/// Item 5: when the explorer's terminal is gone without SIGHUP, the explorer ends (exit 1)
/// within a second instead of spinning on EIO forever.
#[test]
fn a_dead_terminal_ends_the_explorer_within_a_second() {
    let Some((said, err)) = run_pty_script(DEAD_PTY) else { return };
    assert_eq!(said.trim(), "exit 1", "{said}{err}");
}

/// Runs a python3 script that drives the built explorer through a pty (its argument is the
/// binary), with HOME and the XDG folders in a temporary folder: (stdout, stderr), or None
/// (with a printed reason) where python3 is not installed.
fn run_pty_script(script: &str) -> Option<(String, String)> {
    let home = tempfile::tempdir().unwrap();
    let Ok(out) = Command::new("python3")
        .args(["-c", script, env!("CARGO_BIN_EXE_thud")])
        .env("HOME", home.path())
        .env("XDG_CONFIG_HOME", home.path().join("config"))
        .env("XDG_DATA_HOME", home.path().join("data"))
        .output()
    else {
        crate::support::skip::skip("python3 (for its pty module) is not installed");
        return None;
    };
    Some((String::from_utf8_lossy(&out.stdout).into(), String::from_utf8_lossy(&out.stderr).into()))
}

/// Item 14: a hostile terminal sends a bracketed-paste start and 2 MiB without the end marker,
/// then, after the paste's second, `q`. Prints "exit CODE" or "STILL RUNNING".
const ENDLESS_PASTE: &str = r#"
import fcntl, os, pty, select, struct, subprocess, sys, termios, time
m, s = pty.openpty()
fcntl.ioctl(s, termios.TIOCSWINSZ, struct.pack("HHHH", 30, 100, 0, 0))
p = subprocess.Popen([sys.argv[1], "tui"], stdin=s, stdout=s, stderr=s, start_new_session=True,
                     env=dict(os.environ, TERM="xterm-256color"))
os.close(s)
def pump(seconds, data=b""):
    seen, sent, end = b"", 0, time.time() + seconds
    while time.time() < end and (sent < len(data) or not data):
        r, w, _ = select.select([m], [m] if sent < len(data) else [], [], 0.05)
        if r:
            try:
                seen += os.read(m, 65536)
            except OSError:
                break
        if w:
            sent += os.write(m, data[sent:sent + 4096])
    return seen, sent
seen = b""
start = time.time()
while b"parameters" not in seen and time.time() - start < 15:
    seen += pump(0.2)[0]
if b"parameters" not in seen:
    print("NO SCREEN", p.poll(), seen[-200:])
    sys.exit(0)
flood = b"\x1b[200~" + b"x" * (2 << 20)
_, sent = pump(30, flood)
if sent < len(flood):
    print("FLOOD NOT READ", sent)
pump(1.5)
os.write(m, b"q")
end = time.time() + 5
while p.poll() is None and time.time() < end:
    pump(0.1)
if p.poll() is None:
    p.kill()
    p.wait()
    print("STILL RUNNING")
else:
    print("exit", p.returncode)
"#;

/// Item 14: an unterminated bracketed paste times out. crossterm's reader kept everything after
/// `ESC[200~` until `ESC[201~`, so every later key (q included) was swallowed and memory grew;
/// the explorer drops such a paste after a second (keeping none of it) and reads keys again.
#[test]
fn an_endless_bracketed_paste_times_out_and_q_quits() {
    let Some((said, err)) = run_pty_script(ENDLESS_PASTE) else { return };
    assert_eq!(said.trim(), "exit 0", "{said}{err}");
}

/// Item 6: a config problem is a warning, apart from errors: a failing command prints only its
/// one error line; `thud config check` lists every problem with file:line:col and exits 2; a
/// wrong shape such as `thresholds = [1, 2]` is a problem, not read by position.
#[test]
fn config_warnings_stay_apart_from_errors_and_config_check_lists_every_problem() {
    let home = tempfile::tempdir().unwrap();
    let dir = home.path().join("config").join("thud");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("config.toml");
    std::fs::write(&file, "thresholds = [100, 1]\ntheme = \"purple\"\n[keys]\nsave = \"ctrl-\"\n").unwrap();
    let r = thud_in(home.path(), &["simulate", "--mass", "1e308"]);
    assert_eq!(r.code, 2, "{}", r.stderr);
    assert_eq!(r.stderr.lines().count(), 1, "only the error: {}", r.stderr);
    assert!(r.stderr.contains("--mass") && !r.stderr.contains("warning"), "{}", r.stderr);

    let r = thud_in(home.path(), &["config", "check"]);
    assert_eq!(r.code, 2, "{}", r.stderr);
    assert_eq!(r.stderr.lines().count(), 1, "{}", r.stderr);
    assert!(r.stderr.contains("3 problems"), "{}", r.stderr);
    let f = file.display().to_string();
    let lines: Vec<&str> = r.stdout.lines().collect();
    assert_eq!(lines.len(), 3, "{}", r.stdout);
    assert!(lines[0].starts_with(&format!("{f}:1:14: ")) && lines[0].contains("expected a table"), "{}", r.stdout);
    assert!(lines[1].starts_with(&format!("{f}:2:9: ")) && lines[1].contains("purple"), "{}", r.stdout);
    assert!(lines[2].starts_with(&format!("{f}:4:8: ")) && lines[2].contains("'ctrl-' is not a key"), "{}", r.stdout);

    // The thresholds were not read by position: a successful run warns once and uses the
    // defaults (L* = 103 dB, not 100).
    let r = thud_in(home.path(), &["simulate", "--json"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert_eq!(r.stderr.lines().count(), 1, "{}", r.stderr);
    let v: serde_json::Value = serde_json::from_str(&r.stdout).unwrap();
    assert_eq!(v["design"]["thresholds"]["spl_db"].as_f64(), Some(103.0));

    // A good file: no problems, exit 0.
    std::fs::write(&file, "theme = \"mono\"\n[thresholds]\nl_star_db = 100\n").unwrap();
    let r = thud_in(home.path(), &["config", "check"]);
    assert_eq!((r.code, r.stderr.as_str()), (0, ""), "{}", r.stdout);
    assert!(r.stdout.contains("no problems"), "{}", r.stdout);
    // The closing line says what was checked and what is left to the commands.
    assert_eq!(r.stdout.lines().count(), 1, "{}", r.stdout);
    assert!(
        r.stdout.contains("checked: the TOML syntax") && r.stdout.contains("not checked: [design] on another --preset"),
        "{}",
        r.stdout
    );
}

/// Item 10: a saved design is held to the caps of typed values: a duration of 1e6 s (inside
/// the duration's range, over the chart's work cap) is refused on load with the cap's line, as
/// typing it is, and the live design stays. Every preset and the built-in tour pass.
#[test]
fn the_explorer_holds_loaded_files_to_the_caps_of_typed_values() {
    use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
    use thud::design::Design;
    use thud::tui::{fields, App, Msg, Palette};
    let data = tempfile::tempdir().unwrap();
    let mut long = Design::default();
    long.damper.duration_s = 1e6;
    let file = thud::store::DesignFile {
        description: "a long one".into(),
        ensemble: None,
        uncertainty: std::collections::BTreeMap::default(),
        design: long,
    };
    thud::store::save_design(data.path(), "long", &file, false).unwrap();
    let mut app = App::new(Design::default(), "default", Palette::default());
    app.host.data_dir = Some(data.path().to_path_buf());
    let before = app.design.clone();
    for key in [KeyCode::Char('L'), KeyCode::Enter] {
        app.update(Msg::Input(Event::Key(KeyEvent::new(key, KeyModifiers::NONE))));
    }
    let status = app.status().map(|s| s.text.clone()).unwrap_or_default();
    assert!(status.contains("cannot load long") && status.contains("invalid duration: "), "{status}");
    assert!(status.contains("exceed the limit"), "{status}");
    assert_eq!(app.design, before, "nothing loaded");
    // The same line as typing the value.
    let typed = fields::Knob::DURATION.parsed(&Design::default(), "1e6").unwrap_err().to_string();
    assert!(status.contains(&typed), "{status} / {typed}");
    for name in thud::presets::names() {
        fields::check_loaded(&thud::presets::preset(name).unwrap()).unwrap();
    }
    assert!(thud::tui::tour::Tour::load(&thud::tui::tour::TourSource::BuiltIn).is_ok());
}

// ---- Files written and parts merged -------------------------------------------------

/// Asserts a refusal run in `home`: exit 2, one stderr line naming every one of `needles`.
fn assert_refused_in(home: &Path, args: &[&str], needles: &[&str]) {
    let r = thud_in(home, args);
    assert_eq!(r.code, 2, "{args:?}: exit {} stderr {}", r.code, r.stderr);
    assert_eq!(r.stderr.lines().count(), 1, "{args:?}: {}", r.stderr);
    assert!(r.stdout.is_empty(), "{args:?} printed: {}", r.stdout);
    for n in needles {
        assert!(r.stderr.contains(n), "{args:?}: '{n}' not in: {}", r.stderr);
    }
}

#[test]
fn written_files_and_merged_parts_keep_the_contract() {
    let home = tempfile::tempdir().unwrap();
    let h = home.path();
    // Item 1: a link at --out is neither followed nor replaced, with --force too.
    std::fs::write(h.join("victim"), "keep").unwrap();
    std::os::unix::fs::symlink(h.join("victim"), h.join("link.csv")).unwrap();
    let link = h.join("link.csv");
    let link = link.to_str().unwrap();
    assert_refused_in(
        h,
        &["export", "csv", "waveform", "--out", link, "--force"],
        &["invalid --out: ", "symbolic link"],
    );
    assert!(std::fs::symlink_metadata(link).unwrap().file_type().is_symlink());
    // Item 14: `paper ID --out` honours --out, and its refusal names --out.
    std::fs::write(h.join("fig2.txt"), "mine").unwrap();
    let fig = h.join("fig2.txt");
    assert_refused_in(
        h,
        &["paper", "fig2", "--out", fig.to_str().unwrap()],
        &["invalid --out: ", "exists; add --force"],
    );
    // Items 2, 3, 11: a part with a forged ensemble (valid hash) and a merge over its cap.
    let part = h.join("p.jsonl");
    let p = part.to_str().unwrap();
    let r = thud_in(
        h,
        &["sweep", "--masses", "30g:40g:2", "--gaps", "2cm:3cm:2", "--duration", "0.2", "--shard", "0/1", "--out", p],
    );
    assert_eq!(r.code, 0, "{}", r.stderr);
    let text = std::fs::read_to_string(&part).unwrap();
    let (first, rest) = text.split_once('\n').unwrap();
    let header: thud::shard::Header = serde_json::from_str(first).unwrap();
    let mut study = header.study.clone();
    study.ensemble = 1 << 63;
    let forged = serde_json::to_string(&thud::shard::Header::new(study, 0, 1)).unwrap() + "\n" + rest;
    std::fs::write(h.join("forged.jsonl"), forged).unwrap();
    let f = h.join("forged.jsonl");
    assert_refused_in(
        h,
        &["--no-limit", "merge", f.to_str().unwrap(), "--out", "-"],
        &["out of range (invalid ensemble"],
    );
    assert_refused_in(h, &["merge", p, "--out", "-", "--band", "nan"], &["--band"]);
    let v = h.join("v.jsonl");
    std::fs::write(&v, text.replacen("\"format_version\":1", "\"format_version\":1.0", 1)).unwrap();
    assert_refused_in(h, &["merge", v.to_str().unwrap(), "--out", "-"], &["format version 1.0;"]);
}

/// `thud tui --front FILE` with a hostile file (not JSON, far over the size a front can have,
/// a folder, a link to an endless device, a FIFO nothing writes to) is refused with exit 2 and
/// one line naming --front and the file, at once, before the terminal is touched: nothing on
/// standard output (no escape sequence), stdin and stdout not even a terminal.
#[test]
fn a_hostile_front_file_is_refused_before_the_terminal_is_touched() {
    let home = tempfile::tempdir().unwrap();
    let h = home.path();
    std::fs::write(h.join("garbage.json"), "{\"front\": [1, 2,\u{0}").unwrap();
    // 64 GiB, sparse: read whole it would take minutes and all the memory.
    std::fs::File::create(h.join("huge.json")).unwrap().set_len(1 << 36).unwrap();
    std::fs::create_dir(h.join("folder.json")).unwrap();
    std::os::unix::fs::symlink("/dev/zero", h.join("zero.json")).unwrap();
    assert!(Command::new("mkfifo").arg(h.join("fifo.json")).status().unwrap().success());
    for name in ["garbage.json", "huge.json", "folder.json", "zero.json", "fifo.json"] {
        let start = std::time::Instant::now();
        let r = thud_in(h, &["tui", "--front", name]);
        assert_eq!(r.code, 2, "{name}: exit {} stderr {}", r.code, r.stderr);
        assert_eq!(r.stderr.lines().count(), 1, "{name}: {}", r.stderr);
        assert!(r.stderr.contains("--front") && r.stderr.contains(name), "{name}: {}", r.stderr);
        assert!(r.stdout.is_empty(), "{name}: the terminal was written to: {:?}", r.stdout);
        assert!(start.elapsed() < Duration::from_secs(5), "{name}: {:?}", start.elapsed());
    }
}
