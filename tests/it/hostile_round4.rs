#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! Nothing lost, round 4: a result of several files written as one set (a failure between
//! two files, a signal while they are staged or put in place), the explorer ending on a signal
//! while its terminal does not read, and the corners: a tiny `RUST_MIN_STACK`, a strike too
//! slow to fit, the record cap checked while reading, a config over a work cap, flags that
//! would change nothing, and a varied frequency standing in for `--freq`.
//!
//! Runs of the built binary, with HOME and the XDG folders in a temporary folder, each killed
//! after 20 s (a failure).

use std::fs;
use std::os::unix::ffi::OsStrExt;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use thud::fsio::{FAIL_SET_AFTER_FOR_TEST, HOLD_SET_FOR_TEST, HOLD_TEMP_FOR_TEST, TEMP_MARK};

use crate::support::{home, wait};
use home::in_home;
use wait::wait_within;

const BIN: &str = env!("CARGO_BIN_EXE_thud");
const TIMEOUT: Duration = Duration::from_secs(20);

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
fn assert_refused(home: &Path, args: &[&str], words: &[&str]) -> String {
    let (code, _, err) = thud(home, args);
    assert_eq!(code, 2, "{args:?}: {err}");
    assert_eq!(err.lines().count(), 1, "{args:?}: one line: {err}");
    for w in words {
        assert!(err.contains(w), "{args:?}: {w:?} missing from {err}");
    }
    err
}

/// A short bifurcation writing its figure to `a.svg`, `b.pdf` and its table to `c.txt`.
const SET: [&str; 16] = [
    "bifurcation",
    "--vary",
    "f=3Hz:8Hz:3",
    "--force-amplitude",
    "1",
    "--transient",
    "10",
    "--periods",
    "4",
    "--svg",
    "a.svg",
    "--pdf",
    "b.pdf",
    "--out",
    "c.txt",
    "--force",
];
const FILES: [&str; 3] = ["a.svg", "b.pdf", "c.txt"];

/// The set's files' contents (`None` for a missing one).
fn set_now(dir: &Path) -> Vec<Option<Vec<u8>>> {
    FILES.iter().map(|f| fs::read(dir.join(f)).ok()).collect()
}

/// Puts an old set in place: each file holds its own name.
fn old_set(dir: &Path) -> Vec<Option<Vec<u8>>> {
    for f in FILES {
        fs::write(dir.join(f), format!("old {f}")).unwrap();
    }
    set_now(dir)
}

/// Names in `dir` of thud's temporary files.
fn temps(dir: &Path) -> Vec<String> {
    fs::read_dir(dir)
        .unwrap()
        .map(|e| String::from_utf8_lossy(e.unwrap().file_name().as_bytes()).into_owned())
        .filter(|n| n.contains(TEMP_MARK))
        .collect()
}

/// Whether every file of the set is new: there, and none is the old one.
fn all_new(now: &[Option<Vec<u8>>], old: &[Option<Vec<u8>>]) -> bool {
    now.iter().zip(old).all(|(n, o)| n.is_some() && n != o)
}

