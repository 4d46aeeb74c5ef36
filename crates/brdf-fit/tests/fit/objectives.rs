//! The appearance objectives: cube root, relative and image.
//! Each recovers the parameters of data generated exactly from the model
//! (zero residual at the truth), and the image objective's analytic
//! Jacobian agrees with central finite differences of its residuals.

use std::f64::consts::{PI, TAU};

use brdf_core::{Brdf, DirPairs, Parametric, SampleSet};
use brdf_fit::image_objective::{ImageProblem, ImageTerms};
use brdf_fit::{Fit, Objective};
use brdf_models::catalogue::{ModelConfig, build};
use brdf_solve::LeastSquaresProblem;
use nalgebra::Vector3;

use crate::common;
use common::{dir, rgb_samples};

/// RGB data of `name` at `truth` on 3000 quasi-random pairs.
fn data(name: &str, truth: &[f64]) -> SampleSet {
    let cfg = ModelConfig {
        channels: 3,
        ..ModelConfig::default()
    };
    let mut model = build(name, &cfg).expect("model");
    model.set_params(truth).expect("truth in the box");
    rgb_samples(model.as_ref(), 3000)
}

// Blinn-Phong RGB: kd_r kd_g kd_b ks_r ks_g ks_b n.
const TRUTH: [f64; 7] = [0.05, 0.1, 0.3, 0.2, 0.4, 0.6, 40.0];

fn recovers(objective: Objective) {
    let s = data("blinn-phong", &TRUTH);
    let report = Fit::model("blinn-phong")
        .expect("model")
        .objective(objective)
        .run(&s)
        .expect("fit");
    let p = report.model.params();
    for (k, (got, want)) in p.iter().zip(TRUTH).enumerate() {
        assert!(
            (got - want).abs() <= 1e-5 * want.abs().max(1e-3),
            "{}: parameter {k} = {got}, truth {want}",
            objective.name()
        );
    }
    assert!(report.summary.error < 1e-6, "{}", report.summary.error);
}

#[test]
fn cube_root_objective_recovers_exact_data() {
    recovers(Objective::CubeRoot);
}

#[test]
fn relative_objective_recovers_exact_data() {
    recovers(Objective::Relative);
}

#[test]
fn objective_names_round_trip() {
    for o in [Objective::CubeRoot, Objective::Relative, Objective::Image] {
        assert_eq!(Objective::parse(o.name()).expect("parse"), o);
    }
    let e = Objective::parse("cubic").expect_err("unknown");
    assert!(e.to_string().contains("cube-root"), "{e}");
}

/// A small image: 40 pixels over two "images", each pixel a sum of three
/// terms with per-channel weights.
fn terms() -> ImageTerms {
    terms_of(40, 3)
}

/// `pixels` pixels over two "images", each a sum of `per_pixel` terms at
/// quasi-random direction pairs with per-channel weights.
fn terms_of(pixels: usize, per_pixel: usize) -> ImageTerms {
    let n = pixels * per_pixel;
    let mut pairs = DirPairs::with_capacity(n);
    let mut pixel = Vec::new();
    let mut weights = vec![0.0; 3 * n];
    for k in 0..n {
        let x = k as f64;
        let (l, v) = term_pair(k);
        pairs.push(&l, &v);
        pixel.push(k / per_pixel);
        for c in 0..3 {
            weights[c * n + k] = 0.2 + 0.1 * c as f64 + 0.05 * (x * 0.7).sin().abs();
        }
    }
    let images = (0..pixels).map(|p| 2 * p / pixels).collect();
    ImageTerms::new(pairs, weights, 3, &pixel, images).expect("terms")
}

