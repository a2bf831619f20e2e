//! A single-slot background job runner, after gitui's `AsyncSingleJob`: one thread, at most
//! one job queued and one running, and the newest job wins — a new job replaces the queued one
//! and cancels the running one unless that is already doing the same work (equal [`Job::key`]).
//! A panic inside a job is caught and reported as the job's [`JobError`], so a slot is never
//! left "running" with nobody to answer.
//!
//! What a job computes is not here (see `compute.rs`, and the jobs in `worker.rs`).
//! Hand-written on a `Mutex` + `Condvar` because the channel and pool crates queue every job,
//! while this slot must drop the superseded ones and cancel the running one.

use std::any::Any;
use std::cell::{Cell, RefCell};
use std::panic::{self, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard, Once};

/// Why a job gave no result of its own.
#[derive(Debug, thiserror::Error)]
pub enum JobError {
    /// The job panicked: a bug. The message is the panic's, with where it happened.
    #[error("internal error in the {job} job: {message}")]
    Panicked { job: &'static str, message: String },
    /// The runner's thread could not be started, so the job never ran.
    #[error("cannot start the {job} thread: {source}")]
    NoThread {
        job: &'static str,
        #[source]
        source: std::io::Error,
    },
}

/// Where a job's reports go (called from the runner's thread and any threads the job starts).
pub type Sink<R> = dyn Fn(R) + Send + Sync;

/// One kind of background work.
pub trait Job: Send + 'static {
    /// Names the job in thread names and error messages ("simulation").
    const NAME: &'static str;
    /// What the job reports: progress and results, and failures through [`Job::failed`].
    type Report: Send + 'static;
    /// Kept on the runner's thread from one job to the next (a cache); reset after a panic.
    type State: Default;

    /// The work's identity: jobs with equal keys compute the same thing.
    type Key: PartialEq + Clone + Send + 'static;

    /// This job's key.
    fn key(&self) -> &Self::Key;

    /// Does the work, sending its reports through `cx`. A cancelled job may stop early and
    /// report nothing.
    fn run(&self, state: &mut Self::State, cx: &Context<'_, Self::Report>);

    /// The report of this job when it could not give its own: it panicked or never ran.
    fn failed(&self, error: JobError) -> Self::Report;
}

/// What a running job sees: its cancellation flag and where its reports go.
pub struct Context<'a, R> {
    cancel: &'a AtomicBool,
    sink: &'a (dyn Fn(R) + Sync),
}

impl<'a, R> Context<'a, R> {
    /// A context over a flag and a sink (the runner makes one per job; tests and synchronous
    /// callers make their own).
    pub fn new(cancel: &'a AtomicBool, sink: &'a (dyn Fn(R) + Sync)) -> Self {
        Self { cancel, sink }
    }

    /// The flag the runner sets when a newer job replaces this one (engine calls poll it).
    pub fn cancel_flag(&self) -> &'a AtomicBool {
        self.cancel
    }

    /// True once the job has been superseded or cancelled.
    pub fn is_cancelled(&self) -> bool {
        self.cancel.load(Ordering::Relaxed)
    }

    /// Sends one report.
    pub fn report(&self, r: R) {
        (self.sink)(r);
    }
}

/// The slot: the queued job with its cancel flag, and the key and flag of the running one.
struct Slot<J: Job> {
    state: Mutex<SlotState<J>>,
    ready: Condvar,
}

struct SlotState<J: Job> {
    queued: Option<(J, Arc<AtomicBool>)>,
    running: Option<(J::Key, Arc<AtomicBool>)>,
    closed: bool,
}

impl<J: Job> Slot<J> {
    fn new() -> Self {
        Self { state: Mutex::new(SlotState { queued: None, running: None, closed: false }), ready: Condvar::new() }
    }

    /// The state; a poisoned lock is taken as is (no job code runs while it is held).
    fn lock(&self) -> MutexGuard<'_, SlotState<J>> {
        self.state.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    /// Queues `job` (replacing any queued job) and cancels a running job with another key.
    fn put(&self, job: J) {
        let mut s = self.lock();
        if let Some((key, flag)) = &s.running {
            // The same work is already running (and not cancelled): its result will do.
            if key == job.key() && !flag.load(Ordering::Relaxed) {
                s.queued = None;
                return;
            }
            flag.store(true, Ordering::Relaxed);
        }
        s.queued = Some((job, Arc::new(AtomicBool::new(false))));
        self.ready.notify_one();
    }

