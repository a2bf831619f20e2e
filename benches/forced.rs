#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test or benchmark fails
//! Benchmarks of forced vibration beside the Newmark reference design, measured in
//! the same run so that every figure can be given as a ratio to it:
//!
//! - the reference: Newmark-β at dt 1e-7 s on the Fig 9 design, 2 s (the paper's method);
//! - the event solver on the same design: the cost per impact (38 impacts a run);
//! - a forced run (5.5 Hz, F0 2 N, d 1 cm, 8 s): the cost per impact with forcing;
//! - the frequency response: 101 frequencies from rest, 40 forcing periods each (F0 3 N,
//!   d 2 cm, about 3 impacts a period), on every core; and the settled response `thud response`
//!   computes by default (F0 1 N, Table 2);
//! - periodic orbits: forced-rattle's orbit at 3.4 Hz found from the design's start (`thud
//!   orbit`), and its family continued over 3–8 Hz from 26 seed values (`thud continue --vary
//!   f=3Hz:8Hz:26`), on every core.
//!
//! With `--features timing` it also prints where the event solver's time goes on the Fig 9
//! design (contact search, flight recording, contacts).

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use thud::damper::{simulate, DamperParams, RunOptions, Solver};
use thud::design::{linspace, Design};
use thud::response::{response, ResponseOptions};

fn reference(c: &mut Criterion) {
    let p = DamperParams::table2();
    let mut g = c.benchmark_group("reference");
    g.sample_size(10);
    g.bench_function("newmark fig9 2 s dt 1e-7", |b| {
        b.iter(|| simulate(black_box(&p), Solver::newmark_default(), &RunOptions::default()).unwrap());
    });
    g.finish();
}

fn per_impact(c: &mut Criterion) {
    let fig9 = DamperParams::table2();
    let forced = DamperParams {
        force_n: 2.0,
        freq_hz: 5.5,
        gap_m: 0.01,
        v0_m_s: 0.0,
        duration_s: 8.0,
        ..DamperParams::table2()
    };
    for (name, p) in [("fig9", fig9), ("forced", forced)] {
        let n = simulate(&p, Solver::Event, &RunOptions::default()).unwrap().impacts.len();
        eprintln!("{name}: {n} impacts a run");
    }
    c.bench_function("event fig9 2 s", |b| {
        b.iter(|| simulate(black_box(&fig9), Solver::Event, &RunOptions::default()).unwrap());
    });
    c.bench_function("event forced 5.5 Hz 8 s", |b| {
        b.iter(|| simulate(black_box(&forced), Solver::Event, &RunOptions::default()).unwrap());
    });
    #[cfg(feature = "timing")]
    {
        use thud::damper::timing;
        let runs = 2000;
        timing::take();
        for _ in 0..runs {
            simulate(&fig9, Solver::Event, &RunOptions::default()).unwrap();
        }
        let b = timing::take();
        let total = (b.search_ns + b.flight_record_ns + b.contact_ns) as f64;
        let per = |ns: u64| ns as f64 / b.contacts as f64 / 1e3;
        eprintln!(
            "fig9 breakdown over {runs} runs ({} contacts, {} flights): search {:.2} µs/impact ({:.1} %), \
             flight recording {:.2} µs ({:.1} %), contacts {:.2} µs ({:.1} %)",
            b.contacts,
            b.flights,
            per(b.search_ns),
            100.0 * b.search_ns as f64 / total,
            per(b.flight_record_ns),
            100.0 * b.flight_record_ns as f64 / total,
            per(b.contact_ns),
            100.0 * b.contact_ns as f64 / total,
        );
    }
}

fn responses(c: &mut Criterion) {
    let mut d = Design::default();
    d.damper.force_n = 3.0;
    d.damper.gap_m = 0.02;
    d.damper.v0_m_s = 0.0;
    d.damper.duration_s = 0.1;
    d.damper.steady_periods = 20;
    let freqs = linspace(3.0, 8.0, 101);
    // Checked at the first frequency, as `thud response` builds it; each point sets its own.
    d.damper.freq_hz = freqs[0];
    let d = d.check().unwrap();
    let fixed = ResponseOptions { continuation: false, settle: false };
    let r = response(&d, &freqs, &fixed, None, &|| {}).unwrap();
    let ipp: f64 = r.sweeps[0].points.iter().map(|p| p.steady.impacts_per_period).sum::<f64>() / freqs.len() as f64;
    eprintln!("response 101 × 40 periods: {ipp:.2} impacts a period on average (last 20 periods)");
    let mut g = c.benchmark_group("response");
    g.sample_size(10);
    g.bench_function("response 101 points 40 periods all cores", |b| {
        b.iter(|| response(black_box(&d), &freqs, &fixed, None, &|| {}).unwrap());
    });
    let mut cli = Design::default();
    cli.damper.force_n = 1.0;
    cli.damper.v0_m_s = 0.0;
    cli.damper.freq_hz = freqs[0];
    let cli = cli.check().unwrap();
    g.bench_function("response 101 points settled (thud response --force-amplitude 1N)", |b| {
        b.iter(|| response(black_box(&cli), &freqs, &ResponseOptions::default(), None, &|| {}).unwrap());
    });
    g.finish();
}

fn orbits(c: &mut Criterion) {
    use thud::continuation::continue_family;
    use thud::orbit::{find_damper, Request};
    use thud::params::Spelling;
    use thud::study::Vary;
    let mut d = thud::presets::preset("forced-rattle").unwrap();
    d.damper.freq_hz = 3.4;
    let at = d.damper;
    d.damper.freq_hz = 3.0;
    let d = d.check().unwrap();
    let vary = Vary::of_values("freq", &[3.0, 8.0], Spelling::Flag).unwrap();
    let family = continue_family(&d, &vary, 26, None, &|_| {}).unwrap();
    let points: usize = family.iter().map(|b| b.points.len()).sum();
    eprintln!("forced-rattle family over 3–8 Hz: {} branches, {points} points", family.len());
    let mut g = c.benchmark_group("orbits");
    g.sample_size(10);
    g.bench_function("orbit forced-rattle 3.4 Hz from the start", |b| {
        b.iter(|| find_damper(black_box(&at), &Request::default(), None).unwrap());
    });
    g.bench_function("continue forced-rattle 3-8 Hz 26 seeds all cores", |b| {
        b.iter(|| continue_family(black_box(&d), &vary, 26, None, &|_| {}).unwrap());
    });
    g.finish();
}

criterion_group!(benches, reference, per_impact, responses, orbits);
criterion_main!(benches);
