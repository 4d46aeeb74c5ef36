//! Fitting problems built from any [`Parametric`] model and a set of
//! samples: the full non-linear least-squares problem over every parameter
//! ([`ModelProblem`]), and its separable form for variable projection
//! ([`ModelProblem`] also implements [`SeparableProblem`]: the parameters
//! the model declares linear are the coefficients, the others are `a`).
//!
//! Rows are `c * n + j` (channel-major, as `Parametric::eval_batch_at`):
//! residual `s_j (M_c(L_j, V_j; p) - y_cj)` with a per-sample row scale
//! `s_j` (e.g. `sqrt(w_j) cos_i_j` for Ngan's objective). The solvers know
//! nothing about which model this is: the basis columns of the linear
//! parameters are the model's own derivatives with respect to them, and
//! their derivatives with respect to the non-linear ones come from the
//! model's gradient evaluated with that linear parameter set to 1 and the
//! others to 0 (exact for models linear in their linear parameters, which
//! is what `ParamSpec::linear` declares).
//!
//! Models whose channels share one basis ([`SharedBasis`]) are evaluated
//! through it, over the sample set's [`PairGeometry`] computed once here:
//! the full problem's residuals and Jacobian combine the basis with the
//! coefficients, and the separable form has one block per channel sharing
//! one basis matrix (no zero blocks, one factorisation for all channels).
//!
//! Large sample sets (from 8192 samples on) are also cut into cache-sized
//! blocks once: their residuals, and the normal equations the solvers ask
//! for in the same pass
//! ([`LeastSquaresProblem::residuals_and_gram`]), are computed block by
//! block in parallel without storing the Jacobian.

mod blocked;

use brdf_core::{DirPairs, PairGeometry, Parametric, SharedBasis};

use crate::SolveError;
use crate::problem::LeastSquaresProblem;
use crate::scratch::ScratchPool;
use crate::varpro::SeparableProblem;

/// A residual transform applied row by row (log, cube-root objectives):
/// with one, row `i`'s residual is `apply(i, M_i).0` of the model value
/// `M_i` (row `c * n + j`), and its Jacobian row is the model's gradient
/// times `apply(i, M_i).1` (the row scales and targets are not used).
pub trait RowTransform: Send + Sync {
    /// Residual and its derivative in the model value, of row `row` at
    /// model value `m`.
    fn apply(&self, row: usize, m: f64) -> (f64, f64);
}

/// A model, samples and row scales: a least-squares problem.
pub struct ModelProblem<'a> {
    model: &'a dyn Parametric,
    pairs: &'a DirPairs,
    /// Scaled targets `s_j y_cj`, row `c * n + j`.
    targets: Vec<f64>,
    scale: Vec<f64>,
    linear: Vec<usize>,
    nonlinear: Vec<usize>,
    /// Parameter vector the split problem fills in.
    base: Vec<f64>,
    /// The model's channel-shared basis, with the geometry it reads.
    shared: Option<(&'a dyn SharedBasis, PairGeometry)>,
    /// Parameter index of each linear coefficient, in coefficient order.
    coefficients: Vec<usize>,
    pool: ScratchPool,
    /// The samples in cache-sized blocks (empty for small sets).
    blocks: Vec<blocked::Block>,
    /// Residual transform of every row ([`ModelProblem::with_transform`]).
    transform: Option<&'a dyn RowTransform>,
}

