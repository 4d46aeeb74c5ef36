//! Lawson-Hanson NNLS: hand-checked cases and the KKT conditions on random
//! problems.

use brdf_solve::{NnlsTermination, SolveError, nnls};
use faer::Mat;
use proptest::prelude::*;

#[test]
fn unconstrained_optimum_inside_is_returned_unchanged() {
    // A = I, b = (1, 2): x = b.
    let a = Mat::from_fn(2, 2, |i, j| if i == j { 1.0 } else { 0.0 });
    let s = nnls(a.as_ref(), &[1.0, 2.0], 10).unwrap();
    assert_eq!(s.x, vec![1.0, 2.0]);
    assert_eq!(s.termination, NnlsTermination::Optimal);
}

#[test]
fn negative_component_is_clamped_by_hand() {
    // A = I, b = (1, -2): x = (1, 0), residual 2.
    let a = Mat::from_fn(2, 2, |i, j| if i == j { 1.0 } else { 0.0 });
    let s = nnls(a.as_ref(), &[1.0, -2.0], 10).unwrap();
    assert_eq!(s.x, vec![1.0, 0.0]);
    assert!((s.residual_norm - 2.0).abs() < 1e-15);
    assert_eq!(s.passive, vec![0]);
    // Correlated columns: A = [[1, 1], [1, 0], [0, 1]] (as rows), b = (2, 1, -1).
    // Unconstrained: A^T A = [[2,1],[1,2]], A^T b = (3, 1) -> (5/3, -1/3);
    // with x2 = 0: x1 = (A1.b)/(A1.A1) = 3/2.
    let a = Mat::from_fn(3, 2, |i, j| [[1.0, 1.0], [1.0, 0.0], [0.0, 1.0]][i][j]);
    let s = nnls(a.as_ref(), &[2.0, 1.0, -1.0], 10).unwrap();
    assert!((s.x[0] - 1.5).abs() < 1e-14 && s.x[1] == 0.0);
}

#[test]
fn degenerate_inputs() {
    // All-zero data: x = 0.
    let a = Mat::from_fn(4, 3, |i, j| (i + j) as f64);
    let s = nnls(a.as_ref(), &[0.0; 4], 10).unwrap();
    assert_eq!(s.x, vec![0.0; 3]);
    // Duplicated columns and more columns than rows: still a feasible optimum.
    let a = Mat::from_fn(2, 4, |i, _| 1.0 + i as f64);
    let s = nnls(a.as_ref(), &[2.0, 4.0], 20).unwrap();
    assert!(s.x.iter().all(|x| *x >= 0.0));
    assert!(s.residual_norm < 1e-12);
    assert!(matches!(
        nnls(a.as_ref(), &[1.0], 5),
        Err(SolveError::Dimension { .. })
    ));
    assert!(matches!(
        nnls(a.as_ref(), &[1.0, f64::NAN], 5),
        Err(SolveError::NonFinite { .. })
    ));
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]
    #[test]
    fn kkt_conditions_hold(vals in proptest::collection::vec(-1.0..1.0f64, 8 * 4 + 8)) {
        let (m, n) = (8, 4);
        let a = Mat::from_fn(m, n, |i, j| vals[i * n + j]);
        let b: Vec<f64> = vals[m * n..].to_vec();
        let s = nnls(a.as_ref(), &b, 30).unwrap();
        prop_assert_eq!(s.termination, NnlsTermination::Optimal);
        let r: Vec<f64> = (0..m).map(|i| b[i] - (0..n).map(|j| a[(i, j)] * s.x[j]).sum::<f64>()).collect();
        for j in 0..n {
            let w: f64 = (0..m).map(|i| a[(i, j)] * r[i]).sum();
            prop_assert!(s.x[j] >= 0.0);
            if s.x[j] > 0.0 {
                prop_assert!(w.abs() < 1e-10, "passive dual {}", w);
            } else {
                prop_assert!(w < 1e-10, "active dual {}", w);
            }
        }
    }
}
