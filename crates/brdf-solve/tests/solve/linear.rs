//! Linear least squares against hand-derived solutions, exact fits, rank
//! deficiency, weights, and the accuracy loss of the normal equations.

use brdf_solve::linear::leverages;
use brdf_solve::{LstsqMethod, SolveError, lstsq};
use faer::Mat;

const METHODS: [LstsqMethod; 3] = [
    LstsqMethod::PivotedQr,
    LstsqMethod::Svd,
    LstsqMethod::NormalEquations,
];

#[test]
fn hand_derived_overdetermined_system() {
    // A = [[1,0],[0,1],[1,1]], b = (1,2,4): A^T A = [[2,1],[1,2]], A^T b =
    // (5,6), x = (4/3, 7/3), residual (1/3, 1/3, -1/3), norm 1/sqrt(3).
    let a = Mat::from_fn(3, 2, |i, j| [[1.0, 0.0], [0.0, 1.0], [1.0, 1.0]][i][j]);
    let b = Mat::from_fn(3, 1, |i, _| [1.0, 2.0, 4.0][i]);
    for m in METHODS {
        let s = lstsq(a.as_ref(), b.as_ref(), None, m).unwrap();
        assert!((s.x[(0, 0)] - 4.0 / 3.0).abs() < 1e-14, "{m:?}");
        assert!((s.x[(1, 0)] - 7.0 / 3.0).abs() < 1e-14, "{m:?}");
        assert!((s.residual_norm[0] - 1.0 / 3f64.sqrt()).abs() < 1e-14);
        assert_eq!(s.rank, 2);
    }
}

#[test]
fn exact_polynomial_fit_with_two_right_hand_sides() {
    let x: Vec<f64> = (0..10).map(|i| i as f64 / 3.0 - 1.0).collect();
    let a = Mat::from_fn(10, 3, |i, j| x[i].powi(j as i32));
    let b = Mat::from_fn(10, 2, |i, c| {
        if c == 0 {
            1.0 + 2.0 * x[i] - 3.0 * x[i] * x[i]
        } else {
            -0.5 * x[i]
        }
    });
    for m in METHODS {
        let s = lstsq(a.as_ref(), b.as_ref(), None, m).unwrap();
        let expect = [[1.0, 0.0], [2.0, -0.5], [-3.0, 0.0]];
        for j in 0..3 {
            for c in 0..2 {
                assert!(
                    (s.x[(j, c)] - expect[j][c]).abs() < 1e-12,
                    "{m:?} {j} {c}: {}",
                    s.x[(j, c)]
                );
            }
        }
        assert!(s.residual_norm.iter().all(|r| *r < 1e-12));
    }
}

#[test]
fn rank_deficiency_is_detected_and_solved_by_svd_with_minimum_norm() {
    // Two identical columns: y = 2 t is fitted by any (p, q) with p + q = 2;
    // the minimum-norm solution is (1, 1).
    let t: Vec<f64> = (1..=6).map(|i| i as f64).collect();
    let a = Mat::from_fn(6, 2, |i, _| t[i]);
    let b = Mat::from_fn(6, 1, |i, _| 2.0 * t[i]);
    let s = lstsq(a.as_ref(), b.as_ref(), None, LstsqMethod::PivotedQr).unwrap();
    assert_eq!(s.rank, 1);
    assert_eq!(s.method, LstsqMethod::Svd);
    assert!((s.x[(0, 0)] - 1.0).abs() < 1e-12 && (s.x[(1, 0)] - 1.0).abs() < 1e-12);
    // A zero column is rank deficiency too, and gets coefficient 0.
    let a = Mat::from_fn(6, 2, |i, j| if j == 0 { t[i] } else { 0.0 });
    let s = lstsq(a.as_ref(), b.as_ref(), None, LstsqMethod::PivotedQr).unwrap();
    assert_eq!(s.rank, 1);
    assert!((s.x[(0, 0)] - 2.0).abs() < 1e-12 && s.x[(1, 0)] == 0.0);
}

