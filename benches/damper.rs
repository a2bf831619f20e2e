#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test or benchmark fails
//! Benchmarks of the impact-damper solvers (paper Fig 9 design, Table 2 values).

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use thud::damper::{simulate, DamperParams, RunOptions, Solver};

fn event_fig9(c: &mut Criterion) {
    let p = DamperParams::table2();
    c.bench_function("event fig9 2 s", |b| {
        b.iter(|| simulate(black_box(&p), Solver::Event, &RunOptions::default()).unwrap());
    });
}

fn newmark_fig9(c: &mut Criterion) {
    let p = DamperParams::table2();
    let mut g = c.benchmark_group("newmark");
    g.sample_size(10);
    g.bench_function("newmark fig9 2 s dt 1e-7", |b| {
        b.iter(|| simulate(black_box(&p), Solver::Newmark { dt_s: 1e-7 }, &RunOptions::default()).unwrap());
    });
    g.finish();
}

/// The 20×20 design sweep (m 30–100 g, d 2–5 cm, 2 s each, Table 2 values), serially.
fn event_sweep(c: &mut Criterion) {
    let base = DamperParams::table2();
    let mut g = c.benchmark_group("sweep");
    g.sample_size(10);
    g.bench_function("event sweep 20x20", |b| {
        b.iter(|| {
            let mut n = 0;
            for i in 0..20 {
                for j in 0..20 {
                    let p = DamperParams {
                        impact_mass_kg: 0.03 + 0.07 * f64::from(i) / 19.0,
                        gap_m: 0.02 + 0.03 * f64::from(j) / 19.0,
                        ..base
                    };
                    n += simulate(&p, Solver::Event, &RunOptions::default()).unwrap().impacts.len();
                }
            }
            n
        });
    });
    g.finish();
}

/// The same 20×20 chart as the app computes it: `design::sweep` on every core, with e, e_fit,
/// U0max, SPLmax and zone per cell.
fn design_sweep(c: &mut Criterion) {
    let base = thud::design::Design::default().check().unwrap();
    let masses = thud::design::linspace(0.03, 0.1, 20);
    let gaps = thud::design::linspace(0.02, 0.05, 20);
    let mut g = c.benchmark_group("sweep");
    g.sample_size(10);
    g.bench_function("design sweep 20x20 all cores with metrics", |b| {
        b.iter(|| thud::design::sweep(&base, &masses, &gaps, None, &|_, _| {}).unwrap());
    });
    g.finish();
}

criterion_group!(benches, event_fig9, newmark_fig9, event_sweep, design_sweep);
criterion_main!(benches);
