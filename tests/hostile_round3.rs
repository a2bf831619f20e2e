#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! Nothing lost, round 3 (issue 24, items 1–8): signals mid-write, a full disk, the work cap of
//! a forced response, a huge config, `config check`, errors that name their flag, terminals.
//!
//! Runs of the built binary, with HOME and the XDG folders in a temporary folder, each killed
//! after 20 s (a failure). Where a test needs a fresh tmpfs it makes one in a private mount
//! namespace (`unshare -m`, root); where that is not possible it prints why and skips.

use std::ffi::OsStr;
use std::fs;
use std::os::unix::ffi::OsStrExt;
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

#[path = "support/home.rs"]
mod home;
#[path = "support/wait.rs"]
mod wait;
use home::in_home;
use wait::wait_within;

const BIN: &str = env!("CARGO_BIN_EXE_thud");
const TIMEOUT: Duration = Duration::from_secs(20);

/// What one run of thud did.
#[derive(Debug)]
struct Ran {
    code: i32,
    stdout: String,
    stderr: String,
}

fn ran(out: &Output) -> Ran {
    Ran {
        code: out.status.code().unwrap_or(-1),
        stdout: String::from_utf8_lossy(&out.stdout).into(),
        stderr: String::from_utf8_lossy(&out.stderr).into(),
    }
}

/// Runs thud with `args` in `home` (and `env`) to completion.
fn thud_env(home: &Path, args: &[&str], env: &[(&str, &str)]) -> Ran {
    let child = in_home(BIN, args, home, env).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().unwrap();
    ran(&wait_within(child, TIMEOUT, &format!("thud {args:?}")))
}

fn thud(home: &Path, args: &[&str]) -> Ran {
    thud_env(home, args, &[])
}

/// The names in `dir`, sorted (lossy: the names here are ASCII).
fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> =
        fs::read_dir(dir).unwrap().map(|e| String::from_utf8_lossy(e.unwrap().file_name().as_bytes()).into()).collect();
    v.sort();
    v
}

/// A small pseudo-random sequence (the moments to kill at), seeded from the clock and printed
/// so a failure can be replayed.
struct Lcg(u64);
impl Lcg {
    fn new() -> Lcg {
        let seed = std::env::var("THUD_TEST_SEED").ok().and_then(|s| s.parse().ok()).unwrap_or_else(|| {
            std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).unwrap().subsec_nanos().into()
        });
        eprintln!("seed {seed} (THUD_TEST_SEED to replay)");
        Lcg(seed)
    }
    /// Uniform in [0, 1).
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn kill(pid: u32, signal: &str) {
    let _ = Command::new("kill").args([&format!("-{signal}"), &pid.to_string()]).stderr(Stdio::null()).status();
}

// ---- item 1: a set written complete or not at all, under every signal ----------------------

/// The environment variable that makes [`bundle_writer_child`] the writer of a set.
const CHILD_DIR: &str = "THUD_ROUND3_BUNDLE_CHILD";
const BUNDLE_FILES: usize = 16;

/// The set the child writes: files of a few kilobytes each, each different.
fn bundle() -> Vec<(String, Vec<u8>)> {
    (0..BUNDLE_FILES).map(|i| (format!("f{i:02}.csv"), format!("{i},").repeat(1500 + 37 * i).into_bytes())).collect()
}

/// Not a test of its own: run by [`paper_sets_are_complete_or_absent_when_killed_at_random_moments`]
/// as a child process (this test binary, `--exact`), it writes [`bundle`] as the folder named
/// by [`CHILD_DIR`] through the same writer as `paper all` and exits. Run alone it does nothing.
#[test]
fn bundle_writer_child() {
    let Some(dir) = std::env::var_os(CHILD_DIR) else { return };
    let files = bundle();
    let refs: Vec<(&str, &[u8])> = files.iter().map(|(n, b)| (n.as_str(), b.as_slice())).collect();
    thud::export::report::write_bundle(Path::new(&dir), &refs, thud::fsio::Overwrite::Refuse).unwrap();
    thud::signals::exit(0);
}

