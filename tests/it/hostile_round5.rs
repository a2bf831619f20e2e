#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! Hostile round 5: the surfaces added in round 4 tried as a hostile user would. A design
//! search stopped by a signal writes its partial front as every write is made (never through a
//! link planted beside the output, never over a FIFO); a reference point whose hypervolume
//! would overflow, a garbage N in `--vary`, a variable given twice, a continuation with fewer
//! than two seed values are refused in one line naming what was typed; a refused figure file
//! names the flag that gave it.
//!
//! Runs of the built binary, with HOME and the XDG folders in a temporary folder, each killed
//! after 30 s (a failure).

use std::fs;
use std::io::Read;
use std::os::unix::fs::FileTypeExt;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use crate::support::{home, wait};
use home::in_home;
use wait::wait_within;

const BIN: &str = env!("CARGO_BIN_EXE_thud");
const TIMEOUT: Duration = Duration::from_secs(30);

/// Runs thud with `args` in `home` to completion: (code, stdout, stderr).
fn thud(home: &Path, args: &[&str]) -> (i32, String, String) {
    let child = in_home(BIN, args, home, &[]).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().unwrap();
    let out = wait_within(child, TIMEOUT, "thud");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
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

/// A design search long enough to be stopped while it runs, its report to `out`.
fn long_search(out: &str) -> Vec<String> {
    let args = "design --vary mass=20g:120g --vary gap=1cm:6cm --minimize spl_max_db --maximize inclination_cm_s \
                --evaluations 100000 --no-limit --out";
    args.split_whitespace().map(str::to_string).chain([out.to_string()]).collect()
}

/// Starts the long search in `home` writing to `out`, sends SIGINT once it has run `after`,
/// and returns its exit code and stderr.
fn stopped_search(home: &Path, out: &str, after: Duration) -> (i32, String) {
    let child =
        in_home(BIN, &long_search(out), home, &[]).stdout(Stdio::null()).stderr(Stdio::piped()).spawn().unwrap();
    std::thread::sleep(after);
    assert!(Command::new("kill").args(["-INT", &child.id().to_string()]).status().unwrap().success());
    let done = wait_within(child, TIMEOUT, "the stopped design search");
    (done.status.code().unwrap_or(-1), String::from_utf8_lossy(&done.stderr).into())
}

/// The file the partial front went to before: a link planted at that name led the write to
/// the link's target, and the rename then put the link in the output's place.
const OLD_PARTIAL_NAME: &str = ".o.txt.thud-partial.tmp";

#[test]
fn a_stopped_design_search_writes_its_partial_front_never_through_a_planted_link() {
    let home = tempfile::tempdir().unwrap();
    let victim = home.path().join("victim.txt");
    fs::write(&victim, "not thud's\n").unwrap();
    std::os::unix::fs::symlink(&victim, home.path().join(OLD_PARTIAL_NAME)).unwrap();
    let (code, err) = stopped_search(home.path(), "o.txt", Duration::from_secs(4));
    assert_eq!(code, 130, "{err}");
    assert!(err.contains("stopped: wrote the front found so far"), "{err}");
    assert_eq!(fs::read_to_string(&victim).unwrap(), "not thud's\n", "the link's target is untouched");
    let out = home.path().join("o.txt");
    assert!(fs::symlink_metadata(&out).unwrap().is_file(), "o.txt is a file of its own, not a link");
    let text = fs::read_to_string(&out).unwrap();
    assert!(text.contains("PARTIAL (stopped)") && text.contains("spl_max_db"), "{text}");
    let left: Vec<String> = fs::read_dir(home.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| Path::new(n).extension().is_some_and(|x| x == "tmp") && n != OLD_PARTIAL_NAME)
        .collect();
    assert!(left.is_empty(), "no temporary file is left: {left:?}");
}

#[test]
fn a_stopped_design_search_writes_its_partial_front_through_a_fifo_and_keeps_it() {
    let home = tempfile::tempdir().unwrap();
    let fifo = home.path().join("o.txt");
    assert!(Command::new("mkfifo").arg(&fifo).status().unwrap().success());
    // A reader that never blocks (opened O_NONBLOCK, so thud sees it at once) and gives up
    // after the time limit: what it got until the writer closed.
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || {
            use std::os::unix::fs::OpenOptionsExt;
            let nonblock = rustix::fs::OFlags::NONBLOCK.bits() as i32;
            let mut f = fs::OpenOptions::new().read(true).custom_flags(nonblock).open(&fifo).unwrap();
            let (mut got, mut buf, start) = (Vec::new(), vec![0u8; 1 << 16], Instant::now());
            while start.elapsed() < TIMEOUT {
                match f.read(&mut buf) {
                    Ok(0) if !got.is_empty() => break,
                    Ok(0) => std::thread::sleep(Duration::from_millis(20)),
                    Ok(n) => got.extend_from_slice(&buf[..n]),
                    Err(e) if e.kind() == std::io::ErrorKind::WouldBlock => {
                        std::thread::sleep(Duration::from_millis(5));
                    }
                    Err(e) => panic!("reading the FIFO: {e}"),
                }
            }
            String::from_utf8_lossy(&got).into_owned()
        })
    };
    let (code, err) = stopped_search(home.path(), "o.txt", Duration::from_secs(4));
    assert_eq!(code, 130, "{err}");
    assert!(err.contains("stopped: wrote the front found so far"), "{err}");
    let text = reader.join().unwrap();
    assert!(text.contains("PARTIAL (stopped)") && text.contains("spl_max_db"), "the reader got the front: {text}");
    assert!(fs::symlink_metadata(&fifo).unwrap().file_type().is_fifo(), "the FIFO is still a FIFO");
}

