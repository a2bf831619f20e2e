//! What the command-line tests share: running the built `thud`.
#![allow(dead_code)] // each test file that loads this module uses one of the runners, not both

use std::path::Path;
use std::process::{Command, Stdio};

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
