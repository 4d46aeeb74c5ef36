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
//! computed with the QR `Phi_F = Q R_F` of the columns that are free at
//! `c(a)` (for NNLS the active coefficients are zero and stay fixed):
//! `P_perp v = v - Q Q^T v`, `(Phi^+)^T w = Q R_F^-T w`; both in one pass as
//! `v - Phi_F (R_F^T R_F)^-1 (Phi_F^T v + w)`.
//!
//! Several right-hand sides may share one basis (`n_blocks`: the colour
//! channels of a model whose channels share their basis functions): the
//! problem is then block-diagonal, `r_b(a) = Phi(a) c_b - y_b`, and `Phi` is
//! factored once for all blocks. With `m` rows and `l` columns only
//! `[Phi | Y]`'s `(l + B)`-square triangle is formed
//! ([`crate::tall_qr`]); each block's (non-negative) least-squares problem
//! is solved on that triangle, and the Jacobian uses
//! `Q = Phi_F R_F^-1`, so neither `Q` nor the zero blocks are ever stored.
//!
//! [`VarPro`] turns any [`SeparableProblem`] into a [`LeastSquaresProblem`]
//! over `a` alone, so every solver of this crate (LM, bounded, multi-start)
//! fits it.

use faer::Mat;

use crate::problem::{LeastSquaresProblem, fd_jacobian};
use crate::scratch::ScratchPool;
use crate::{LstsqMethod, SolveError, lstsq, nnls, tall_qr};

/// A separable least-squares problem: residual rows `Phi(a) c_b - y_b` for
/// each of `n_blocks` right-hand sides sharing the basis `Phi`.
pub trait SeparableProblem {
    /// Number of non-linear parameters `a`.
    fn n_nonlinear(&self) -> usize;
    /// Number of linear coefficients per block (columns of `Phi`).
    fn n_linear(&self) -> usize;
    /// Number of rows of `Phi` (rows per block).
    fn n_rows(&self) -> usize;
    /// Number of right-hand sides sharing `Phi` (default 1).
    fn n_blocks(&self) -> usize {
        1
    }
    /// The targets, block after block (length `n_blocks * n_rows`).
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
    /// Basis buffers reused across evaluations.
    pool: ScratchPool,
}

/// `[Phi | Y]` reduced to its triangle: `R` (`l x l`) and `Q^T y_b`.
struct Reduced {
    r: Mat<f64>,
    qty: Vec<Vec<f64>>,
}

impl<'a, S: SeparableProblem + ?Sized> VarPro<'a, S> {
    /// Wrap `problem`; `nonneg` makes every linear coefficient `>= 0`.
    pub fn new(problem: &'a S, nonneg: bool) -> Self {
        Self {
            problem,
            nonneg,
            pool: ScratchPool::new(),
        }
    }

    fn dims(&self) -> (usize, usize, usize) {
        let p = self.problem;
        (p.n_rows(), p.n_linear(), p.n_blocks())
    }

    /// The optimal linear coefficients at `a`, block after block
    /// (`c[b * n_linear + t]`).
    pub fn linear_coefficients(&self, a: &[f64]) -> Result<Vec<f64>, SolveError> {
        let (m, l, _) = self.dims();
        self.pool.with(m * l, |phi| {
            self.problem.basis(a, phi, None);
            self.solve_linear(phi)
        })
    }