    /// Waits for the next job and marks it running; None when closed.
    fn take(&self) -> Option<(J, Arc<AtomicBool>)> {
        let mut s = self.lock();
        loop {
            if s.closed {
                return None;
            }
            if let Some((job, flag)) = s.queued.take() {
                s.running = Some((job.key().clone(), flag.clone()));
                return Some((job, flag));
            }
            s = self.ready.wait(s).unwrap_or_else(std::sync::PoisonError::into_inner);
        }
    }

    fn finished(&self) {
        self.lock().running = None;
    }

    /// Drops the queued job and cancels the running one.
    fn cancel(&self) {
        let mut s = self.lock();
        s.queued = None;
        if let Some((_, flag)) = &s.running {
            flag.store(true, Ordering::Relaxed);
        }
    }

    fn pending(&self) -> bool {
        let s = self.lock();
        s.queued.is_some() || s.running.is_some()
    }

    fn close(&self) {
        self.cancel();
        self.lock().closed = true;
        self.ready.notify_all();
    }
}

/// One slot served by one thread: jobs of type `J`, newest wins. Dropping it cancels the
/// running job and lets the thread end.
pub struct SingleJob<J: Job> {
    slot: Arc<Slot<J>>,
    sink: Arc<Sink<J::Report>>,
    /// Why the thread could not be started (then every job is answered with that error).
    no_thread: Option<std::io::Error>,
}

impl<J: Job> SingleJob<J> {
    /// Starts the thread; reports go to `sink`. Also chains the panic hook of [`catch`] (once):
    /// start runners after the terminal's hook is installed, so that a job's panic does not
    /// restore the terminal under the running app.
    pub fn start(sink: Arc<Sink<J::Report>>) -> Self {
        install_hook();
        let slot = Arc::new(Slot::new());
        let (s, k) = (slot.clone(), sink.clone());
        let spawned = std::thread::Builder::new().name(format!("thud-{}", J::NAME)).spawn(move || serve(&s, &*k));
        Self { slot, sink, no_thread: spawned.err() }
    }

    /// Queues `job`: it replaces the queued job and cancels the running one (unless that one
    /// has the same key and is not cancelled: then `job` is dropped and the running one answers).
    pub fn spawn(&self, job: J) {
        match &self.no_thread {
            None => self.slot.put(job),
            Some(e) => {
                let source = std::io::Error::new(e.kind(), e.to_string());
                (self.sink)(job.failed(JobError::NoThread { job: J::NAME, source }));
            }
        }
    }

    /// Drops the queued job and cancels the running one.
    pub fn cancel(&self) {
        self.slot.cancel();
    }

    /// True while a job is queued or running.
    pub fn is_pending(&self) -> bool {
        self.slot.pending()
    }
}

impl<J: Job> Drop for SingleJob<J> {
    fn drop(&mut self) {
        self.slot.close();
    }
}

/// The runner's thread: takes jobs until the slot is closed. A panicking job frees the slot,
/// resets the state (it may be half-updated) and reports [`JobError::Panicked`].
fn serve<J: Job>(slot: &Slot<J>, sink: &Sink<J::Report>) {
    let mut state = J::State::default();
    while let Some((job, cancel)) = slot.take() {
        let cx = Context::new(&cancel, sink);
        let outcome = catch(J::NAME, || job.run(&mut state, &cx));
        slot.finished();
        if let Err(e) = outcome {
            state = J::State::default();
            sink(job.failed(e));
        }
    }
}

thread_local! {
    /// True while this thread runs code inside [`catch`].
    static CATCHING: Cell<bool> = const { Cell::new(false) };
    /// The message of the last panic caught on this thread (set by the panic hook).
    static CAUGHT: RefCell<Option<String>> = const { RefCell::new(None) };
}

