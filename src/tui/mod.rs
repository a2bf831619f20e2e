//! The terminal explorer: tune mass, gap and observer live and watch the readout, the
//! waveform, the polar, the time history and the zone chart follow.
//!
//! One way data flow: terminal events (own thread) and worker results arrive on one channel as
//! [`Msg`]s; [`App::update`] changes the state and returns [`Request`]s for the [`Worker`];
//! the screen is redrawn after each batch of messages (no fast tick). The UI thread never runs
//! a simulation.
//!
//! It is made to teach with: the chart never contradicts the readout (its marker is the live
//! design, at its mass and gap, with the design's own zone), every plot has round ticks and
//! axis titles with units, the selected field's meaning, unit and range are in the status line,
//! the help's second page says what the numbers mean, and a guided tour (`T`, `thud tui
//! --tour [FILE]`) tells the paper's story step by step with the real computations.
//!
//! The modules, from the state out: `app` (the state, grouped by concern, and the changes a
//! message makes to it: `app/state.rs`, `change`, `screen`, `guide`, `files`, `input`,
//! `update`); `worker` (requests, results, the five job slots) on `job` (the generic
//! single-slot runner) calling `compute` (the physics each job does), results tagged with the
//! typed keys of `cache_key` (built on `fingerprint`); `ui` (`draw` and the layout, reading
//! the state only) drawing one module per area: `header`, `status`, `footer`, `caption` (the
//! tour's), `popups` (help and the lists), and the panels `params`, `readout`, `waveform`,
//! `polar`, `history`, `chart`, `response`, `bifurcation`, `anim`, `table1` (Table 1 beside
//! both models) and `front` (the design front of `thud tui --front FILE`), the readout's and
//! the chart's view-models beside their widgets (the small panels' few lines stay in `ui`, as
//! the app imports those widgets' types), their frames from
//! `titles` (on `plot` and `theme`, whose ASCII spelling is [`crate::ascii`]'s); `fields` (the
//! editable parameters), `explain` (what each field and number means), `files` (the export
//! menu), `tour` (the guided tour's steps), `keys` (the key table), `input_reader` (the input
//! thread) on `input_parse` (the terminal's bytes to crossterm events, a bracketed paste held
//! to a time and a size), `hangup` and `terminal` (setup and restore).

pub mod anim;
pub mod app;
pub mod bifurcation;
pub mod cache_key;
mod caption;
pub mod chart;
pub mod clamp;
pub mod compute;
pub mod explain;
pub mod fields;
pub mod files;
pub mod fingerprint;
mod footer;
pub mod front;
pub mod hangup;
mod header;
pub mod history;
pub mod input_parse;
pub mod input_reader;
pub mod job;
pub mod keys;
pub mod params;
pub mod plot;
pub mod polar;
mod popups;
pub mod readout;
pub mod response;
pub mod sgr16;
mod status;
pub mod table1;
pub mod terminal;
pub mod theme;
mod titles;
pub mod tour;
pub mod ui;
pub mod view;
pub mod waveform;
pub mod worker;

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, Receiver};
use std::sync::Arc;
use std::time::{Duration, Instant};

use ratatui::backend::Backend;
use ratatui::Terminal;

pub use app::{App, Msg, Options};
pub use theme::Palette;
pub use worker::{Request, Worker};

use crate::error::ThudError;
use crate::{config, presets, store};

