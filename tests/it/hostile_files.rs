#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! Nothing lost, round 2: the real binary run against special
//! files, killed mid-write, and given names that are not UTF-8.
//!
//! The device tests run inside a private mount namespace (`unshare -m`) with a fresh tmpfs on
//! `/dev`, so even a broken build can only replace nodes the test made itself; where namespaces
//! are not available (not root, no `unshare`) they print why and skip.

use std::ffi::OsStr;
use std::fs;
use std::os::unix::ffi::OsStrExt;
use std::os::unix::process::ExitStatusExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use thud::fsio::{HOLD_TEMP_FOR_TEST, NAMED_TEMPS_FOR_TEST};

use crate::support::home;
use crate::support::wait;
use home::in_home;
use wait::wait_within;

const BIN: &str = env!("CARGO_BIN_EXE_thud");
const TIMEOUT: Duration = Duration::from_secs(20);

/// Runs thud to completion: (code, stdout, stderr).
fn thud(args: &[&OsStr], home: &Path) -> (i32, String, String) {
    let child = in_home(BIN, args, home, &[]).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().unwrap();
    let out = wait_within(child, TIMEOUT, "thud");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

fn os(args: &[&str]) -> Vec<&'static OsStr> {
    args.iter().map(|a| OsStr::new(Box::leak(a.to_string().into_boxed_str()))).collect()
}

/// The names in `dir` as bytes, sorted.
fn names(dir: &Path) -> Vec<Vec<u8>> {
    let mut v: Vec<Vec<u8>> = fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().as_bytes().to_vec()).collect();
    v.sort();
    v
}

