//! A stranger for the pids-limit tests: a user id that no process on the machine runs as, and a
//! copy of the built `thud` that it can run. Root ignores RLIMIT_NPROC (`ulimit -u`), so those
//! tests run `thud` as another user; `nobody` does not do: the limit counts every process of
//! the user (other tests, other programs running as `nobody`), and `nobody` cannot reach a
//! binary built in a private folder (a clone in root's home or any mode-0700 folder: "Permission
//! denied", exit 126). The copy sits in a fresh folder under /tmp owned by the stranger (mode
//! 0755), removed with the stranger.

use std::os::unix::fs::PermissionsExt;
use std::path::PathBuf;
use std::process::{Command, Stdio};

/// Where the stranger's user id is taken from: inside 16 bits, as a container's user namespace
/// maps, and above the ids distributions give to people and services.
const UIDS: std::ops::Range<u32> = 20_000..60_000;

/// A user id with no process, and its copy of `thud`.
pub struct Stranger {
    pub uid: u32,
    /// The stranger's folder (its own, mode 0755, under /tmp), removed on drop.
    pub dir: tempfile::TempDir,
    /// The copy of the built `thud` in `dir`.
    pub bin: PathBuf,
}

impl Stranger {
    /// A stranger for the test numbered `slot` (tests running at the same time take different
    /// slots), or None — with the reason printed — where the test cannot run: not root, no
    /// `setpriv`, no free user id, or /tmp not reachable for another user.
    pub fn new(slot: u32) -> Option<Self> {
        let root = Command::new("id").arg("-u").output().is_ok_and(|o| o.stdout.starts_with(b"0\n"));
        let setpriv = Command::new("setpriv").arg("--version").output().is_ok_and(|o| o.status.success());
        if !root || !setpriv {
            crate::support::skip::skip(
                "needs root and setpriv to run thud as another user under ulimit -u (root ignores the limit)",
            );
            return None;
        }
        let Some(uid) = free_uid(slot) else {
            crate::support::skip::skip(&format!("no user id in {UIDS:?} without processes"));
            return None;
        };
        let dir = tempfile::Builder::new().prefix("thud-stranger-").tempdir_in("/tmp").unwrap();
        std::os::unix::fs::chown(dir.path(), Some(uid), Some(uid)).unwrap();
        std::fs::set_permissions(dir.path(), std::fs::Permissions::from_mode(0o755)).unwrap();
        let bin = dir.path().join("thud");
        crate::common::copy_thud(&bin);
        std::fs::set_permissions(&bin, std::fs::Permissions::from_mode(0o755)).unwrap();
        let s = Stranger { uid, dir, bin };
        let reachable = Command::new("setpriv")
            .args(s.setpriv())
            .arg("test")
            .arg("-x")
            .arg(&s.bin)
            .stdin(Stdio::null())
            .status()
            .is_ok_and(|st| st.success());
        if !reachable {
            crate::support::skip::skip(&format!(
                "user {uid} cannot run {} (is /tmp closed to other users?)",
                s.bin.display()
            ));
            return None;
        }
        Some(s)
    }

    /// The `setpriv` options that run the command after them as the stranger.
    pub fn setpriv(&self) -> [String; 3] {
        let id = self.uid;
        [format!("--reuid={id}"), format!("--regid={id}"), "--clear-groups".to_string()]
    }

    /// The command line that runs what follows it as the stranger (`setpriv --reuid=…`).
    pub fn setpriv_line(&self) -> String {
        format!("setpriv {}", self.setpriv().join(" "))
    }
}

/// A user id in [`UIDS`] that no account has and no process runs as, picked from this process's
/// id and `slot` so that test runs at the same time pick different ones.
fn free_uid(slot: u32) -> Option<u32> {
    let passwd = std::fs::read_to_string("/etc/passwd").unwrap_or_default();
    let accounts: Vec<u32> = passwd.lines().filter_map(|l| l.split(':').nth(2)?.parse().ok()).collect();
    let busy = running_uids();
    let span = UIDS.end - UIDS.start;
    let start = (std::process::id() % (span / 8)) * 8 + slot % 8;
    (0..span / 8)
        .map(|k| UIDS.start + (start + k * 8) % span)
        .find(|uid| !accounts.contains(uid) && !busy.contains(uid))
}

/// The real, effective, saved and file-system user ids of every process (from /proc).
fn running_uids() -> Vec<u32> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir("/proc").into_iter().flatten().flatten() {
        let Ok(status) = std::fs::read_to_string(entry.path().join("status")) else { continue };
        if let Some(line) = status.lines().find(|l| l.starts_with("Uid:")) {
            out.extend(line.split_whitespace().skip(1).filter_map(|v| v.parse::<u32>().ok()));
        }
    }
    out
}
