//! Dense linear least squares `min_x ||W^(1/2) (A x - b)||` for one or more
//! right-hand sides (one per channel), on faer's factorisations.
//!
//! - [`LstsqMethod::PivotedQr`] (default): columns scaled to unit norm, then
//!   column-pivoted Householder QR; the numerical rank is the number of
//!   `|R_kk| > tol |R_00|` with `tol = max(m, n) eps` (LAPACK's `xGELSY`
//!   convention). A rank-deficient problem is re-solved by SVD and reported
//!   as such.
//! - [`LstsqMethod::Svd`]: minimum-norm solution from the thin SVD, singular
//!   values below `tol s_max` treated as zero.
//! - [`LstsqMethod::NormalEquations`]: Cholesky of `A^T A`. Offered because it
//!   is what many codes do, and documented as the worse choice: it squares the
//!   condition number, so a problem with `kappa(A) = 1e8` loses all digits
//!   (the polynomial model's design matrix at high degree is such a problem;
//!   `tests/solve/linear.rs` shows the loss).

use faer::linalg::solvers::SolveLstsq;
use faer::{Mat, MatRef, Side};

use crate::SolveError;

/// Which factorisation solves the problem.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum LstsqMethod {
    /// Column-scaled, column-pivoted QR with a rank report (default).
    #[default]
    PivotedQr,
    /// Thin SVD, minimum-norm solution.
    Svd,
    /// Cholesky of the normal equations (documented as less accurate).
    NormalEquations,
}

/// The solution and what the solver learnt about the problem.
#[derive(Clone, Debug)]
pub struct LstsqSolution {
    /// `n x k` solution, one column per right-hand side.
    pub x: Mat<f64>,
    /// Numerical rank of the (scaled, weighted) design.
    pub rank: usize,
    /// Residual norm `||W^(1/2)(A x - b)||` per right-hand side.
    pub residual_norm: Vec<f64>,
    /// Estimate of the 2-norm condition number of the scaled design
    /// (`|R_00| / |R_rr|` for QR, `s_max / s_min` for SVD).
    pub condition: f64,
    /// The method that produced `x` (SVD when QR found rank deficiency).
    pub method: LstsqMethod,
}

fn check_finite(what: &'static str, m: MatRef<'_, f64>) -> Result<(), SolveError> {
    for j in 0..m.ncols() {
        for i in 0..m.nrows() {
            let v = m[(i, j)];
            if !v.is_finite() {
                return Err(SolveError::NonFinite {
                    what,
                    row: i,
                    col: j,
                    value: v,
                });
            }
        }
    }
    Ok(())
}

/// Solve `min ||W^(1/2)(A x - b)||` column by column of `b`. `weights` (one
/// per row, finite and `>= 0`) may be `None` for ordinary least squares.
pub fn lstsq(
    a: MatRef<'_, f64>,
    b: MatRef<'_, f64>,
    weights: Option<&[f64]>,
    method: LstsqMethod,
) -> Result<LstsqSolution, SolveError> {
    let (m, n) = (a.nrows(), a.ncols());
    if m == 0 || n == 0 {
        return Err(SolveError::Empty {
            what: "design matrix",
        });
    }
    if b.nrows() != m {
        return Err(SolveError::Dimension {
            what: "rows of A vs rows of b",
            left: m,
            right: b.nrows(),
        });
    }
    check_finite("A", a)?;
    check_finite("b", b)?;
    let sw = sqrt_weights(weights, m)?;
    let (aw, bw, scale) = scaled_problem(a, b, &sw);
    let tol = (m.max(n) as f64) * f64::EPSILON;
    let (mut y, rank, condition, used) = match method {
        LstsqMethod::PivotedQr => pivoted_qr_solve(&aw, &bw, tol)?,
        LstsqMethod::Svd => {
            let (y, rank, cond) = svd_solve(&aw, &bw, tol)?;
            (y, rank, cond, LstsqMethod::Svd)
        }
        LstsqMethod::NormalEquations => normal_equations_solve(&aw, &bw)?,
    };
    for j in 0..n {
        for c in 0..y.ncols() {
            y[(j, c)] /= scale[j];
        }
    }
    let residual_norm = residual_norms(a, b, y.as_ref(), &sw);
    Ok(LstsqSolution {
        x: y,
        rank,
        residual_norm,
        condition,
        method: used,
    })
}