fn spawn_writer(target: &Path) -> std::process::Child {
    Command::new(std::env::current_exe().unwrap())
        .args(["--exact", "bundle_writer_child", "--test-threads=1", "--quiet"])
        .env(CHILD_DIR, target)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap()
}

/// `target` holds nothing or the whole set, byte for byte.
fn assert_all_or_nothing(target: &Path, what: &str) -> bool {
    if !target.exists() {
        return false;
    }
    let want = bundle();
    let mut want_names: Vec<String> = want.iter().map(|(n, _)| n.clone()).collect();
    want_names.sort();
    assert_eq!(names(&target), want_names, "{what}: a partial set was put in place");
    for (n, b) in &want {
        assert_eq!(&fs::read(target.join(n)).unwrap(), b, "{what}: {n} differs");
    }
    true
}

#[test]
fn paper_sets_are_complete_or_absent_when_killed_at_random_moments() {
    let home = tempfile::tempdir().unwrap();
    let home = home.path().canonicalize().unwrap();
    // How long one whole write takes here (start-up included).
    let start = Instant::now();
    let status = wait_within(spawn_writer(&home.join("whole")), TIMEOUT, "writer").status;
    let whole = start.elapsed();
    assert!(status.success());
    fs::remove_dir_all(home.join("whole")).unwrap();
    let mut rng = Lcg::new();
    let signals = ["TERM", "INT", "HUP"];
    // 21 runs at once (each waits mostly on its disk syncs), each killed at its own moment
    // anywhere from start-up to past the last rename (they run slower together).
    let runs: Vec<_> = (0..21)
        .map(|round| {
            let (signal, at) = (signals[round % 3], whole.mul_f64(rng.next() * 1.2));
            let target = home.join(format!("set{round}"));
            std::thread::spawn(move || {
                let child = spawn_writer(&target);
                std::thread::sleep(at);
                kill(child.id(), signal);
                let status = wait_within(child, TIMEOUT, "killed writer").status;
                (target, format!("SIG{signal} at {at:?} (status {status:?})"))
            })
        })
        .collect();
    let done: Vec<_> = runs.into_iter().map(|r| r.join().unwrap()).collect();
    let left = names(&home);
    assert!(left.iter().all(|n| n.starts_with("set")), "a temporary folder or file was left: {left:?} ({done:?})");
    let absent: Vec<_> = done.iter().filter(|(target, what)| !assert_all_or_nothing(target, what)).collect();
    let complete = done.len() - absent.len();
    // A rerun after each interruption writes the whole set.
    let reruns: Vec<_> = absent.iter().map(|(target, what)| (spawn_writer(target), target, what)).collect();
    for (child, target, what) in reruns {
        assert!(wait_within(child, TIMEOUT, "rerun").status.success(), "{what}");
        assert!(assert_all_or_nothing(target, &format!("rerun after {what}")));
    }
    let absent = absent.len();
    eprintln!("whole write {whole:?}: {complete} complete, {absent} absent");
}

