//! Samples per second of every catalogue model's batch value and
//! value-plus-derivatives, on the same 10,000 fixed direction pairs and at
//! each model's default parameters.

use std::hint::black_box;

use brdf_models::{ModelConfig, catalogue};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};

fn models(c: &mut Criterion) {
    let pairs = brdf_benches::fixed_pairs(10_000);
    let n = pairs.len();
    let config = ModelConfig::default();
    let mut g = c.benchmark_group("models");
    g.throughput(Throughput::Elements(n as u64));
    for entry in catalogue() {
        let Ok(model) = (entry.build)(&config) else {
            continue;
        };
        let p = model.params().to_vec();
        let nc = model.channels();
        let np = model.n_params();
        let mut out = vec![0.0; nc * n];
        let mut jac = vec![0.0; nc * n * np];
        g.bench_function(format!("{}/value", entry.name), |b| {
            b.iter(|| {
                model.eval_batch_at(black_box(&p), &pairs, &mut out);
                black_box(out[0])
            })
        });
        g.bench_function(format!("{}/value+jacobian", entry.name), |b| {
            b.iter(|| {
                model.eval_grad_batch_at(black_box(&p), &pairs, &mut out, &mut jac);
                black_box(jac[0])
            })
        });
    }
    g.finish();
}

criterion_group!(benches, models);
criterion_main!(benches);