#[test]
fn a_failure_between_two_files_of_a_set_puts_back_the_old_set() {
    let home = tempfile::tempdir().unwrap();
    let dir = home.path();
    let old = old_set(dir);
    // A failure before the second and before the third file is put in place.
    for after in ["1", "2"] {
        let (code, _, err) = thud_env(dir, &SET, &[(FAIL_SET_AFTER_FOR_TEST, after)]);
        assert_ne!(code, 0, "the injected failure fails the run: {err}");
        assert!(err.contains("injected"), "{err}");
        assert_eq!(set_now(dir), old, "after {after} file(s) placed, the old set is back: {err}");
        assert_eq!(temps(dir), Vec::<String>::new(), "no temporary file is left");
    }
    // Without old files, a failure leaves none of the new ones.
    let fresh = tempfile::tempdir().unwrap();
    let no_force = &SET[..SET.len() - 1];
    let (code, _, err) = thud_env(fresh.path(), no_force, &[(FAIL_SET_AFTER_FOR_TEST, "2")]);
    assert_ne!(code, 0, "{err}");
    assert_eq!(set_now(fresh.path()), vec![None, None, None], "no new file stays: {err}");
    assert_eq!(temps(fresh.path()), Vec::<String>::new());
    // And without the failure the whole new set is written.
    let (code, _, err) = thud(dir, &SET);
    assert_eq!(code, 0, "{err}");
    assert!(all_new(&set_now(dir), &old), "{err}");
    assert!(
        set_now(dir)[0].as_ref().unwrap().starts_with(b"<svg")
            || set_now(dir)[0].as_ref().unwrap().starts_with(b"<?xml")
    );
    assert!(set_now(dir)[1].as_ref().unwrap().starts_with(b"%PDF"));
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
fn a_signal_while_the_set_is_staged_leaves_the_old_set() {
    let home = tempfile::tempdir().unwrap();
    let dir = home.path();
    let old = old_set(dir);
    // Held with all three temporary files written, before any is put in place.
    let status = term_when(dir, &[(HOLD_TEMP_FOR_TEST, "30000")], |d| temps(d).len() == 3);
    assert_eq!(status.code(), Some(128 + 15), "{status:?}");
    assert_eq!(set_now(dir), old, "the old set, whole");
    assert_eq!(temps(dir), Vec::<String>::new(), "the staged files are removed");
}

#[test]
fn a_signal_while_the_set_is_put_in_place_waits_for_the_new_set() {
    let home = tempfile::tempdir().unwrap();
    let dir = home.path();
    let old = old_set(dir);
    // Held 1.5 s after the first file is in place: the signal comes between two renames.
    let first_placed = |d: &Path| fs::read(d.join(FILES[0])).ok() != old[0];
    let status = term_when(dir, &[(HOLD_SET_FOR_TEST, "1500")], first_placed);
    // The signal's exit (143) waits for the set; the run may finish first (0).
    assert!(matches!(status.code(), Some(0 | 143)), "{status:?}");
    assert!(
        all_new(&set_now(dir), &old),
        "the new set, whole: {:?}",
        set_now(dir).iter().map(Option::is_some).collect::<Vec<_>>()
    );
    assert_eq!(temps(dir), Vec::<String>::new(), "the replaced files are removed");
}

/// Drives the explorer through a pty whose master stops being read: resizes make it draw
/// whole frames until its write blocks; then `sys.argv[2]` is sent. Prints "exit CODE in S s"
/// or "STILL RUNNING" (after `sys.argv[3]` s), and on stderr whether a thread was seen blocked
/// in the terminal's write.
const STALLED_PTY: &str = r#"
import fcntl, os, pty, select, signal, struct, subprocess, sys, termios, time
m, s = pty.openpty()
def size(r, c):
    fcntl.ioctl(m, termios.TIOCSWINSZ, struct.pack("HHHH", r, c, 0, 0))
size(30, 100)
p = subprocess.Popen([sys.argv[1], "tui"], stdin=s, stdout=s, stderr=s, start_new_session=True,
                     env=dict(os.environ, TERM="xterm-256color"))
os.close(s)
seen, start = b"", time.time()
while b"parameters" not in seen and time.time() - start < 15:
    if select.select([m], [], [], 0.1)[0]:
        seen += os.read(m, 65536)
if b"parameters" not in seen or p.poll() is not None:
    print("NO SCREEN", p.poll(), seen[-200:])
    sys.exit(0)
def blocked():
    for t in os.listdir(f"/proc/{p.pid}/task"):
        try:
            wchan = open(f"/proc/{p.pid}/task/{t}/wchan").read()
        except OSError:
            continue
        if "tty_write" in wchan or "wait_woken" in wchan or "n_tty" in wchan:
            return True
    return False
end, i = time.time() + 15, 0
while time.time() < end:
    i += 1
    size(30 + i % 2 * 20, 100 + i % 2 * 60)
    p.send_signal(signal.SIGWINCH)
    time.sleep(0.02)
    if i > 50 and blocked():
        break
print("blocked", blocked(), "after", i, "resizes", file=sys.stderr)
time.sleep(0.3)
t0 = time.time()
p.send_signal(getattr(signal, sys.argv[2]))
try:
    code = p.wait(timeout=float(sys.argv[3]))
    print("exit", code, "in %.3f s" % (time.time() - t0))
except subprocess.TimeoutExpired:
    p.kill()
    p.wait()
    print("STILL RUNNING")
"#;

#[test]
fn the_explorer_ends_within_a_second_of_a_signal_while_its_terminal_does_not_read() {
    for (signal, code) in [("SIGTERM", 143), ("SIGHUP", 129), ("SIGINT", 130)] {
        let home = tempfile::tempdir().unwrap();
        let Ok(out) = in_home("python3", &["-c", STALLED_PTY, BIN, signal, "3"], home.path(), &[]).output() else {
            crate::support::skip::skip("python3 (for its pty module) is not installed");
            return;
        };
        let said = String::from_utf8_lossy(&out.stdout);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains("blocked True"), "{signal}: the explorer never blocked on its terminal: {said}{err}");
        let mut words = said.split_whitespace();
        assert_eq!(words.next(), Some("exit"), "{signal}: {said}{err}");
        assert_eq!(words.next(), Some(code.to_string().as_str()), "{signal}: {said}");
        let seconds: f64 = words.nth(1).unwrap().parse().unwrap();
        assert!(seconds < 1.0, "{signal}: ended {seconds} s after the signal");
    }
}

