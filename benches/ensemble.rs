#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test or benchmark fails
//! The robust design chart: 20 × 20 cells × 16 ensemble runs = 6 400 runs of
//! 2 s by the event-driven solver, against ONE design by the paper's Newmark-β at dt 1e-7 s
//! (the Fig 9 design, 2 s), measured side by side in one bench run. Target: the chart under 3×
//! the Newmark design, then under 1.5× (measured 1.29–1.33×, docs/model.md
//! §11). Both include the metrics (e, e_fit, U0max, SPLmax, zone).

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use thud::damper::Solver;
use thud::design::{self, linspace, Design};
use thud::ensemble;

fn robust_chart_vs_newmark(c: &mut Criterion) {
    let newmark = Design { solver: Solver::Newmark { dt_s: 1e-7 }, ..Design::paper_fig9() }.check().unwrap();
    let base = Design::paper_fig9().check().unwrap();
    let masses = linspace(0.03, 0.1, 20);
    let gaps = linspace(0.02, 0.05, 20);
    let mut g = c.benchmark_group("robust chart vs newmark");
    g.sample_size(10);
    g.bench_function("newmark fig9 2 s dt 1e-7 (one design)", |b| {
        b.iter(|| design::evaluate(black_box(&newmark), 0, None).unwrap());
    });
    g.bench_function("robust chart 20x20 x 16 runs all cores", |b| {
        b.iter(|| ensemble::sweep(black_box(&base), &masses, &gaps, 16, None, &|_, _| {}).unwrap());
    });
    g.bench_function("plain chart 20x20 all cores", |b| {
        b.iter(|| design::sweep(black_box(&base), &masses, &gaps, None, &|_, _| {}).unwrap());
    });
    g.finish();
}

criterion_group!(benches, robust_chart_vs_newmark);
criterion_main!(benches);
