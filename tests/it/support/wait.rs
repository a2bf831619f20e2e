//! Waiting for a child `thud` with a time limit: the tests' guard against a hang.
//!
//! [`wait_within`] bounds wall time, which a loaded machine stretches; [`wait_within_cpu`]
//! bounds the child's own CPU time, which load does not stretch, with a wall-time guard kept
//! only for a child that blocks without computing.

use std::io::Read;
use std::process::{Child, ExitStatus, Output};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// Waits for `child` at most `limit`; kills it and fails the test (naming `what`) past that.
/// Its piped stdout and stderr are read while it runs, so a child that writes more than a
/// pipe holds is not mistaken for a hang.
pub fn wait_within(mut child: Child, limit: Duration, what: &str) -> Output {
    let stdout = drain(child.stdout.take());
    let stderr = drain(child.stderr.take());
    let status = wait_or_kill(&mut child, limit, what);
    Output { status, stdout: stdout.join().unwrap(), stderr: stderr.join().unwrap() }
}

/// Reads `pipe` (if piped) to its end on a thread of its own.
fn drain(pipe: Option<impl Read + Send + 'static>) -> JoinHandle<Vec<u8>> {
    std::thread::spawn(move || {
        let mut bytes = Vec::new();
        if let Some(mut p) = pipe {
            let _ = p.read_to_end(&mut bytes);
        }
        bytes
    })
}

fn wait_or_kill(child: &mut Child, limit: Duration, what: &str) -> ExitStatus {
    wait_or_kill_by(child, what, |_, elapsed| (elapsed > limit).then(|| format!("{limit:?}")))
}

/// Waits for `child` while it has used at most `cpu` of CPU time (user and system, all its
/// threads) and at most `wall` of wall time; kills it and fails the test (naming `what` and the
/// bound passed) past either. The CPU bound is the budget of a run's work: a machine shared by
/// other builds slows the child's wall clock, not its CPU time. `wall` only catches a child
/// that blocks without computing (a deadlock, a read that never returns), so it can be generous.
pub fn wait_within_cpu(mut child: Child, cpu: Duration, wall: Duration, what: &str) -> Output {
    let stdout = drain(child.stdout.take());
    let stderr = drain(child.stderr.take());
    let status = wait_or_kill_by(&mut child, what, |pid, elapsed| {
        if elapsed > wall {
            return Some(format!("{wall:?} of wall time"));
        }
        cpu_time(pid).filter(|used| *used > cpu).map(|used| format!("{cpu:?} of CPU time (used {used:?})"))
    });
    Output { status, stdout: stdout.join().unwrap(), stderr: stderr.join().unwrap() }
}

/// The CPU time (user + system, all threads) process `pid` has used so far, from
/// `/proc/PID/stat`; `None` once it is gone or where there is no `/proc`.
fn cpu_time(pid: u32) -> Option<Duration> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    // The command name (field 2) is in parentheses and may hold spaces: count after it.
    let fields: Vec<&str> = stat.get(stat.rfind(')')? + 2..)?.split(' ').collect();
    // Fields 14 and 15 (utime, stime) are the 12th and 13th after the name.
    let ticks: u64 = fields.get(11)?.parse::<u64>().ok()? + fields.get(12)?.parse::<u64>().ok()?;
    // In USER_HZ, which Linux fixes at 100 a second for what it reports to user space.
    Some(Duration::from_millis(ticks * 10))
}

/// Polls `child` until it exits or `over(pid, elapsed)` names the bound it passed.
fn wait_or_kill_by(child: &mut Child, what: &str, over: impl Fn(u32, Duration) -> Option<String>) -> ExitStatus {
    let start = Instant::now();
    loop {
        if let Some(status) = child.try_wait().unwrap() {
            return status;
        }
        if let Some(bound) = over(child.id(), start.elapsed()) {
            let _ = child.kill();
            let _ = child.wait();
            panic!("{what} did not finish within {bound}");
        }
        std::thread::sleep(Duration::from_millis(5));
    }
}
