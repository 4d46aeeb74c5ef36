//! Variable projection (Golub & Pereyra 1973) for separable problems
//! `min_{a, c} ||y - Phi(a) c||^2`, with the linear coefficients `c`
//! optionally non-negative (Ngan et al. 2005 and Kurt 2007 project `kd`,
//! `ks` out this way).
//!
//! For given non-linear parameters `a`, `c(a)` is the (non-negative) least
//! squares solution and the reduced residual is `r(a) = Phi c(a) - y =
//! -P_perp y`. Its Jacobian is the full Golub-Pereyra one (not Kaufman's
//! approximation):
//!
//! `dr/da_k = P_perp (dPhi/da_k) c - (Phi^+)^T (dPhi/da_k)^T r`,
//!
//! computed with the thin QR `Phi_P = Q R` of the columns that are free at
//! `c(a)` (for NNLS the active coefficients are zero and stay fixed):
//! `P_perp v = v - Q Q^T v`, `(Phi^+)^T w = Q R^-T w`.
//!
//! [`VarPro`] turns any [`SeparableProblem`] into a [`LeastSquaresProblem`]
//! over `a` alone, so every solver of this crate (LM, bounded, multi-start)
//! fits it.

use std::cell::RefCell;

use faer::Mat;

use crate::problem::{LeastSquaresProblem, fd_jacobian};
use crate::{LstsqMethod, SolveError, lstsq, nnls};

/// A separable least-squares problem: residual rows `Phi(a) c - y`.
pub trait SeparableProblem {
    /// Number of non-linear parameters `a`.
    fn n_nonlinear(&self) -> usize;
    /// Number of linear coefficients `c` (columns of `Phi`).
    fn n_linear(&self) -> usize;
    /// Number of rows.
    fn n_rows(&self) -> usize;
    /// The targets `y` (length `n_rows`).
    fn targets(&self) -> &[f64];
    /// `Phi(a)` column-major into `phi` (`n_rows * n_linear`); when `dphi`
    /// is given, `dPhi/da_k` into `dphi[k * n_rows * n_linear ..]`, each
    /// column-major.
    fn basis(&self, a: &[f64], phi: &mut [f64], dphi: Option<&mut [f64]>);
}

/// The reduced problem over the non-linear parameters.
pub struct VarPro<'a, S: SeparableProblem + ?Sized> {
    problem: &'a S,
    nonneg: bool,
    /// The basis buffer reused by `residuals` (one allocation per problem).
    phi: RefCell<Vec<f64>>,
}

impl<'a, S: SeparableProblem + ?Sized> VarPro<'a, S> {
    /// Wrap `problem`; `nonneg` makes every linear coefficient `>= 0`.
    pub fn new(problem: &'a S, nonneg: bool) -> Self {
        let (m, l) = (problem.n_rows(), problem.n_linear());
        Self {
            problem,
            nonneg,
            phi: RefCell::new(vec![0.0; m * l]),
        }
    }

    /// The optimal linear coefficients at `a`.
    pub fn linear_coefficients(&self, a: &[f64]) -> Result<Vec<f64>, SolveError> {
        let mut phi = self.phi.borrow_mut();
        self.problem.basis(a, &mut phi, None);
        self.solve_linear(&phi)
    }

    /// The optimal linear coefficients at `a` within the box
    /// `lower <= c <= upper` (infinite ends impose nothing; with `nonneg`
    /// the lower ends are at least 0), by least squares with inequality
    /// constraints ([`crate::lsi`]). For a stage that fixes `a` and must
    /// return coefficients inside the model's box, which NNLS alone does
    /// not guarantee (it knows no upper bounds).
    pub fn linear_coefficients_in_box(
        &self,
        a: &[f64],
        lower: &[f64],
        upper: &[f64],
    ) -> Result<Vec<f64>, SolveError> {
        let (m, l) = (self.problem.n_rows(), self.problem.n_linear());
        if lower.len() != l || upper.len() != l {
            return Err(SolveError::Dimension {
                what: "box ends vs linear coefficients",
                left: lower.len().min(upper.len()),
                right: l,
            });
        }
        let mut phi = self.phi.borrow_mut();
        self.problem.basis(a, &mut phi, None);
        let e = Mat::from_fn(m, l, |i, j| phi[j * m + i]);
        // Rows of G x >= h: x_j >= lo_j and -x_j >= -hi_j for finite ends.
        let mut rows: Vec<(usize, f64, f64)> = Vec::new();
        for j in 0..l {
            let lo = if self.nonneg {
                lower[j].max(0.0)
            } else {
                lower[j]
            };
            if lo.is_finite() {
                rows.push((j, 1.0, lo));
            }
            if upper[j].is_finite() {
                rows.push((j, -1.0, -upper[j]));
            }
        }
        let g = Mat::from_fn(
            rows.len(),
            l,
            |i, j| if rows[i].0 == j { rows[i].1 } else { 0.0 },
        );
        let h: Vec<f64> = rows.iter().map(|r| r.2).collect();
        crate::lsi(e.as_ref(), self.problem.targets(), g.as_ref(), &h)
    }