/// Runs `f`; a panic in it becomes [`JobError::Panicked`] naming `job`. While `f` runs, a
/// panic on this thread is kept from the panic hook that was installed before (which would
/// print it over the screen and restore the terminal the app is still drawing on).
pub fn catch<R>(job: &'static str, f: impl FnOnce() -> R) -> Result<R, JobError> {
    install_hook();
    let was = CATCHING.with(|c| c.replace(true));
    // Unwind safety: after a panic the job's state is reset and the job itself only reports.
    let result = panic::catch_unwind(AssertUnwindSafe(f));
    CATCHING.with(|c| c.set(was));
    result.map_err(|payload| {
        let message = CAUGHT.with(|c| c.borrow_mut().take()).unwrap_or_else(|| payload_text(payload.as_ref()));
        JobError::Panicked { job, message }
    })
}

/// True on a thread running a job inside [`catch`] (a panic there becomes an error message).
pub fn catching() -> bool {
    CATCHING.with(Cell::get)
}

/// Chains a panic hook (once) that keeps the message of a panic inside [`catch`] for its
/// error and passes every other panic to the hook installed before it.
fn install_hook() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let previous = panic::take_hook();
        panic::set_hook(Box::new(move |info| {
            if catching() {
                let at = info.location().map_or_else(String::new, |l| format!(" (at {}:{})", l.file(), l.line()));
                let text = format!("{}{at}", payload_text(info.payload()));
                CAUGHT.with(|c| *c.borrow_mut() = Some(text));
            } else {
                previous(info);
            }
        }));
    });
}

