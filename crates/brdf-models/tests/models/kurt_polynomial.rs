//! Kurt's polynomial model: counts, PCA, reciprocity, clamping, derivatives.

use brdf_core::{Brdf, DirPairs, Parametric, spherical_to_cartesian};
use brdf_models::{KurtPolynomial, Pca, PolyVariant};
use nalgebra::Vector3;

fn pairs() -> DirPairs {
    let mut p = DirPairs::default();
    for i in 0..12 {
        for j in 0..7 {
            let l = spherical_to_cartesian(0.1 + 0.12 * i as f64, 0.3 * j as f64);
            let v = spherical_to_cartesian(1.3 - 0.1 * i as f64, 2.0 + 0.5 * j as f64);
            p.push(&l, &v);
        }
    }
    p
}

#[test]
fn coefficient_and_stored_number_counts() {
    for (p, kurt) in [(1, 7), (2, 9), (8, 21)] {
        let m = KurtPolynomial::new(PolyVariant::Isotropic, p, 1, Pca::identity(2)).unwrap();
        assert_eq!(m.coefficients_per_channel(), 2 * p + 1);
        assert_eq!(m.kurt_stored_numbers(), kurt);
        assert_eq!(m.stored_numbers(), 2 * p + 1 + 2 + 4);
    }
    let m = KurtPolynomial::new(PolyVariant::Anisotropic, 3, 3, Pca::identity(3)).unwrap();
    assert_eq!(m.coefficients_per_channel(), 10);
    assert_eq!(m.n_params(), 30);
    assert_eq!(m.param_specs()[10].name, "b0_g");
    assert!(KurtPolynomial::new(PolyVariant::Isotropic, 0, 1, Pca::identity(2)).is_err());
    assert!(KurtPolynomial::new(PolyVariant::Isotropic, 1, 1, Pca::identity(3)).is_err());
}

#[test]
fn pca_is_centred_decorrelated_ordered_and_sign_fixed() {
    let p = pairs();
    let pca = Pca::from_pairs(PolyVariant::Isotropic, &p).unwrap();
    assert!(pca.variances[0] >= pca.variances[1]);
    // Scores have zero mean and zero covariance; their variances are the
    // eigenvalues.
    let n = p.len() as f64;
    let z: Vec<[f64; 3]> = (0..p.len())
        .map(|j| pca.scores(PolyVariant::Isotropic, &p.l(j), &p.v(j)))
        .collect();
    let m0: f64 = z.iter().map(|s| s[0]).sum::<f64>() / n;
    let m1: f64 = z.iter().map(|s| s[1]).sum::<f64>() / n;
    let c01: f64 = z.iter().map(|s| s[0] * s[1]).sum::<f64>() / (n - 1.0);
    let v0: f64 = z.iter().map(|s| s[0] * s[0]).sum::<f64>() / (n - 1.0);
    assert!(m0.abs() < 1e-14 && m1.abs() < 1e-14);
    assert!(c01.abs() < 1e-14);
    assert!((v0 - pca.variances[0]).abs() < 1e-12);
    // Sign rule: the largest component of every axis is positive.
    for i in 0..2 {
        let a = &pca.axes[i * 2..i * 2 + 2];
        let big = if a[0].abs() >= a[1].abs() { a[0] } else { a[1] };
        assert!(big > 0.0);
    }
    // Reproducible: the same data give bit-identical transforms.
    assert_eq!(pca, Pca::from_pairs(PolyVariant::Isotropic, &p).unwrap());
    let mut one = DirPairs::default();
    one.push(&Vector3::z(), &Vector3::z());
    assert!(Pca::from_pairs(PolyVariant::Isotropic, &one).is_err());
}

#[test]
fn reciprocal_by_construction_and_clamped_at_zero() {
    let p = pairs();
    for variant in [PolyVariant::Isotropic, PolyVariant::Anisotropic] {
        let pca = Pca::from_pairs(variant, &p).unwrap();
        let mut m = KurtPolynomial::new(variant, 4, 1, pca).unwrap();
        let np = m.n_params();
        let coeffs: Vec<f64> = (0..np)
            .map(|k| ((k * 7 + 3) % 11) as f64 / 5.0 - 1.0)
            .collect();
        m.set_params(&coeffs).unwrap();
        let (mut a, mut b) = ([0.0], [0.0]);
        let mut clamped = 0;
        for j in 0..p.len() {
            m.eval(&p.l(j), &p.v(j), &mut a);
            m.eval(&p.v(j), &p.l(j), &mut b);
            assert_eq!(a[0], b[0], "{variant:?} pair {j}");
            assert!(a[0] >= 0.0);
            let mut row = vec![0.0; np];
            m.design_row(&p.l(j), &p.v(j), &mut row);
            let s: f64 = row.iter().zip(&coeffs).map(|(x, c)| x * c).sum();
            assert!((a[0] - s.max(0.0)).abs() < 1e-12);
            if s < 0.0 {
                clamped += 1;
            }
        }
        assert!(clamped > 0, "the test should exercise the clamp");
    }
}

#[test]
fn derivatives_are_the_design_row_and_match_finite_differences_where_unclamped() {
    let p = pairs();
    let pca = Pca::from_pairs(PolyVariant::Isotropic, &p).unwrap();
    let mut m = KurtPolynomial::new(PolyVariant::Isotropic, 3, 3, pca).unwrap();
    let np = m.n_params();
    let coeffs: Vec<f64> = (0..np).map(|k| 0.3 + 0.01 * k as f64).collect();
    m.set_params(&coeffs).unwrap();
    let (mut out, mut grad) = (vec![0.0; 3], vec![0.0; 3 * np]);
    let mut fd = vec![0.0; 3 * np];
    for j in (0..p.len()).step_by(5) {
        m.eval_grad_at(&coeffs, &p.l(j), &p.v(j), &mut out, &mut grad);
        brdf_core::central_difference_grad(&m, &coeffs, &p.l(j), &p.v(j), &mut fd);
        for k in 0..3 * np {
            assert!(
                (grad[k] - fd[k]).abs() < 1e-7 * (1.0 + fd[k].abs()),
                "{k}: {} vs {}",
                grad[k],
                fd[k]
            );
        }
    }
}
