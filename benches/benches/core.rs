//! Core geometry throughput: half/difference conversions per second.

use std::hint::black_box;

use brdf_core::HalfDiff;
use criterion::{Criterion, Throughput, criterion_group, criterion_main};

fn half_diff(c: &mut Criterion) {
    let pairs = brdf_benches::fixed_pairs(10_000);
    let mut g = c.benchmark_group("half_diff");
    g.throughput(Throughput::Elements(pairs.len() as u64));
    g.bench_function("from_directions", |b| {
        b.iter(|| {
            let mut s = 0.0;
            for j in 0..pairs.len() {
                if let Some(h) = HalfDiff::from_directions(&pairs.l(j), &pairs.v(j)) {
                    s += h.theta_d;
                }
            }
            black_box(s)
        })
    });
    g.finish();
}

criterion_group!(benches, half_diff);
criterion_main!(benches);
