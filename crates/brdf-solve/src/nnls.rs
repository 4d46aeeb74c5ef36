//! Non-negative least squares `min ||A x - b|| s.t. x >= 0` by the active-set
//! method of Lawson & Hanson (1974, "Solving Least Squares Problems", ch. 23).
//!
//! The passive set `P` starts empty; the variable with the largest dual
//! `w = A^T (b - A x)` enters `P`; the unconstrained least-squares solution on
//! `P` (column-scaled, column-pivoted QR on a workspace reused through the
//! iterations; through [`crate::lstsq`], by SVD, on rank deficiency)
//! is accepted when positive, otherwise the step is cut back at the first
//! variable that would become negative and that variable leaves `P`. At the
//! solution the KKT conditions hold: `x >= 0`, `w <= tol` on the active set,
//! `w = 0` on the passive set (up to rounding).

use faer::{Mat, MatRef};

use crate::small_qr::SmallQr;
use crate::{LstsqMethod, SolveError, lstsq};

/// Why NNLS stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NnlsTermination {
    /// The KKT conditions hold.
    Optimal,
    /// The iteration cap was reached (the current feasible `x` is returned).
    MaxIterations,
}

/// Result of [`nnls`].
#[derive(Clone, Debug)]
pub struct NnlsSolution {
    /// The solution, `x >= 0`.
    pub x: Vec<f64>,
    /// Indices of the passive (free, positive) variables.
    pub passive: Vec<usize>,
    /// Outer iterations.
    pub iterations: usize,
    /// `||A x - b||`.
    pub residual_norm: f64,
    /// Why it stopped.
    pub termination: NnlsTermination,
}

/// Solve `min ||A x - b||` subject to `x >= 0`. `max_iter` caps the outer
/// iterations (`3 n` is Lawson-Hanson's suggestion).
pub fn nnls(a: MatRef<'_, f64>, b: &[f64], max_iter: usize) -> Result<NnlsSolution, SolveError> {
    let tol = check_and_tolerance(a, b)?;
    let n = a.ncols();
    let mut x = vec![0.0; n];
    let mut passive = vec![false; n];
    let mut qr = SmallQr::new();
    let mut iterations = 0;
    let mut termination = NnlsTermination::Optimal;
    loop {
        let w = dual(a, b, &x);
        let candidate = (0..n)
            .filter(|&j| !passive[j] && w[j] > tol)
            .max_by(|&i, &j| w[i].total_cmp(&w[j]));
        let Some(t) = candidate else { break };
        if iterations >= max_iter {
            termination = NnlsTermination::MaxIterations;
            break;
        }
        iterations += 1;
        passive[t] = true;
        restore_feasibility(a, b, tol, &mut passive, &mut x, &mut qr)?;
    }
    let residual_norm = residual_norm(a, b, &x);
    Ok(NnlsSolution {
        passive: (0..n).filter(|&j| passive[j]).collect(),
        x,
        iterations,
        residual_norm,
        termination,
    })
}

/// Check the shapes and `b`, and return the tolerance of the dual test,
/// `10 eps ||A||_1 max(m, n)`: the dual of a variable that cannot lower the
/// residual is rounding noise of that size, and letting it enter the
/// passive set could keep the iteration from ending. A non-finite `A`
/// shows as a non-finite norm (reported at row 0, column 0).
fn check_and_tolerance(a: MatRef<'_, f64>, b: &[f64]) -> Result<f64, SolveError> {
    let (m, n) = (a.nrows(), a.ncols());
    if m == 0 || n == 0 {
        return Err(SolveError::Empty {
            what: "design matrix",
        });
    }
    if b.len() != m {
        return Err(SolveError::Dimension {
            what: "rows of A vs length of b",
            left: m,
            right: b.len(),
        });
    }
    for (i, v) in b.iter().enumerate() {
        if !v.is_finite() {
            return Err(SolveError::NonFinite {
                what: "b",
                row: i,
                col: 0,
                value: *v,
            });
        }
    }
    let norm1 = (0..n)
        .map(|j| (0..m).map(|i| a[(i, j)].abs()).sum::<f64>())
        .fold(0.0, f64::max);
    if !norm1.is_finite() {
        return Err(SolveError::NonFinite {
            what: "A",
            row: 0,
            col: 0,
            value: norm1,
        });
    }
    Ok(10.0 * f64::EPSILON * norm1 * (m.max(n) as f64))
}

