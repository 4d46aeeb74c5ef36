//! Parameter covariance and standard errors at a least-squares solution:
//! `Cov = s^2 (J^T J)^-1` with `s^2 = ||r||^2 / (m - n)`, computed from the
//! thin SVD of `J` (`(J^T J)^-1 = V S^-2 V^T`), never by inverting `J^T J`.
//! For a tall `J` the SVD is that of its triangle `R` (`J = Q R` has the
//! singular values and right vectors of `R`), so millions of residuals cost
//! one pass of [`crate::tall_qr`].
//! Singular values below `max(m, n) eps s_max` are treated as zero: the
//! corresponding directions are unidentifiable and their variances infinite.

use faer::Mat;

use crate::SolveError;
use crate::problem::LeastSquaresProblem;

/// `n x n` covariance matrix (row-major) of the parameters at `p`.
pub fn covariance<P: LeastSquaresProblem + ?Sized>(
    problem: &P,
    p: &[f64],
) -> Result<Vec<f64>, SolveError> {
    let (m, n) = (problem.n_residuals(), problem.n_params());
    if m <= n {
        return Err(SolveError::Dimension {
            what: "covariance needs more residuals than parameters",
            left: m,
            right: n,
        });
    }
    let mut r = vec![0.0; m];
    problem.residuals(p, &mut r);
    let mut jac = vec![0.0; m * n];
    problem.jacobian(p, &mut jac);
    if let Some(i) = r.iter().chain(&jac).position(|v| !v.is_finite()) {
        return Err(SolveError::NonFinite {
            what: "residuals or Jacobian at the solution",
            row: i,
            col: 0,
            value: f64::NAN,
        });
    }
    let s2 = r.iter().map(|v| v * v).sum::<f64>() / (m - n) as f64;
    covariance_from_jacobian(&jac, m, n, s2)
}

/// `s2 (J^T J)^-1` from a row-major `m x n` Jacobian.
pub fn covariance_from_jacobian(
    jac: &[f64],
    m: usize,
    n: usize,
    s2: f64,
) -> Result<Vec<f64>, SolveError> {
    let mut j = Mat::from_fn(m, n, |i, k| jac[i * n + k]);
    let r = crate::tall_qr::r_factor(j.as_mut());
    let svd = r.thin_svd().map_err(|e| SolveError::Factorisation {
        method: "SVD",
        reason: format!("{e:?}"),
    })?;
    let s = svd.S().column_vector();
    let v = svd.V();
    let smax = (0..n).map(|k| s[k]).fold(0.0f64, f64::max);
    let tol = (m.max(n) as f64) * f64::EPSILON * smax;
    let mut cov = vec![0.0; n * n];
    for a in 0..n {
        for b in 0..n {
            let mut acc = 0.0;
            for k in 0..n {
                if s[k] > tol {
                    acc += v[(a, k)] * v[(b, k)] / (s[k] * s[k]);
                } else if v[(a, k)].abs() > 1e-12 && v[(b, k)].abs() > 1e-12 {
                    acc = f64::INFINITY;
                }
            }
            cov[a * n + b] = s2 * acc;
        }
    }
    Ok(cov)
}

/// Standard errors `sqrt(diag(Cov))` at `p`.
pub fn standard_errors<P: LeastSquaresProblem + ?Sized>(
    problem: &P,
    p: &[f64],
) -> Result<Vec<f64>, SolveError> {
    let n = problem.n_params();
    let cov = covariance(problem, p)?;
    Ok((0..n).map(|k| cov[k * n + k].sqrt()).collect())
}
