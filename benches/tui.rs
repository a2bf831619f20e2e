#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test or benchmark fails
//! Benchmarks of the explorer: one full frame at 200×60, a mass change until the readout and
//! waveform are updated (through the real worker threads), and the default chart filling; and
//! the same two as the user sees them at 200×60: a mass step until its frame is redrawn, and
//! the chart filling with a frame drawn after every batch of results, as the event loop does.

use std::sync::mpsc::{self, Receiver};
use std::time::{Duration, Instant};

use criterion::{criterion_group, criterion_main, Criterion};
use ratatui::backend::TestBackend;
use ratatui::Terminal;
use thud::design::Design;
use thud::tui::app::{App, Msg};
use thud::tui::compute::{Grid, Grids};
use thud::tui::{compute_sync, draw, Palette, Worker};

fn computed(grids: Grids) -> App {
    let mut app = App::with_grids(Design::default(), "default", Palette::default(), grids);
    let reqs = app.initial_requests();
    compute_sync(&mut app, reqs);
    app
}

/// Feeds worker results to the app until `done` holds.
fn pump(app: &mut App, worker: &Worker, rx: &Receiver<Msg>, done: impl Fn(&App) -> bool) {
    while !done(app) {
        let msg = rx.recv_timeout(Duration::from_secs(30)).expect("worker answers");
        for r in app.update(msg) {
            worker.submit(r);
        }
    }
}

fn frame(c: &mut Criterion) {
    let mut app = computed(Grids::default());
    let mut term = Terminal::new(TestBackend::new(200, 60)).unwrap();
    c.bench_function("tui frame 200x60 (full redraw, TestBackend)", |b| {
        b.iter(|| {
            term.clear().unwrap();
            draw(&mut term, &mut app).unwrap();
        });
    });
}

fn mass_change(c: &mut Criterion) {
    let (tx, rx) = mpsc::channel();
    let worker = Worker::start(move |d| {
        let _ = tx.send(Msg::Work(d));
    });
    let mut app = App::with_grids(
        Design::default(),
        "default",
        Palette::default(),
        Grids { coarse: None, fine: Grid::standard(2, 2) },
    );
    for r in app.initial_requests() {
        worker.submit(r);
    }
    pump(&mut app, &worker, &rx, |a| !a.busy());
    let mut step = 0u32;
    c.bench_function("tui mass change -> readout + waveform (worker, uncached)", |b| {
        b.iter(|| {
            // A new mass every time so the worker's cache cannot answer.
            step += 1;
            let m = 0.0405 + 1e-6 * f64::from(step);
            let gap = app.design.damper.gap_m;
            for r in app.select_design(m, gap) {
                worker.submit(r);
            }
            pump(&mut app, &worker, &rx, |a| !a.design_busy());
        });
    });
}

fn chart_fill(c: &mut Criterion) {
    let mut g = c.benchmark_group("tui chart fill (worker, uncached)");
    g.sample_size(10).measurement_time(Duration::from_secs(20));
    let (tx, rx) = mpsc::channel();
    let worker = Worker::start(move |d| {
        let _ = tx.send(Msg::Work(d));
    });
    let mut step = 0u32;
    // The explorer's robust chart: N = 16 runs a cell over the same grids.
    let cases = [
        ("coarse 6x5", Grids { coarse: None, fine: Grid::standard(6, 5) }, 1),
        ("default: 6x5 then 16x12", Grids::default(), 1),
        ("default: 6x5 then 16x12, N = 16 runs a cell", Grids::default(), 16),
    ];
    for (name, grids, runs) in cases {
        g.bench_function(name, |b| {
            b.iter_custom(|iters| {
                let mut total = Duration::ZERO;
                for _ in 0..iters {
                    step += 1;
                    let mut d = Design::default();
                    d.damper.v0_m_s += 1e-9 * f64::from(step);
                    let mut app = App::with_grids(d, "default", Palette::default(), grids.clone());
                    if runs > 1 {
                        // N set as a user sets it (the field), not by poking the state.
                        app.selected = thud::tui::fields::Knob::ALL
                            .iter()
                            .position(|k| *k == thud::tui::fields::Knob::RUNS)
                            .unwrap();
                        drop(app.submit_text(&runs.to_string()));
                    }
                    let t0 = Instant::now();
                    for r in app.initial_requests() {
                        worker.submit(r);
                    }
                    pump(&mut app, &worker, &rx, |a| !a.chart_busy());
                    total += t0.elapsed();
                }
                total
            });
        });
    }
    g.finish();
}

/// Feeds worker results to the app, drawing a 200×60 frame after each batch (as the event loop
/// does), until `done` holds.
fn pump_drawing(
    app: &mut App,
    term: &mut Terminal<TestBackend>,
    worker: &Worker,
    rx: &Receiver<Msg>,
    done: impl Fn(&App) -> bool,
) {
    while !done(app) {
        let first = rx.recv_timeout(Duration::from_secs(30)).expect("worker answers");
        let mut next = Some(first);
        while let Some(msg) = next {
            for r in app.update(msg) {
                worker.submit(r);
            }
            next = rx.try_recv().ok();
        }
        draw(term, app).unwrap();
    }
}