/// The dual `w = A^T (b - A x)`: the negative gradient of `||A x - b||^2 / 2`,
/// so a variable with `w_j > 0` would lower the residual by growing.
fn dual(a: MatRef<'_, f64>, b: &[f64], x: &[f64]) -> Vec<f64> {
    let (m, n) = (a.nrows(), a.ncols());
    let r: Vec<f64> = (0..m)
        .map(|i| b[i] - (0..n).map(|j| a[(i, j)] * x[j]).sum::<f64>())
        .collect();
    (0..n)
        .map(|j| (0..m).map(|i| a[(i, j)] * r[i]).sum())
        .collect()
}

/// Lawson-Hanson's inner loop after a variable entered the passive set:
/// solve on the passive columns; accept the solution `z` if it is positive,
/// else move `x` towards `z` as far as feasibility allows and drop the
/// passive variables that reach zero, then solve again.
fn restore_feasibility(
    a: MatRef<'_, f64>,
    b: &[f64],
    tol: f64,
    passive: &mut [bool],
    x: &mut Vec<f64>,
    qr: &mut SmallQr,
) -> Result<(), SolveError> {
    let n = a.ncols();
    // Each pass of the inner loop frees at least one variable, so it
    // ends within n passes; a non-finite sub-solution (overflow) or a
    // step that frees none would otherwise loop for ever.
    for _ in 0..=n {
        let z = solve_passive(a, b, passive, qr)?;
        if let Some(j) = (0..n).find(|&j| passive[j] && !z[j].is_finite()) {
            return Err(SolveError::Factorisation {
                method: "NNLS",
                reason: format!("the sub-problem's coefficient {j} is not finite (overflow)"),
            });
        }
        if (0..n).filter(|&j| passive[j]).all(|j| z[j] > 0.0) {
            *x = z;
            break;
        }
        step_to_boundary(x, &z, passive, tol);
        if !passive.iter().any(|p| *p) {
            break;
        }
    }
    Ok(())
}

/// Step from `x` towards `z` until the first passive variable hits 0, and
/// free the passive variables that reach `tol` or below (set to exactly 0,
/// so that rounding cannot leave a slightly negative or tiny coefficient).
fn step_to_boundary(x: &mut [f64], z: &[f64], passive: &mut [bool], tol: f64) {
    let n = x.len();
    let alpha = (0..n)
        .filter(|&j| passive[j] && z[j] <= 0.0)
        .map(|j| x[j] / (x[j] - z[j]))
        .fold(f64::INFINITY, f64::min);
    for j in 0..n {
        x[j] += alpha * (z[j] - x[j]);
        if passive[j] && x[j] <= tol {
            passive[j] = false;
            x[j] = 0.0;
        }
    }
}

/// `||A x - b||`.
fn residual_norm(a: MatRef<'_, f64>, b: &[f64], x: &[f64]) -> f64 {
    let (m, n) = (a.nrows(), a.ncols());
    (0..m)
        .map(|i| {
            let r = b[i] - (0..n).map(|j| a[(i, j)] * x[j]).sum::<f64>();
            r * r
        })
        .sum::<f64>()
        .sqrt()
}

/// The unconstrained least-squares solution on the passive columns (zero
/// elsewhere): [`SmallQr`] on its reused buffers, or [`lstsq`] (which
/// re-solves by SVD) when those columns are numerically rank-deficient.
fn solve_passive(
    a: MatRef<'_, f64>,
    b: &[f64],
    passive: &[bool],
    qr: &mut SmallQr,
) -> Result<Vec<f64>, SolveError> {
    let n = a.ncols();
    let cols: Vec<usize> = (0..n).filter(|&j| passive[j]).collect();
    let mut xs = vec![0.0; cols.len()];
    qr.factor_columns(a, &cols, true);
    if !qr.solve(b, &mut xs) {
        let ap = Mat::from_fn(a.nrows(), cols.len(), |i, k| a[(i, cols[k])]);
        let bm = Mat::from_fn(a.nrows(), 1, |i, _| b[i]);
        let s = lstsq(ap.as_ref(), bm.as_ref(), None, LstsqMethod::PivotedQr)?;
        xs.iter_mut()
            .enumerate()
            .for_each(|(k, v)| *v = s.x[(k, 0)]);
    }
    let mut z = vec![0.0; n];
    for (k, &j) in cols.iter().enumerate() {
        z[j] = xs[k];
    }
    Ok(z)
}