#[test]
fn a_stack_of_one_byte_asked_does_not_abort_a_sweep() {
    let home = tempfile::tempdir().unwrap();
    let args = ["sweep", "--vary", "f=3Hz:8Hz:3", "--force-amplitude", "1", "--duration", "0.5", "--csv"];
    let (code, out, err) = thud_env(home.path(), &args, &[("RUST_MIN_STACK", "1"), ("RAYON_NUM_THREADS", "2")]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(out.lines().count(), 4, "a header and three rows: {out}");
}

#[test]
fn a_strike_too_slow_to_fit_names_v0_as_typed() {
    let home = tempfile::tempdir().unwrap();
    let (code, csv, err) = thud(home.path(), &["simulate", "--c1", "60", "--csv", "--samples", "6001"]);
    assert_eq!(code, 0, "{err}");
    fs::write(home.path().join("d.csv"), csv).unwrap();
    let err = assert_refused(home.path(), &["fit", "damper", "--data", "d.csv", "--v0", "1e-300"], &["--v0", "1e-300"]);
    assert!(!err.contains("c1:") && !err.contains("NaN"), "{err}");
}

#[test]
fn the_record_cap_is_checked_while_reading() {
    let home = tempfile::tempdir().unwrap();
    // One row past the cap of 1e7 samples, then a row that is no number: had the whole file
    // been parsed before the cap, that row would be the error.
    let mut text = String::with_capacity(45_000_000);
    text += "t_s,x_m\n";
    text += &"0,0\n".repeat(10_000_001);
    text += "oops,0\n";
    fs::write(home.path().join("big.csv"), text).unwrap();
    let start = Instant::now();
    let args = ["fit", "structure", "--main-mass", "1", "--data", "big.csv"];
    // Ten million rows take seconds to read on a busy machine: a longer wait than the others.
    let child = in_home(BIN, &args, home.path(), &[]).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().unwrap();
    let out = wait_within(child, Duration::from_secs(180), "thud fit");
    let (code, err) = (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stderr));
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--data big.csv: more than 1e7 rows") && err.contains("--no-limit"), "{err}");
    assert!(!err.contains("oops"), "refused at the cap, before the last row: {err}");
    eprintln!("refused in {:.2} s", start.elapsed().as_secs_f64());
}

