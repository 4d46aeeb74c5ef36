//! The problem trait every non-linear solver of this crate works on.
//!
//! A [`LeastSquaresProblem`] says how many parameters and residuals it has,
//! how to compute the residual vector `r(p)` and (optionally) its Jacobian
//! `J = dr/dp`. The solvers minimise `1/2 ||r(p)||^2`; they know nothing
//! else about the problem. A problem without an analytic Jacobian inherits
//! a central finite-difference one ([`fd_jacobian`]). A problem over
//! millions of rows can also offer the normal equations in the same pass as
//! its residuals ([`LeastSquaresProblem::residuals_and_gram`]), so the
//! solver never stores the Jacobian.

/// A non-linear least-squares problem `min_p 1/2 sum_i r_i(p)^2`.
pub trait LeastSquaresProblem {
    /// Number of parameters `n`.
    fn n_params(&self) -> usize;
    /// Number of residuals `m`.
    fn n_residuals(&self) -> usize;
    /// Residuals `r(p)` into `out` (length `m`). A residual that cannot be
    /// computed is written as NaN; solvers treat such a point as rejected.
    fn residuals(&self, p: &[f64], out: &mut [f64]);
    /// Jacobian `J[i * n + k] = d r_i / d p_k` (row-major, `m x n`).
    /// Defaults to central finite differences.
    fn jacobian(&self, p: &[f64], jac: &mut [f64]) {
        fd_jacobian(self, p, jac);
    }
    /// The residuals and the normal equations at `p` in one pass over the
    /// data, without storing the Jacobian: `r(p)` into `out` (length `m`)
    /// and the Gram matrix of the augmented Jacobian `[J | r]` into `gram`
    /// (`(n+1) x (n+1)`, row-major: `J^T J`, then `J^T r` in the last column
    /// and row, `r^T r` in the corner). Returns false, writing nothing, when
    /// the problem has no such pass (the default); the solvers then call
    /// [`residuals`](Self::residuals) and [`jacobian`](Self::jacobian).
    fn residuals_and_gram(&self, _p: &[f64], _out: &mut [f64], _gram: &mut [f64]) -> bool {
        false
    }
}

/// Central finite-difference Jacobian (row-major `m x n`) of any problem,
/// with step `eps^(1/3) max(|p_k|, 1)`.
pub fn fd_jacobian<P: LeastSquaresProblem + ?Sized>(problem: &P, p: &[f64], jac: &mut [f64]) {
    let (m, n) = (problem.n_residuals(), problem.n_params());
    let mut q = p.to_vec();
    let mut f1 = vec![0.0; m];
    let mut f2 = vec![0.0; m];
    for k in 0..n {
        let h = f64::EPSILON.cbrt() * p[k].abs().max(1.0);
        q[k] = p[k] + h;
        problem.residuals(&q, &mut f1);
        q[k] = p[k] - h;
        problem.residuals(&q, &mut f2);
        q[k] = p[k];
        for i in 0..m {
            jac[i * n + k] = (f1[i] - f2[i]) / (2.0 * h);
        }
    }
}
