//! Samples per second of the renderer models' fitting kernels:
//! `principled` and `gltf` with three channels, value only and value +
//! derivatives over 10,000 fixed direction pairs, through the batch
//! kernels the fits call (`renderer/<model>/value`,
//! `.../value+derivatives`) and through the single-point dual-number
//! formula they replace (`.../duals-per-pair`, value + derivatives), at a
//! parameter point where every lobe is active (sheen, clear coat,
//! anisotropy non-zero), so no branch is skipped.

use std::hint::black_box;

use brdf_core::Parametric;
use brdf_models::{GltfPbr, Principled};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};

fn bench_model(c: &mut Criterion, name: &str, model: &dyn Parametric) {
    let pairs = brdf_benches::fixed_pairs(10_000);
    let n = pairs.len();
    let (nc, np) = (model.channels(), model.n_params());
    let p = model.params().to_vec();
    let mut out = vec![0.0; nc * n];
    let mut jac = vec![0.0; nc * n * np];
    let mut g = c.benchmark_group(format!("renderer/{name}"));
    g.throughput(Throughput::Elements(n as u64));
    g.bench_function("value", |b| {
        b.iter(|| {
            model.eval_batch_at(black_box(&p), &pairs, &mut out);
            black_box(out[0])
        })
    });
    g.bench_function("value+derivatives", |b| {
        b.iter(|| {
            model.eval_grad_batch_at(black_box(&p), &pairs, &mut out, &mut jac);
            black_box(jac[0])
        })
    });
    let (mut f, mut grad) = (vec![0.0; nc], vec![0.0; nc * np]);
    g.bench_function("duals-per-pair", |b| {
        b.iter(|| {
            for j in 0..n {
                model.eval_grad_at(black_box(&p), &pairs.l(j), &pairs.v(j), &mut f, &mut grad);
            }
            black_box(grad[0])
        })
    });
    g.finish();
}

fn renderer(c: &mut Criterion) {
    // base_color (rgb), metallic, specular, spec_tint, roughness,
    // anisotropic, sheen, sheen_tint, clearcoat, clearcoat_gloss
    let principled = [0.6, 0.4, 0.2, 0.3, 0.5, 0.4, 0.5, 0.2, 0.3, 0.5, 0.3, 0.6];
    match Principled::new(3, &principled) {
        Ok(m) => bench_model(c, "principled", &m),
        Err(e) => eprintln!("principled: {e}"),
    }
    // base_color (rgb), metallic, roughness
    match GltfPbr::new(3, &[0.6, 0.4, 0.2, 0.3, 0.4]) {
        Ok(m) => bench_model(c, "gltf", &m),
        Err(e) => eprintln!("gltf: {e}"),
    }
}

criterion_group!(benches, renderer);
criterion_main!(benches);