fn at_200x60(c: &mut Criterion) {
    let mut g = c.benchmark_group("tui at 200x60 (worker, uncached, frames drawn)");
    g.sample_size(10).measurement_time(Duration::from_secs(20));
    let (tx, rx) = mpsc::channel();
    let worker = Worker::start(move |d| {
        let _ = tx.send(Msg::Work(d));
    });
    let mut term = Terminal::new(TestBackend::new(200, 60)).unwrap();
    let mut app = App::new(Design::default(), "default", Palette::default());
    for r in app.initial_requests() {
        worker.submit(r);
    }
    pump_drawing(&mut app, &mut term, &worker, &rx, |a| !a.busy());
    let mut step = 0u32;
    g.bench_function("mass step -> readout, pulse, polar, history redrawn", |b| {
        b.iter(|| {
            step += 1;
            let m = 0.0405 + 1e-6 * f64::from(step);
            let gap = app.design.damper.gap_m;
            for r in app.select_design(m, gap) {
                worker.submit(r);
            }
            draw(&mut term, &mut app).unwrap();
            pump_drawing(&mut app, &mut term, &worker, &rx, |a| !a.design_busy());
        });
    });
    g.bench_function("chart fill: 6x5 then 16x12, drawn as it fills", |b| {
        b.iter_custom(|iters| {
            let mut total = Duration::ZERO;
            for _ in 0..iters {
                step += 1;
                let mut d = Design::default();
                d.damper.v0_m_s += 1e-9 * f64::from(step);
                let mut app = App::new(d, "default", Palette::default());
                let t0 = Instant::now();
                for r in app.initial_requests() {
                    worker.submit(r);
                }
                draw(&mut term, &mut app).unwrap();
                pump_drawing(&mut app, &mut term, &worker, &rx, |a| !a.chart_busy());
                total += t0.elapsed();
            }
            total
        });
    });
    g.finish();
}

/// A writer that counts the bytes sent through it.
struct Count(std::sync::Arc<std::sync::atomic::AtomicUsize>);

impl std::io::Write for Count {
    fn write(&mut self, b: &[u8]) -> std::io::Result<usize> {
        self.0.fetch_add(b.len(), std::sync::atomic::Ordering::Relaxed);
        Ok(b.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// The animation: one frame at 200×60 (a frame of time on, then the redraw ratatui diffs), and
/// the bytes one second of playback (30 frames) sends at 80×24 through the real backend, at the
/// slowest speed and at 1× (printed: criterion measures time).
fn animation(c: &mut Criterion) {
    use ratatui::backend::CrosstermBackend;
    use ratatui::layout::Rect;
    use ratatui::{TerminalOptions, Viewport};
    use std::sync::atomic::{AtomicUsize, Ordering};
    use thud::tui::anim::{Anim, FRAME_S, SPEEDS};
    let small = Grids { coarse: None, fine: Grid::standard(4, 4) };
    for speed in [0, SPEEDS.len() - 1] {
        let mut app = computed(small.clone());
        app.anim = Some(Anim { speed, ..Anim::default() });
        let sent = std::sync::Arc::new(AtomicUsize::new(0));
        let opts = TerminalOptions { viewport: Viewport::Fixed(Rect::new(0, 0, 80, 24)) };
        let mut term = Terminal::with_options(CrosstermBackend::new(Count(sent.clone())), opts).unwrap();
        draw(&mut term, &mut app).unwrap();
        let first = sent.load(Ordering::Relaxed);
        for _ in 0..30 {
            app.update(Msg::Frame(FRAME_S));
            draw(&mut term, &mut app).unwrap();
        }
        let bytes = sent.load(Ordering::Relaxed) - first;
        println!("animation at 80x24, speed {}x: {bytes} bytes per second of playback", SPEEDS[speed]);
    }
    let mut app = computed(small);
    app.anim = Some(Anim::default());
    let mut term = Terminal::new(TestBackend::new(200, 60)).unwrap();
    let mut worst = Duration::ZERO;
    c.bench_function("tui animation frame 200x60 (a frame on, redraw)", |b| {
        b.iter(|| {
            let t = Instant::now();
            app.update(Msg::Frame(FRAME_S));
            if app.anim.as_ref().is_some_and(|a| !a.playing) {
                app.anim = Some(Anim::default());
            }
            draw(&mut term, &mut app).unwrap();
            worst = worst.max(t.elapsed());
        });
    });
    println!("animation frame at 200x60: slowest {worst:?} (budget 33 ms)");
}

criterion_group!(benches, frame, mass_change, chart_fill, at_200x60, animation);
criterion_main!(benches);
