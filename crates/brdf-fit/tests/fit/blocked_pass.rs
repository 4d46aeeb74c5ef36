//! The blocked pass of `ModelProblem` on large sample sets: its
//! residuals equal the model's own batch values, its normal equations equal
//! `J^T J` and `J^T r` formed from the stored Jacobian, it gives the same
//! bits for one and for two threads, and the bounded solver reaches the
//! same fit with it as without it.

use std::f64::consts::TAU;

use brdf_core::{DirPairs, Parametric};
use brdf_models::catalogue::{ModelConfig, build};
use brdf_solve::{
    Constraints, LeastSquaresProblem, LmOptions, ModelProblem, bounded_least_squares,
};
use nalgebra::Vector3;

/// Direction pairs on a deterministic quasi-random pattern, some of them
/// below the horizon (the kernels' invalid branch).
fn pairs(n: usize) -> DirPairs {
    let mut out = DirPairs::with_capacity(n);
    let dir = |a: f64, b: f64| {
        let th = a * 1.5;
        Vector3::new(th.sin() * b.cos(), th.sin() * b.sin(), th.cos())
    };
    for j in 0..n {
        let f = j as f64;
        let (a, b, c, d) = (
            (f * 0.618_033_988_75).fract(),
            (f * 0.414_213_562_37).fract(),
            (f * 0.732_050_807_57).fract(),
            (f * 0.236_067_977_5).fract(),
        );
        out.push(&dir(a, TAU * b), &dir(c, TAU * d));
    }
    out
}

/// A problem of `name` with `channels` channels over 10,000 samples whose
/// targets are the model at `truth` plus a fixed perturbation.
fn setup(
    name: &str,
    channels: usize,
    truth: &[f64],
) -> (Box<dyn Parametric>, DirPairs, Vec<f64>, Vec<f64>) {
    let cfg = ModelConfig {
        channels,
        ..ModelConfig::default()
    };
    let model = build(name, &cfg).expect("model");
    let pairs = pairs(10_000);
    let n = pairs.len();
    let mut values = vec![0.0; n * channels];
    model.eval_batch_at(truth, &pairs, &mut values);
    for (i, v) in values.iter_mut().enumerate() {
        *v *= 1.0 + 0.05 * ((i as f64) * 0.37).sin();
    }
    let scale: Vec<f64> = (0..n).map(|j| 0.5 + pairs.lz[j].abs()).collect();
    (model, pairs, values, scale)
}

/// `[J | r]^T [J | r]` from the stored Jacobian.
fn reference_gram(prob: &ModelProblem<'_>, p: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let (m, np) = (prob.n_residuals(), prob.n_params());
    let mut r = vec![0.0; m];
    let mut jac = vec![0.0; m * np];
    prob.residuals(p, &mut r);
    prob.jacobian(p, &mut jac);
    let w = np + 1;
    let mut g = vec![0.0; w * w];
    for i in 0..m {
        let row: Vec<f64> = jac[i * np..(i + 1) * np]
            .iter()
            .copied()
            .chain([r[i]])
            .collect();
        for a in 0..w {
            for b in 0..w {
                g[a * w + b] += row[a] * row[b];
            }
        }
    }
    (r, g)
}

fn check_gram(name: &str, channels: usize, truth: &[f64], at: &[f64]) {
    let (model, pairs, values, scale) = setup(name, channels, truth);
    let prob = ModelProblem::new(model.as_ref(), &pairs, &values, &scale).expect("problem");
    let (m, np) = (prob.n_residuals(), prob.n_params());
    let (r_ref, g_ref) = reference_gram(&prob, at);
    // Residuals: the model's own values, scaled, minus the scaled targets.
    let n = pairs.len();
    let mut vals = vec![0.0; m];
    model.eval_batch_at(at, &pairs, &mut vals);
    for i in 0..m {
        let want = vals[i] * scale[i % n] - values[i] * scale[i % n];
        assert!(
            (r_ref[i] - want).abs() <= 1e-12 * (1.0 + want.abs()),
            "{name} row {i}"
        );
    }
    let mut r = vec![0.0; m];
    let mut g = vec![0.0; (np + 1) * (np + 1)];
    assert!(
        prob.residuals_and_gram(at, &mut r, &mut g),
        "{name}: no blocked pass"
    );
    for i in 0..m {
        assert!(
            (r[i] - r_ref[i]).abs() <= 1e-13 * (1.0 + r_ref[i].abs()),
            "{name} residual {i}"
        );
    }
    for (k, (a, b)) in g.iter().zip(&g_ref).enumerate() {
        let tol = 1e-11
            * (g_ref[(k / (np + 1)) * (np + 2)].abs() * g_ref[(k % (np + 1)) * (np + 2)].abs())
                .sqrt();
        assert!((a - b).abs() <= tol + 1e-300, "{name} gram {k}: {a} vs {b}");
    }
    // The same bits for one and for two threads.
    let on = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("pool");
        pool.install(|| {
            let mut r = vec![0.0; m];
            let mut g = vec![0.0; (np + 1) * (np + 1)];
            prob.residuals_and_gram(at, &mut r, &mut g);
            (r, g)
        })
    };
    assert_eq!(on(1), on(2), "{name}: thread count changed the result");
}

