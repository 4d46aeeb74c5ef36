//! The two roads to the triangle of a tall matrix ([`brdf_solve::tall_qr`]):
//! the guarded normal equations against a hand-checked identity
//! (`R^T R = A^T A`, `R^T (Q^T B) = A^T B`) and against the Householder QR,
//! on matrices taller than one parallel block; and the guard refusing an
//! ill-conditioned, a rank-deficient and a non-finite matrix.

use brdf_solve::tall_qr::{gram_triangle, r_factor};
use faer::Mat;

/// A deterministic, well-conditioned `m x k` matrix (rows on a smooth
/// curve plus a fixed pseudo-random part).
fn tall(m: usize, k: usize) -> Mat<f64> {
    Mat::from_fn(m, k, |i, j| {
        let t = i as f64 / m as f64;
        let h = ((i * 7919 + j * 104_729) % 1000) as f64 / 1000.0;
        t.powi(j as i32) + 0.1 * h
    })
}

#[test]
fn normal_equations_satisfy_the_defining_identities() {
    let (m, k) = (70_000, 4);
    let a = tall(m, k);
    let b = Mat::from_fn(m, 2, |i, j| ((i + 3 * j) % 17) as f64 - 8.0);
    let (r, qtb) = gram_triangle(a.as_ref(), b.as_ref()).expect("well conditioned");
    let ata = a.transpose() * &a;
    let rtr = r.transpose() * &r;
    let atb = a.transpose() * &b;
    let rtq = r.transpose() * &qtb;
    for i in 0..k {
        for j in 0..k {
            if j < i {
                assert_eq!(r[(i, j)], 0.0, "R is upper triangular");
            }
            assert!((rtr[(i, j)] - ata[(i, j)]).abs() <= 1e-12 * ata[(i, i)].abs().max(1.0));
        }
        for j in 0..2 {
            assert!((rtq[(i, j)] - atb[(i, j)]).abs() <= 1e-10 * atb.norm_l2());
        }
    }
}

#[test]
fn normal_equations_equal_householder_qr_up_to_signs() {
    let (m, k) = (5_000, 3);
    let a = tall(m, k);
    let b = Mat::from_fn(m, 1, |i, _| (i as f64 / m as f64).sin());
    let (r, qtb) = gram_triangle(a.as_ref(), b.as_ref()).expect("well conditioned");
    // QR of [A | b]: its leading k x k block is R, its last column Q^T b.
    let mut ab = Mat::from_fn(m, k + 1, |i, j| if j < k { a[(i, j)] } else { b[(i, 0)] });
    let raug = r_factor(ab.as_mut());
    for i in 0..k {
        let sign = raug[(i, i)].signum();
        for j in i..k {
            let q = sign * raug[(i, j)];
            assert!(
                (r[(i, j)] - q).abs() <= 1e-9 * r[(i, i)].abs(),
                "R[{i},{j}]"
            );
        }
        let q = sign * raug[(i, k)];
        assert!(
            (qtb[(i, 0)] - q).abs() <= 1e-9 * q.abs().max(1.0),
            "Q^T b[{i}]"
        );
    }
}

#[test]
fn the_guard_refuses_what_the_normal_equations_cannot_do() {
    let m = 1_000;
    let b = Mat::from_fn(m, 1, |i, _| i as f64);
    // Two columns equal to 1e-5 relative: cond ~ 1e5, beyond the guard.
    let near = Mat::from_fn(m, 2, |i, j| {
        let t = i as f64 / m as f64;
        1.0 + t + if j == 1 { 1e-5 * t * t } else { 0.0 }
    });
    assert!(gram_triangle(near.as_ref(), b.as_ref()).is_none());
    // A zero column (rank deficient).
    let zero = Mat::from_fn(m, 2, |i, j| if j == 0 { i as f64 } else { 0.0 });
    assert!(gram_triangle(zero.as_ref(), b.as_ref()).is_none());
    // A non-finite entry.
    let mut bad = tall(m, 2);
    bad[(17, 1)] = f64::NAN;
    assert!(gram_triangle(bad.as_ref(), b.as_ref()).is_none());
    bad[(17, 1)] = f64::INFINITY;
    assert!(gram_triangle(bad.as_ref(), b.as_ref()).is_none());
}