#[test]
fn image_problem_in_chunks_gives_the_normal_equations_of_its_jacobian() {
    // 600 pixels of 37 terms: 22 200 terms, cut into about eleven chunks
    // of whole pixels. The fused pass's Gram matrix of [J | r] equals the
    // one formed from the stored Jacobian and residuals, the Jacobian
    // agrees with central differences across the chunk boundaries, and
    // both are the same bits on one thread as on two.
    let (model, truth) = model_and_truth();
    let t = terms_of(600, 37);
    let reference = t.render(truth.as_ref(), 3);
    // The render against a plain sum over the terms.
    let mut values = vec![0.0; 3];
    let n = t.len();
    for q in [0, 299, 599] {
        for c in 0..3 {
            let plain: f64 = (q * 37..(q + 1) * 37)
                .map(|k| {
                    let (l, v) = term_pair(k);
                    let mut pairs = DirPairs::with_capacity(1);
                    pairs.push(&l, &v);
                    truth.eval_pairs(&pairs, &mut values);
                    t.weights()[c * n + k] * values[c]
                })
                .sum();
            let got = reference[c * 600 + q];
            assert!((got - plain).abs() <= 1e-12 * plain.abs(), "{got} {plain}");
        }
    }
    let exposures = t.exposures(&reference, 3);
    let problem = ImageProblem::new(model.as_ref(), &t, &reference, &exposures).expect("problem");
    let p = [0.1, 0.2, 0.2, 0.3, 0.3, 0.5, 25.0];
    let (m, np) = (problem.n_residuals(), p.len());
    let on = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("pool");
        pool.install(|| {
            let (mut r, mut jac) = (vec![0.0; m], vec![0.0; m * np]);
            let mut gram = vec![0.0; (np + 1) * (np + 1)];
            problem.jacobian(&p, &mut jac);
            let (mut r2, mut r3) = (vec![0.0; m], vec![0.0; m]);
            problem.residuals(&p, &mut r2);
            assert!(problem.residuals_and_gram(&p, &mut r3, &mut gram));
            r.copy_from_slice(&r2);
            assert_eq!(r2, r3);
            (r, jac, gram)
        })
    };
    let (r, jac, gram) = on(1);
    assert_eq!((r.clone(), jac.clone(), gram.clone()), on(2));
    let w = np + 1;
    for a in 0..w {
        for b in 0..w {
            let col = |i: usize, k: usize| if k == np { r[i] } else { jac[i * np + k] };
            let want: f64 = (0..m).map(|i| col(i, a) * col(i, b)).sum();
            let got = gram[a * w + b];
            assert!(
                (got - want).abs() <= 1e-10 * want.abs().max(1e-12),
                "gram[{a}][{b}] {got} against {want}"
            );
        }
    }
    assert_jacobian_matches_fd(&problem, &p, &jac, 7);
}

/// The direction pair of term `k` of [`terms_of`] (quasi-random).
fn term_pair(k: usize) -> (Vector3<f64>, Vector3<f64>) {
    let x = k as f64;
    (
        dir(
            (x * 0.618_033_988_75).fract(),
            TAU * (x * 0.414_213_562_37).fract(),
        ),
        dir(
            (x * 0.732_050_807_57).fract(),
            TAU * (x * 0.236_067_977_5).fract(),
        ),
    )
}

/// The RGB Blinn-Phong to fit and the one at [`TRUTH`].
fn model_and_truth() -> (Box<dyn Parametric>, Box<dyn Parametric>) {
    let cfg = ModelConfig {
        channels: 3,
        ..ModelConfig::default()
    };
    let model = build("blinn-phong", &cfg).expect("model");
    let mut truth = build("blinn-phong", &cfg).expect("model");
    truth.set_params(&TRUTH).expect("truth");
    (model, truth)
}

/// The analytic Jacobian `jac` of `problem` at `p` against central
/// differences of its residuals, on every `step`-th row.
fn assert_jacobian_matches_fd(problem: &ImageProblem, p: &[f64], jac: &[f64], step: usize) {
    let (m, np) = (problem.n_residuals(), p.len());
    let (mut rp, mut rm) = (vec![0.0; m], vec![0.0; m]);
    for k in 0..np {
        let h = 1e-6 * p[k].abs().max(1e-3);
        let (mut up, mut dn) = (p.to_vec(), p.to_vec());
        up[k] += h;
        dn[k] -= h;
        problem.residuals(&up, &mut rp);
        problem.residuals(&dn, &mut rm);
        for i in (0..m).step_by(step) {
            let fd = (rp[i] - rm[i]) / (2.0 * h);
            let an = jac[i * np + k];
            assert!(
                (fd - an).abs() <= 1e-6 * an.abs().max(1e-3),
                "row {i} parameter {k}: analytic {an}, finite difference {fd}"
            );
        }
    }
}

