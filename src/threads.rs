//! The one parallel pool (rayon's global pool), built once at start-up so that a thread that
//! cannot be started never panics.
//!
//! Left to itself rayon builds its global pool on first use and panics
//! (`ThreadPoolBuildError … WouldBlock`) when the operating system refuses one of its threads:
//! a pids limit (`ulimit -u`, a container's `pids.max`) or `RAYON_NUM_THREADS=1500`. And it can
//! be built only once: a failed build cannot be retried with fewer threads. So the threads are
//! started here first, by hand, each parked on a channel; as many as the system allows (up to
//! the wanted count) are then handed to rayon through its spawn handler, which therefore cannot
//! fail. With none at all, the pool is the calling thread alone.
//!
//! The wanted count: `--threads N` if given, else `RAYON_NUM_THREADS` (rayon's own variable; a
//! value that is not a whole number ≥ 1 means "automatic", as for rayon), else one per CPU the
//! process may use. Either is held to [`limits::THREADS`].

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, Sender};

use rayon::ThreadBuilder;

use crate::limits;

/// rayon's environment variable for the thread count.
pub const ENV: &str = "RAYON_NUM_THREADS";

/// Set by [`init`] when the pool is the calling thread alone.
static CALLING_ONLY: AtomicBool = AtomicBool::new(false);

/// What [`init`] did.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Pool {
    /// Threads wanted (after the range).
    pub wanted: usize,
    /// Threads the pool has; 1 with `calling_thread_only` is the calling thread itself.
    pub threads: usize,
    /// No worker thread could be started: parallel work runs on the calling thread.
    pub calling_thread_only: bool,
    /// One line for stderr when the pool is not what was asked for.
    pub warning: Option<String>,
}

/// The wanted thread count: `flag` (already range-checked), else [`ENV`] held to
/// [`limits::THREADS`] (a warning when it had to be lowered), else the available parallelism.
pub fn wanted(flag: Option<usize>, env: Option<&str>) -> (usize, Option<String>) {
    let max = limits::THREADS.max as usize;
    if let Some(n) = flag {
        return (n, None);
    }
    match env.map(str::trim).and_then(|t| t.parse::<u64>().ok()).filter(|&n| n > 0) {
        Some(n) if n > max as u64 => (
            max,
            Some(format!("warning: {ENV}={n} is more than {max}, the most worker threads thud starts; using {max}")),
        ),
        Some(n) => (usize::try_from(n).unwrap_or(max), None),
        None => (std::thread::available_parallelism().map_or(1, std::num::NonZero::get).min(max), None),
    }
}

/// The smallest stack a worker thread gets (std's own default): the integrators recurse
/// little, but a stack of a few bytes (`RUST_MIN_STACK=1`) overflows at the first call.
pub const MIN_WORKER_STACK: usize = 2 << 20;

/// A worker thread's stack: `RUST_MIN_STACK` (std's variable) when it asks for more than
/// [`MIN_WORKER_STACK`], else that.
fn worker_stack() -> usize {
    let asked = std::env::var("RUST_MIN_STACK").ok().and_then(|v| v.trim().parse::<usize>().ok());
    asked.map_or(MIN_WORKER_STACK, |n| n.max(MIN_WORKER_STACK))
}

/// A started thread waiting for the rayon worker it will become.
struct Parked {
    slot: Sender<ThreadBuilder>,
    thread: std::thread::JoinHandle<()>,
}

/// Starts up to `n` threads, each waiting for the rayon worker it will become; returns them
/// and, if fewer than `n` could be started, why the next one could not.
fn park(n: usize) -> (Vec<Parked>, Option<std::io::Error>) {
    let mut parked = Vec::with_capacity(n);
    for i in 0..n {
        let (slot, rx) = mpsc::channel::<ThreadBuilder>();
        let spawned =
            std::thread::Builder::new().name(format!("thud-pool-{i}")).stack_size(worker_stack()).spawn(move || {
                // Unused threads see their channel closed and end.
                if let Ok(worker) = rx.recv() {
                    worker.run();
                }
            });
        match spawned {
            Ok(thread) => parked.push(Parked { slot, thread }),
            Err(e) => return (parked, Some(e)),
        }
    }
    (parked, None)
}

/// Ends parked threads that will not be used, and waits until they are gone, so the threads
/// they leave room for can be started right after.
fn release(unused: Vec<Parked>) {
    let threads: Vec<_> = unused.into_iter().map(|p| p.thread).collect();
    for t in threads {
        let _ = t.join();
    }
}

/// Builds the global pool with `wanted` threads, or as many as the system allows while
/// leaving room for `reserve` other threads (the explorer's input and job threads, the signal
/// thread), or the calling thread alone. Call once, before any parallel work; a second call
/// changes nothing and returns the pool as it is.
pub fn init(wanted: usize, reserve: usize) -> Pool {
    let wanted = wanted.max(1);
    let (mut parked, failure) = park(wanted + reserve);
    // Without a failure the reserve was there and is given back; with one, the reserve comes
    // out of what was started.
    let keep = if failure.is_some() { parked.len().saturating_sub(reserve) } else { wanted };
    release(parked.split_off(keep.min(parked.len())));
    let started = parked.len();
    let built = if started == 0 {
        rayon::ThreadPoolBuilder::new().num_threads(1).use_current_thread().build_global()
    } else {
        let mut slots = parked.into_iter().map(|p| p.slot);
        rayon::ThreadPoolBuilder::new()
            .num_threads(started)
            .thread_name(|i| format!("thud-pool-{i}"))
            .spawn_handler(move |worker| {
                let slot = slots.next().ok_or_else(|| std::io::Error::other("no parked thread left"))?;
                slot.send(worker).map_err(|_| std::io::Error::other("a parked thread ended"))
            })
            .build_global()
    };
    if built.is_err() {
        // Already built (a second call, or a test harness): report it as it is.
        return Pool { wanted, threads: rayon::current_num_threads(), calling_thread_only: false, warning: None };
    }
    CALLING_ONLY.store(started == 0, Ordering::Relaxed);
    let reason = failure.map_or_else(String::new, |e| format!(" ({e})"));
    let warning = match started {
        0 => Some(format!(
            "warning: no worker thread could be started{reason}; running on the calling thread alone (slower)"
        )),
        s if s < wanted => {
            Some(format!("warning: only {s} of {wanted} worker threads could be started{reason}; running with {s}"))
        }
        _ => None,
    };
    Pool { wanted, threads: started.max(1), calling_thread_only: started == 0, warning }
}

/// True when [`init`] found no worker thread: parallel work runs on the thread that called
/// [`init`] only, so other threads must not start any.
pub fn calling_thread_only() -> bool {
    CALLING_ONLY.load(Ordering::Relaxed)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_flag_wins_then_the_environment_held_to_the_range() {
        assert_eq!(wanted(Some(3), Some("8")), (3, None));
        assert_eq!(wanted(None, Some("8")).0, 8);
        let (n, w) = wanted(None, Some("100000"));
        assert_eq!(n, limits::THREADS.max as usize);
        assert!(w.is_some_and(|w| w.contains("RAYON_NUM_THREADS=100000")));
        for auto in ["0", "abc", "", "-3"] {
            let (n, w) = wanted(None, Some(auto));
            assert!(n >= 1 && w.is_none(), "{auto}");
        }
    }

    #[test]
    fn parked_threads_are_counted_and_released() {
        let (parked, failure) = park(3);
        assert_eq!(parked.len(), 3);
        assert!(failure.is_none());
        release(parked);
    }
}