/// Why the explorer could not run.
#[derive(Debug, thiserror::Error)]
pub enum TuiError {
    /// The starting preset is unknown or its file is bad.
    #[error(transparent)]
    Preset(#[from] ThudError),
    /// No usable terminal (not a tty, or setting it up failed).
    #[error("cannot use the terminal ({0}); the explorer needs an interactive terminal (over SSH: ssh -t host thud)")]
    Terminal(#[source] std::io::Error),
    /// Drawing on the terminal failed.
    #[error("cannot draw on the terminal: {0}")]
    Draw(#[source] std::io::Error),
    /// The `--tour` file cannot be read or is not a valid tour.
    #[error(transparent)]
    Tour(#[from] tour::TourError),
    /// A thread the explorer needs could not be started.
    #[error("cannot start the explorer's {0} thread ({1}); the system refuses new threads (a pids limit?)")]
    Thread(&'static str, #[source] std::io::Error),
    /// The `--front` file cannot be read or is not a front the explorer can show.
    #[error(transparent)]
    Front(#[from] front::FrontError),
    /// The terminal hung up while the explorer ran (its input reports POLLHUP).
    #[error("the terminal is gone (its input hung up); the explorer ended")]
    TerminalGone,
}

impl TuiError {
    /// The exit status: 1 for a terminal or system failure, 2 for bad input (preset, tour).
    pub fn exit_code(&self) -> i32 {
        match self {
            TuiError::Preset(_) | TuiError::Tour(_) | TuiError::Front(_) => 2,
            TuiError::Terminal(_) | TuiError::Draw(_) | TuiError::Thread(..) | TuiError::TerminalGone => 1,
        }
    }
}

/// Set this environment variable to make the explorer panic right after it took over the
/// terminal: the end-to-end test uses it to check that the panic hook restores the terminal.
/// Read only in a build with the `test-hooks` feature (the test suite's; see [`crate::fsio`]).
pub const PANIC_FOR_TEST: &str = "THUD_TUI_PANIC_FOR_TEST";

/// How often the spinner turns while work is in flight.
const TICK: Duration = Duration::from_millis(120);

/// Runs the explorer until the user quits. Errors (bad preset, no terminal) come back before
/// or after the screen is restored. The user's `config.toml` is read (never written): a
/// problem with it is shown in the status line and the defaults are used.
pub fn run(opts: &Options) -> Result<(), TuiError> {
    let front = opts.front.as_deref().map(front::Front::load).transpose()?;
    // With a front the explorer starts on the search's starting design.
    let design = match &front {
        Some(f) => f.base.clone(),
        None => presets::preset(&opts.preset)?,
    };
    fields::check_loaded(&design)?;
    let tour_def = opts.tour.as_ref().map(tour::Tour::load).transpose()?;
    let theme = Palette::from_env(opts.ascii);
    let name = if front.is_some() { "front-start" } else { opts.preset.as_str() };
    let mut app = App::new(design, name, theme);
    app.host.tour_def = tour_def.map(Arc::new);
    app.mouse = opts.mouse;
    app.configure(&config::load_user_config());
    if let Some(t) = opts.theme {
        // The command line wins over config.toml (NO_COLOR still wins over both).
        app.theme = Palette { ascii: app.theme.ascii, ..theme }.with_theme(t);
    }
    app.host.data_dir = store::Dirs::project().map(|d| d.data_dir);
    if let Some(f) = front {
        app.host.front = Some(Arc::new(f));
        app.act(keys::Action::FrontView);
    }
    if let Some(dir) = &opts.export_dir {
        app.host.export_dir.clone_from(dir);
    }
    if crate::threads::calling_thread_only() {
        // The worker slots' parallel work would wait for the calling thread forever.
        return Err(TuiError::Thread("worker", std::io::Error::other("no worker thread could be started")));
    }
    // The config's `mouse = false` turned it off in `configure`.
    let (mut term, _guard) = terminal::setup(app.mouse).map_err(TuiError::Terminal)?;
    #[cfg(feature = "test-hooks")]
    assert!(
        std::env::var_os(PANIC_FOR_TEST).is_none(),
        "{PANIC_FOR_TEST} is set: panicking on purpose to test the terminal restore"
    );
    let (tx, rx) = mpsc::channel();
    let busy = Arc::new(AtomicBool::new(true));
    let reader = input_reader::Reader::open().map_err(TuiError::Terminal)?;
    let input_gone = Arc::new(AtomicBool::new(false));
    input_reader::spawn(reader, tx.clone(), busy.clone(), input_gone.clone(), TICK)
        .map_err(|e| TuiError::Thread("input", e))?;
    let on_hangup = tx.clone();
    // Without the watch the explorer runs as before (a dead terminal ends it at the next draw).
    let gone = hangup::watch(move || drop(on_hangup.send(Msg::Hangup))).ok();
    let worker = Worker::start(move |d| {
        let _ = tx.send(Msg::Work(d));
    });
    if opts.tour.is_some() {
        for r in app.start_tour() {
            worker.submit(r);
        }
    }
    let ended = event_loop(&mut term, &mut app, &worker, &rx, &busy);
    // The guard restores the cursor; ratatui's own drop would print (and, with stderr on the
    // same dead terminal, panic) when it cannot show it.
    std::mem::forget(term);
    if input_gone.load(Ordering::SeqCst) || gone.is_some_and(|g| g.load(Ordering::SeqCst)) {
        return Err(TuiError::TerminalGone);
    }
    ended.map_err(TuiError::Draw)
}

/// Draw, block for a message, handle it and everything else already queued, repeat.
pub fn event_loop<B: Backend>(
    term: &mut Terminal<B>,
    app: &mut App,
    worker: &Worker,
    rx: &Receiver<Msg>,
    busy: &AtomicBool,
) -> Result<(), B::Error> {
    for r in app.initial_requests() {
        worker.submit(r);
    }
    let frame = Duration::from_secs_f64(anim::FRAME_S);
    let mut last_frame = Instant::now();
    loop {
        draw(term, app)?;
        busy.store(app.busy(), Ordering::Relaxed);
        // While the animation plays, a frame every 1/30 s (the time that went by since the
        // last one); paused or closed, nothing is drawn until a message comes.
        let first = if app.anim_playing() {
            let wait = frame.saturating_sub(last_frame.elapsed());
            match rx.recv_timeout(wait) {
                Ok(m) => m,
                Err(mpsc::RecvTimeoutError::Timeout) => {
                    let real = last_frame.elapsed().as_secs_f64();
                    last_frame = Instant::now();
                    Msg::Frame(real)
                }
                Err(mpsc::RecvTimeoutError::Disconnected) => return Ok(()),
            }
        } else {
            let Ok(m) = rx.recv() else { return Ok(()) };
            last_frame = Instant::now();
            m
        };
        let mut next = Some(first);
        while let Some(msg) = next {
            for r in app.update(msg) {
                worker.submit(r);
            }
            if app.quit {
                return Ok(());
            }
            next = rx.try_recv().ok();
        }
    }
}

/// Draws one frame and remembers where the chart is (for clicks) and whether it is shown.
pub fn draw<B: Backend>(term: &mut Terminal<B>, app: &mut App) -> Result<(), B::Error> {
    let mut drawn = ui::Drawn::default();
    term.draw(|f| drawn = ui::draw(f, app))?;
    app.drawn = drawn;
    Ok(())
}

/// Computes every result `app` asks for on the calling thread, until nothing is left to do.
/// Deterministic: used by the snapshot tests and benchmarks.
pub fn compute_sync(app: &mut App, requests: Vec<Request>) {
    let mut queue: std::collections::VecDeque<Request> = requests.into();
    while let Some(req) = queue.pop_front() {
        let done = std::sync::Mutex::new(Vec::new());
        worker::run_sync(&req, &|d| done.lock().unwrap_or_else(std::sync::PoisonError::into_inner).push(d));
        for d in done.into_inner().unwrap_or_else(std::sync::PoisonError::into_inner) {
            queue.extend(app.update(Msg::Work(d)));
        }
    }
}
