#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! Hostile round 6: `thud design --save DIR --out FILE` writes its result as one set (the
//! folder of front designs and the report: a failure or a signal between the two leaves the old
//! set or the new one, and no temporary file), and refuses a `--save` folder it could not write
//! before the search; a range FROM:TO:N whose ends are one value and N > 1 (N identical rows)
//! is refused by every command that reads one.
//!
//! Runs of the built binary, with HOME and the XDG folders in a temporary folder, each killed
//! after 30 s (a failure).

use std::fs;
use std::os::unix::ffi::OsStrExt;
use std::os::unix::fs::PermissionsExt;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use thud::fsio::{FAIL_SET_AFTER_FOR_TEST, HOLD_SET_FOR_TEST, HOLD_TEMP_FOR_TEST, TEMP_MARK};

use crate::support::{home, wait};
use home::in_home;
use wait::wait_within;

const BIN: &str = env!("CARGO_BIN_EXE_thud");
const TIMEOUT: Duration = Duration::from_secs(30);

/// Runs thud with `args` in `home` (and `env`) to completion: (code, stdout, stderr).
fn thud_env(home: &Path, args: &[&str], env: &[(&str, &str)]) -> (i32, String, String) {
    let child = in_home(BIN, args, home, env).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().unwrap();
    let out = wait_within(child, TIMEOUT, "thud");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

fn thud(home: &Path, args: &[&str]) -> (i32, String, String) {
    thud_env(home, args, &[])
}

/// A refusal: exit 2 and one line on stderr holding every one of `words`.
fn assert_refused(home: &Path, args: &[&str], words: &[&str]) {
    let (code, _, err) = thud(home, args);
    assert_eq!(code, 2, "{args:?}: {err}");
    assert_eq!(err.lines().count(), 1, "{args:?}: one line: {err}");
    for w in words {
        assert!(err.contains(w), "{args:?}: {w:?} missing from {err}");
    }
}

/// A short search saving its front in `front/` and its report in `report.txt`, replacing them.
const SET: [&str; 13] = [
    "design",
    "--vary",
    "mass=20g:120g",
    "--minimize",
    "spl_max_db",
    "--evaluations",
    "4",
    "--save",
    "front",
    "--out",
    "report.txt",
    "--json",
    "--force",
];

/// The set as it stands: the front folder's files (name, contents) and the report.
type SetNow = (Option<Vec<(String, String)>>, Option<String>);

fn set_now(dir: &Path) -> SetNow {
    let front = fs::read_dir(dir.join("front")).ok().map(|d| {
        let mut files: Vec<(String, String)> = d
            .map(|e| {
                let e = e.unwrap();
                (String::from_utf8_lossy(e.file_name().as_bytes()).into_owned(), fs::read_to_string(e.path()).unwrap())
            })
            .collect();
        files.sort();
        files
    });
    (front, fs::read_to_string(dir.join("report.txt")).ok())
}

/// Puts an old set in place: a previous front of five designs (more than the new one has) and
/// a report, each file holding its own name.
fn old_set(dir: &Path) -> SetNow {
    fs::create_dir(dir.join("front")).unwrap();
    for k in 1..=5 {
        let name = format!("design-{k:02}.toml");
        fs::write(dir.join("front").join(&name), format!("old {name}")).unwrap();
    }
    fs::write(dir.join("report.txt"), "old report").unwrap();
    set_now(dir)
}

/// Whether the set is the new one, whole: every design file and the report written by this
/// run (none of the old ones), the report naming each saved file.
fn is_new(now: &SetNow) -> bool {
    let (Some(front), Some(report)) = now else { return false };
    !front.is_empty()
        && report.starts_with('{')
        && front.iter().all(|(name, text)| {
            text.contains("thud design: front design") && report.contains(&format!("\"file\": \"{name}\""))
        })
}

/// Names in `dir` of thud's temporary files and folders.
fn temps(dir: &Path) -> Vec<String> {
    fs::read_dir(dir)
        .unwrap()
        .map(|e| String::from_utf8_lossy(e.unwrap().file_name().as_bytes()).into_owned())
        .filter(|n| n.contains(TEMP_MARK))
        .collect()
}

#[test]
fn a_failure_between_the_saved_front_and_the_report_puts_back_the_old_set() {
    let home = tempfile::tempdir().unwrap();
    let dir = home.path();
    let old = old_set(dir);
    // Before the folder is put in place, and between the folder and the report.
    for after in ["0", "1"] {
        let (code, _, err) = thud_env(dir, &SET, &[(FAIL_SET_AFTER_FOR_TEST, after)]);
        assert_ne!(code, 0, "the injected failure fails the run: {err}");
        assert!(err.contains("injected"), "{err}");
        assert_eq!(set_now(dir), old, "after {after} placed, the old set is back: {err}");
        assert_eq!(temps(dir), Vec::<String>::new(), "no temporary file is left");
    }
    // Without an old set, a failure leaves neither the folder nor the report.
    let fresh = tempfile::tempdir().unwrap();
    let no_force = &SET[..SET.len() - 1];
    let (code, _, err) = thud_env(fresh.path(), no_force, &[(FAIL_SET_AFTER_FOR_TEST, "1")]);
    assert_ne!(code, 0, "{err}");
    assert_eq!(set_now(fresh.path()), (None, None), "nothing new stays: {err}");
    assert_eq!(temps(fresh.path()), Vec::<String>::new());
    // An empty folder given for the front stays an empty folder.
    fs::create_dir(fresh.path().join("front")).unwrap();
    let (code, _, err) = thud_env(fresh.path(), no_force, &[(FAIL_SET_AFTER_FOR_TEST, "1")]);
    assert_ne!(code, 0, "{err}");
    assert_eq!(set_now(fresh.path()), (Some(Vec::new()), None), "{err}");
    // And without the failure the whole new set replaces the old one (its five designs too).
    let (code, _, err) = thud(dir, &SET);
    assert_eq!(code, 0, "{err}");
    let now = set_now(dir);
    assert!(is_new(&now), "{now:?}: {err}");
    assert_eq!(temps(dir), Vec::<String>::new());
}

/// Starts the set's run with `env`, waits until `ready` holds of the folder, sends SIGTERM and
/// returns the exit status.
fn term_when(dir: &Path, env: &[(&str, &str)], ready: impl Fn(&Path) -> bool) -> std::process::ExitStatus {
    let mut child = in_home(BIN, &SET, dir, env).stdout(Stdio::null()).stderr(Stdio::null()).spawn().unwrap();
    let start = Instant::now();
    while !ready(dir) {
        assert!(start.elapsed() < TIMEOUT, "the run never got there: {:?}", temps(dir));
        assert!(child.try_wait().unwrap().is_none(), "the run ended before the signal");
        std::thread::sleep(Duration::from_millis(10));
    }
    let pid = i32::try_from(child.id()).unwrap();
    assert!(Command::new("kill").args(["-TERM", &pid.to_string()]).status().unwrap().success());
    let start = Instant::now();
    loop {
        if let Some(status) = child.try_wait().unwrap() {
            return status;
        }
        assert!(start.elapsed() < TIMEOUT, "SIGTERM did not end the run");
        std::thread::sleep(Duration::from_millis(10));
    }
}

#[test]
fn a_signal_while_the_front_and_report_are_staged_leaves_the_old_set() {
    let home = tempfile::tempdir().unwrap();
    let dir = home.path();
    let old = old_set(dir);
    // Each staged file is held 2 s; the signal comes once the report's is there (the front's
    // folder staged before it).
    let report_staged = |d: &Path| temps(d).iter().any(|t| t.starts_with(".report.txt"));
    let status = term_when(dir, &[(HOLD_TEMP_FOR_TEST, "2000")], report_staged);
    assert_eq!(status.code(), Some(128 + 15), "{status:?}");
    assert_eq!(set_now(dir), old, "the old set, whole");
    assert_eq!(temps(dir), Vec::<String>::new(), "the staged folder and file are removed");
}

#[test]
fn a_signal_between_the_front_and_the_report_waits_for_the_new_set() {
    let home = tempfile::tempdir().unwrap();
    let dir = home.path();
    let old = old_set(dir);
    // Held 1.5 s once the front is in place: the signal comes before the report is.
    let front_placed = |d: &Path| set_now(d).0 != old.0;
    let status = term_when(dir, &[(HOLD_SET_FOR_TEST, "1500")], front_placed);
    // The signal's exit (143) waits for the set; the run may finish first (0).
    assert!(matches!(status.code(), Some(0 | 143)), "{status:?}");
    let now = set_now(dir);
    assert!(is_new(&now), "the new set, whole: {now:?}");
    assert_eq!(temps(dir), Vec::<String>::new(), "the replaced folder and file are removed");
}

/// A search of 100 000 designs saving into `save`: a refusal that came after the search would
/// take far beyond the test's time.
fn long_save(save: &str, more: &[&'static str]) -> Vec<String> {
    let args = "design --vary mass=20g:120g --minimize spl_max_db --evaluations 100000 --no-limit --save";
    args.split_whitespace()
        .map(str::to_string)
        .chain([save.to_string()])
        .chain(more.iter().map(std::string::ToString::to_string))
        .collect()
}

#[test]
fn a_save_folder_that_cannot_be_written_is_refused_before_the_search() {
    let home = tempfile::tempdir().unwrap();
    let dir = home.path();
    let refused = |save: &str, more: &[&'static str], words: &[&str]| {
        let args = long_save(save, more);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        assert_refused(dir, &args, &[&["invalid --save: "][..], words].concat());
    };
    // A planted link to a folder, even an empty one, even with --force.
    fs::create_dir(dir.join("empty")).unwrap();
    std::os::unix::fs::symlink("empty", dir.join("link")).unwrap();
    refused("link", &[], &["link", "symbolic link"]);
    refused("link", &["--force"], &["link", "symbolic link"]);
    assert!(fs::read_dir(dir.join("empty")).unwrap().next().is_none(), "nothing written through the link");
    // A folder holding something: without --force; with it, anything but a previous front.
    fs::create_dir(dir.join("busy")).unwrap();
    fs::write(dir.join("busy/notes.txt"), "mine").unwrap();
    refused("busy", &[], &["busy", "not empty", "--force"]);
    refused("busy", &["--force"], &["busy", "notes.txt"]);
    assert_eq!(fs::read(dir.join("busy/notes.txt")).unwrap(), b"mine");
    // A read-only folder, and a folder inside a read-only one.
    fs::create_dir(dir.join("ro")).unwrap();
    fs::set_permissions(dir.join("ro"), fs::Permissions::from_mode(0o555)).unwrap();
    refused("ro", &[], &["ro", "read-only"]);
    refused("ro/front", &[], &["ro/front", "cannot be written"]);
    fs::set_permissions(dir.join("ro"), fs::Permissions::from_mode(0o755)).unwrap();
    // A file, and an output inside the folder (replaced with it).
    fs::write(dir.join("file"), "x").unwrap();
    refused("file", &[], &["file", "not a folder"]);
    refused("front", &["--out", "front/report.txt"], &["front", "--out"]);
    refused("front", &["--svg", "./front/f.svg", "--maximize", "inclination_cm_s"], &["front", "--svg"]);
    assert_eq!(temps(dir), Vec::<String>::new());
    assert!(!dir.join("front").exists());
}

#[test]
fn a_range_with_one_value_at_both_ends_and_several_values_is_refused_everywhere() {
    let home = tempfile::tempdir().unwrap();
    let dir = home.path();
    let cases: [(&[&str], &[&str]); 7] = [
        (
            &["sweep", "--vary", "mass=30g:30g:3"],
            &["invalid --vary: ", "'mass=30g:30g:3'", "FROM and TO are one value"],
        ),
        (&["sweep", "--vary", "mass=30g:0.03kg:3"], &["invalid --vary: ", "'mass=30g:0.03kg:3'"]),
        (&["sweep", "--masses", "30g:30g:3", "--gaps", "2cm:5cm:2"], &["invalid --masses: ", "'30g:30g:3'"]),
        (&["bifurcation", "--vary", "f=5Hz:5Hz:3", "--force-amplitude", "1"], &["invalid --vary: ", "'f=5Hz:5Hz:3'"]),
        (&["continue", "--vary", "f=5Hz:5Hz:4", "--force-amplitude", "1"], &["invalid --vary: ", "'f=5Hz:5Hz:4'"]),
        (&["continue", "--vary", "f=5Hz:5Hz", "--force-amplitude", "1"], &["invalid --vary: ", "'f=5Hz:5Hz':"]),
        (
            &[
                "design",
                "--vary",
                "mass=20g:120g",
                "--minimize",
                "spl_max_db",
                "--force-amplitude",
                "1",
                "--freq",
                "5Hz",
                "--over",
                "freqs=5Hz:5Hz:3",
            ],
            &["invalid --over: ", "'5Hz:5Hz:3'"],
        ),
    ];
    for (args, words) in cases {
        assert_refused(dir, args, words);
    }
    // One value once is a plain axis: one row.
    let (code, out, err) = thud(dir, &["sweep", "--vary", "mass=30g:30g:1", "--csv"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(out.lines().count(), 2, "a header and one row: {out}");
    // The design's own range: FROM below TO, as before.
    assert_refused(dir, &["design", "--vary", "mass=30g:30g", "--minimize", "spl_max_db"], &["--vary mass", "below"]);
}

/// An orbit not found from the user's `--guess` is refused naming `--guess`, the start given.
#[test]
fn an_orbit_not_found_from_a_guess_names_the_guess() {
    let home = tempfile::tempdir().unwrap();
    let args = ["orbit", "--force-amplitude", "1", "--freq", "5Hz", "--guess", "0,0,0,0"];
    assert_refused(home.path(), &args, &["invalid --guess: ", "no periodic orbit found"]);
}

/// A family of branches (`continue --vary NAME=FROM:TO:N`) over a design with no force found
/// no orbit at any seed and said "0 branches" with exit 0; it is refused as one branch is,
/// naming --force-amplitude. Varying the force itself still starts the family.
#[test]
fn a_family_without_a_force_is_refused_as_one_branch_is() {
    let home = tempfile::tempdir().unwrap();
    let dir = home.path();
    let words = ["invalid --force-amplitude: ", "0 N", "needs a harmonic force"];
    for args in [
        &["continue", "--vary", "f=3Hz:8Hz:3"][..],
        &["continue", "--vary", "mass=30g:40g:3"][..],
        &["continue", "--vary", "mass=30g:40g"][..],
        &["continue", "--vary", "mass=30g:40g:3", "--freq", "5Hz", "--json"][..],
    ] {
        assert_refused(dir, args, &words);
    }
    // A seed outside a range was skipped the same way ("0 branches"); it is refused as FROM
    // is for one branch, naming the parameter.
    let forced = ["continue", "--force-amplitude", "1", "--freq", "5Hz", "--vary"];
    for (vary, words) in [
        ("ball-position=-1:-2:2", &["invalid --ball-position: ", "-1 m", "inside the clearance"][..]),
        ("ball-position=0:3cm:4", &["invalid --ball-position: ", "0.02 m", "inside the clearance"][..]),
    ] {
        assert_refused(dir, &[&forced[..], &[vary]].concat(), words);
    }
    let (code, out, err) = thud(dir, &["continue", "--vary", "force=0N:3N:2", "--freq", "6Hz", "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert!(!v["branches"].as_array().unwrap().is_empty(), "a branch from the seed with a force: {out}");
}

/// `design --save DIR` puts DIR in place by renaming a folder onto it, which a path ending in
/// `.` or `..` cannot take: `--save .` searched and then failed with exit 1 ("Device or resource
/// busy"). It is refused before the search, naming what was typed, and nothing is written.
#[test]
fn a_save_folder_ending_in_a_dot_is_refused_before_the_search() {
    let home = tempfile::tempdir().unwrap();
    let dir = home.path();
    fs::create_dir(dir.join("s")).unwrap();
    for save in [".", "./", "s/.", "s/./", "s/..", ".."] {
        let args =
            ["design", "--vary", "mass=20g:120g", "--minimize", "spl_max_db", "--evaluations", "4", "--save", save];
        assert_refused(dir, &args, &["invalid --save: ", save, "ends in . or .."]);
        let (_, _, err) = thud(dir, &[&args[..], &["--force"]].concat());
        assert!(err.contains("ends in . or .."), "{save} --force: {err}");
    }
    assert_eq!(fs::read_dir(dir.join("s")).unwrap().count(), 0);
    assert_eq!(temps(dir), Vec::<String>::new());
}

/// A continuation or a bifurcation diagram over a parameter that does not move the damper (the
/// listener's place, the air, the zone thresholds) gave one orbit repeated at every value; it
/// is refused naming `--vary` and the parameter.
#[test]
fn a_parameter_that_does_not_move_the_damper_is_not_varied_by_orbit_studies() {
    let home = tempfile::tempdir().unwrap();
    let dir = home.path();
    let forced = ["--force-amplitude", "1", "--freq", "5Hz", "--vary"];
    for (command, vary, name) in [
        ("continue", "theta=10:20", "theta"),
        ("continue", "l-star=90:100:3", "l-star"),
        ("continue", "air-temperature=0:30:2", "air-temperature"),
        ("bifurcation", "r=0.5:1:3", "r"),
        ("bifurcation", "sound-speed=300:400:3", "sound-speed"),
    ] {
        let args = [&[command][..], &forced[..], &[vary]].concat();
        assert_refused(dir, &args, &["invalid --vary: ", vary, &format!("{name} does not change the motion")]);
    }
}