/// The real `paper all`, killed by TERM, INT and HUP just after its temporary folder appears
/// (while it writes): nothing or the whole set, no temporary folder, exit 128 + the signal.
#[test]
fn paper_all_killed_while_writing_leaves_nothing_or_the_set() {
    let full = {
        let mut v = thud::export::report::expected_files();
        v.sort();
        v
    };
    let mut rng = Lcg::new();
    let runs: Vec<_> = [("TERM", 143), ("INT", 130), ("HUP", 129)]
        .into_iter()
        .map(|(signal, code)| {
            let home = tempfile::tempdir().unwrap();
            let child = in_home(BIN, &["paper", "all", "--out", "paper"], home.path(), &[])
                .stdout(Stdio::null())
                .stderr(Stdio::null())
                .spawn()
                .unwrap();
            (home, child, signal, code, Duration::from_millis((rng.next() * 150.0) as u64))
        })
        .collect();
    for (home, child, signal, code, delay) in runs {
        let start = Instant::now();
        let seen = loop {
            if names(home.path()).iter().any(|n| n.starts_with(".paper.thud-")) {
                break true;
            }
            if start.elapsed() > TIMEOUT || home.path().join("paper").exists() {
                break false;
            }
            std::thread::sleep(Duration::from_millis(2));
        };
        std::thread::sleep(delay);
        kill(child.id(), signal);
        let status = wait_within(child, TIMEOUT, "paper all").status;
        let left = names(home.path());
        let what = format!("SIG{signal} {delay:?} after the folder appeared ({seen}): {status:?}, left {left:?}");
        assert!(left.is_empty() || left == ["paper"], "{what}");
        if left == ["paper"] {
            assert_eq!(names(&home.path().join("paper")), full, "{what}");
        } else {
            assert_eq!(status.code(), Some(code), "{what}");
        }
    }
}

// ---- items 1 and 8: a full or read-only disk -------------------------------------------------

/// Runs `script` with `sh` in a private mount namespace (`$T` is thud, `$D` a fresh folder
/// whose tmpfs is mounted by `mount_opts`); `None` (skipped, with the reason printed) where
/// namespaces are not available.
fn on_small_tmpfs(mount_opts: &str, script: &str) -> Option<Output> {
    let dir = tempfile::tempdir().unwrap();
    let probe = Command::new("unshare")
        .args(["-m", "sh", "-c", "mount -t tmpfs none \"$1\"", "sh"])
        .arg(dir.path())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    if !probe {
        eprintln!("skipped: no private mount namespace here (needs root and util-linux `unshare -m`)");
        return None;
    }
    let full = format!("mount -t tmpfs -o {mount_opts} none \"$D\" || exit 99\ncd \"$D\"\n{script}");
    let child = Command::new("unshare")
        .args(["-m", "sh", "-c", &full])
        .env("T", BIN)
        .env("D", dir.path())
        .env("HOME", dir.path())
        .env("XDG_CONFIG_HOME", dir.path().join("config"))
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let out = wait_within(child, TIMEOUT, script);
    assert_ne!(out.status.code(), Some(99), "could not mount a tmpfs");
    Some(out)
}

/// A full disk: the write fails with exit 1 and one line, and leaves neither a partial file or
/// set nor the folders it created for it; a read-only disk likewise (exit 1, not "invalid").
#[test]
fn a_full_or_read_only_disk_is_an_io_error_that_leaves_no_new_folder() {
    let cases = [
        ("size=64k", "\"$T\" export wav --duration 2 --out new/dir/a.wav"),
        ("size=64k", "\"$T\" paper all --out new/dir/paper"),
        ("size=64k", "\"$T\" paper all --out paper"),
        ("size=64k,ro", "\"$T\" paper all --out new/paper"),
        ("size=64k,ro", "\"$T\" export csv waveform --points 5 --out new/a.csv"),
    ];
    let runs: Vec<_> = cases
        .into_iter()
        .map(|(opts, cmd)| {
            let script = format!("err=$({cmd} 2>&1 >/dev/null); echo \"$?\"; ls -A; printf '%s\\n' \"$err\" >&2");
            (opts, cmd, std::thread::spawn(move || on_small_tmpfs(opts, &script)))
        })
        .collect();
    for (opts, cmd, run) in runs {
        let Some(out) = run.join().unwrap() else { return };
        let r = ran(&out);
        let mut lines = r.stdout.lines();
        let code = lines.next().unwrap_or_default();
        let left: Vec<&str> = lines.collect();
        let what = format!("{opts}: {cmd}: exit {code}, left {left:?}, stderr {}", r.stderr);
        assert_eq!(code, "1", "{what}");
        assert_eq!(r.stderr.lines().count(), 1, "{what}");
        assert!(r.stderr.contains("cannot write"), "{what}");
        assert!(left.is_empty(), "{what}");
    }
}
