//! Least squares with linear inequality constraints (LSI),
//! `min ||E x - f|| s.t. G x >= h`, by Lawson & Hanson's reduction
//! (1974, ch. 23): with the thin QR `E = Q R` (E of full column rank) and
//! the unconstrained solution `x0 = R^-1 Q^T f`, substitute `z = R (x - x0)`;
//! the problem becomes the least-distance programme (LDP)
//! `min ||z|| s.t. (G R^-1) z >= h - G x0`, which is solved through one
//! non-negative least-squares problem: with `M = [A^T; b^T]` and
//! `e = (0, ..., 0, 1)`, `u = argmin_{u >= 0} ||M u - e||`, `rho = M u - e`,
//! the LDP solution is `z = -rho[..n] / rho[n]` (infeasible if `rho = 0`).
//!
//! This is the subproblem of the bounded solver: every damped Gauss-Newton
//! step is an LSI problem whose constraints keep the next iterate in the box
//! and the linear inequalities. `E` is small there (the damped, stacked
//! Jacobian's triangle), so its QR is the column-scaled, column-pivoted
//! [`SmallQr`] on one workspace (`E = Q R D P^T`, `D` the column scales,
//! `P` the pivoting; `R D P^T` takes the place of `R` above), which also
//! detects a rank-deficient `E` instead of dividing by a zero pivot.

use faer::{Mat, MatRef};

use crate::small_qr::SmallQr;
use crate::{SolveError, nnls};

/// Solve `min ||E x - f|| s.t. G x >= h` (E must have full column rank).
/// Returns `Err(SolveError::Factorisation)` when the constraints are
/// infeasible.
pub fn lsi(
    e: MatRef<'_, f64>,
    f: &[f64],
    g: MatRef<'_, f64>,
    h: &[f64],
) -> Result<Vec<f64>, SolveError> {
    let (m, n) = (e.nrows(), e.ncols());
    if m < n || n == 0 {
        return Err(SolveError::Dimension {
            what: "LSI needs rows >= columns of E",
            left: m,
            right: n,
        });
    }
    if f.len() != m || g.nrows() != h.len() || (g.nrows() > 0 && g.ncols() != n) {
        return Err(SolveError::Dimension {
            what: "LSI operand sizes",
            left: f.len(),
            right: m,
        });
    }
    let mut qr = SmallQr::new();
    qr.factor(e, None, true);
    let mut x0 = vec![0.0; n];
    if !qr.solve(f, &mut x0) {
        return Err(SolveError::Factorisation {
            method: "LSI",
            reason: "E is numerically rank-deficient (LSI needs full column rank)".into(),
        });
    }
    let mc = g.nrows();
    let gx0: Vec<f64> = (0..mc)
        .map(|i| (0..n).map(|k| g[(i, k)] * x0[k]).sum::<f64>())
        .collect();
    if (0..mc).all(|i| gx0[i] >= h[i]) {
        return Ok(x0);
    }
    // A^T = R'^-T G^T with E = Q R', R' = R D P^T (pivoted, scaled QR).
    let mut at = Mat::zeros(n, mc);
    let mut row = vec![0.0; n];
    for i in 0..mc {
        row.iter_mut().enumerate().for_each(|(k, v)| *v = g[(i, k)]);
        qr.solve_rt_in_place(&mut row);
        at.col_mut(i)
            .iter_mut()
            .zip(&row)
            .for_each(|(a, v)| *a = *v);
    }
    let b: Vec<f64> = (0..mc).map(|i| h[i] - gx0[i]).collect();
    let mmat = Mat::from_fn(n + 1, mc, |k, i| if k < n { at[(k, i)] } else { b[i] });
    let mut rhs = vec![0.0; n + 1];
    rhs[n] = 1.0;
    let sol = nnls(mmat.as_ref(), &rhs, 3 * mc.max(n + 1) + 10)?;
    let mut rho = vec![0.0; n + 1];
    for k in 0..=n {
        rho[k] = (0..mc).map(|i| mmat[(k, i)] * sol.x[i]).sum::<f64>() - rhs[k];
    }
    let rnorm = rho.iter().map(|v| v * v).sum::<f64>().sqrt();
    if rnorm <= 1e3 * f64::EPSILON || rho[n].abs() <= f64::EPSILON * rnorm {
        return Err(SolveError::Factorisation {
            method: "LSI",
            reason: "the linear inequality constraints are infeasible".into(),
        });
    }
    let z: Vec<f64> = (0..n).map(|k| -rho[k] / rho[n]).collect();
    let mut dx = vec![0.0; n];
    qr.solve_r(&z, &mut dx);
    Ok((0..n).map(|k| x0[k] + dx[k]).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Columns of different norms in the wrong order, so the pivoted,
    /// scaled QR permutes and scales them: `min (x0 - 1)^2 + 100 (x1 - 1)^2`
    /// s.t. `x0 + x1 <= 1`. By hand (KKT: `2 (x0 - 1) = 200 (x1 - 1)` on
    /// `x0 + x1 = 1`): `x = (1/101, 100/101)`.
    #[test]
    fn pivoted_scaled_factor_gives_the_hand_solution() {
        let e = Mat::from_fn(3, 2, |i, j| [[1.0, 0.0], [0.0, 10.0], [0.0, 0.0]][i][j]);
        let g = Mat::from_fn(1, 2, |_, _| -1.0);
        let x = lsi(e.as_ref(), &[1.0, 10.0, 0.0], g.as_ref(), &[-1.0]).unwrap();
        let want = [1.0 / 101.0, 100.0 / 101.0];
        for (x, w) in x.iter().zip(want) {
            assert!((x - w).abs() < 1e-14, "{x} vs {w}");
        }
        // Unconstrained optimum feasible: returned as is.
        let x = lsi(e.as_ref(), &[0.25, 2.5, 0.0], g.as_ref(), &[-1.0]).unwrap();
        assert!(
            (x[0] - 0.25).abs() < 1e-15 && (x[1] - 0.25).abs() < 1e-15,
            "{x:?}"
        );
        // A rank-deficient E is an error, not a division by zero.
        let e = Mat::from_fn(3, 2, |i, _| i as f64);
        assert!(lsi(e.as_ref(), &[1.0, 2.0, 3.0], g.as_ref(), &[-1.0]).is_err());
    }
}
