//! Solver speed on fixed problems and fixed tolerances (the defaults):
//! Levenberg-Marquardt on a sum of exponentials (Lanczos' data), variable
//! projection + the bounded solver fitting Ward to 2,000 synthetic samples,
//! the same fit without projection, and dense least squares / NNLS on a
//! 10,000 x 15 design.

use std::hint::black_box;

use brdf_models::{ModelConfig, build};
use brdf_solve::{
    Constraints, LeastSquaresProblem, LmOptions, LstsqMethod, ModelProblem, VarPro,
    bounded_least_squares, levenberg_marquardt, lstsq, nnls,
};
use criterion::{Criterion, criterion_group, criterion_main};
use faer::Mat;

struct Exps {
    x: Vec<f64>,
    y: Vec<f64>,
}

impl LeastSquaresProblem for Exps {
    fn n_params(&self) -> usize {
        6
    }
    fn n_residuals(&self) -> usize {
        self.x.len()
    }
    fn residuals(&self, p: &[f64], out: &mut [f64]) {
        for (i, x) in self.x.iter().enumerate() {
            out[i] = (0..3)
                .map(|k| p[2 * k] * (-p[2 * k + 1] * x).exp())
                .sum::<f64>()
                - self.y[i];
        }
    }
    fn jacobian(&self, p: &[f64], jac: &mut [f64]) {
        for (i, x) in self.x.iter().enumerate() {
            for k in 0..3 {
                let e = (-p[2 * k + 1] * x).exp();
                jac[i * 6 + 2 * k] = e;
                jac[i * 6 + 2 * k + 1] = -p[2 * k] * x * e;
            }
        }
    }
}

fn solvers(c: &mut Criterion) {
    let mut g = c.benchmark_group("solvers");
    let x: Vec<f64> = (0..24).map(|i| 0.05 * i as f64).collect();
    let y = x
        .iter()
        .map(|x| 0.0951 * (-x).exp() + 0.8607 * (-3.0 * x).exp() + 1.5576 * (-5.0 * x).exp())
        .collect();
    let exps = Exps { x, y };
    let opts = LmOptions::default();
    g.bench_function("lm/lanczos-start2", |b| {
        b.iter(|| levenberg_marquardt(&exps, black_box(&[0.5, 0.7, 3.6, 4.2, 4.0, 6.3]), &opts))
    });

    let mut ward = build("ward", &ModelConfig::default()).unwrap();
    ward.set_params(&[0.2, 0.4, 0.12]).unwrap();
    let pairs = brdf_benches::fixed_pairs(2000);
    let mut values = vec![0.0; pairs.len()];
    ward.eval_batch_at(&[0.2, 0.4, 0.12], &pairs, &mut values);
    let scale: Vec<f64> = (0..pairs.len()).map(|j| pairs.lz[j]).collect();
    let mp = ModelProblem::new(ward.as_ref(), &pairs, &values, &scale).unwrap();
    let nl = Constraints::boxed(vec![1e-6], vec![0.5]).unwrap();
    g.bench_function("varpro+bounded/ward-2000", |b| {
        b.iter(|| {
            let vp = VarPro::new(&mp, true);
            bounded_least_squares(&vp, black_box(&[0.3]), &nl, &opts)
        })
    });
    let full = Constraints::boxed(vec![0.0, 0.0, 1e-6], vec![1.0, 1.0, 0.5]).unwrap();
    g.bench_function("bounded-all-parameters/ward-2000", |b| {
        b.iter(|| bounded_least_squares(&mp, black_box(&[0.3, 0.2, 0.3]), &full, &opts))
    });

    let (m, n) = (10_000, 15);
    let a = Mat::from_fn(m, n, |i, j| {
        ((i * 31 + j * 17) % 97) as f64 / 97.0 + if i % n == j { 1.0 } else { 0.0 }
    });
    let bv: Vec<f64> = (0..m).map(|i| ((i * 13) % 29) as f64 / 29.0).collect();
    let bm = Mat::from_fn(m, 1, |i, _| bv[i]);
    g.bench_function("lstsq-pivoted-qr/10000x15", |b| {
        b.iter(|| lstsq(a.as_ref(), bm.as_ref(), None, LstsqMethod::PivotedQr))
    });
    g.bench_function("nnls/10000x15", |b| b.iter(|| nnls(a.as_ref(), &bv, 100)));
    g.finish();
}

criterion_group!(benches, solvers);
criterion_main!(benches);
