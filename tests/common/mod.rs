//! What the command-line tests share: running the built `thud`.

use std::process::Command;

/// Runs the built `thud` with `args`: (exit code, stdout, stderr); -1 when a signal ended it.
pub fn thud(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_thud")).args(args).output().expect("run thud");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}