/// Whether this machine lets the test make a private mount namespace with a tmpfs.
fn namespaces() -> bool {
    let ok = Command::new("unshare")
        .args(["-m", "sh", "-c", "mount -t tmpfs none /mnt"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    if !ok {
        crate::support::skip::skip("no private mount namespace here (needs root and util-linux `unshare -m`)");
    }
    ok
}

/// Runs `script` with `sh` in a private mount namespace whose `/dev` is a fresh tmpfs (`$T` is
/// thud). Output and the exit status of `sh`.
fn in_private_dev(script: &str) -> Output {
    let full = format!("mount -t tmpfs none /dev || exit 99\n{script}");
    let child = Command::new("unshare")
        .args(["-m", "sh", "-c", &full])
        .env("T", BIN)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let out = wait_within(child, TIMEOUT, script);
    assert_ne!(out.status.code(), Some(99), "could not mount a tmpfs on the private /dev");
    out
}

/// The export every device test runs, with `--force` (which must still replace nothing).
const EXPORT: &str = "\"$T\" export csv waveform --points 5 --force";

#[test]
fn out_dev_stdout_with_force_writes_through_and_never_replaces_the_link() {
    if !namespaces() {
        return;
    }
    // The exact case: /dev/stdout is a symlink to /proc/self/fd/1.
    let out = in_private_dev(&format!(
        "ln -s /proc/self/fd/1 /dev/stdout\n{EXPORT} --out /dev/stdout; echo \"rc=$?\"\nstat -c 'after=%F' /dev/stdout"
    ));
    let text = String::from_utf8_lossy(&out.stdout);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(text.starts_with("t_s,p_pa\n"), "the CSV goes to standard output: {text} {err}");
    assert!(text.contains("rc=0\n"), "{text} {err}");
    assert!(text.contains("after=symbolic link"), "/dev/stdout must stay a link: {text}");
    // `-` is standard output too, and writes no file.
    let out = in_private_dev(&format!("cd /dev && {EXPORT} --out -; echo \"rc=$?\"; ls -A /dev | wc -l"));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.starts_with("t_s,p_pa\n") && text.contains("rc=0\n0\n"), "{text}");
}

#[test]
fn devices_fifos_links_and_folders_are_written_through_or_refused_never_replaced() {
    if !namespaces() {
        return;
    }
    // (setup, target, exit code, what it must still be: `stat -c '%F %t:%T'`)
    let cases = [
        ("mknod /dev/null c 1 3", "/dev/null", 0, "character special file 1:3"),
        ("mknod /dev/mem c 1 1", "/dev/mem", 2, "character special file 1:1"),
        ("mknod /dev/full c 1 7", "/dev/full", 2, "character special file 1:7"),
        ("mknod /dev/disk b 7 0", "/dev/disk", 2, "block special file 7:0"),
        ("mkdir /dev/dir", "/dev/dir", 2, "directory 0:0"),
        ("mkfifo /dev/fifo", "/dev/fifo", 2, "fifo 0:0"),
        ("echo keep > /dev/file && ln -s /dev/file /dev/link", "/dev/link", 2, "symbolic link 0:0"),
        ("ln -s /dev/nowhere /dev/dangling", "/dev/dangling", 2, "symbolic link 0:0"),
        ("mknod /dev/null c 1 3 && ln -s /dev/null /dev/to-null", "/dev/to-null", 0, "symbolic link 0:0"),
    ];
    for (setup, target, code, still) in cases {
        let out = in_private_dev(&format!(
            "{setup} || exit 98\n{EXPORT} --out {target} >/dev/out 2>/dev/err; echo \"rc=$?\"\n\
             stat -c '%F %t:%T' {target}\necho \"err=$(cat /dev/err)\"\ncat /dev/file 2>&1; ls -A /dev | tr '\\n' ' '"
        ));
        let text = String::from_utf8_lossy(&out.stdout);
        assert_ne!(out.status.code(), Some(98), "{setup}");
        assert!(text.contains(&format!("rc={code}\n")), "{target}: {text}");
        assert!(text.contains(&format!("\n{still}\n")), "{target} was replaced: {text}");
        if code == 2 {
            let err = text.lines().find(|l| l.starts_with("err=")).unwrap();
            assert!(err.starts_with("err=thud: invalid --out: ") && err.contains(target), "{err}");
        }
        if target == "/dev/link" {
            assert!(text.contains("\nkeep\n"), "the link's target is untouched: {text}");
        }
        assert!(!text.contains(".thud-"), "a temporary file is left: {text}");
    }
    // A FIFO with a reader is written through.
    let out = in_private_dev(&format!(
        "mkfifo /dev/fifo && exec 3<>/dev/fifo\n{EXPORT} --out /dev/fifo; echo \"rc=$?\"\n\
         stat -c '%F' /dev/fifo; head -1 <&3"
    ));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("rc=0\nfifo\nt_s,p_pa\n"), "{text} {}", String::from_utf8_lossy(&out.stderr));
}

/// Whether `dir` supports O_TMPFILE.
fn tmpfile_supported(dir: &Path) -> bool {
    use rustix::fs::{Mode, OFlags};
    rustix::fs::open(dir, OFlags::WRONLY | OFlags::TMPFILE, Mode::from_bits_truncate(0o600)).is_ok()
}

/// True once `pid` holds an open temporary file in `dir` (named or anonymous).
fn holds_temp(pid: u32, dir: &Path) -> bool {
    let Ok(fds) = fs::read_dir(format!("/proc/{pid}/fd")) else { return false };
    fds.filter_map(|fd| fs::read_link(fd.ok()?.path()).ok()).any(|target| {
        let t = target.to_string_lossy();
        target.parent() == Some(dir) && (t.ends_with(" (deleted)") || t.ends_with(".tmp"))
    })
}

/// Starts `program args` (which writes `dir/e.csv`, held before linking), waits for its
/// temporary file, kills it with SIGKILL and returns what is left in `dir`.
fn kill_9_mid_write(program: &str, args: &[&OsStr], home: &Path, dir: &Path, env: &[(&str, &str)]) -> Vec<Vec<u8>> {
    let mut env = env.to_vec();
    env.push((HOLD_TEMP_FOR_TEST, "30000"));
    let mut child = in_home(program, args, home, &env).stdout(Stdio::null()).stderr(Stdio::null()).spawn().unwrap();
    let pid = child.id();
    let start = Instant::now();
    while !holds_temp(pid, dir) {
        assert!(start.elapsed() < TIMEOUT, "no temporary file appeared in {}", dir.display());
        std::thread::sleep(Duration::from_millis(20));
    }
    child.kill().unwrap();
    let status = child.wait().unwrap();
    assert_eq!(status.signal(), Some(9));
    names(dir)
}