#[test]
fn blocked_normal_equations_match_the_stored_jacobian() {
    // Ashikhmin-Shirley, RGB (a shared basis: per-channel blocks).
    check_gram(
        "ashikhmin-shirley",
        3,
        &[0.3, 0.4, 0.5, 0.2, 0.25, 0.3, 40.0, 0.1],
        &[0.35, 0.3, 0.45, 0.1, 0.3, 0.2, 25.0, 0.3],
    );
    // Oren-Nayar (no shared basis: the model's batch gradient).
    check_gram("oren-nayar", 1, &[0.6, 0.3], &[0.5, 0.4]);
}

/// The problem without its blocked pass: the solver stores the Jacobian.
struct Unfused<'a>(&'a ModelProblem<'a>);

impl LeastSquaresProblem for Unfused<'_> {
    fn n_params(&self) -> usize {
        self.0.n_params()
    }
    fn n_residuals(&self) -> usize {
        self.0.n_residuals()
    }
    fn residuals(&self, p: &[f64], out: &mut [f64]) {
        self.0.residuals(p, out)
    }
    fn jacobian(&self, p: &[f64], jac: &mut [f64]) {
        self.0.jacobian(p, jac)
    }
}

#[test]
fn bounded_fit_is_the_same_with_and_without_the_blocked_pass() {
    let truth = [0.3, 0.2, 40.0, 0.1];
    let (model, pairs, values, scale) = setup("ashikhmin-shirley", 1, &truth);
    let prob = ModelProblem::new(model.as_ref(), &pairs, &values, &scale).expect("problem");
    let lower = vec![0.0, 0.0, 0.0, 0.0];
    let upper = vec![1.0, 1.0, 1e6, 0.999];
    let c = Constraints::boxed(lower, upper).expect("box");
    let opts = LmOptions::default();
    let p0 = [0.5, 0.05, 100.0, 0.333];
    let fused = bounded_least_squares(&prob, &p0, &c, &opts).expect("fused");
    let plain = bounded_least_squares(&Unfused(&prob), &p0, &c, &opts).expect("plain");
    assert!(fused.termination.is_converged(), "{:?}", fused.termination);
    assert!((fused.ssr - plain.ssr).abs() <= 1e-12 * plain.ssr);
    for (a, b) in fused.params.iter().zip(&plain.params) {
        assert!((a - b).abs() <= 1e-8 * b.abs().max(1e-3), "{a} vs {b}");
    }
}

/// A row transform for the test: `ln(1 + m)` against the row's index.
struct LogRows;

impl brdf_solve::RowTransform for LogRows {
    fn apply(&self, row: usize, m: f64) -> (f64, f64) {
        let t = 0.01 * row as f64;
        ((1.0 + m.max(0.0)).ln() - t, 1.0 / (1.0 + m.max(0.0)))
    }
}

/// `residuals_and_jacobian` (one pass of the model's gradient, what the
/// image objective calls) gives the rows of `residuals` and `jacobian`:
/// plain and transformed rows, a model of its own batch gradient
/// (principled) and one of a shared basis (Ashikhmin-Shirley), small sets
/// and a blocked one.
#[test]
fn residuals_and_jacobian_equal_the_two_passes() {
    let cases: [(&str, usize, Vec<f64>, usize); 3] = [
        (
            "principled",
            3,
            vec![0.5, 0.3, 0.2, 0.4, 0.5, 0.2, 0.35, 0.1, 0.3, 0.4, 0.2, 0.6],
            2048,
        ),
        (
            "ashikhmin-shirley",
            3,
            vec![0.3, 0.4, 0.5, 0.2, 0.25, 0.3, 40.0, 0.1],
            2048,
        ),
        ("oren-nayar", 1, vec![0.6, 0.3], 10_000),
    ];
    for (name, channels, at, n) in cases {
        let (model, _, _, _) = setup(name, channels, &at);
        let pairs = pairs(n);
        let values = vec![0.1; n * channels];
        let scale: Vec<f64> = (0..n).map(|j| 0.5 + pairs.lz[j].abs()).collect();
        let plain = ModelProblem::new(model.as_ref(), &pairs, &values, &scale).expect("problem");
        let log = ModelProblem::new(model.as_ref(), &pairs, &values, &scale)
            .expect("problem")
            .with_transform(&LogRows);
        for (kind, prob) in [("plain", &plain), ("log", &log)] {
            let (m, np) = (prob.n_residuals(), prob.n_params());
            let (mut r, mut j) = (vec![0.0; m], vec![0.0; m * np]);
            prob.residuals(&at, &mut r);
            prob.jacobian(&at, &mut j);
            let (mut r1, mut j1) = (vec![f64::NAN; m], vec![f64::NAN; m * np]);
            prob.residuals_and_jacobian(&at, &mut r1, &mut j1);
            let close = |a: &[f64], b: &[f64]| {
                a.iter()
                    .zip(b)
                    .all(|(x, y)| (x - y).abs() <= 1e-12 * (1.0 + x.abs().max(y.abs())))
            };
            assert!(close(&r, &r1), "{name} {kind}: residuals differ");
            assert!(close(&j, &j1), "{name} {kind}: Jacobians differ");
        }
    }
}
