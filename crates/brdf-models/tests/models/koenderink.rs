//! Koenderink's expansion: basis counts, Zernike polynomials against their
//! closed forms, a basis value derived by hand, reciprocity, order 0 = Lambert.

use std::f64::consts::PI;

use brdf_core::{Brdf, Parametric, spherical_to_cartesian};
use brdf_models::Koenderink;
use brdf_models::koenderink::zernike_radial;

#[test]
fn orders_2_4_8_give_5_14_55_coefficients() {
    for (order, count) in [(0, 1), (2, 5), (4, 14), (8, 55)] {
        assert_eq!(
            Koenderink::basis_indices(order).len(),
            count,
            "order {order}"
        );
        assert_eq!(Koenderink::new(order, 3).unwrap().n_params(), 3 * count);
    }
    assert_eq!(
        Koenderink::basis_indices(2),
        vec![(0, 0, 0), (0, 0, 2), (0, 2, 2), (1, 1, 1), (2, 2, 2)]
    );
    assert!(Koenderink::new(21, 1).is_err());
    assert!(Koenderink::new(2, 0).is_err());
}

#[test]
fn zernike_radial_matches_closed_forms() {
    for rho in [0.0, 0.3, 0.7, 1.0, 2f64.sqrt() * (0.5f64).sin()] {
        let r2 = rho * rho;
        assert!((zernike_radial(0, 0, rho) - 1.0).abs() < 1e-15);
        assert!((zernike_radial(2, 0, rho) - (2.0 * r2 - 1.0)).abs() < 1e-14);
        assert!((zernike_radial(4, 0, rho) - (6.0 * r2 * r2 - 6.0 * r2 + 1.0)).abs() < 1e-14);
        assert!((zernike_radial(3, 1, rho) - (3.0 * r2 * rho - 2.0 * rho)).abs() < 1e-14);
        assert!((zernike_radial(4, 2, rho) - (4.0 * r2 * r2 - 3.0 * r2)).abs() < 1e-14);
        assert_eq!(zernike_radial(3, 0, rho), 0.0);
        // R_n^n = rho^n, and R_n^m(1) = 1.
        assert!((zernike_radial(5, 5, rho) - rho.powi(5)).abs() < 1e-15);
    }
    assert!((zernike_radial(8, 2, 1.0) - 1.0).abs() < 1e-12);
}

#[test]
fn basis_value_by_hand() {
    // theta_i = 60 deg, phi_i = 0; theta_o = 90 - 1e-6 ~ grazing, phi_o = 90 deg.
    // rho_i = sqrt(1 - cos 60) = sqrt(0.5); rho_o = sqrt(1 - cos theta_o).
    // K(1, 1, 1) = R_1^1(rho_i) R_1^1(rho_o) cos(-90 deg) = 0 and
    // K(2, 2, 2) = rho_i^2 rho_o^2 cos(180 deg) = -0.5 rho_o^2;
    // K(0, 0, 2) = R_2^0(rho_o) + R_2^0(rho_i) = (2 rho_o^2 - 1) + 0.
    let to = PI / 2.0 - 1e-6;
    let l = spherical_to_cartesian(PI / 3.0, 0.0);
    let v = spherical_to_cartesian(to, PI / 2.0);
    let m = Koenderink::new(2, 1).unwrap();
    let mut b = [0.0; 5];
    m.basis(&l, &v, &mut b);
    let ro2 = 1.0 - to.cos();
    assert!((b[0] - 1.0).abs() < 1e-15);
    assert!((b[1] - (2.0 * ro2 - 1.0)).abs() < 1e-12);
    assert!(
        (b[2] - (2.0 * ro2 - 1.0) * 0.0).abs() < 1e-12,
        "R_2^0(rho_i) = 0 at 60 deg"
    );
    assert!(b[3].abs() < 1e-12);
    assert!((b[4] + 0.5 * ro2).abs() < 1e-12);
}

#[test]
fn reciprocal_and_order_zero_is_lambert() {
    let mut m = Koenderink::new(8, 1).unwrap();
    let p: Vec<f64> = (0..55).map(|k| 0.3 / (1.0 + k as f64)).collect();
    m.set_params(&p).unwrap();
    let dirs = brdf_core::plausibility::hemisphere_directions(6, 5, 1e-6);
    let r = brdf_core::plausibility::reciprocity_deviation(&m, &dirs);
    assert!(r.max_rel < 1e-12, "{r:?}");
    let mut lam = Koenderink::new(0, 2).unwrap();
    lam.set_params(&[0.2 / PI, 0.9 / PI]).unwrap();
    let mut f = [0.0; 2];
    lam.eval(
        &spherical_to_cartesian(1.2, 0.3),
        &spherical_to_cartesian(0.4, 2.0),
        &mut f,
    );
    assert!((f[0] - 0.2 / PI).abs() < 1e-15 && (f[1] - 0.9 / PI).abs() < 1e-15);
    // Clamped at zero; the derivative stays that of the unclamped sum.
    lam.set_params(&[-0.1, 0.1]).unwrap();
    let mut g = [0.0; 4];
    lam.eval_grad_at(
        &[-0.1, 0.1],
        &spherical_to_cartesian(0.2, 0.0),
        &spherical_to_cartesian(0.2, 1.0),
        &mut f,
        &mut g,
    );
    assert_eq!(f, [0.0, 0.1]);
    assert_eq!(g, [1.0, 0.0, 0.0, 1.0]);
}
