#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! Nothing lost, round 3: signals mid-write, a full disk, the work cap of
//! a forced response, a huge config, `config check`, errors that name their flag, terminals.
//!
//! Runs of the built binary, with HOME and the XDG folders in a temporary folder, each killed
//! after 20 s (a failure). Where a test needs a fresh tmpfs it makes one in a private mount
//! namespace (`unshare -m`, root); where that is not possible it prints why and skips.

use std::fs;
use std::os::unix::ffi::OsStrExt;
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use crate::support::{home, wait};
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
        .args(["--exact", "hostile_round3::bundle_writer_child", "--test-threads=1", "--quiet"])
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
    assert_eq!(names(target), want_names, "{what}: a partial set was put in place");
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
        crate::support::skip::skip("no private mount namespace here (needs root and util-linux `unshare -m`)");
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

// ---- item 2: a forced response at a high frequency ------------------------------------------

/// The steady windows of a long flight were searched one by one: a response at 1e5 Hz ran for
/// minutes. Now it is linear; the work cap's estimate (forcing periods) holds.
#[test]
fn a_forced_response_at_a_high_frequency_finishes_quickly() {
    let home = tempfile::tempdir().unwrap();
    let start = Instant::now();
    let r =
        thud(home.path(), &["response", "--force-amplitude", "1N", "--freqs", "1e5:1e5:1", "--periods", "2", "--json"]);
    let took = start.elapsed();
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(took < Duration::from_secs(10), "took {took:?}");
}

// ---- item 3: a huge config ----------------------------------------------------------------

fn write_config(home: &Path, text: &str) {
    let dir = home.join("config/thud");
    fs::create_dir_all(&dir).unwrap();
    fs::write(dir.join("config.toml"), text).unwrap();
}