#[test]
fn config_check_refuses_a_step_every_command_refuses() {
    let home = tempfile::tempdir().unwrap();
    let dir = home.path().join("config/thud");
    fs::create_dir_all(&dir).unwrap();
    fs::write(dir.join("config.toml"), "[design]\nsolver = \"newmark\"\ndt = 1e-14\n").unwrap();
    let (code, out, err) = thud(home.path(), &["config", "check"]);
    assert_eq!(code, 2, "{out}{err}");
    assert!(out.contains(":3:") && out.contains("dt") && out.contains("Newmark steps"), "at dt's line: {out}");
    // The commands refuse it with the same cap, naming the key.
    let (code, _, err) = thud(home.path(), &["simulate", "--json"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("dt in config.toml [design]") && err.contains("Newmark steps"), "{err}");
    // A step the commands take passes.
    fs::write(dir.join("config.toml"), "[design]\nsolver = \"newmark\"\ndt = 1e-6\n").unwrap();
    let (code, out, err) = thud(home.path(), &["config", "check"]);
    assert_eq!(code, 0, "{out}{err}");
}

#[test]
fn the_air_of_the_paper_model_is_not_a_temperature_or_a_pressure() {
    let home = tempfile::tempdir().unwrap();
    for flag in ["--air-temperature", "--air-pressure"] {
        let value = if flag == "--air-temperature" { "30" } else { "90kPa" };
        assert_refused(home.path(), &["simulate", flag, value], &[flag, "paper model", "physical"]);
        assert_refused(home.path(), &["simulate", "--model", "paper", flag, value], &[flag, "--model paper"]);
        let (code, _, err) = thud(home.path(), &["simulate", "--model", "physical", flag, value, "--json"]);
        assert_eq!(code, 0, "the physical model takes it: {err}");
    }
}

#[test]
fn a_study_of_orbits_refuses_a_duration_or_settle_it_would_not_use() {
    let home = tempfile::tempdir().unwrap();
    let forced = ["--force-amplitude", "1", "--freq", "5"];
    for cmd in [&["bifurcation", "--vary", "f=3Hz:8Hz:3"][..], &["impact-map"], &["basins", "--grid", "3"]] {
        for extra in [&["--duration", "5"][..], &["--settle"]] {
            let args: Vec<&str> = cmd.iter().chain(&forced).chain(extra).copied().collect();
            assert_refused(home.path(), &args, &[extra[0], "--transient"]);
        }
    }
}

#[test]
fn a_varied_frequency_needs_a_force_and_is_the_frequency() {
    let home = tempfile::tempdir().unwrap();
    // Without a force every row would be the same: refused.
    assert_refused(home.path(), &["sweep", "--vary", "f=3Hz:8Hz:3"], &["--vary", "f=3Hz:8Hz:3", "--force-amplitude"]);
    // With a force and no --freq: the varied frequency is the frequency, rows differ.
    let (code, out, err) =
        thud(home.path(), &["sweep", "--vary", "f=3Hz:8Hz:3", "--force-amplitude", "1", "--duration", "1", "--csv"]);
    assert_eq!(code, 0, "{err}");
    let rows: Vec<&str> = out.lines().skip(1).map(|l| l.split_once(',').unwrap().1).collect();
    assert_eq!(rows.len(), 3, "{out}");
    assert!(rows.iter().any(|r| *r != rows[0]), "the frequency changes the result: {out}");
    let (code, _, err) = thud(
        home.path(),
        &["bifurcation", "--vary", "f=3Hz:8Hz:3", "--force-amplitude", "1", "--transient", "10", "--periods", "4"],
    );
    assert_eq!(code, 0, "bifurcation takes the varied frequency too: {err}");
}