#[test]
fn a_reference_point_whose_hypervolume_overflows_is_refused() {
    let home = tempfile::tempdir().unwrap();
    let search = ["design", "--vary", "mass=20g:120g", "--minimize", "spl_max_db", "--maximize", "inclination_cm_s"];
    for reference in ["1e308,-1e308", "1e151,0", "0,-2e150"] {
        let args: Vec<&str> = search.iter().copied().chain(["--evaluations", "8", "--reference", reference]).collect();
        assert_refused(home.path(), &args, &["--reference", reference, "1e150"]);
    }
    // Inside the bound the search runs and its hypervolume is a number.
    let args: Vec<&str> = search.iter().copied().chain(["--evaluations", "8", "--reference", "1e150,-1e150"]).collect();
    let (code, out, err) = thud(home.path(), &[&args[..], &["--json"]].concat());
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert!(v["hypervolume"].as_f64().is_some_and(f64::is_finite), "{out}");
}

#[test]
fn a_design_variable_takes_a_count_as_n_or_none_and_is_given_once() {
    let home = tempfile::tempdir().unwrap();
    let run = |vary: &str| -> (i32, String) {
        let (code, _, err) =
            thud(home.path(), &["design", "--vary", vary, "--minimize", "spl_max_db", "--evaluations", "4"]);
        (code, err)
    };
    for n in ["abc", "0", "-1", "2.5", "1e9"] {
        let vary = format!("mass=20g:120g:{n}");
        let (code, err) = run(&vary);
        assert_eq!((code, err.lines().count()), (2, 1), "{vary}: {err}");
        assert!(err.contains("--vary mass") && err.contains(n), "{vary}: {err}");
    }
    for vary in ["mass=20g:120g", "mass=20g:120g:5"] {
        let (code, err) = run(vary);
        assert_eq!(code, 0, "{vary}: {err}");
    }
    let (code, _, err) =
        thud(home.path(), &["design", "--vary", "mass=20g:120g", "--vary", "mass=30g:40g", "--minimize", "spl_max_db"]);
    assert_eq!((code, err.lines().count()), (2, 1), "{err}");
    assert!(err.contains("--vary mass") && err.contains("varied twice"), "{err}");
}

#[test]
fn a_continuation_needs_two_to_a_thousand_seed_values() {
    let home = tempfile::tempdir().unwrap();
    for n in ["0", "1", "1001", "abc", "2.5", "-2"] {
        let vary = format!("f=3Hz:8Hz:{n}");
        assert_refused(home.path(), &["continue", "--vary", &vary], &["--vary", &vary, "2 to 1000"]);
    }
}

