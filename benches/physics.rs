#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test or benchmark fails
//! Benchmarks of the acoustics: one `pulse` evaluation (a ~2,000-point waveform plus all levels).

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use thud::acoustics::{Field, Observer, Radiation, Source};
use thud::contact::{Impact, Target};

fn pulse(c: &mut Criterion) {
    let impact = Impact { mass_kg: 0.0405, u0_m_s: 1.4, k_hz: 5.6e8, target: Target::FixedPlate };
    for source in [Source::Dipole, Source::Quadrupole] {
        let rad = Radiation { source, ..Default::default() };
        c.bench_function(&format!("pulse {} (2000-point waveform + levels)", source.name()), |b| {
            b.iter(|| {
                let contact = black_box(impact).contact();
                let field = Field::new(0.01905, &contact, &Observer::new(0.7, 45.0), &rad).unwrap();
                let w = field.waveform(2000);
                let l = field.levels();
                black_box((w, l))
            });
        });
        c.bench_function(&format!("spl {} (rms over tau only)", source.name()), |b| {
            b.iter(|| {
                let contact = black_box(impact).contact();
                let field = Field::new(0.01905, &contact, &Observer::new(0.7, 45.0), &rad).unwrap();
                black_box(field.spl_db())
            });
        });
    }
}

criterion_group!(benches, pulse);
criterion_main!(benches);
