#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::case_sensitive_file_extension_comparisons,
    clippy::items_after_statements
)] // a panic is how a test fails; file names here are ours
//! Files as found: the real binary run with
//! HOME and the XDG folders in a temporary directory. No export replaces an existing file
//! without --force; none replaces a device, FIFO or folder even with it; none follows a symlink
//! planted at a temporary name; none leaves a temporary file after success, an error, SIGTERM or
//! (on Linux, with O_TMPFILE) kill -9; a config that is a FIFO or a symlink to /dev/zero is
//! refused at once with a warning.
//!
//! Device nodes: the tests that could replace a device on broken code use a private node made
//! with `mknod` in the temporary folder (when the test runs as root); the real `/dev/null` and
//! `/dev/full` are only tried in a test that checks they are still character devices after.

use std::fs;
use std::os::unix::fs::{FileTypeExt, MetadataExt};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use thud::fsio::{HOLD_TEMP_FOR_TEST, NAMED_TEMPS_FOR_TEST};

use crate::support::home;
use crate::support::wait;
use home::in_home;
use wait::wait_within;

const BIN: &str = env!("CARGO_BIN_EXE_thud");
const TIMEOUT: Duration = Duration::from_secs(20);

/// thud with HOME and the XDG folders inside `home`, run in `home`, with extra environment.
fn command(args: &[&str], home: &Path, env: &[(&str, &str)]) -> Command {
    in_home(BIN, args, home, env)
}

/// Runs to completion within [`TIMEOUT`] (killed and failed after it): (code, stdout, stderr).
fn run(args: &[&str], home: &Path, env: &[(&str, &str)]) -> (i32, String, String) {
    let child = command(args, home, env).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().unwrap();
    let out = wait_within(child, TIMEOUT, &format!("thud {args:?}"));
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

/// The names in `dir`, sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> =
        fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    v.sort();
    v
}

/// Names in `dir` that look like a temporary file of thud's (old pattern or new).
fn temp_files(dir: &Path) -> Vec<String> {
    names(dir).into_iter().filter(|n| n.starts_with('.') && n.ends_with(".tmp")).collect()
}

/// The two ways a file is written: anonymous O_TMPFILE (the default on Linux) and a named
/// temporary file (the fallback), forced with the environment seam.
const STRATEGIES: [&[(&str, &str)]; 2] = [&[], &[(NAMED_TEMPS_FOR_TEST, "1")]];

fn one_line_exit_2(code: i32, out: &str, err: &str, needles: &[&str]) {
    assert_eq!(code, 2, "{err}");
    assert!(out.is_empty(), "{out}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    for n in needles {
        assert!(err.contains(n), "{n:?} not in {err}");
    }
}

#[test]
fn an_existing_out_is_refused_without_force_and_replaced_with_it() {
    for env in STRATEGIES {
        let home = tempfile::tempdir().unwrap();
        let target = home.path().join("e.csv");
        fs::write(&target, "precious\n").unwrap();
        let (code, out, err) = run(&["export", "csv", "history", "--out", "e.csv"], home.path(), env);
        one_line_exit_2(code, &out, &err, &["e.csv", "exists", "--force"]);
        assert_eq!(fs::read_to_string(&target).unwrap(), "precious\n", "{env:?}");
        let (code, _, err) = run(&["export", "csv", "history", "--out", "e.csv", "--force"], home.path(), env);
        assert_eq!(code, 0, "{err}");
        assert!(fs::read_to_string(&target).unwrap().starts_with("t_s,x_m,y_m,x_free_m\n"));
        // A refused SVG and WAV too (every export goes through the same writer).
        for (args, name) in
            [(&["export", "svg", "waveform"][..], "e.svg"), (&["export", "wav", "--duration", "0.1"][..], "e.wav")]
        {
            fs::write(home.path().join(name), "precious").unwrap();
            let (code, out, err) = run(&[args, &["--out", name]].concat(), home.path(), env);
            one_line_exit_2(code, &out, &err, &[name, "--force"]);
            assert_eq!(fs::read_to_string(home.path().join(name)).unwrap(), "precious");
        }
        assert_eq!(temp_files(home.path()), Vec::<String>::new());
    }
}