/// The text of a panic payload (`panic!` gives a `&str` or a `String`).
fn payload_text(payload: &(dyn Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| (*s).to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "a panic without a message".to_string())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::mpsc;
    use std::time::{Duration, Instant};

    /// A job that waits on a gate (so tests control when it ends; `stops`: or until it is
    /// cancelled), can panic, and reports (key, Ok(jobs run so far)) or (key, Err(message)).
    struct Test {
        key: String,
        gate: Option<Arc<(Mutex<bool>, Condvar)>>,
        stops: bool,
        panic: bool,
    }

    type Report = (String, Result<usize, JobError>);

    impl Test {
        fn new(key: &str) -> Self {
            Self { key: key.into(), gate: None, stops: false, panic: false }
        }
        fn gated(key: &str, gate: &Arc<(Mutex<bool>, Condvar)>) -> Self {
            Self { gate: Some(gate.clone()), ..Self::new(key) }
        }
        fn stopping(key: &str, gate: &Arc<(Mutex<bool>, Condvar)>) -> Self {
            Self { stops: true, ..Self::gated(key, gate) }
        }
        fn panicking(key: &str) -> Self {
            Self { panic: true, ..Self::new(key) }
        }
    }

    impl Job for Test {
        const NAME: &'static str = "test";
        type Report = Report;
        /// Jobs run so far on this thread.
        type State = usize;

        type Key = String;

        fn key(&self) -> &String {
            &self.key
        }

        fn run(&self, runs: &mut usize, cx: &Context<'_, Report>) {
            *runs += 1;
            if let Some(gate) = &self.gate {
                let (open, cv) = &**gate;
                let mut g = open.lock().unwrap();
                let stop = |open: bool| open || (self.stops && cx.is_cancelled());
                while !stop(*g) {
                    g = cv.wait_timeout(g, Duration::from_millis(5)).unwrap().0;
                }
            }
            assert!(!self.panic, "job {} blew up", self.key);
            if !cx.is_cancelled() {
                cx.report((self.key.clone(), Ok(*runs)));
            }
        }

        fn failed(&self, error: JobError) -> Report {
            (self.key.clone(), Err(error))
        }
    }

    /// A report with its error as `None`: how many jobs ran, if the job finished.
    fn ran((key, result): Report) -> (String, Option<usize>) {
        (key, result.ok())
    }

    fn runner() -> (SingleJob<Test>, mpsc::Receiver<Report>) {
        let (tx, rx) = mpsc::channel();
        let sink: Arc<Sink<Report>> = Arc::new(move |r| {
            let _ = tx.send(r);
        });
        (SingleJob::start(sink), rx)
    }

    fn recv(rx: &mpsc::Receiver<Report>) -> Report {
        rx.recv_timeout(Duration::from_secs(10)).expect("the runner answered")
    }

    fn gate() -> Arc<(Mutex<bool>, Condvar)> {
        Arc::new((Mutex::new(false), Condvar::new()))
    }

    fn open(g: &Arc<(Mutex<bool>, Condvar)>) {
        *g.0.lock().unwrap() = true;
        g.1.notify_all();
    }

    /// Waits until the first job is running (taken from the queue).
    fn until_running(r: &SingleJob<Test>) {
        let t0 = Instant::now();
        while r.slot.lock().queued.is_some() || r.slot.lock().running.is_none() {
            assert!(t0.elapsed() < Duration::from_secs(10), "the job started");
            std::thread::yield_now();
        }
    }

    #[test]
    fn newest_job_wins_over_the_queued_and_the_running_one() {
        let (r, rx) = runner();
        let g = gate();
        r.spawn(Test::gated("a", &g));
        until_running(&r);
        r.spawn(Test::new("b"));
        r.spawn(Test::new("c"));
        open(&g);
        let (key, result) = recv(&rx);
        assert_eq!(key, "c", "a was cancelled (reports nothing), b was replaced by c");
        assert_eq!(result.ok(), Some(2), "only a and c ran");
        assert!(rx.recv_timeout(Duration::from_millis(100)).is_err(), "nothing else reported");
    }

    #[test]
    fn the_same_work_already_running_is_not_started_again() {
        let (r, rx) = runner();
        let g = gate();
        r.spawn(Test::gated("a", &g));
        until_running(&r);
        r.spawn(Test::new("a"));
        assert!(r.slot.lock().queued.is_none(), "the running a will answer");
        open(&g);
        assert_eq!(ran(recv(&rx)), ("a".to_string(), Some(1)));
    }

    #[test]
    fn a_job_whose_running_copy_was_cancelled_is_queued_again() {
        let (r, _rx) = runner();
        let g = gate();
        r.spawn(Test::gated("a", &g));
        until_running(&r);
        let flag_a = r.slot.lock().running.as_ref().map(|(_, f)| f.clone()).unwrap();
        r.spawn(Test::new("b"));
        assert!(flag_a.load(Ordering::Relaxed), "a newer job cancels the running one");
        r.spawn(Test::new("a"));
        let queued = r.slot.lock().queued.as_ref().map(|(j, _)| j.key.clone());
        assert_eq!(queued, Some("a".to_string()), "back to a: a runs again, b is dropped");
        open(&g);
    }

    #[test]
    fn cancel_stops_the_running_job_and_drops_the_queued_one() {
        let (r, rx) = runner();
        let g = gate();
        r.spawn(Test::stopping("a", &g));
        until_running(&r);
        r.spawn(Test::stopping("b", &g));
        r.cancel();
        let t0 = Instant::now();
        while r.is_pending() {
            assert!(t0.elapsed() < Duration::from_secs(10), "the cancelled job ended without the gate opening");
            std::thread::yield_now();
        }
        assert!(rx.recv_timeout(Duration::from_millis(100)).is_err(), "a cancelled job reports nothing");
        r.spawn(Test::new("c"));
        assert_eq!(ran(recv(&rx)), ("c".to_string(), Some(2)), "the runner goes on");
    }

    #[test]
    fn a_panicking_job_becomes_an_error_and_frees_the_slot() {
        let (r, rx) = runner();
        r.spawn(Test::panicking("boom"));
        let (key, result) = recv(&rx);
        assert_eq!(key, "boom");
        let message = result.expect_err("a panic is an error").to_string();
        assert!(message.contains("internal error in the test job: job boom blew up"), "{message}");
        assert!(message.contains("job.rs"), "says where: {message}");
        assert!(!r.is_pending(), "no slot stuck running");
        r.spawn(Test::new("after"));
        assert_eq!(ran(recv(&rx)), ("after".to_string(), Some(1)), "the thread lives on; its state was reset");
    }

    #[test]
    fn catch_passes_results_through_and_is_off_after() {
        assert_eq!(catch("x", || 7).unwrap(), 7);
        assert!(!catching());
        let e = catch::<()>("x", || panic!("{}", String::from("owned"))).unwrap_err();
        assert!(matches!(&e, JobError::Panicked { job: "x", message } if message.starts_with("owned")), "{e}");
        assert!(!catching());
    }
}
