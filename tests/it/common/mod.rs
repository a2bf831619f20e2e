//! What the command-line tests share: running the built `thud`.
#![allow(dead_code)] // each test file that loads this module uses one of the runners, not both

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Duration;

use crate::support::wait::wait_within;

/// Runs the built `thud` with `args`: (exit code, stdout, stderr); -1 when a signal ended it.
pub fn thud(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_thud")).args(args).output().expect("run thud");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

/// Runs the built `thud` with HOME and the XDG folders in `home` (no config of the machine's
/// user is read) and stdin closed: (exit code, stdout, stderr); -1 when a signal ended it.
pub fn thud_in(home: &Path, args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_thud"))
        .args(args)
        .env("HOME", home)
        .env("XDG_CONFIG_HOME", home.join("config"))
        .env("XDG_DATA_HOME", home.join("data"))
        .env_remove("XDG_CONFIG_DIRS")
        .stdin(Stdio::null())
        .output()
        .expect("run thud");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

/// What one run of thud did.
#[derive(Debug)]
pub struct Ran {
    /// The exit code; -1 when a signal ended it.
    pub code: i32,
    pub stdout: String,
    pub stderr: String,
}

/// As [`thud_in`], with `home` as the working folder too, and the run killed (a test failure)
/// after `limit`.
pub fn thud_within(home: &Path, args: &[&str], limit: Duration) -> Ran {
    let child = Command::new(env!("CARGO_BIN_EXE_thud"))
        .args(args)
        .current_dir(home)
        .env("HOME", home)
        .env("XDG_CONFIG_HOME", home.join("config"))
        .env("XDG_DATA_HOME", home.join("data"))
        .env_remove("XDG_CONFIG_DIRS")
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run thud");
    let out = wait_within(child, limit, &format!("{args:?}"));
    Ran {
        code: out.status.code().unwrap_or(-1),
        stdout: String::from_utf8_lossy(&out.stdout).into(),
        stderr: String::from_utf8_lossy(&out.stderr).into(),
    }
}

/// Copies the built `thud` to `to`, by a `cp` of its own: a copy written by this process would
/// hold the file open for writing, and a child another test spawns at that moment inherits that
/// descriptor until its own exec, so running the copy could fail with "Text file busy"
/// (ETXTBSY; seen once in CI in `docs::man_finds_thud_after_man_install`).
pub fn copy_thud(to: &Path) {
    let status = Command::new("cp").arg(env!("CARGO_BIN_EXE_thud")).arg(to).stdin(Stdio::null()).status();
    assert!(status.is_ok_and(|s| s.success()), "cp thud {}", to.display());
}