#[test]
fn kill_9_leaves_nothing_even_without_proc() {
    let home = tempfile::tempdir().unwrap();
    fs::create_dir(home.path().join("out")).unwrap();
    let dir = home.path().join("out").canonicalize().unwrap();
    if !tmpfile_supported(&dir) {
        crate::support::skip::skip(&format!("O_TMPFILE is not supported in {}", dir.display()));
        return;
    }
    if !namespaces() {
        return;
    }
    let target = dir.join("e.csv");
    // /proc hidden from thud (a tmpfs over it): the anonymous file is linked with AT_EMPTY_PATH.
    let script =
        format!("mount -t tmpfs none /proc || exit 99; exec \"$T\" export csv history --out '{}'", target.display());
    let args = os(&["-m", "sh", "-c", &script]);
    let cmd_env = [("T", BIN)];
    let left = kill_9_mid_write("unshare", &args, home.path(), &dir, &cmd_env);
    assert_eq!(left, Vec::<Vec<u8>>::new(), "a temporary file survived kill -9 without /proc");
    // And the file is written there when not killed.
    let out = in_home("unshare", &args, home.path(), &cmd_env).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert_eq!(names(&dir), [b"e.csv".to_vec()]);
}

#[test]
fn a_named_temporary_left_by_kill_9_is_removed_by_the_next_write() {
    for force in [false, true] {
        let home = tempfile::tempdir().unwrap();
        let dir = home.path().join("out");
        fs::create_dir(&dir).unwrap();
        let dir = dir.canonicalize().unwrap();
        let target = dir.join("e.csv");
        if force {
            fs::write(&target, "old\n").unwrap();
        }
        let t = target.to_str().unwrap();
        let mut args = vec!["export", "csv", "history", "--out", t];
        if force {
            args.push("--force");
        }
        let left = kill_9_mid_write(BIN, &os(&args), home.path(), &dir, &[(NAMED_TEMPS_FOR_TEST, "1")]);
        let temps: Vec<&Vec<u8>> = left.iter().filter(|n| n.starts_with(b".e.csv.thud-")).collect();
        assert_eq!(temps.len(), 1, "the fallback leaves its recognisable name: {left:?}");
        // Over a second later (a name younger than that may be another run's, not yet locked),
        // any write into the folder removes it; the old file is all that is left of the kill.
        std::thread::sleep(Duration::from_millis(1100));
        let (code, _, err) =
            thud(&os(&["export", "csv", "waveform", "--points", "5", "--out", "out/w.csv"]), home.path());
        assert_eq!(code, 0, "{err}");
        let mut expected = vec![b"w.csv".to_vec()];
        if force {
            expected.insert(0, b"e.csv".to_vec());
            assert_eq!(fs::read_to_string(&target).unwrap(), "old\n", "the old file, not the new");
        }
        assert_eq!(names(&dir), expected, "force {force}");
    }
}

