//! The Jacobian at an iterate reduced to what every damped step needs, and
//! the damped step itself (see the parent module's doc for the method).

use faer::Mat;
use faer::linalg::solvers::SolveLstsq;

use super::all_finite;
use crate::{lsi, tall_qr};

/// Rows per tile of the Jacobian's copy into the QR workspace.
const TRANSPOSE_TILE: usize = 64;

/// The Jacobian at the current point, reduced to what a step needs: the
/// triangle `R` of `J = Q R`, `Q^T r`, the column norms `||J_k|| = ||R_k||`
/// and the gradient `g = J^T r = R^T Q^T r`. Every damped step is then a
/// `2n x n` problem, whatever the number of residuals.
pub(super) struct Factored {
    pub(super) r: Mat<f64>,
    pub(super) qtr: Vec<f64>,
    pub(super) colnorm: Vec<f64>,
    pub(super) g: Vec<f64>,
}

impl Factored {
    /// Reduce `[J | r]` (`jac` row-major): by the guarded normal equations
    /// where they are accurate, else by QR in `ws`, the reused `m x (n+1)`
    /// workspace ([`tall_qr`]).
    pub(super) fn new(jac: &[f64], r: &[f64], n: usize, ws: &mut Option<Mat<f64>>) -> Self {
        Self::by_normal_equations(jac, r, n).unwrap_or_else(|| Self::by_qr(jac, r, n, ws))
    }

    /// The guarded normal equations; `None` where they are not accurate
    /// (or `J` is not finite: a non-finite entry makes the Gram matrix
    /// non-finite, which the guard refuses).
    pub(super) fn by_normal_equations(jac: &[f64], r: &[f64], n: usize) -> Option<Self> {
        let m = r.len();
        let jm = faer::MatRef::from_row_major_slice(jac, m, n);
        let rm = faer::MatRef::from_column_major_slice(r, m, 1);
        let (rr, qtr) = tall_qr::gram_triangle(jm, rm)?;
        Some(Self::from_triangle(
            rr,
            (0..n).map(|i| qtr[(i, 0)]).collect(),
        ))
    }

    /// The guarded normal equations a problem formed in its residual pass
    /// (`gram`: the `(n+1) x (n+1)` row-major Gram matrix of `[J | r]`);
    /// `None` where they are not accurate. Exactly zero columns (a
    /// parameter without influence at this point, such as a tint whose lobe
    /// is off) do not send the rest of the solve to the stored Jacobian and
    /// QR: they get zero rows and columns in `R`, as in QR's.
    pub(super) fn from_gram(gram: &[f64], n: usize) -> Option<Self> {
        let w = n + 1;
        let g = Mat::from_fn(n, n, |i, k| gram[i * w + k]);
        let h = Mat::from_fn(n, 1, |i, _| gram[i * w + n]);
        let (rr, qtr) = tall_qr::triangle_from_gram_with_zero_columns(g.as_ref(), h)?;
        Some(Self::from_triangle(
            rr,
            (0..n).map(|i| qtr[(i, 0)]).collect(),
        ))
    }

    /// Householder QR of `[J | r]` in `ws` (allocated on first use).
    pub(super) fn by_qr(jac: &[f64], r: &[f64], n: usize, ws: &mut Option<Mat<f64>>) -> Self {
        let m = r.len();
        let ws = ws.get_or_insert_with(|| Mat::<f64>::zeros(m, n + 1));
        // The row-major Jacobian into the columns, a tile of rows at a
        // time: each tile is read once, contiguously, where a column at a
        // time read the whole Jacobian `n` entries apart, once per column
        // (most of this function's time on an RGB model of 30 parameters).
        for i0 in (0..m).step_by(TRANSPOSE_TILE) {
            let rows = TRANSPOSE_TILE.min(m - i0);
            let tile = &jac[i0 * n..(i0 + rows) * n];
            for k in 0..n {
                let col = ws
                    .col_mut(k)
                    .try_as_col_major_mut()
                    .map(|c| c.as_slice_mut());
                if let Some(col) = col {
                    for (v, row) in col[i0..i0 + rows].iter_mut().zip(tile.chunks_exact(n)) {
                        *v = row[k];
                    }
                }
            }
        }
        if let Some(col) = ws.col_mut(n).try_as_col_major_mut() {
            col.as_slice_mut().copy_from_slice(r);
        }
        let raug = tall_qr::r_factor(ws.as_mut());
        let rows = raug.nrows().min(n);
        let rr = Mat::from_fn(n, n, |i, k| if i < rows { raug[(i, k)] } else { 0.0 });
        let qtr: Vec<f64> = (0..n)
            .map(|i| if i < rows { raug[(i, n)] } else { 0.0 })
            .collect();
        debug_assert!(m >= n);
        Self::from_triangle(rr, qtr)
    }

    /// The column norms and gradient from `R` and `Q^T r`.
    fn from_triangle(rr: Mat<f64>, qtr: Vec<f64>) -> Self {
        let n = qtr.len();
        let colnorm = (0..n)
            .map(|k| (0..=k).map(|i| rr[(i, k)].powi(2)).sum::<f64>().sqrt())
            .collect();
        let g = (0..n)
            .map(|k| (0..=k).map(|i| rr[(i, k)] * qtr[i]).sum())
            .collect();
        Factored {
            r: rr,
            qtr,
            colnorm,
            g,
        }
    }

    /// The damped step `min ||R d + Q^T r||^2 + lambda ||D d||^2` (subject to
    /// `G d >= h` when constrained) and its predicted cost reduction.
    pub(super) fn step(
        &self,
        d: &[f64],
        lambda: f64,
        constrained: Option<(&Mat<f64>, &[f64])>,
    ) -> Option<(Vec<f64>, f64)> {
        let n = d.len();
        let sl = lambda.sqrt();
        let e = Mat::from_fn(2 * n, n, |i, k| {
            if i < n {
                self.r[(i, k)]
            } else if i - n == k {
                sl * d[k]
            } else {
                0.0
            }
        });
        let f: Vec<f64> = (0..2 * n)
            .map(|i| if i < n { -self.qtr[i] } else { 0.0 })
            .collect();
        let delta = match constrained {
            Some((gmat, h)) => lsi::lsi(e.as_ref(), &f, gmat.as_ref(), h).ok()?,
            None => {
                let fm = Mat::from_fn(2 * n, 1, |i, _| f[i]);
                let s = e.qr().solve_lstsq(&fm);
                (0..n).map(|k| s[(k, 0)]).collect()
            }
        };
        if !all_finite(&delta) {
            return None;
        }
        Some((delta.clone(), self.predicted_reduction(&delta)))
    }

    /// `cost - 1/2 ||r + J d||^2 = 1/2 (||Q^T r||^2 - ||R d + Q^T r||^2)`.
    fn predicted_reduction(&self, delta: &[f64]) -> f64 {
        let n = delta.len();
        let mut before = 0.0;
        let mut after = 0.0;
        for i in 0..n {
            let rd: f64 = (i..n).map(|k| self.r[(i, k)] * delta[k]).sum();
            before += self.qtr[i] * self.qtr[i];
            after += (rd + self.qtr[i]).powi(2);
        }
        0.5 * (before - after)
    }
}
