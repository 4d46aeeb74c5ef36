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
//! and the linear inequalities.

use faer::linalg::solvers::SolveLstsq;
use faer::{Mat, MatRef};

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
    // faer's QR, not the crate's small one: with the workspace's default
    // target (SSE2), removing faer's (AVX) calls here left the vector
    // state dirty for the model code after each step, which then ran at
    // half speed (Lafortune on CUReT; gone with target-cpu=x86-64-v3).
    let qr = e.qr();
    let fm = Mat::from_fn(m, 1, |i, _| f[i]);
    let x0m = qr.solve_lstsq(&fm);
    let x0: Vec<f64> = (0..n).map(|i| x0m[(i, 0)]).collect();
    let mc = g.nrows();
    let gx0: Vec<f64> = (0..mc)
        .map(|i| (0..n).map(|k| g[(i, k)] * x0[k]).sum::<f64>())
        .collect();
    if (0..mc).all(|i| gx0[i] >= h[i]) {
        return Ok(x0);
    }
    let r = qr.thin_R();
    // A^T = R^-T G^T: solve R^T X = G^T (R^T is lower triangular).
    let mut at = Mat::from_fn(n, mc, |k, i| g[(i, k)]);
    r.transpose().solve_lower_triangular_in_place(at.as_mut());
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
    let mut z = Mat::from_fn(n, 1, |k, _| -rho[k] / rho[n]);
    r.solve_upper_triangular_in_place(z.as_mut());
    Ok((0..n).map(|k| x0[k] + z[(k, 0)]).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Columns of different norms: `min (x0 - 1)^2 + 100 (x1 - 1)^2` s.t.
    /// `x0 + x1 <= 1`. By hand (KKT: `2 (x0 - 1) = 200 (x1 - 1)` on
    /// `x0 + x1 = 1`): `x = (1/101, 100/101)`; with the unconstrained
    /// optimum feasible, that optimum.
    #[test]
    fn weighted_problem_gives_the_hand_solution() {
        let e = Mat::from_fn(3, 2, |i, j| [[1.0, 0.0], [0.0, 10.0], [0.0, 0.0]][i][j]);
        let g = Mat::from_fn(1, 2, |_, _| -1.0);
        let x = lsi(e.as_ref(), &[1.0, 10.0, 0.0], g.as_ref(), &[-1.0]).unwrap();
        let want = [1.0 / 101.0, 100.0 / 101.0];
        for (x, w) in x.iter().zip(want) {
            assert!((x - w).abs() < 1e-14, "{x} vs {w}");
        }
        let x = lsi(e.as_ref(), &[0.25, 2.5, 0.0], g.as_ref(), &[-1.0]).unwrap();
        assert!(
            (x[0] - 0.25).abs() < 1e-15 && (x[1] - 0.25).abs() < 1e-15,
            "{x:?}"
        );
    }
}
