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

use brdf_core::{DirPairs, Parametric};

use crate::SolveError;
use crate::problem::LeastSquaresProblem;
use crate::varpro::SeparableProblem;

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
        let linear = (0..specs.len()).filter(|k| specs[*k].linear).collect();
        let nonlinear = (0..specs.len()).filter(|k| !specs[*k].linear).collect();
        Ok(Self {
            model,
            pairs,
            targets,
            scale: scale.to_vec(),
            linear,
            nonlinear,
            base: model.params().to_vec(),
        })
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
        for (t, k) in self.linear.iter().enumerate() {
            p[*k] = c[t];
        }
        p
    }

    fn rows(&self) -> usize {
        self.pairs.len() * self.model.channels()
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
        let n = self.pairs.len();
        self.model.eval_batch_at(p, self.pairs, out);
        for (i, o) in out.iter_mut().enumerate() {
            *o = *o * self.scale[i % n] - self.targets[i];
        }
    }

    fn jacobian(&self, p: &[f64], jac: &mut [f64]) {
        let n = self.pairs.len();
        let np = p.len();
        let mut val = vec![0.0; self.rows()];
        self.model.eval_grad_batch_at(p, self.pairs, &mut val, jac);
        for i in 0..self.rows() {
            let s = self.scale[i % n];
            for v in &mut jac[i * np..(i + 1) * np] {
                *v *= s;
            }
        }
    }
}

impl SeparableProblem for ModelProblem<'_> {
    fn n_nonlinear(&self) -> usize {
        self.nonlinear.len()
    }

    fn n_linear(&self) -> usize {
        self.linear.len()
    }

    fn n_rows(&self) -> usize {
        self.rows()
    }

    fn targets(&self) -> &[f64] {
        &self.targets
    }

    fn basis(&self, a: &[f64], phi: &mut [f64], dphi: Option<&mut [f64]>) {
        let (m, n) = (self.rows(), self.pairs.len());
        let np = self.model.n_params();
        let nl = self.linear.len();
        let mut val = vec![0.0; m];
        let mut jac = vec![0.0; m * np];
        match dphi {
            None => {
                // One gradient evaluation gives every basis column.
                let p = self.assemble(a, &vec![0.0; nl]);
                self.model
                    .eval_grad_batch_at(&p, self.pairs, &mut val, &mut jac);
                for (t, k) in self.linear.iter().enumerate() {
                    for i in 0..m {
                        phi[t * m + i] = jac[i * np + k] * self.scale[i % n];
                    }
                }
            }
            Some(dphi) => {
                // Column t of Phi is the model with c = e_t; its gradient
                // with respect to a gives dPhi_t/da.
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