/// The square roots of the row weights (all 1 without weights): the rows
/// of `A` and `b` are multiplied by them, so that an ordinary least-squares
/// solve minimises the weighted norm. A negative or non-finite weight is
/// refused: its square root would put a NaN or an infinity into the rows.
fn sqrt_weights(weights: Option<&[f64]>, m: usize) -> Result<Vec<f64>, SolveError> {
    let Some(w) = weights else {
        return Ok(vec![1.0; m]);
    };
    if w.len() != m {
        return Err(SolveError::Dimension {
            what: "weights vs rows",
            left: w.len(),
            right: m,
        });
    }
    if let Some((_, &bad)) = w
        .iter()
        .enumerate()
        .find(|(_, x)| !(x.is_finite() && **x >= 0.0))
    {
        return Err(SolveError::InvalidOption {
            name: "weight",
            value: bad,
            reason: "weights must be finite and >= 0",
        });
    }
    Ok(w.iter().map(|x| x.sqrt()).collect())
}

/// The weighted design with its columns scaled to unit norm, the weighted
/// right-hand sides, and the column scales (zero columns keep 1). Unit
/// columns make the rank test `|R_kk| > tol |R_00|` independent of the
/// units of the coefficients; the caller divides the solution by the scales.
fn scaled_problem(
    a: MatRef<'_, f64>,
    b: MatRef<'_, f64>,
    sw: &[f64],
) -> (Mat<f64>, Mat<f64>, Vec<f64>) {
    let (m, n) = (a.nrows(), a.ncols());
    let mut aw = Mat::from_fn(m, n, |i, j| sw[i] * a[(i, j)]);
    let bw = Mat::from_fn(m, b.ncols(), |i, j| sw[i] * b[(i, j)]);
    let scale: Vec<f64> = (0..n)
        .map(|j| {
            let s = (0..m).map(|i| aw[(i, j)] * aw[(i, j)]).sum::<f64>().sqrt();
            if s > 0.0 { s } else { 1.0 }
        })
        .collect();
    for j in 0..n {
        for i in 0..m {
            aw[(i, j)] /= scale[j];
        }
    }
    (aw, bw, scale)
}

/// Column-pivoted QR of the scaled design, returning `(x, rank, condition,
/// method)`. The rank is counted from `R`'s diagonal as `xGELSY` does; a
/// rank-deficient design is re-solved by [`svd_solve`] for its minimum-norm
/// solution (dividing by the negligible pivots would amplify rounding) and
/// reported as SVD.
fn pivoted_qr_solve(
    aw: &Mat<f64>,
    bw: &Mat<f64>,
    tol: f64,
) -> Result<(Mat<f64>, usize, f64, LstsqMethod), SolveError> {
    let (m, n) = (aw.nrows(), aw.ncols());
    let qr = aw.col_piv_qr();
    let r = qr.thin_R();
    let k = m.min(n);
    let r0 = r[(0, 0)].abs();
    let rank = (0..k).filter(|&i| r[(i, i)].abs() > tol * r0).count();
    if rank == n {
        let cond = if rank > 0 {
            r0 / r[(rank - 1, rank - 1)].abs()
        } else {
            f64::INFINITY
        };
        Ok((qr.solve_lstsq(bw), rank, cond, LstsqMethod::PivotedQr))
    } else {
        let (y, rank, cond) = svd_solve(aw, bw, tol)?;
        Ok((y, rank, cond, LstsqMethod::Svd))
    }
}