#[test]
fn zero_weight_removes_a_row() {
    let t: Vec<f64> = (0..8).map(|i| i as f64).collect();
    let a = Mat::from_fn(8, 2, |i, j| if j == 0 { 1.0 } else { t[i] });
    let b = Mat::from_fn(8, 1, |i, _| if i == 3 { 100.0 } else { 0.5 + 0.25 * t[i] });
    let mut w = vec![1.0; 8];
    w[3] = 0.0;
    let s = lstsq(a.as_ref(), b.as_ref(), Some(&w), LstsqMethod::PivotedQr).unwrap();
    assert!((s.x[(0, 0)] - 0.5).abs() < 1e-13 && (s.x[(1, 0)] - 0.25).abs() < 1e-13);
    assert!(s.residual_norm[0] < 1e-12);
}

#[test]
fn normal_equations_lose_the_digits_qr_keeps() {
    // Degree-11 polynomial on [0, 1]: kappa of the column-scaled Vandermonde
    // matrix is ~1e8, so QR keeps ~8 digits while the normal equations
    // (kappa^2 ~ 1e16) keep none or fail.
    let n = 60;
    let deg = 11;
    let x: Vec<f64> = (0..n).map(|i| i as f64 / (n - 1) as f64).collect();
    let a = Mat::from_fn(n, deg + 1, |i, j| x[i].powi(j as i32));
    let coef: Vec<f64> = (0..=deg).map(|j| 1.0 / (1.0 + j as f64)).collect();
    let b = Mat::from_fn(n, 1, |i, _| {
        (0..=deg).map(|j| coef[j] * x[i].powi(j as i32)).sum()
    });
    let err = |m: LstsqMethod| -> Result<f64, SolveError> {
        let s = lstsq(a.as_ref(), b.as_ref(), None, m)?;
        Ok((0..=deg)
            .map(|j| (s.x[(j, 0)] - coef[j]).abs())
            .fold(0.0, f64::max))
    };
    let qr = err(LstsqMethod::PivotedQr).unwrap();
    assert!(qr < 1e-5, "QR error {qr}");
    match err(LstsqMethod::NormalEquations) {
        Ok(ne) => assert!(ne > 1e3 * qr, "normal equations {ne} vs QR {qr}"),
        Err(SolveError::Factorisation { .. }) => {}
        Err(e) => panic!("{e}"),
    }
}

#[test]
fn leverages_sum_to_the_rank_and_are_one_over_m_for_a_constant_column() {
    let a = Mat::from_fn(5, 1, |_, _| 3.0);
    let h = leverages(a.as_ref()).unwrap();
    assert!(h.iter().all(|x| (x - 0.2).abs() < 1e-15));
    let a = Mat::from_fn(7, 3, |i, j| ((i + 1) as f64).powi(j as i32));
    let h = leverages(a.as_ref()).unwrap();
    assert!((h.iter().sum::<f64>() - 3.0).abs() < 1e-12);
}

#[test]
fn bad_input_is_a_typed_error() {
    let a = Mat::from_fn(3, 2, |i, j| if (i, j) == (1, 1) { f64::NAN } else { 1.0 });
    let b = Mat::from_fn(3, 1, |_, _| 1.0);
    let e = lstsq(a.as_ref(), b.as_ref(), None, LstsqMethod::PivotedQr).unwrap_err();
    assert!(matches!(
        e,
        SolveError::NonFinite {
            what: "A",
            row: 1,
            col: 1,
            ..
        }
    ));
    assert!(e.to_string().contains("row 1, column 1"), "{e}");
    let a = Mat::from_fn(3, 2, |_, _| 1.0);
    let b2 = Mat::from_fn(4, 1, |_, _| 1.0);
    assert!(matches!(
        lstsq(a.as_ref(), b2.as_ref(), None, LstsqMethod::Svd),
        Err(SolveError::Dimension { .. })
    ));
    assert!(matches!(
        lstsq(
            a.as_ref(),
            b.as_ref(),
            Some(&[1.0, -1.0, 1.0]),
            LstsqMethod::Svd
        ),
        Err(SolveError::InvalidOption { .. })
    ));
    let empty = Mat::<f64>::zeros(0, 2);
    assert!(matches!(
        lstsq(
            empty.as_ref(),
            Mat::<f64>::zeros(0, 1).as_ref(),
            None,
            LstsqMethod::Svd
        ),
        Err(SolveError::Empty { .. })
    ));
}
