#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test or benchmark fails
//! The event solver's contact schemes on the Fig 9 design (2 s, 38 impacts) in the same run,
//! beside the Newmark reference design: the reference Dormand–Prince 5(4) in t, the
//! experimental Sundman–Taylor scheme, the Sundman–DOP853 scheme and the Sundman–Adams scheme,
//! the default (docs/model.md §11). Divide by the
//! impacts a run (printed) for the cost per impact.

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use thud::damper::{simulate, simulate_with, ContactScheme, DamperParams, RunOptions, Solver};

fn schemes(c: &mut Criterion) {
    let p = DamperParams::table2();
    let n = simulate(&p, Solver::Event, &RunOptions::default()).unwrap().impacts.len();
    eprintln!("fig9: {n} impacts a run");
    let mut g = c.benchmark_group("contact scheme");
    for scheme in [
        ContactScheme::DormandPrince,
        ContactScheme::SundmanTaylor,
        ContactScheme::SundmanDop853,
        ContactScheme::SundmanAdams,
    ] {
        g.bench_function(format!("event fig9 2 s {scheme:?}"), |b| {
            b.iter(|| simulate_with(black_box(&p), Solver::Event, &RunOptions::default(), scheme).unwrap());
        });
    }
    g.sample_size(10);
    g.bench_function("newmark fig9 2 s dt 1e-7", |b| {
        b.iter(|| simulate(black_box(&p), Solver::newmark_default(), &RunOptions::default()).unwrap());
    });
    g.finish();
}

criterion_group!(benches, schemes);
criterion_main!(benches);