/// Makes a private character device like /dev/full (1,7) at `path`; false if not permitted.
fn private_full(path: &Path) -> bool {
    Command::new("mknod").arg(path).args(["c", "1", "7"]).output().is_ok_and(|o| o.status.success())
}

#[test]
fn a_device_fifo_or_folder_is_refused_even_with_force_and_left_as_it_was() {
    let home = tempfile::tempdir().unwrap();
    let dev = home.path().join("full-device");
    let fifo = home.path().join("pipe");
    let folder = home.path().join("folder.csv");
    assert!(Command::new("mkfifo").arg(&fifo).status().unwrap().success());
    fs::create_dir(&folder).unwrap();
    // A FIFO is written through while something reads it; with no reader it is refused.
    let mut targets: Vec<(PathBuf, &str)> =
        vec![(fifo.clone(), "FIFO with no reader"), (folder.clone(), "directory; thud writes through only")];
    if private_full(&dev) {
        targets.push((dev.clone(), "character device; thud writes through only"));
    } else {
        crate::support::skip::skip("mknod is not permitted (needs root): the case of a private device");
    }
    for env in STRATEGIES {
        for (target, kind) in &targets {
            let before = fs::symlink_metadata(target).unwrap();
            for force in [false, true] {
                let t = target.to_str().unwrap();
                let args =
                    [&["export", "csv", "history", "--out", t][..], if force { &["--force"] } else { &[] }].concat();
                let (code, out, err) = run(&args, home.path(), env);
                one_line_exit_2(code, &out, &err, &[t, kind]);
                let after = fs::symlink_metadata(target).unwrap();
                assert_eq!(after.file_type(), before.file_type(), "{t} changed type");
                assert_eq!((after.ino(), after.rdev()), (before.ino(), before.rdev()), "{t} was replaced");
            }
        }
    }
    assert!(fs::symlink_metadata(&fifo).unwrap().file_type().is_fifo());
    assert_eq!(temp_files(home.path()), Vec::<String>::new());
    // `paper all` refuses a device or folder among its files the same way, before any work.
    let out_dir = home.path().join("paper");
    fs::create_dir_all(out_dir.join("REPORT.md")).unwrap();
    let (code, out, err) = run(&["paper", "all", "--out", "paper", "--force"], home.path(), &[]);
    one_line_exit_2(code, &out, &err, &["REPORT.md", "directory"]);
    assert_eq!(names(&out_dir), ["REPORT.md"], "nothing written");
}

#[test]
fn the_real_dev_null_is_written_through_and_dev_full_refused_and_both_stay_devices() {
    for (dev, code) in [("/dev/null", 0), ("/dev/full", 2)] {
        let Ok(before) = fs::symlink_metadata(dev) else { continue };
        assert!(before.file_type().is_char_device(), "{dev} is not a character device before the test");
        let home = tempfile::tempdir().unwrap();
        for force in [false, true] {
            let args =
                [&["export", "csv", "waveform", "--out", dev][..], if force { &["--force"] } else { &[] }].concat();
            let (got, out, err) = run(&args, home.path(), &[]);
            let after = fs::symlink_metadata(dev).unwrap();
            assert!(after.file_type().is_char_device(), "{dev} IS NO LONGER A DEVICE: recreate it (mknod)");
            assert_eq!(after.rdev(), before.rdev(), "{dev}");
            if code == 0 {
                assert_eq!(got, 0, "{err}");
            } else {
                one_line_exit_2(got, &out, &err, &[dev, "character device"]);
            }
        }
    }
}

