//! Samples per second of every catalogue model's batch value and
//! value-plus-derivatives, on the same 10,000 fixed direction pairs and at
//! each model's default parameters (`models/...`, the general per-pair
//! evaluation); and of the fitting kernels (`kernels/...`): the
//! channel-shared basis of every model that has one, over geometry
//! precomputed once per sample set (`PairGeometry`), as the solvers call it
//! at every iteration, value only and with the basis derivatives.

use std::hint::black_box;

use brdf_core::PairGeometry;
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

fn kernels(c: &mut Criterion) {
    let pairs = brdf_benches::fixed_pairs(10_000);
    let geom = PairGeometry::new(&pairs);
    let n = pairs.len();
    let config = ModelConfig::default();
    let mut g = c.benchmark_group("kernels");
    g.throughput(Throughput::Elements(n as u64));
    for entry in catalogue() {
        let Ok(model) = (entry.build)(&config) else {
            continue;
        };
        let Some(basis) = model.shared_basis() else {
            continue;
        };
        let p = model.params().to_vec();
        let nq = model.param_specs().iter().filter(|s| !s.linear).count();
        let l = basis.basis_len();
        let mut phi = vec![0.0; l * n];
        let mut dphi = vec![0.0; l * nq * n];
        g.bench_function(format!("{}/value", entry.name), |b| {
            b.iter(|| {
                basis.basis_batch(black_box(&p), &pairs, &geom, &mut phi, None);
                black_box(phi[0])
            })
        });
        g.bench_function(format!("{}/value+derivatives", entry.name), |b| {
            b.iter(|| {
                basis.basis_batch(black_box(&p), &pairs, &geom, &mut phi, Some(&mut dphi));
                black_box(dphi[0])
            })
        });
    }
    g.finish();
}

/// The renderer models' batch kernels: value, and value and
/// Jacobian, RGB, at a non-trivial parameter vector (every lobe on), as
/// the solvers call them every pass (`renderer_kernels/<model>/<path>`).
fn renderer_kernels(c: &mut Criterion) {
    let pairs = brdf_benches::fixed_pairs(10_000);
    let n = pairs.len();
    let config = ModelConfig {
        channels: 3,
        ..ModelConfig::default()
    };
    let mut g = c.benchmark_group("renderer_kernels");
    g.throughput(Throughput::Elements(n as u64));
    for name in ["principled", "gltf"] {
        let Ok(model) = brdf_models::catalogue::build(name, &config) else {
            continue;
        };
        // Defaults moved inside the box so no lobe is off.
        let p: Vec<f64> = model
            .param_specs()
            .iter()
            .map(|s| {
                let (lo, hi) = (s.lower.max(-1.0), s.upper.min(2.0));
                lo + 0.37 * (hi - lo)
            })
            .collect();
        let np = p.len();
        let mut out = vec![0.0; 3 * n];
        let mut jac = vec![0.0; 3 * n * np];
        g.bench_function(format!("{name}/value"), |b| {
            b.iter(|| {
                model.eval_batch_at(black_box(&p), &pairs, &mut out);
                black_box(out[0])
            })
        });
        g.bench_function(format!("{name}/value+derivatives"), |b| {
            b.iter(|| {
                model.eval_grad_batch_at(black_box(&p), &pairs, &mut out, &mut jac);
                black_box(jac[0])
            })
        });
    }
    g.finish();
}

criterion_group!(benches, models, kernels, renderer_kernels);
criterion_main!(benches);
