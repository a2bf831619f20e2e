//! A program run in a private home: the file tests' environment.

use std::ffi::OsStr;
use std::path::Path;
use std::process::{Command, Stdio};

use thud::fsio::{HOLD_TEMP_FOR_TEST, NAMED_TEMPS_FOR_TEST};

/// `program args` run in `home`, with HOME and the XDG folders inside it, stdin closed, and
/// the temporary-file test seams off unless `env` (set last) turns one on.
pub fn in_home<S: AsRef<OsStr>>(program: &str, args: &[S], home: &Path, env: &[(&str, &str)]) -> Command {
    let mut c = Command::new(program);
    c.args(args)
        .current_dir(home)
        .env("HOME", home)
        .env("XDG_CONFIG_HOME", home.join("config"))
        .env("XDG_DATA_HOME", home.join("data"))
        .env_remove(NAMED_TEMPS_FOR_TEST)
        .env_remove(HOLD_TEMP_FOR_TEST)
        .stdin(Stdio::null());
    for (k, v) in env {
        c.env(k, v);
    }
    c
}