impl<'a> ModelProblem<'a> {
    /// `values[c * n + j]` measured, `scale[j]` row scales.
    pub fn new(
        model: &'a dyn Parametric,
        pairs: &'a DirPairs,
        values: &[f64],
        scale: &[f64],
    ) -> Result<Self, SolveError> {
        let n = pairs.len();
        let nc = model.channels();
        if n == 0 {
            return Err(SolveError::Empty { what: "samples" });
        }
        if values.len() != n * nc || scale.len() != n {
            return Err(SolveError::Dimension {
                what: "values (channels x samples) and scales vs samples",
                left: values.len(),
                right: n * nc,
            });
        }
        for (i, v) in values.iter().chain(scale).enumerate() {
            if !v.is_finite() {
                return Err(SolveError::NonFinite {
                    what: "values or row scales",
                    row: i,
                    col: 0,
                    value: *v,
                });
            }
        }
        let targets = (0..n * nc).map(|i| values[i] * scale[i % n]).collect();
        let specs = model.param_specs();
        let linear: Vec<usize> = (0..specs.len()).filter(|k| specs[*k].linear).collect();
        let nonlinear = (0..specs.len()).filter(|k| !specs[*k].linear).collect();
        let shared = model.shared_basis().map(|b| (b, PairGeometry::new(pairs)));
        let coefficients = match &shared {
            Some((b, _)) => (0..nc)
                .flat_map(|c| (0..b.basis_len()).map(move |t| b.coefficient_index(c, t)))
                .collect(),
            None => linear.clone(),
        };
        let blocks = if n >= blocked::MIN_SAMPLES {
            blocked::blocks(pairs, shared.is_some())
        } else {
            Vec::new()
        };
        Ok(Self {
            model,
            pairs,
            targets,
            scale: scale.to_vec(),
            linear,
            nonlinear,
            base: model.params().to_vec(),
            shared,
            coefficients,
            pool: ScratchPool::new(),
            blocks,
            transform: None,
        })
    }

    /// The problem with residuals transformed row by row ([`RowTransform`]);
    /// evaluated through the model's batch gradient (not its shared basis),
    /// with the fused blocked pass on large sets.
    pub fn with_transform(mut self, transform: &'a dyn RowTransform) -> Self {
        self.transform = Some(transform);
        if !self.blocks.is_empty() {
            self.blocks = blocked::blocks(self.pairs, false);
        }
        self
    }

    /// The channel-shared basis, when the problem is evaluated through it
    /// (not under a row transform).
    fn shared(&self) -> Option<&(&'a dyn SharedBasis, PairGeometry)> {
        self.shared.as_ref().filter(|_| self.transform.is_none())
    }

    /// Parameter index of each linear coefficient in the order of the
    /// separable form's coefficient vector (channel after channel for a
    /// model with a shared basis).
    pub fn coefficient_indices(&self) -> &[usize] {
        &self.coefficients
    }

    /// Indices of the linear parameters.
    pub fn linear_indices(&self) -> &[usize] {
        &self.linear
    }

    /// Indices of the non-linear parameters.
    pub fn nonlinear_indices(&self) -> &[usize] {
        &self.nonlinear
    }

    /// The full parameter vector from non-linear values `a` and linear `c`.
    pub fn assemble(&self, a: &[f64], c: &[f64]) -> Vec<f64> {
        let mut p = self.base.clone();
        for (t, k) in self.nonlinear.iter().enumerate() {
            p[*k] = a[t];
        }
        for (t, k) in self.coefficients.iter().enumerate() {
            p[*k] = c[t];
        }
        p
    }

    fn rows(&self) -> usize {
        self.pairs.len() * self.model.channels()
    }

    /// Residuals and Jacobian at `p` from one pass of the model's batch
    /// gradient, which yields the values with the derivatives: a caller
    /// that needs both (the image objective sums them into pixels) would
    /// otherwise evaluate the model twice, [`LeastSquaresProblem::residuals`]
    /// then [`LeastSquaresProblem::jacobian`]. Same rows as those two.
    pub fn residuals_and_jacobian(&self, p: &[f64], out: &mut [f64], jac: &mut [f64]) {
        if !self.blocks.is_empty() || self.shared().is_some() {
            // These paths have their own evaluation (cache blocks, the
            // shared basis): no single gradient pass to share.
            self.residuals(p, out);
            return self.jacobian(p, jac);
        }
        self.gradient_pass(p, out, jac);
    }

