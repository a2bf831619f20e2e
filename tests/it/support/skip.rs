//! A test that cannot run here says so instead of passing green. Outside CI it prints one
//! `skipped: …` line and, when `THUD_TEST_SKIPS` names a file, adds the line to it (`.ci/run`
//! counts them). In CI (`CI` set and not `false` or `0`) it fails: CI installs what every test
//! needs (`.ci/run`), so a missing tool there is a broken runner, not a test to leave out.

use std::io::Write;

/// Whether this is a CI run (`CI=true`, as CI services set it).
pub fn in_ci() -> bool {
    std::env::var("CI").is_ok_and(|v| !v.is_empty() && v != "false" && v != "0")
}

/// The test (or the part of it) cannot run here, for `reason`: a failure in CI, else a counted
/// skip. The caller returns (or goes on without the part) after it.
pub fn skip(reason: &str) {
    assert!(!in_ci(), "cannot run in CI: {reason} (.ci/run installs what the tests need)");
    eprintln!("skipped: {reason}");
    if let Some(path) = std::env::var_os("THUD_TEST_SKIPS") {
        let line = format!("{}: {reason}\n", std::thread::current().name().unwrap_or("a test"));
        // One write of one line on a file opened for appending: lines of tests running at the
        // same time do not mix.
        let appended = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(&path)
            .and_then(|mut f| f.write_all(line.as_bytes()));
        if let Err(e) = appended {
            panic!("cannot count the skip in {}: {e}", path.to_string_lossy());
        }
    }
}