    /// The optimal linear coefficients at `a` within the box
    /// `lower <= c <= upper` (one entry per coefficient of every block;
    /// infinite ends impose nothing; with `nonneg` the lower ends are at
    /// least 0), by least squares with inequality constraints
    /// ([`crate::lsi`](fn@crate::lsi)) on each block's reduced triangle. For a stage that
    /// fixes `a` and must return coefficients inside the model's box, which
    /// NNLS alone does not guarantee (it knows no upper bounds).
    pub fn linear_coefficients_in_box(
        &self,
        a: &[f64],
        lower: &[f64],
        upper: &[f64],
    ) -> Result<Vec<f64>, SolveError> {
        let (m, l, nb) = self.dims();
        if lower.len() != l * nb || upper.len() != l * nb {
            return Err(SolveError::Dimension {
                what: "box ends vs linear coefficients",
                left: lower.len().min(upper.len()),
                right: l * nb,
            });
        }
        let red = self.pool.with(m * l, |phi| {
            self.problem.basis(a, phi, None);
            self.reduce(phi)
        })?;
        let mut out = Vec::with_capacity(l * nb);
        for b in 0..nb {
            // The ends of coefficient j (infinite ends impose nothing).
            let lo = |j: usize| {
                let v = lower[b * l + j];
                if self.nonneg { v.max(0.0) } else { v }
            };
            let hi = |j: usize| upper[b * l + j];
            // Rows of G x >= h: x_j >= lo_j and -x_j >= -hi_j for finite ends.
            let mut rows: Vec<(usize, f64, f64)> = Vec::new();
            for j in 0..l {
                if lo(j).is_finite() {
                    rows.push((j, 1.0, lo(j)));
                }
                if hi(j).is_finite() {
                    rows.push((j, -1.0, -hi(j)));
                }
            }
            let g = Mat::from_fn(
                rows.len(),
                l,
                |i, j| if rows[i].0 == j { rows[i].1 } else { 0.0 },
            );
            let h: Vec<f64> = rows.iter().map(|r| r.2).collect();
            let x = crate::lsi(red.r.as_ref(), &red.qty[b], g.as_ref(), &h)?;
            // LSI's reduction to a least-distance problem meets an active
            // bound only to rounding (1 - 1.9e-14 for an upper bound of 1):
            // such a coefficient is set on its bound, so the report says it
            // sits there.
            out.extend(x.iter().enumerate().map(|(j, &v)| {
                let near = |bound: f64| {
                    bound.is_finite()
                        && (v - bound).abs() <= ACTIVE_BOUND_RTOL * bound.abs().max(1.0)
                };
                if v <= lo(j) || near(lo(j)) {
                    lo(j)
                } else if v >= hi(j) || near(hi(j)) {
                    hi(j)
                } else {
                    v
                }
            }));
        }
        Ok(out)
    }

    /// Factor `[Phi | Y]`.
    fn reduce(&self, phi: &[f64]) -> Result<Reduced, SolveError> {
        let (m, l, nb) = self.dims();
        let y = self.problem.targets();
        if let Some(i) = phi.iter().position(|v| !v.is_finite()) {
            return Err(SolveError::NonFinite {
                what: "basis",
                row: i % m.max(1),
                col: i / m.max(1),
                value: phi[i],
            });
        }
        let pm = faer::MatRef::from_column_major_slice(&phi[..m * l], m, l);
        let ym = faer::MatRef::from_column_major_slice(&y[..m * nb], m, nb);
        if let Some((r, qty)) = tall_qr::gram_triangle(pm, ym) {
            let qty = (0..nb)
                .map(|b| (0..l).map(|i| qty[(i, b)]).collect())
                .collect();
            return Ok(Reduced { r, qty });
        }
        let raug = self.pool.with(m * (l + nb), |buf| {
            buf[..m * l].copy_from_slice(&phi[..m * l]);
            buf[m * l..].copy_from_slice(&y[..m * nb]);
            tall_qr::r_factor(faer::MatMut::from_column_major_slice_mut(buf, m, l + nb))
        });
        let rows = raug.nrows().min(l);
        let r = Mat::from_fn(l, l, |i, k| if i < rows { raug[(i, k)] } else { 0.0 });
        let qty = (0..nb)
            .map(|b| {
                (0..l)
                    .map(|i| if i < rows { raug[(i, l + b)] } else { 0.0 })
                    .collect()
            })
            .collect();
        Ok(Reduced { r, qty })
    }

    fn solve_linear(&self, phi: &[f64]) -> Result<Vec<f64>, SolveError> {
        self.solve_from(&self.reduce(phi)?)
    }

    /// Residual rows `Phi c_b - y_b` of every block into `out`.
    fn combine(&self, phi: &[f64], c: &[f64], out: &mut [f64]) {
        let (m, l, nb) = self.dims();
        let y = self.problem.targets();
        for b in 0..nb {
            let o = &mut out[b * m..(b + 1) * m];
            o.copy_from_slice(&y[b * m..(b + 1) * m]);
            o.iter_mut().for_each(|v| *v = -*v);
            for t in 0..l {
                let ct = c[b * l + t];
                if ct != 0.0 {
                    let col = &phi[t * m..(t + 1) * m];
                    for i in 0..m {
                        o[i] += col[i] * ct;
                    }
                }
            }
        }
    }
}