#[test]
fn image_problem_jacobian_matches_finite_differences() {
    let (model, truth) = model_and_truth();
    let t = terms();
    let reference = t.render(truth.as_ref(), 3);
    let exposures = t.exposures(&reference, 3);
    let problem = ImageProblem::new(model.as_ref(), &t, &reference, &exposures).expect("problem");
    let p = [0.1, 0.2, 0.2, 0.3, 0.3, 0.5, 25.0];
    let m = problem.n_residuals();
    let mut jac = vec![0.0; m * p.len()];
    problem.jacobian(&p, &mut jac);
    assert_jacobian_matches_fd(&problem, &p, &jac, 1);
    // At the truth the residuals vanish.
    let mut r = vec![0.0; m];
    problem.residuals(&TRUTH, &mut r);
    assert!(r.iter().all(|r| r.abs() < 1e-12));
}

#[test]
fn image_terms_render_sums_weighted_values() {
    // A Lambertian of albedo a: every term is a/pi, so a pixel of three
    // terms is a/pi times the sum of its weights.
    struct Lambert(f64);
    impl Brdf for Lambert {
        fn channels(&self) -> usize {
            1
        }
        fn eval(&self, _l: &Vector3<f64>, _v: &Vector3<f64>, out: &mut [f64]) {
            out[0] = self.0 / PI;
        }
    }
    let t = terms();
    let px = t.render(&Lambert(0.5), 3);
    for c in 0..3 {
        for p in 0..40 {
            let w: f64 = (3 * p..3 * p + 3).map(|k| t.weights()[c * 120 + k]).sum();
            assert!((px[c * 40 + p] - 0.5 / PI * w).abs() < 1e-15);
        }
    }
}

#[test]
fn image_problem_ends_with_the_mean_colour_rows() {
    // After the pixel rows, one row per image and channel:
    // W sqrt(n_i) (ln(eps + mean_i(e_i P_c(model))) - ln(eps + mean_i(e_i P_c(ref)))),
    // computed here from the plain renders of both.
    use brdf_fit::image_objective::{LOG_FLOOR, MEAN_COLOUR_WEIGHT};
    let (model, truth) = model_and_truth();
    let t = terms();
    let reference = t.render(truth.as_ref(), 3);
    let exposures = t.exposures(&reference, 3);
    let problem = ImageProblem::new(model.as_ref(), &t, &reference, &exposures).expect("problem");
    let (np, ni) = (t.pixels(), t.images());
    assert_eq!(problem.n_residuals(), 3 * np + 3 * ni);
    let p = [0.1, 0.2, 0.2, 0.3, 0.3, 0.5, 25.0];
    let mut fit = build(
        "blinn-phong",
        &ModelConfig {
            channels: 3,
            ..ModelConfig::default()
        },
    )
    .expect("model");
    fit.set_params(&p).expect("in the box");
    let px = t.render(fit.as_ref(), 3);
    let mut r = vec![0.0; problem.n_residuals()];
    problem.residuals(&p, &mut r);
    // `terms()` puts the first half of the pixels in image 0.
    for i in 0..ni {
        let pixels = (i * np / 2)..((i + 1) * np / 2);
        let n = pixels.len() as f64;
        for c in 0..3 {
            let mean = |v: &[f64]| {
                pixels
                    .clone()
                    .map(|q| exposures[i] * v[c * np + q])
                    .sum::<f64>()
                    / n
            };
            let want = MEAN_COLOUR_WEIGHT
                * n.sqrt()
                * ((LOG_FLOOR + mean(&px)).ln() - (LOG_FLOOR + mean(&reference)).ln());
            let got = r[3 * np + i * 3 + c];
            assert!(
                (got - want).abs() <= 1e-12 * want.abs().max(1.0),
                "image {i} channel {c}: {got} against {want}"
            );
            assert!(
                want.abs() > 1e-3,
                "the rows must see this colour difference"
            );
        }
    }
}