#[test]
fn a_refused_figure_file_names_the_flag_that_gave_it() {
    let home = tempfile::tempdir().unwrap();
    fs::write(home.path().join("old.svg"), "old").unwrap();
    fs::write(home.path().join("old.pdf"), "old").unwrap();
    fs::create_dir(home.path().join("folder")).unwrap();
    let sweep = ["sweep", "--vary", "mass=30g:100g:3"];
    let design = [
        "design",
        "--vary",
        "mass=20g:120g",
        "--minimize",
        "spl_max_db",
        "--maximize",
        "inclination_cm_s",
        "--evaluations",
        "4",
    ];
    let bifurcation = ["bifurcation", "--vary", "f=3Hz:8Hz:3", "--force-amplitude", "1", "--transient", "10"];
    for command in [&sweep[..], &design[..], &bifurcation[..]] {
        for (flag, file, words) in [
            ("--svg", "old.svg", "exists"),
            ("--pdf", "old.pdf", "exists"),
            ("--svg", "folder", "directory"),
            ("--pdf", "/dev/full", "device"),
        ] {
            let args: Vec<&str> = command.iter().copied().chain([flag, file]).collect();
            assert_refused(home.path(), &args, &[&format!("invalid {flag}: "), file, words]);
        }
    }
    assert_eq!(fs::read_to_string(home.path().join("old.svg")).unwrap(), "old");
}

/// No silent skips: a test that cannot run says so through the counted skip
/// (`support::skip::skip`), which `.ci/run` counts and CI fails on; none prints its own
/// "skipped" line or is marked `#[ignore]` (cargo counts those, and CI fails on them too, but a
/// test that never runs is no test).
#[test]
fn every_skip_in_the_tests_goes_through_the_counted_skip() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/it");
    let mut files = vec![];
    for dir in [root.clone(), root.join("support"), root.join("common")] {
        let Ok(entries) = fs::read_dir(&dir) else { continue };
        files.extend(entries.map(|e| e.unwrap().path()).filter(|p| p.extension().is_some_and(|x| x == "rs")));
    }
    assert!(files.len() > 40, "the test files are found: {}", files.len());
    let mut counted = 0;
    let mut own = vec![];
    for f in &files {
        let text = fs::read_to_string(f).unwrap();
        counted += text.matches("support::skip::skip(").count();
        if f.ends_with("support/skip.rs") || f.ends_with("hostile_round5.rs") {
            continue;
        }
        for (i, line) in text.lines().enumerate() {
            let l = line.to_lowercase();
            let prints_skip = (l.contains("println!(") || l.contains("print!(")) && l.contains("skip");
            if prints_skip || l.trim_start().starts_with("#[ignore") {
                own.push(format!("{}:{}: {}", f.display(), i + 1, line.trim()));
            }
        }
    }
    assert!(counted >= 10, "the counted skip is what the tests use ({counted} calls)");
    assert!(own.is_empty(), "a skip that is not counted:\n{}", own.join("\n"));
}

/// A design file whose value is out of range is refused naming the file the user typed (the
/// value came from it, not from a flag); the flag, typed, overrides the file's value.
#[test]
fn an_out_of_range_value_in_a_design_file_names_the_file() {
    let home = tempfile::tempdir().unwrap();
    let (code, _, err) = thud(
        home.path(),
        &["design", "--vary", "mass=20g:120g", "--minimize", "spl_max_db", "--evaluations", "4", "--save", "front"],
    );
    assert_eq!(code, 0, "{err}");
    let saved = fs::read_to_string(home.path().join("front/design-01.toml")).unwrap();
    let line = saved.lines().find(|l| l.starts_with("duration_s = ")).unwrap().to_string();
    fs::write(home.path().join("long.toml"), saved.replace(&line, "duration_s = 1e300")).unwrap();
    for command in [&["simulate"][..], &["sweep", "--masses", "30g:100g:2", "--gaps", "2cm:5cm:2"][..]] {
        let args: Vec<&str> = command.iter().copied().chain(["--design", "long.toml"]).collect();
        assert_refused(home.path(), &args, &["invalid --design: long.toml: ", "duration", "1e300"]);
    }
    let (code, _, err) = thud(home.path(), &["simulate", "--design", "long.toml", "--duration", "0.5"]);
    assert_eq!(code, 0, "{err}");
    assert_refused(
        home.path(),
        &["simulate", "--design", "long.toml", "--duration", "1e300"],
        &["invalid --duration: "],
    );
}

/// `thud continue --vary f=…` takes its frequency from the varied one, as every study does: no
/// `--freq` needed beside a force.
#[test]
fn a_continuation_in_frequency_needs_no_freq() {
    let home = tempfile::tempdir().unwrap();
    let (code, out, err) = thud(home.path(), &["continue", "--vary", "f=3Hz:4Hz", "--force-amplitude", "1", "--json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["design"]["damper"]["freq_hz"].as_f64(), Some(3.0), "FROM stands in for --freq: {out}");
    assert_eq!(v["points"][0]["value"].as_f64(), Some(3.0), "the branch starts at FROM: {out}");
}