impl<S: SeparableProblem + ?Sized> LeastSquaresProblem for VarPro<'_, S> {
    fn n_params(&self) -> usize {
        self.problem.n_nonlinear()
    }

    fn n_residuals(&self) -> usize {
        self.problem.n_rows() * self.problem.n_blocks()
    }

    fn residuals(&self, a: &[f64], out: &mut [f64]) {
        let (m, l, _) = self.dims();
        self.pool.with(m * l, |phi| {
            self.problem.basis(a, phi, None);
            match self.solve_linear(phi) {
                Ok(c) => self.combine(phi, &c, out),
                Err(_) => out.fill(f64::NAN),
            }
        })
    }

    fn jacobian(&self, a: &[f64], jac: &mut [f64]) {
        let (m, l, _) = self.dims();
        let n = self.problem.n_nonlinear();
        let done = self.pool.with(m * l, |phi| {
            self.pool.with(n * m * l, |dphi| {
                self.problem.basis(a, phi, Some(dphi));
                self.golub_pereyra(phi, dphi, jac)
            })
        });
        if !done {
            fd_jacobian(self, a, jac);
        }
    }
}

impl<S: SeparableProblem + ?Sized> VarPro<'_, S> {
    /// The full Golub-Pereyra Jacobian into `jac`; false when it is not
    /// defined by the formula (failed solve, rank-deficient free columns).
    fn golub_pereyra(&self, phi: &[f64], dphi: &[f64], jac: &mut [f64]) -> bool {
        let (m, _, nb) = self.dims();
        let Ok(red) = self.reduce(phi) else {
            return false;
        };
        let Ok(c) = self.solve_from(&red) else {
            return false;
        };
        self.pool.with(m * nb, |r| {
            self.combine(phi, &c, r);
            self.golub_pereyra_columns(phi, dphi, &red, &c, r, jac)
        })
    }

    /// The Jacobian columns of every block from the reduced basis, the
    /// coefficients `c` and the residuals `r` at `a`. Called once per
    /// Jacobian of every start: its buffers come from the pool, and the
    /// small triangular solves are done in place (no matrix per column).
    fn golub_pereyra_columns(
        &self,
        phi: &[f64],
        dphi: &[f64],
        red: &Reduced,
        c: &[f64],
        r: &[f64],
        jac: &mut [f64],
    ) -> bool {
        let (m, l, nb) = self.dims();
        let n = self.problem.n_nonlinear();
        let mut free = Vec::with_capacity(l);
        let mut z = vec![0.0; l];
        self.pool.with(m, |u| {
            for b in 0..nb {
                let cb = &c[b * l..(b + 1) * l];
                let rb = &r[b * m..(b + 1) * m];
                // Free columns: all for least squares, the positive ones for NNLS.
                free.clear();
                free.extend((0..l).filter(|j| !self.nonneg || cb[*j] > 0.0));
                let refactored;
                let rf = if free.is_empty() {
                    None
                } else if free.len() == l {
                    Some(&red.r)
                } else {
                    let mut sub = Mat::from_fn(l, free.len(), |i, s| red.r[(i, free[s])]);
                    refactored = tall_qr::r_factor(sub.as_mut());
                    Some(&refactored)
                };
                if rf.is_some_and(|rf| !well_conditioned(rf, free.len())) {
                    return false;
                }
                for k in 0..n {
                    let dk = &dphi[k * m * l..(k + 1) * m * l];
                    u.fill(0.0);
                    for t in 0..l {
                        if cb[t] != 0.0 {
                            let col = &dk[t * m..(t + 1) * m];
                            for i in 0..m {
                                u[i] += col[i] * cb[t];
                            }
                        }
                    }
                    if let Some(rf) = rf {
                        // v = Phi_F^T u + dPhi_kF^T r, z = R_F^-1 R_F^-T v.
                        let z = &mut z[..free.len()];
                        for (s, zs) in z.iter_mut().enumerate() {
                            let (pc, dc) = (&phi[free[s] * m..], &dk[free[s] * m..]);
                            *zs = (0..m).map(|i| pc[i] * u[i] + dc[i] * rb[i]).sum::<f64>();
                        }
                        solve_normal_in_place(rf, z);
                        for (s, &t) in free.iter().enumerate() {
                            let col = &phi[t * m..(t + 1) * m];
                            let zs = z[s];
                            for i in 0..m {
                                u[i] -= col[i] * zs;
                            }
                        }
                    }
                    for i in 0..m {
                        jac[(b * m + i) * n + k] = u[i];
                    }
                }
            }
            true
        })
    }

    fn solve_from(&self, red: &Reduced) -> Result<Vec<f64>, SolveError> {
        let (_, l, nb) = self.dims();
        let mut out = Vec::with_capacity(l * nb);
        for b in 0..nb {
            if self.nonneg {
                // When the unconstrained solution is positive it is the NNLS
                // solution (every coefficient passive, zero dual): one
                // triangular solve instead of the active-set loop.
                match positive_triangular_solution(&red.r, &red.qty[b]) {
                    Some(x) => out.extend(x),
                    None => out.extend(nnls(red.r.as_ref(), &red.qty[b], 3 * l + 10)?.x),
                }
            } else {
                let ym = Mat::from_fn(l, 1, |i, _| red.qty[b][i]);
                let s = lstsq(red.r.as_ref(), ym.as_ref(), None, LstsqMethod::PivotedQr)?;
                out.extend((0..l).map(|j| s.x[(j, 0)]));
            }
        }
        Ok(out)
    }
}