    /// One pass of the model's batch gradient at `p`: the residual rows
    /// (transformed or scaled, as [`LeastSquaresProblem::residuals`] forms
    /// them without blocks or a shared basis) into `out`, the Jacobian's
    /// rows scaled by each row's derivative into `jac`.
    fn gradient_pass(&self, p: &[f64], out: &mut [f64], jac: &mut [f64]) {
        let (n, np) = (self.pairs.len(), p.len());
        self.model.eval_grad_batch_at(p, self.pairs, out, jac);
        for (i, o) in out.iter_mut().enumerate() {
            let (r, s) = match self.transform {
                Some(t) => t.apply(i, *o),
                None => (*o * self.scale[i % n] - self.targets[i], self.scale[i % n]),
            };
            *o = r;
            for v in &mut jac[i * np..(i + 1) * np] {
                *v *= s;
            }
        }
    }

    /// Full residuals through the shared basis.
    fn shared_residuals(&self, sb: &(&dyn SharedBasis, PairGeometry), p: &[f64], out: &mut [f64]) {
        let (b, geom) = sb;
        let (n, nc, l) = (self.pairs.len(), self.model.channels(), b.basis_len());
        self.pool.with(l * n, |phi| {
            b.basis_batch(p, self.pairs, geom, phi, None);
            for c in 0..nc {
                let o = &mut out[c * n..(c + 1) * n];
                o.fill(0.0);
                for t in 0..l {
                    let x = p[self.coefficients[c * l + t]];
                    let col = &phi[t * n..(t + 1) * n];
                    for j in 0..n {
                        o[j] += x * col[j];
                    }
                }
                let y = &self.targets[c * n..(c + 1) * n];
                for j in 0..n {
                    o[j] = o[j] * self.scale[j] - y[j];
                }
            }
        })
    }

    /// Full Jacobian through the shared basis: `d/dx_{c,t} = s_j phi_t` on
    /// channel `c`'s rows, `d/dq_u = s_j sum_t x_{c,t} dphi_{t,u}`.
    fn shared_jacobian(&self, sb: &(&dyn SharedBasis, PairGeometry), p: &[f64], jac: &mut [f64]) {
        let (b, geom) = sb;
        let (n, nc, l) = (self.pairs.len(), self.model.channels(), b.basis_len());
        let (np, nq) = (p.len(), self.nonlinear.len());
        self.pool.with(l * n, |phi| {
            self.pool.with(l * nq * n, |dphi| {
                b.basis_batch(p, self.pairs, geom, phi, Some(dphi));
                // Row by row, so the row-major Jacobian is written in order
                // (each row set whole: no separate zeroing pass).
                for c in 0..nc {
                    let ks = &self.coefficients[c * l..(c + 1) * l];
                    let rows = jac[c * n * np..(c + 1) * n * np].chunks_exact_mut(np);
                    for (j, row) in rows.enumerate() {
                        let sj = self.scale[j];
                        row.fill(0.0);
                        for (t, &k) in ks.iter().enumerate() {
                            row[k] = phi[t * n + j] * sj;
                            let x = p[k] * sj;
                            for (u, &ku) in self.nonlinear.iter().enumerate() {
                                row[ku] += x * dphi[(t * nq + u) * n + j];
                            }
                        }
                    }
                }
            })
        })
    }
}

impl LeastSquaresProblem for ModelProblem<'_> {
    fn n_params(&self) -> usize {
        self.model.n_params()
    }

    fn n_residuals(&self) -> usize {
        self.rows()
    }

    fn residuals(&self, p: &[f64], out: &mut [f64]) {
        if !self.blocks.is_empty() {
            return self.blocked_pass(p, out, None);
        }
        if let Some(sb) = self.shared() {
            return self.shared_residuals(sb, p, out);
        }
        let n = self.pairs.len();
        self.model.eval_batch_at(p, self.pairs, out);
        if let Some(t) = self.transform {
            for (i, o) in out.iter_mut().enumerate() {
                *o = t.apply(i, *o).0;
            }
            return;
        }
        for (i, o) in out.iter_mut().enumerate() {
            *o = *o * self.scale[i % n] - self.targets[i];
        }
    }

    fn residuals_and_gram(&self, p: &[f64], out: &mut [f64], gram: &mut [f64]) -> bool {
        if self.blocks.is_empty() {
            return false;
        }
        self.blocked_pass(p, out, Some(gram));
        true
    }

    fn jacobian(&self, p: &[f64], jac: &mut [f64]) {
        if let Some(sb) = self.shared() {
            return self.shared_jacobian(sb, p, jac);
        }
        // The values the gradient pass yields are not needed here.
        self.pool
            .with(self.rows(), |val| self.gradient_pass(p, val, jac));
    }
}