#[test]
fn names_that_are_not_utf8_are_used_as_given_and_shown_escaped() {
    let home = tempfile::tempdir().unwrap();
    let name = OsStr::from_bytes(b"caf\xe9.csv");
    let mut args = os(&["export", "csv", "waveform", "--points", "5", "--out"]);
    args.push(name);
    let (code, _, err) = thud(&args, home.path());
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("wrote caf\\xe9.csv"), "{err}");
    let files = names(home.path());
    assert_eq!(files, [b"caf\xe9.csv".to_vec()], "exactly the file named, nothing else");
    let (code, _, err) = thud(&args, home.path());
    assert_eq!(code, 2);
    assert_eq!(err, "thud: invalid --out: caf\\xe9.csv exists; add --force to replace it\n");
    // A part and a merge with such names.
    let part = OsStr::from_bytes(b"p\xff.jsonl");
    let mut args =
        os(&["sweep", "--masses", "30g:40g:2", "--gaps", "2cm:3cm:2", "--duration", "0.2", "--shard", "0/1", "--out"]);
    args.push(part);
    let (code, _, err) = thud(&args, home.path());
    assert_eq!(code, 0, "{err}");
    assert!(home.path().join(part).is_file());
    let merged = OsStr::from_bytes(b"m\xfe.json");
    let mut args = os(&["merge"]);
    args.extend([part, OsStr::new("--out"), merged]);
    let (code, _, err) = thud(&args, home.path());
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("wrote m\\xfe.json"), "{err}");
    let mut args = os(&["merge"]);
    args.extend([OsStr::from_bytes(b"gone\xff.jsonl"), OsStr::new("--out"), OsStr::new("-")]);
    let (code, _, err) = thud(&args, home.path());
    assert_eq!(code, 2);
    assert!(err.contains("gone\\xff.jsonl") && err.lines().count() == 1, "{err}");
    let mut files = names(home.path());
    files.sort();
    let mut expected = vec![b"caf\xe9.csv".to_vec(), b"m\xfe.json".to_vec(), b"p\xff.jsonl".to_vec()];
    expected.sort();
    assert_eq!(files, expected);
}

#[test]
fn a_very_long_out_path_keeps_the_reason_in_the_message() {
    let home = tempfile::tempdir().unwrap();
    let deep: PathBuf = (0..12).map(|_| "d".repeat(60)).collect();
    fs::create_dir_all(home.path().join(&deep)).unwrap();
    let target = deep.join("e.csv");
    fs::write(home.path().join(&target), "mine").unwrap();
    let (code, _, err) =
        thud(&os(&["export", "csv", "waveform", "--points", "5", "--out", target.to_str().unwrap()]), home.path());
    assert_eq!(code, 2);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.ends_with("e.csv exists; add --force to replace it\n"), "the reason is cut away: {err}");
    assert!(err.contains('…'), "{err}");
}

/// The files of a complete `paper all` set, sorted.
fn full_set() -> Vec<Vec<u8>> {
    let mut v: Vec<Vec<u8>> = thud::export::report::expected_files().into_iter().map(String::into_bytes).collect();
    v.sort();
    v
}

#[test]
fn paper_all_writes_a_complete_set_or_nothing_and_a_rerun_after_a_failure_works() {
    let home = tempfile::tempdir().unwrap();
    // A file size limit (as a full disk would) stops it at its first larger file: nothing is
    // left, neither a partial set nor a temporary folder.
    let script = format!("trap '' XFSZ; ulimit -f 16; exec '{BIN}' paper all --out paper");
    let mut child = in_home("sh", &os(&["-c", &script]), home.path(), &[]);
    let child = child.stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().unwrap();
    let out = wait_within(child, TIMEOUT, "limited paper all");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_ne!(out.status.code(), Some(0), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert_eq!(names(home.path()), Vec::<Vec<u8>>::new(), "{err}");
    // The same run again, without the limit, writes the whole set.
    let (code, _, err) = thud(&os(&["paper", "all", "--out", "paper"]), home.path());
    assert_eq!(code, 0, "{err}");
    assert_eq!(names(&home.path().join("paper")), full_set());
    assert_eq!(names(home.path()), [b"paper".to_vec()]);
    // A second run keeps it without --force and replaces it whole with it.
    let (code, _, err) = thud(&os(&["paper", "all", "--out", "paper"]), home.path());
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("exists; add --force"), "{err}");
    fs::write(home.path().join("paper/table1.csv"), "old").unwrap();
    let (code, _, err) = thud(&os(&["paper", "all", "--out", "paper", "--force"]), home.path());
    assert_eq!(code, 0, "{err}");
    assert!(fs::read_to_string(home.path().join("paper/table1.csv")).unwrap().starts_with("radius_mm,"));
    assert_eq!(names(home.path()), [b"paper".to_vec()], "no temporary folder left");
    // A folder with other files is never mixed with a set, even with --force.
    fs::write(home.path().join("paper/notes.txt"), "mine").unwrap();
    let (code, _, err) = thud(&os(&["paper", "all", "--out", "paper", "--force"]), home.path());
    assert_eq!(code, 2, "{err}");
    assert!(err.starts_with("thud: invalid --out: paper holds notes.txt"), "{err}");
    assert_eq!(fs::read_to_string(home.path().join("paper/notes.txt")).unwrap(), "mine");
}