#[test]
fn a_symlink_at_the_target_is_refused_with_or_without_force_and_never_replaced() {
    for env in STRATEGIES {
        let home = tempfile::tempdir().unwrap();
        let victim = home.path().join("victim.txt");
        fs::write(&victim, "do not touch\n").unwrap();
        let link = home.path().join("out.csv");
        std::os::unix::fs::symlink(&victim, &link).unwrap();
        for force in [false, true] {
            let args = [&["export", "csv", "history", "--out", "out.csv"][..], if force { &["--force"] } else { &[] }]
                .concat();
            let (code, out, err) = run(&args, home.path(), env);
            one_line_exit_2(code, &out, &err, &["invalid --out", "out.csv", "symbolic link"]);
            assert!(fs::symlink_metadata(&link).unwrap().file_type().is_symlink(), "the link is left");
            assert_eq!(fs::read_to_string(&victim).unwrap(), "do not touch\n", "its pointee is untouched");
        }
        assert_eq!(temp_files(home.path()), Vec::<String>::new());
    }
}

/// The pid the next process will likely get (Linux), to plant symlinks for the old
/// `.NAME.PID-SEQ.tmp` pattern.
fn next_pids() -> std::ops::Range<u32> {
    let last = fs::read_to_string("/proc/sys/kernel/ns_last_pid").ok().and_then(|s| s.trim().parse().ok());
    let from = last.unwrap_or(std::process::id()) + 1;
    from..from + 3000
}

#[test]
fn symlinks_planted_at_any_plausible_temporary_name_are_never_followed() {
    for env in STRATEGIES {
        for force in [false, true] {
            let home = tempfile::tempdir().unwrap();
            let victim = home.path().join("victim.txt");
            fs::write(&victim, "do not touch\n").unwrap();
            let mut planted = Vec::new();
            for pid in next_pids() {
                for seq in 0..2 {
                    planted.push(format!(".e.csv.{pid}-{seq}.tmp"));
                }
            }
            for n in [
                ".e.csv.tmp",
                ".e.csv..tmp",
                ".e.csv.000000.tmp",
                ".e.csv.aaaaaa.tmp",
                ".e.csv.AAAAAA.tmp",
                ".e.csv.1.tmp",
                ".e.csv.thud-aaaaaa.tmp",
                ".e.csv.thud-AAAAAA.tmp",
            ] {
                planted.push(n.to_string());
            }
            for n in &planted {
                std::os::unix::fs::symlink(&victim, home.path().join(n)).unwrap();
            }
            if force {
                fs::write(home.path().join("e.csv"), "old\n").unwrap();
            }
            let args =
                [&["export", "csv", "history", "--out", "e.csv"][..], if force { &["--force"] } else { &[] }].concat();
            let (code, _, err) = run(&args, home.path(), env);
            assert_eq!(code, 0, "{err}");
            assert_eq!(
                fs::read_to_string(&victim).unwrap(),
                "do not touch\n",
                "{env:?} force {force}: followed a link"
            );
            let e = fs::symlink_metadata(home.path().join("e.csv")).unwrap();
            assert!(e.file_type().is_file(), "e.csv is a regular file");
            assert!(fs::read_to_string(home.path().join("e.csv")).unwrap().starts_with("t_s,"));
            for n in &planted {
                let p = home.path().join(n);
                assert!(fs::symlink_metadata(&p).unwrap().file_type().is_symlink(), "{n}");
                assert_eq!(fs::read_link(&p).unwrap(), victim, "{n}");
            }
            let mut expected: Vec<String> = planted.clone();
            expected.extend(["e.csv".to_string(), "victim.txt".to_string()]);
            expected.sort();
            assert_eq!(names(home.path()), expected, "nothing else is left");
        }
    }
}