    fn solve_linear(&self, phi: &[f64]) -> Result<Vec<f64>, SolveError> {
        let (m, l) = (self.problem.n_rows(), self.problem.n_linear());
        let pm = Mat::from_fn(m, l, |i, j| phi[j * m + i]);
        let y = self.problem.targets();
        if self.nonneg {
            Ok(nnls(pm.as_ref(), y, 3 * l + 10)?.x)
        } else {
            let ym = Mat::from_fn(m, 1, |i, _| y[i]);
            let s = lstsq(pm.as_ref(), ym.as_ref(), None, LstsqMethod::PivotedQr)?;
            Ok((0..l).map(|j| s.x[(j, 0)]).collect())
        }
    }
}

impl<S: SeparableProblem + ?Sized> LeastSquaresProblem for VarPro<'_, S> {
    fn n_params(&self) -> usize {
        self.problem.n_nonlinear()
    }

    fn n_residuals(&self) -> usize {
        self.problem.n_rows()
    }

    fn residuals(&self, a: &[f64], out: &mut [f64]) {
        let (m, l) = (self.problem.n_rows(), self.problem.n_linear());
        let mut phi = self.phi.borrow_mut();
        self.problem.basis(a, &mut phi, None);
        if phi.iter().any(|v| !v.is_finite()) {
            out.fill(f64::NAN);
            return;
        }
        match self.solve_linear(&phi) {
            Ok(c) => {
                let y = self.problem.targets();
                for i in 0..m {
                    out[i] = (0..l).map(|j| phi[j * m + i] * c[j]).sum::<f64>() - y[i];
                }
            }
            Err(_) => out.fill(f64::NAN),
        }
    }

    fn jacobian(&self, a: &[f64], jac: &mut [f64]) {
        let (m, l, n) = (
            self.problem.n_rows(),
            self.problem.n_linear(),
            self.problem.n_nonlinear(),
        );
        let mut phi = vec![0.0; m * l];
        let mut dphi = vec![0.0; n * m * l];
        self.problem.basis(a, &mut phi, Some(&mut dphi));
        let Ok(c) = self.solve_linear(&phi) else {
            jac.fill(f64::NAN);
            return;
        };
        let y = self.problem.targets();
        let r: Vec<f64> = (0..m)
            .map(|i| (0..l).map(|j| phi[j * m + i] * c[j]).sum::<f64>() - y[i])
            .collect();
        // Free columns: all for least squares, the positive ones for NNLS.
        let free: Vec<usize> = (0..l).filter(|j| !self.nonneg || c[*j] > 0.0).collect();
        let nf = free.len();
        let (q, rr) = if nf > 0 {
            let pm = Mat::from_fn(m, nf, |i, t| phi[free[t] * m + i]);
            let qr = pm.qr();
            let rr = qr.thin_R().to_owned();
            let rmax = (0..nf).map(|t| rr[(t, t)].abs()).fold(0.0f64, f64::max);
            if (0..nf).any(|t| rr[(t, t)].abs() <= 1e-12 * rmax) {
                // Rank-deficient free columns: the projector's derivative is
                // not defined by this formula; use differences instead.
                drop(rr);
                fd_jacobian(self, a, jac);
                return;
            }
            (Some(qr.compute_thin_Q()), Some(rr))
        } else {
            (None, None)
        };
        for k in 0..n {
            let dk = &dphi[k * m * l..(k + 1) * m * l];
            // u = dPhi_k c, w = dPhi_k^T r (free columns only).
            let mut u: Vec<f64> = (0..m)
                .map(|i| (0..l).map(|j| dk[j * m + i] * c[j]).sum())
                .collect();
            let mut col = vec![0.0; m];
            if let (Some(q), Some(rr)) = (&q, &rr) {
                // P_perp u.
                let qtu: Vec<f64> = (0..nf)
                    .map(|t| (0..m).map(|i| q[(i, t)] * u[i]).sum())
                    .collect();
                for i in 0..m {
                    u[i] -= (0..nf).map(|t| q[(i, t)] * qtu[t]).sum::<f64>();
                }
                // z = R^-T w, then Q z.
                let mut z = Mat::from_fn(nf, 1, |t, _| {
                    (0..m).map(|i| dk[free[t] * m + i] * r[i]).sum::<f64>()
                });
                rr.as_ref()
                    .transpose()
                    .solve_lower_triangular_in_place(z.as_mut());
                for i in 0..m {
                    col[i] = u[i] - (0..nf).map(|t| q[(i, t)] * z[(t, 0)]).sum::<f64>();
                }
            } else {
                col.copy_from_slice(&u);
            }
            for i in 0..m {
                jac[i * n + k] = col[i];
            }
        }
    }
}