#[test]
fn paper_all_killed_leaves_no_partial_set_and_the_next_run_clears_its_folder() {
    let home = tempfile::tempdir().unwrap();
    let dir = home.path().canonicalize().unwrap();
    let env = [(HOLD_TEMP_FOR_TEST, "30000")];
    let mut child = in_home(BIN, &os(&["paper", "all", "--out", "paper"]), &dir, &env)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    // Wait until its temporary folder exists and holds a file being written.
    let start = Instant::now();
    let temp = loop {
        let found = names(&dir).into_iter().find(|n| n.starts_with(b".paper.thud-"));
        if let Some(t) = found.filter(|t| holds_temp(child.id(), &dir.join(OsStr::from_bytes(t)))) {
            break dir.join(OsStr::from_bytes(&t));
        }
        assert!(start.elapsed() < TIMEOUT, "no temporary folder appeared: {:?}", names(&dir));
        std::thread::sleep(Duration::from_millis(20));
    };
    child.kill().unwrap();
    child.wait().unwrap();
    assert!(!dir.join("paper").exists(), "no partial set");
    assert!(temp.is_dir(), "SIGKILL leaves the temporary folder (recognisable by its name)");
    std::thread::sleep(Duration::from_millis(1100));
    let (code, _, err) = thud(&os(&["paper", "all", "--out", "paper"]), &dir);
    assert_eq!(code, 0, "{err}");
    assert_eq!(names(&dir), [b"paper".to_vec()], "the killed run's folder is removed");
    assert_eq!(names(&dir.join("paper")), full_set());
}

#[test]
fn paper_one_item_honours_out() {
    let home = tempfile::tempdir().unwrap();
    let (code, table, err) = thud(&os(&["paper", "fig2", "--csv"]), home.path());
    assert_eq!(code, 0, "{err}");
    let (code, out, err) = thud(&os(&["paper", "fig2", "--csv", "--out", "x"]), home.path());
    assert_eq!(code, 0, "{err}");
    assert!(out.is_empty(), "{out}");
    assert_eq!(fs::read_to_string(home.path().join("x")).unwrap(), table);
    let (code, _, err) = thud(&os(&["paper", "fig2", "--out", "x"]), home.path());
    assert_eq!(code, 2);
    assert_eq!(err, "thud: invalid --out: x exists; add --force to replace it\n");
    let (code, _, err) = thud(&os(&["paper", "fig2", "--json", "--out", "x", "--force"]), home.path());
    assert_eq!(code, 0, "{err}");
    assert!(fs::read_to_string(home.path().join("x")).unwrap().starts_with('{'));
    let (code, out, err) = thud(&os(&["paper", "fig2", "--csv", "--out", "-"]), home.path());
    assert_eq!(code, 0, "{err}");
    assert_eq!(out, table);
}

#[test]
fn a_tour_file_name_that_is_not_utf8_is_shown_escaped() {
    let home = tempfile::tempdir().unwrap();
    let mut args = os(&["tui", "--tour"]);
    args.push(OsStr::from_bytes(b"nope\xe9.toml"));
    let (code, _, err) = thud(&args, home.path());
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("nope\\xe9.toml") && err.lines().count() == 1, "{err}");
}

#[test]
fn a_value_that_is_not_utf8_where_text_is_expected_names_its_flag() {
    let home = tempfile::tempdir().unwrap();
    let mut args = os(&["simulate", "--mass"]);
    args.push(OsStr::from_bytes(b"4\xe9g"));
    let (code, out, err) = thud(&args, home.path());
    assert_eq!((code, out.as_str()), (2, ""));
    assert_eq!(err, "thud: invalid --mass: '4\\xe9g' is not UTF-8 text (only a file name may be any bytes)\n");
}