#[test]
fn no_temporary_file_is_left_after_success_or_an_error() {
    for env in STRATEGIES {
        let home = tempfile::tempdir().unwrap();
        let dir = home.path().join("out");
        // Success: several kinds, and a --force replacement.
        for (args, name) in [
            (&["export", "csv", "history"][..], "h.csv"),
            (&["export", "svg", "history"][..], "h.svg"),
            (&["export", "wav", "--duration", "0.2"][..], "s.wav"),
        ] {
            let p = format!("out/{name}");
            let (code, _, err) = run(&[args, &["--out", &p]].concat(), home.path(), env);
            assert_eq!(code, 0, "{err}");
            let (code, _, err) = run(&[args, &["--out", &p, "--force"]].concat(), home.path(), env);
            assert_eq!(code, 0, "{err}");
        }
        assert_eq!(names(&dir), ["h.csv", "h.svg", "s.wav"], "{env:?}");
        // An error after the temporary file exists: the file size limit (EFBIG) hits while the
        // WAV is being written (SIGXFSZ ignored, as a shell with `ulimit -f` would have it).
        let errdir = home.path().join("limited");
        fs::create_dir(&errdir).unwrap();
        let script = format!("trap '' XFSZ; ulimit -f 8; exec '{BIN}' export wav --duration 0.5 --out big.wav");
        let mut c = in_home("sh", &["-c", &script], &errdir, env);
        let out = wait_within(c.stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().unwrap(), TIMEOUT, "limited");
        let err = String::from_utf8_lossy(&out.stderr);
        // A failed write is I/O, not bad input: exit 1 (ARCHITECTURE.md's contract).
        assert_eq!(out.status.code(), Some(1), "{err}");
        assert!(err.contains("cannot write") && err.contains("big.wav"), "{err}");
        assert_eq!(names(&errdir), Vec::<String>::new(), "{env:?}: nothing left after the error");
    }
}

/// True once `pid` holds an open temporary file in `dir`: a named `.NAME.*.tmp` there, or an
/// anonymous O_TMPFILE one (its /proc fd link reads `DIR/#INODE (deleted)`).
fn holds_temp(pid: u32, dir: &Path) -> bool {
    let Ok(fds) = fs::read_dir(format!("/proc/{pid}/fd")) else { return false };
    fds.filter_map(|fd| fs::read_link(fd.ok()?.path()).ok()).any(|target| {
        let t = target.to_string_lossy();
        target.parent() == Some(dir) && (t.ends_with(" (deleted)") || t.ends_with(".tmp"))
    })
}

/// Starts a held export, waits until its temporary file exists, sends `signal`, and checks that
/// nothing is left in the folder.
fn signal_mid_export_leaves_nothing(signal: &str, env: &[(&str, &str)]) {
    let home = tempfile::tempdir().unwrap();
    let dir = home.path().join("out");
    fs::create_dir(&dir).unwrap();
    let dir = dir.canonicalize().unwrap();
    let mut env = env.to_vec();
    env.push((HOLD_TEMP_FOR_TEST, "30000"));
    let target = dir.join("e.csv");
    let child = command(&["export", "csv", "history", "--out", target.to_str().unwrap()], home.path(), &env)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let pid = child.id();
    let start = Instant::now();
    while !holds_temp(pid, &dir) {
        assert!(start.elapsed() < TIMEOUT, "{env:?}: no temporary file in {} appeared", dir.display());
        std::thread::sleep(Duration::from_millis(20));
    }
    assert!(Command::new("kill").args([signal, &pid.to_string()]).status().unwrap().success());
    let out = wait_within(child, Duration::from_secs(10), "the signalled export");
    use std::os::unix::process::ExitStatusExt;
    let by_signal = out.status.signal().is_some() || out.status.code().is_some_and(|c| c > 128);
    assert!(by_signal, "{env:?}: {:?} {}", out.status, String::from_utf8_lossy(&out.stderr));
    assert_eq!(names(&dir), Vec::<String>::new(), "{env:?} {signal}: files left (the export was held before linking)");
}