/// 110 000 problem tables (989 KB, under the read cap): every command read the file in
/// quadratic time (63 s); now in linear time, and `config check` lists a bounded number.
#[test]
fn a_config_with_a_hundred_thousand_problems_is_read_at_once() {
    let home = tempfile::tempdir().unwrap();
    let text: String = (0..110_000).map(|i| format!("[x{i}]\n")).collect();
    assert!(text.len() < 1 << 20);
    write_config(home.path(), &text);
    let start = Instant::now();
    let r = thud(home.path(), &["config", "check"]);
    let took = start.elapsed();
    assert_eq!(r.code, 2, "{}", r.stderr);
    let lines: Vec<&str> = r.stdout.lines().collect();
    assert_eq!(lines.len(), thud::config::MAX_LISTED_PROBLEMS + 1, "{}", &r.stdout[..400.min(r.stdout.len())]);
    assert!(lines[0].contains(":1:2: unknown key 'x0'"), "{}", lines[0]);
    assert!(lines.last().unwrap().contains("and 109900 more problems"), "{}", lines.last().unwrap());
    assert_eq!(r.stderr.lines().count(), 1, "{}", r.stderr);
    let r = thud(home.path(), &["limits"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(took < Duration::from_secs(10), "config check took {took:?}");
}

// ---- item 4: `config check` checks what the commands check -------------------------------

#[test]
fn config_check_reports_what_the_commands_refuse_one_line_each() {
    let home = tempfile::tempdir().unwrap();
    // A material no design accepts: every design command stopped on it (exit 2) while the
    // check said "no problems". Now the check reports it, and the commands treat it as every
    // config problem: the defaults, and a warning naming the key.
    write_config(home.path(), "[design]\nsphere = \"bogus\"\n");
    let sim = thud(home.path(), &["simulate", "--samples", "5"]);
    assert!(sim.stderr.contains("config.toml:2:10: invalid sphere in config.toml [design]"), "{}", sim.stderr);
    let r = thud(home.path(), &["config", "check"]);
    assert_eq!(r.code, 2, "{}{}", r.stdout, r.stderr);
    assert_eq!(r.stdout.lines().count(), 1, "{}", r.stdout);
    assert!(r.stdout.contains("config.toml:2:10: invalid sphere") && r.stdout.contains("'bogus'"), "{}", r.stdout);
    assert!(!r.stdout.contains("no problems"));
    // Problems whose text holds nan or inf are listed, not an internal error.
    write_config(
        home.path(),
        "[thresholds]\nl_star_db = nan\ne_star_cm_s = inf\n[design]\nmass = -inf\ntheme = \"inf\"\n",
    );
    let r = thud(home.path(), &["config", "check"]);
    assert_eq!(r.code, 2, "{}{}", r.stdout, r.stderr);
    assert!(!r.stderr.contains("internal error"), "{}", r.stderr);
    assert_eq!(r.stdout.lines().count(), 4, "one line per problem: {}", r.stdout);
    assert_eq!(r.stderr.lines().count(), 1, "{}", r.stderr);
}

// ---- item 5: errors name the flag or key ---------------------------------------------------

fn assert_one_line(r: &Ran, code: i32, needles: &[&str], what: &str) {
    assert_eq!(r.code, code, "{what}: {}", r.stderr);
    assert_eq!(r.stderr.lines().count(), 1, "{what}: {}", r.stderr);
    for n in needles {
        assert!(r.stderr.contains(n), "{what}: wants {n:?}: {}", r.stderr);
    }
}

#[test]
fn errors_name_the_flag_or_the_key() {
    let home = tempfile::tempdir().unwrap();
    let h = home.path();
    for (args, needle) in [
        (&["simulate", "--sphere", "bogus"][..], "invalid --sphere: unknown material 'bogus'"),
        (&["simulate", "--sphere", "steel", "--plate", "bogus"][..], "invalid --plate: unknown material 'bogus'"),
        (&["pulse", "--sphere", "bogus"][..], "invalid --sphere: unknown material 'bogus'"),
        (&["pulse", "--sphere", "steel", "--plate", "bogus"][..], "invalid --plate: unknown material 'bogus'"),
        (&["--threads", "-1", "simulate"][..], "invalid --threads: "),
        (&["simulate", "--threads", "-1"][..], "invalid --threads: "),
    ] {
        assert_one_line(&thud(h, args), 2, &[needle], &format!("{args:?}"));
    }
    // A thread warning is not printed before an error: the error is the one line.
    let r = thud_env(h, &["simulate", "--mass", "x"], &[("RAYON_NUM_THREADS", "100000")]);
    assert_one_line(&r, 2, &["invalid --mass"], "RAYON_NUM_THREADS=100000");
    // …and beside a success it is.
    let r = thud_env(h, &["limits"], &[("RAYON_NUM_THREADS", "100000")]);
    assert_eq!(r.code, 0);
    assert!(r.stderr.contains("RAYON_NUM_THREADS"), "{}", r.stderr);
    // The config's material names its key (a config problem: a warning, the defaults used).
    write_config(h, "[design]\nsphere = \"bogus\"\n");
    let r = thud(h, &["simulate", "--mass", "x"]);
    assert_one_line(&r, 2, &["invalid --mass"], "a config problem beside an error");
    let r = thud(h, &["limits"]);
    assert!(r.stderr.contains("invalid sphere in config.toml [design]: unknown material 'bogus'"), "{}", r.stderr);
    // A config dt is named as the config's key, not blamed on --duration.
    write_config(h, "[design]\nsolver = \"newmark\"\ndt = 1e-9\n");
    let r = thud(h, &["simulate", "--duration", "20"]);
    assert_one_line(&r, 2, &["dt in config.toml [design]"], "config dt");
    assert!(!r.stderr.contains("invalid --duration"), "{}", r.stderr);
}

/// A part's cell of 1e308 is shown short, so the reason stays inside the cut line.
#[test]
fn a_huge_cell_is_shown_short() {
    let home = tempfile::tempdir().unwrap();
    let h = home.path();
    let r = thud(
        h,
        &[
            "sweep",
            "--masses",
            "30g:40g:2",
            "--gaps",
            "2cm:3cm:2",
            "--duration",
            "0.2",
            "--shard",
            "0/1",
            "--out",
            "p.json",
        ],
    );
    assert_eq!(r.code, 0, "{}", r.stderr);
    let text = fs::read_to_string(h.join("p.json")).unwrap();
    // The first number of the first run's record, forged to 1e308.
    let at = text.find("\"spl_max_db\":").expect("a run has spl_max_db") + "\"spl_max_db\":".len();
    let end = at + text[at..].find([',', '}']).unwrap();
    let forged = format!("{}1e308{}", &text[..at], &text[end..]);
    fs::write(h.join("p.json"), forged).unwrap();
    let r = thud(h, &["merge", "p.json", "--out", "m.json"]);
    assert_one_line(&r, 2, &["1e308 is out of range"], "merge");
    assert!(!r.stderr.contains("00000000000"), "{}", r.stderr);
}

/// A tour step's long title is cut so the problem after it shows.
#[test]
fn a_long_tour_step_title_does_not_hide_the_problem() {
    let home = tempfile::tempdir().unwrap();
    let title = "T".repeat(500);
    let tour = format!("title = \"t\"\n[[step]]\ntitle = \"{title}\"\npanel = \"nowhere\"\ncaption = \"c\"\n");
    let r = thud::tui::tour::Tour::parse("t.toml", &tour).unwrap_err().to_string();
    assert!(r.contains("panel 'nowhere'"), "{r}");
    assert!(r.chars().count() < 200, "{r}");
    drop(home);
}

// ---- item 7: terminals ---------------------------------------------------------------------

/// Drives the explorer in a pty per signal, all at once: each is sent its signal once the
/// screen is up; prints "NAME exit CODE sent BOOL cooked BOOL left BOOL" per signal (cooked:
/// canonical mode and echo are back on; left: the alternate screen was left). Then a binary export
/// to the pty's own path.
const SIGNALS_PTY: &str = r#"
import fcntl, os, pty, resource, select, signal, struct, subprocess, sys, termios, time
sigs = [("PWR", signal.SIGPWR), ("STKFLT", 16), ("IO", signal.SIGIO), ("RTMIN+3", signal.SIGRTMIN + 3),
        ("ABRT", signal.SIGABRT), ("TRAP", signal.SIGTRAP), ("SYS", signal.SIGSYS), ("RTMAX", signal.SIGRTMAX),
        ("ILL", signal.SIGILL), ("FPE", signal.SIGFPE), ("SEGV", signal.SIGSEGV)]
runs = []
slaves = {}
no_core = lambda: resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
for name, num in sigs:
    m, s = pty.openpty()
    fcntl.ioctl(s, termios.TIOCSWINSZ, struct.pack("HHHH", 30, 100, 0, 0))
    p = subprocess.Popen([sys.argv[1], "tui"], stdin=s, stdout=s, stderr=s, start_new_session=True,
                         env=dict(os.environ, TERM="xterm-256color"), preexec_fn=no_core)
    # Kept open, to read the terminal's settings after thud has ended.
    slaves[name] = s
    runs.append([name, num, m, p, b"", False])
end = time.time() + 30
while time.time() < end and any(r[3].poll() is None for r in runs):
    ms = [r[2] for r in runs]
    rd, _, _ = select.select(ms, [], [], 0.05)
    for r in runs:
        if r[2] in rd:
            try:
                r[4] += os.read(r[2], 65536)
            except OSError:
                pass
        if not r[5] and b"parameters" in r[4]:
            r[5] = True
            mark = len(r[4])
            r.append(mark)
            os.kill(r[3].pid, r[1])
for r in runs:
    while r[3].poll() is not None:
        rd, _, _ = select.select([r[2]], [], [], 0.2)
        if not rd:
            break
        try:
            data = os.read(r[2], 65536)
        except OSError:
            break
        if not data:
            break
        r[4] += data
for r in runs:
    if r[3].poll() is None:
        r[3].kill(); r[3].wait()
        print(r[0], "STILL RUNNING")
        continue
    after = r[4][r[6]:] if len(r) > 6 else b""
    lflag = termios.tcgetattr(slaves[r[0]])[3]
    cooked = bool(lflag & termios.ICANON) and bool(lflag & termios.ECHO)
    print(r[0], "exit", r[3].returncode, "sent", r[5], "cooked", cooked, "left", b"\x1b[?1049l" in after)
m, s = pty.openpty()
path = os.ttyname(s)
for what in (["export", "wav", "--duration", "0.01"], ["export", "pdf", "waveform"]):
    p = subprocess.run([sys.argv[1]] + what + ["--out", path], stdin=subprocess.DEVNULL, capture_output=True, timeout=20)
    print("tty", what[1], p.returncode, p.stderr.decode().strip().replace("\n", " | "))
"#;

#[test]
fn every_signal_that_ends_the_explorer_restores_the_terminal_and_no_binary_goes_to_one() {
    let home = tempfile::tempdir().unwrap();
    let Ok(out) = Command::new("python3")
        .args(["-c", SIGNALS_PTY, BIN])
        .env("HOME", home.path())
        .env("XDG_CONFIG_HOME", home.path().join("config"))
        .env("XDG_DATA_HOME", home.path().join("data"))
        .output()
    else {
        crate::support::skip::skip("python3 (for its pty module) is not installed");
        return;
    };
    let said = String::from_utf8_lossy(&out.stdout);
    let err = String::from_utf8_lossy(&out.stderr);
    let nums = [("PWR", 30), ("STKFLT", 16), ("IO", 29), ("ABRT", 6), ("TRAP", 5), ("SYS", 31)];
    // The faults restore the terminal from their handler and die by the signal itself (Python
    // reports -n), as a shell would report them.
    let faults = [("ILL", 4), ("FPE", 8), ("SEGV", 11)];
    for line in said.lines().filter(|l| !l.starts_with("tty")) {
        let name = line.split(' ').next().unwrap();
        let want = nums.iter().find(|(n, _)| *n == name).map(|(_, k)| format!("exit {}", 128 + k));
        let killed = faults.iter().find(|(n, _)| *n == name).map(|(_, k)| format!("exit -{k} "));
        assert!(line.contains("sent True") && line.ends_with("cooked True left True"), "{line}\n{said}{err}");
        if let Some(want) = want {
            assert!(line.contains(&want), "{line} (want {want})");
        } else if let Some(killed) = killed {
            assert!(line.contains(&killed), "{line} (want {killed})");
        } else {
            let code: i32 = line.split(' ').nth(2).unwrap().parse().unwrap();
            assert!(code > 128 + 33, "{line}");
        }
    }
    assert_eq!(said.lines().filter(|l| !l.starts_with("tty")).count(), 11, "{said}{err}");
    for line in said.lines().filter(|l| l.starts_with("tty")) {
        assert!(line.starts_with("tty wav 2 ") || line.starts_with("tty pdf 2 "), "{line}");
        assert!(line.contains("is binary"), "{line}");
    }
    assert_eq!(said.lines().filter(|l| l.starts_with("tty")).count(), 2, "{said}{err}");
}