/// Whether the `nf x nf` triangle `r` is numerically non-singular (every
/// diagonal entry above `1e-12` times the largest); where it is not, the
/// projector's derivative is not given by the formula.
fn well_conditioned(r: &Mat<f64>, nf: usize) -> bool {
    if r.nrows() < nf || r.ncols() < nf {
        return false;
    }
    let rmax = (0..nf).map(|t| r[(t, t)].abs()).fold(0.0f64, f64::max);
    (0..nf).all(|t| r[(t, t)].abs() > 1e-12 * rmax)
}

/// `z <- R^-1 R^-T z` for the upper triangle `R` (its leading `z.len()`
/// square): the normal-equation solve of the free columns, by forward and
/// back substitution in place.
fn solve_normal_in_place(r: &Mat<f64>, z: &mut [f64]) {
    let nf = z.len();
    for i in 0..nf {
        let mut t = z[i];
        for j in 0..i {
            t -= r[(j, i)] * z[j];
        }
        z[i] = t / r[(i, i)];
    }
    for i in (0..nf).rev() {
        let mut t = z[i];
        for j in i + 1..nf {
            t -= r[(i, j)] * z[j];
        }
        z[i] = t / r[(i, i)];
    }
}

/// Relative distance to a bound within which an LSI coefficient is taken
/// to sit on it (the rounding of the least-distance reduction, far below
/// any difference a fit could resolve).
const ACTIVE_BOUND_RTOL: f64 = 1e-12;

/// The solution of the triangular system `R x = q` when `R` is numerically
/// non-singular (every diagonal entry above `1e-12` times the largest) and
/// every entry of `x` is positive; `None` otherwise.
fn positive_triangular_solution(r: &Mat<f64>, q: &[f64]) -> Option<Vec<f64>> {
    let l = r.ncols();
    if r.nrows() != l || q.len() != l {
        return None;
    }
    let rmax = (0..l).map(|t| r[(t, t)].abs()).fold(0.0f64, f64::max);
    if (0..l).any(|t| !(r[(t, t)].abs() > 1e-12 * rmax)) {
        return None;
    }
    let mut z = Mat::from_fn(l, 1, |i, _| q[i]);
    r.as_ref().solve_upper_triangular_in_place(z.as_mut());
    let x: Vec<f64> = (0..l).map(|i| z[(i, 0)]).collect();
    x.iter().all(|v| *v > 0.0 && v.is_finite()).then_some(x)
}