#[test]
fn sigterm_and_sigint_mid_export_leave_no_temporary_file() {
    for env in STRATEGIES {
        signal_mid_export_leaves_nothing("-TERM", env);
        signal_mid_export_leaves_nothing("-INT", env);
    }
}

#[test]
fn kill_9_mid_export_leaves_nothing_with_anonymous_temporary_files() {
    // O_TMPFILE: the temporary file has no name, so even SIGKILL leaves nothing to clean.
    // (Skipped where the folder's file system lacks O_TMPFILE: then the named fallback is used,
    // which only SIGINT/SIGTERM/SIGHUP can clean up.)
    let probe = tempfile::tempdir().unwrap();
    if !tmpfile_supported(probe.path()) {
        crate::support::skip::skip(&format!("O_TMPFILE is not supported in {}", probe.path().display()));
        return;
    }
    signal_mid_export_leaves_nothing("-KILL", &[]);
}

fn tmpfile_supported(dir: &Path) -> bool {
    use rustix::fs::{Mode, OFlags};
    rustix::fs::open(dir, OFlags::WRONLY | OFlags::TMPFILE, Mode::from_bits_truncate(0o600)).is_ok()
}

#[test]
fn out_dash_writes_to_standard_output_and_no_file() {
    let home = tempfile::tempdir().unwrap();
    let (code, out, err) = run(&["export", "csv", "waveform", "--points", "20", "--out", "-"], home.path(), &[]);
    assert_eq!(code, 0, "{err}");
    let (code, _, err) = run(&["export", "csv", "waveform", "--points", "20", "--out", "w.csv"], home.path(), &[]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(out, fs::read_to_string(home.path().join("w.csv")).unwrap());
    assert!(!home.path().join("-").exists());
    let (code, _, err) = run(&["paper", "all", "--out", "-"], home.path(), &[]);
    one_line_exit_2(code, "", &err, &["--out DIR"]);
}

#[test]
fn paper_all_keeps_existing_files_unless_force() {
    let home = tempfile::tempdir().unwrap();
    let dir = home.path().join("paper");
    fs::create_dir(&dir).unwrap();
    fs::write(dir.join("table1.csv"), "mine\n").unwrap();
    let (code, out, err) = run(&["paper", "all", "--out", "paper"], home.path(), &[]);
    one_line_exit_2(code, &out, &err, &["table1.csv", "exists", "--force"]);
    assert_eq!(names(&dir), ["table1.csv"], "nothing written when one file is refused");
    assert_eq!(fs::read_to_string(dir.join("table1.csv")).unwrap(), "mine\n");
    let (code, _, err) = run(&["paper", "all", "--out", "paper", "--force"], home.path(), &[]);
    assert_eq!(code, 0, "{err}");
    assert!(fs::read_to_string(dir.join("table1.csv")).unwrap().starts_with("radius_mm,"));
    assert_eq!(names(&dir).len(), thud::export::report::expected_files().len());
}

/// `config.toml` at `home`'s config folder.
fn config_path(home: &Path) -> PathBuf {
    let p = home.join("config").join("thud").join("config.toml");
    fs::create_dir_all(p.parent().unwrap()).unwrap();
    p
}

/// `thud presets` with this config: prompt, exit 0, the presets listed, one warning line with
/// `needle`.
fn presets_warn(home: &Path, needle: &str) {
    let start = Instant::now();
    let (code, out, err) = run(&["presets"], home, &[]);
    assert!(start.elapsed() < Duration::from_secs(5), "took {:?}", start.elapsed());
    assert_eq!(code, 0, "{err}");
    assert!(out.lines().any(|l| l.starts_with("default")), "{out}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(err.contains("warning") && err.contains("config.toml") && err.contains(needle), "{err}");
    assert!(err.contains("default settings"), "{err}");
}

#[test]
fn a_config_that_is_a_fifo_or_a_link_to_dev_zero_is_refused_promptly() {
    let home = tempfile::tempdir().unwrap();
    let cfg = config_path(home.path());
    assert!(Command::new("mkfifo").arg(&cfg).status().unwrap().success());
    presets_warn(home.path(), "FIFO");
    assert!(fs::symlink_metadata(&cfg).unwrap().file_type().is_fifo(), "left as it was");
    fs::remove_file(&cfg).unwrap();
    std::os::unix::fs::symlink("/dev/zero", &cfg).unwrap();
    presets_warn(home.path(), "character device");
    fs::remove_file(&cfg).unwrap();
    // A symlink to a FIFO is refused as well.
    let fifo = home.path().join("fifo");
    assert!(Command::new("mkfifo").arg(&fifo).status().unwrap().success());
    std::os::unix::fs::symlink(&fifo, &cfg).unwrap();
    presets_warn(home.path(), "FIFO");
}

#[test]
fn a_config_over_the_size_limit_is_refused_and_a_symlinked_one_is_used() {
    let home = tempfile::tempdir().unwrap();
    let cfg = config_path(home.path());
    let mut big = "[thresholds]\nl_star_db = 90.0\n".to_string();
    big += &"# padding\n".repeat((thud::fsio::MAX_READ_BYTES as usize) / 10 + 1);
    fs::write(&cfg, &big).unwrap();
    presets_warn(home.path(), "larger than");
    // A dotfile manager's symlink to a regular file is fine: its thresholds are used.
    fs::remove_file(&cfg).unwrap();
    let real = home.path().join("dotfiles-config.toml");
    fs::write(&real, "[thresholds]\nl_star_db = 90.0\n").unwrap();
    std::os::unix::fs::symlink(&real, &cfg).unwrap();
    let (code, out, err) = run(&["simulate", "--duration", "0.1", "--json"], home.path(), &[]);
    assert_eq!(code, 0, "{err}");
    assert!(err.is_empty(), "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["design"]["thresholds"]["spl_db"], 90.0);
}

#[test]
fn two_outputs_naming_one_file_are_refused_before_anything_is_written() {
    // `--svg`, `--pdf` and `--out` of one run are three files: two of them naming one place
    // (however spelled) is refused with one line before any work, and nothing is written or
    // replaced, with --force too; so is a figure on standard output beside the table.
    let home = tempfile::tempdir().unwrap();
    fs::create_dir(home.path().join("sub")).unwrap();
    fs::write(home.path().join("old.x"), "kept").unwrap();
    for cmd in ["bifurcation", "impact-map", "basins", "sweep"] {
        let base: Vec<&str> = match cmd {
            "bifurcation" => vec![cmd, "--preset", "forced-rattle", "--vary", "f=7Hz:8Hz:3"],
            "sweep" => vec![cmd, "--vary", "v0=1:2:2"],
            _ => vec![cmd, "--preset", "forced-rattle"],
        };
        for (outputs, needles) in [
            (&["--svg", "o.x", "--out", "o.x"][..], &["--out", "o.x", "--svg"][..]),
            (&["--svg", "o.x", "--pdf", "sub/../o.x"][..], &["--pdf", "--svg"][..]),
            (&["--svg", "old.x", "--pdf", "./old.x", "--force"][..], &["--pdf", "old.x"][..]),
            (&["--out", "p.x", "--pdf", "p.x", "--force"][..], &["--pdf", "p.x", "--out"][..]),
            (&["--svg", "-"][..], &["--svg", "standard output"][..]),
            (&["--out", "-", "--pdf", "-"][..], &["--pdf", "standard output"][..]),
        ] {
            let args = [&base[..], outputs].concat();
            let (code, out, err) = run(&args, home.path(), &[]);
            one_line_exit_2(code, &out, &err, needles);
            assert_eq!(names(home.path()), ["old.x", "sub"], "{args:?}");
            assert_eq!(fs::read_to_string(home.path().join("old.x")).unwrap(), "kept", "{args:?}");
        }
    }
}
