//! Kurt's polynomial in the pipeline: the normal equations lose accuracy at
//! high degree while the QR path does not; robust IRLS resists outliers
//! where OLS does not; the expected-bias analysis vanishes for a true model
//! the fit can represent and shrinks with the degree for one it cannot.

use brdf_core::{DirPairs, SampleSet};
use brdf_fit::pipeline::fit;
use brdf_fit::{FitOptions, Solver};
use brdf_models::kurt_polynomial::{Pca, PolyVariant};
use brdf_models::{KurtPolynomial, ModelConfig, build};
use brdf_solve::{LstsqMethod, lstsq};
use brdf_study::bias::expected_bias;
use brdf_study::synthetic::scattered_pairs;
use faer::Mat;

fn pairs(n: usize) -> DirPairs {
    let mut p = DirPairs::with_capacity(n);
    for (l, v) in scattered_pairs(n, 80f64.to_radians()) {
        p.push(l.vector(), v.vector());
    }
    p
}

#[test]
fn normal_equations_lose_digits_at_high_degree_qr_does_not() {
    let dp = pairs(600);
    let degree = 12;
    let pca = Pca::from_pairs(PolyVariant::Isotropic, &dp).unwrap();
    let poly = KurtPolynomial::new(PolyVariant::Isotropic, degree, 1, pca).unwrap();
    let k = poly.coefficients_per_channel();
    let mut row = vec![0.0; k];
    let x = Mat::from_fn(dp.len(), k, |j, c| {
        poly.design_row(&dp.l(j), &dp.v(j), &mut row);
        row[c]
    });
    // Known coefficients, exact data.
    let truth: Vec<f64> = (0..k).map(|c| 1.0 / (1.0 + c as f64)).collect();
    let y = Mat::from_fn(dp.len(), 1, |j, _| {
        (0..k).map(|c| x[(j, c)] * truth[c]).sum()
    });
    let err = |m: LstsqMethod| {
        let s = lstsq(x.as_ref(), y.as_ref(), None, m).unwrap();
        (0..k)
            .map(|c| (s.x[(c, 0)] - truth[c]).abs())
            .fold(0.0f64, f64::max)
    };
    let qr = err(LstsqMethod::PivotedQr);
    let ne = err(LstsqMethod::NormalEquations);
    assert!(qr < 1e-6, "QR error {qr}");
    assert!(
        ne > 1e3 * qr,
        "normal equations {ne} vs QR {qr}: the squared condition number must show"
    );
}

#[test]
fn irls_resists_outliers_ols_does_not() {
    let dp = pairs(300);
    let config = ModelConfig {
        degree: 3,
        ..ModelConfig::default()
    };
    let e = brdf_models::entry("polynomial").unwrap();
    let mut truth = (e.build_for_data.unwrap())(&config, &dp).unwrap();
    let p: Vec<f64> = (0..truth.n_params())
        .map(|c| 0.3 / (1.0 + c as f64))
        .collect();
    truth.set_params(&p).unwrap();
    let mut s = SampleSet::new("outliers", "test", vec!["grey".into()]);
    let mut f = [0.0];
    for j in 0..dp.len() {
        truth.eval_at(&p, &dp.l(j), &dp.v(j), &mut f);
        let spike = if j % 29 == 0 { 5.0 } else { 0.0 };
        s.push(
            &brdf_core::Direction::new_unchecked(dp.l(j)),
            &brdf_core::Direction::new_unchecked(dp.v(j)),
            &[f[0] + spike],
            1.0,
        )
        .unwrap();
    }
    let mut m = (e.build_for_data.unwrap())(&config, &dp).unwrap();
    let robust = fit(m.as_mut(), &s, &FitOptions::default()).unwrap();
    assert!(
        robust.solver.starts_with("IRLS (bisquare"),
        "{}",
        robust.solver
    );
    let rob: Vec<f64> = robust.parameters.iter().map(|q| q.value).collect();
    let ols = fit(
        m.as_mut(),
        &s,
        &FitOptions {
            solver: Solver::Ols,
            ..FitOptions::default()
        },
    )
    .unwrap();
    let ols: Vec<f64> = ols.parameters.iter().map(|q| q.value).collect();
    let dev = |v: &[f64]| {
        v.iter()
            .zip(&p)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0f64, f64::max)
    };
    assert!(
        dev(&rob) < 1e-8,
        "IRLS recovers the truth despite outliers: {}",
        dev(&rob)
    );
    assert!(
        dev(&ols) > 1e-2,
        "OLS is pulled by the outliers: {}",
        dev(&ols)
    );
}

#[test]
fn expected_bias_vanishes_when_representable_and_shrinks_with_degree() {
    let design = pairs(400);
    let space = pairs(1200);
    // A degree-2 polynomial truth (in the same PCA scores) is represented
    // exactly by degrees >= 2.
    let e = brdf_models::entry("polynomial").unwrap();
    let mut truth = (e.build_for_data.unwrap())(
        &ModelConfig {
            degree: 2,
            ..ModelConfig::default()
        },
        &design,
    )
    .unwrap();
    truth.set_params(&[0.3, 0.1, -0.05, 0.02, 0.04]).unwrap();
    // Clamping at 0 would make it non-polynomial: keep it positive.
    let b = expected_bias(truth.as_ref(), 2, &design, &space).unwrap();
    assert!(b.max_abs < 1e-12, "{b:?}");
    let b4 = expected_bias(truth.as_ref(), 4, &design, &space).unwrap();
    assert!(b4.max_abs < 1e-12, "{b4:?}");
    let b1 = expected_bias(truth.as_ref(), 1, &design, &space).unwrap();
    assert!(b1.max_abs > 1e-4, "{b1:?}");
    // A Ward lobe is not a polynomial: the bias shrinks as p grows.
    let mut ward = build("ward", &ModelConfig::default()).unwrap();
    ward.set_params(&[0.3, 0.2, 0.3]).unwrap();
    let r: Vec<f64> = [1, 3, 6, 10]
        .iter()
        .map(|p| {
            expected_bias(ward.as_ref(), *p, &design, &space)
                .unwrap()
                .rms
        })
        .collect();
    assert!(r[0] > r[1] && r[1] > r[2] && r[2] > r[3], "{r:?}");
}

#[test]
fn saved_polynomial_carries_its_pca_and_evaluates_identically() {
    let dp = pairs(200);
    let config = ModelConfig {
        degree: 4,
        ..ModelConfig::default()
    };
    let e = brdf_models::entry("polynomial").unwrap();
    let mut m = (e.build_for_data.unwrap())(&config, &dp).unwrap();
    let p: Vec<f64> = (0..m.n_params()).map(|c| 0.2 / (1.0 + c as f64)).collect();
    m.set_params(&p).unwrap();
    let saved = brdf_study::saved_model::SavedModel::capture(
        m.as_ref(),
        &config,
        &dp,
        None,
        &["y".to_string()],
        Default::default(),
    )
    .unwrap();
    let path = std::env::temp_dir().join(format!("poly-{}.json", std::process::id()));
    saved.save(&path).unwrap();
    let back = brdf_study::saved_model::SavedModel::load(&path)
        .unwrap()
        .build()
        .unwrap();
    // New direction pairs, not the fitted ones.
    let (mut a, mut b) = ([0.0], [0.0]);
    for (l, v) in scattered_pairs(300, 1.3).into_iter().skip(250) {
        m.eval(l.vector(), v.vector(), &mut a);
        back.eval(l.vector(), v.vector(), &mut b);
        assert_eq!(a, b);
    }
}