impl SeparableProblem for ModelProblem<'_> {
    fn n_nonlinear(&self) -> usize {
        self.nonlinear.len()
    }

    fn n_linear(&self) -> usize {
        match &self.shared {
            Some((b, _)) => b.basis_len(),
            None => self.linear.len(),
        }
    }

    fn n_rows(&self) -> usize {
        match &self.shared {
            Some(_) => self.pairs.len(),
            None => self.rows(),
        }
    }

    fn n_blocks(&self) -> usize {
        match &self.shared {
            Some(_) => self.model.channels(),
            None => 1,
        }
    }

    fn targets(&self) -> &[f64] {
        &self.targets
    }

    fn basis(&self, a: &[f64], phi: &mut [f64], dphi: Option<&mut [f64]>) {
        let nl = self.n_linear();
        let p = self.assemble(a, &vec![0.0; self.coefficients.len()]);
        match &self.shared {
            Some(sb) => self.shared_basis_scaled(sb, &p, phi, dphi),
            None => self.general_basis(&p, a, phi, dphi, nl),
        }
    }
}

impl ModelProblem<'_> {
    /// The separable basis of a shared-basis model: row-scaled `phi`, and
    /// `dphi` in the separable layout `[u * n * L + t * n + j]`.
    fn shared_basis_scaled(
        &self,
        (b, geom): &(&dyn SharedBasis, PairGeometry),
        p: &[f64],
        phi: &mut [f64],
        dphi: Option<&mut [f64]>,
    ) {
        let (n, l, nq) = (self.pairs.len(), b.basis_len(), self.nonlinear.len());
        let scale_rows = |col: &mut [f64]| {
            for (v, s) in col.iter_mut().zip(&self.scale) {
                *v *= s;
            }
        };
        match dphi {
            None => b.basis_batch(p, self.pairs, geom, phi, None),
            Some(dphi) => self.pool.with(l * nq * n, |raw| {
                b.basis_batch(p, self.pairs, geom, phi, Some(raw));
                for t in 0..l {
                    for u in 0..nq {
                        let src = &raw[(t * nq + u) * n..(t * nq + u + 1) * n];
                        let dst = &mut dphi[u * n * l + t * n..u * n * l + (t + 1) * n];
                        dst.copy_from_slice(src);
                        scale_rows(dst);
                    }
                }
            }),
        }
        for col in phi.chunks_exact_mut(n) {
            scale_rows(col);
        }
    }

    /// The separable basis of any model, from its gradient: column `t` is the
    /// model with the `t`-th linear parameter 1 and the others 0.
    fn general_basis(
        &self,
        p0: &[f64],
        a: &[f64],
        phi: &mut [f64],
        dphi: Option<&mut [f64]>,
        nl: usize,
    ) {
        let (m, n) = (self.rows(), self.pairs.len());
        let np = self.model.n_params();
        let mut val = vec![0.0; m];
        let mut jac = vec![0.0; m * np];
        match dphi {
            None => {
                // One gradient evaluation gives every basis column.
                self.model
                    .eval_grad_batch_at(p0, self.pairs, &mut val, &mut jac);
                for (t, k) in self.linear.iter().enumerate() {
                    for i in 0..m {
                        phi[t * m + i] = jac[i * np + k] * self.scale[i % n];
                    }
                }
            }
            Some(dphi) => {
                let mut c = vec![0.0; nl];
                for t in 0..nl {
                    c.fill(0.0);
                    c[t] = 1.0;
                    let p = self.assemble(a, &c);
                    self.model
                        .eval_grad_batch_at(&p, self.pairs, &mut val, &mut jac);
                    for i in 0..m {
                        let s = self.scale[i % n];
                        phi[t * m + i] = val[i] * s;
                        for (u, k) in self.nonlinear.iter().enumerate() {
                            dphi[u * m * nl + t * m + i] = jac[i * np + k] * s;
                        }
                    }
                }
            }
        }
    }
}