/// Cholesky of `A^T A` on the scaled design, returning `(x, n, NaN,
/// method)`: this method estimates neither the rank nor the condition
/// number, so the rank is reported as full and the condition as unknown.
fn normal_equations_solve(
    aw: &Mat<f64>,
    bw: &Mat<f64>,
) -> Result<(Mat<f64>, usize, f64, LstsqMethod), SolveError> {
    use faer::linalg::solvers::Solve;
    let ata = aw.transpose() * aw;
    let atb = aw.transpose() * bw;
    let llt = ata
        .llt(Side::Lower)
        .map_err(|e| SolveError::Factorisation {
            method: "Cholesky of the normal equations",
            reason: format!("{e:?}"),
        })?;
    let y = llt.solve(&atb);
    Ok((y, aw.ncols(), f64::NAN, LstsqMethod::NormalEquations))
}

/// `||W^(1/2)(A x - b)||` per right-hand side, from the unscaled `A` and
/// `b`, so that the reported norm is that of the returned `x`.
fn residual_norms(
    a: MatRef<'_, f64>,
    b: MatRef<'_, f64>,
    y: MatRef<'_, f64>,
    sw: &[f64],
) -> Vec<f64> {
    let (m, n) = (a.nrows(), a.ncols());
    (0..b.ncols())
        .map(|c| {
            (0..m)
                .map(|i| {
                    let ax: f64 = (0..n).map(|j| a[(i, j)] * y[(j, c)]).sum();
                    let r = sw[i] * (ax - b[(i, c)]);
                    r * r
                })
                .sum::<f64>()
                .sqrt()
        })
        .collect()
}

/// Minimum-norm solution by thin SVD; returns `(x, rank, s_max/s_min_kept)`.
fn svd_solve(a: &Mat<f64>, b: &Mat<f64>, tol: f64) -> Result<(Mat<f64>, usize, f64), SolveError> {
    let svd = a.thin_svd().map_err(|e| SolveError::Factorisation {
        method: "SVD",
        reason: format!("{e:?}"),
    })?;
    let s = svd.S().column_vector();
    let (u, v) = (svd.U(), svd.V());
    let k = s.nrows();
    let smax = (0..k).map(|i| s[i]).fold(0.0, f64::max);
    let keep: Vec<usize> = (0..k).filter(|&i| s[i] > tol * smax).collect();
    let mut x = Mat::zeros(a.ncols(), b.ncols());
    for &i in &keep {
        for c in 0..b.ncols() {
            let coef: f64 = (0..a.nrows()).map(|r| u[(r, i)] * b[(r, c)]).sum::<f64>() / s[i];
            for j in 0..a.ncols() {
                x[(j, c)] += v[(j, i)] * coef;
            }
        }
    }
    let smin = keep.iter().map(|&i| s[i]).fold(f64::INFINITY, f64::min);
    Ok((
        x,
        keep.len(),
        if keep.is_empty() {
            f64::INFINITY
        } else {
            smax / smin
        },
    ))
}

/// Leverages `h_i = [A (A^T A)^+ A^T]_ii = ||Q_i||^2` of the rows of `A`
/// (used by robust regression): `Q` = the first `rank` columns of the thin Q
/// of the column-pivoted QR, the numerical rank counted as in [`lstsq`]
/// (`|R_kk| > max(m, n) eps |R_00|`), so that a rank-deficient design gets
/// the leverages of its column space (summing to the rank, as MATLAB's
/// `robustfit` computes them from its pivoted QR).
pub fn leverages(a: MatRef<'_, f64>) -> Result<Vec<f64>, SolveError> {
    let (m, n) = (a.nrows(), a.ncols());
    if m == 0 || n == 0 {
        return Err(SolveError::Empty {
            what: "design matrix",
        });
    }
    check_finite("A", a)?;
    let qr = a.to_owned().col_piv_qr();
    let r = qr.thin_R();
    let tol = (m.max(n) as f64) * f64::EPSILON * r[(0, 0)].abs();
    let rank = (0..m.min(n)).filter(|&k| r[(k, k)].abs() > tol).count();
    let q = qr.compute_thin_Q();
    let mut h = vec![0.0; m];
    for j in 0..rank {
        let col = q.col(j);
        for (i, hi) in h.iter_mut().enumerate() {
            *hi += col[i] * col[i];
        }
    }
    Ok(h)
}
