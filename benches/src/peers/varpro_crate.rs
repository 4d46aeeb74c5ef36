//! The `varpro` crate (variable projection on the `levenberg-marquardt`
//! crate, SVD for the linear subproblem) on a peer problem: non-linear
//! parameters of a `kd/pi + ks S` model from the start, the linear
//! coefficients solved without sign constraints (the crate has none); the
//! channels of an RGB problem share the basis and are fitted as multiple
//! right-hand sides. Weights are the row scales, so the crate minimises the
//! same `||s (y - Phi c)||^2`. The outcome says whether it left the box.
//!
//! The basis comes from the workspace's model: column `t` is the one-channel
//! model with linear parameter `t` set to 1 and the others to 0, and its
//! gradient gives the column's derivatives (one batch pass per column,
//! computed once per parameter change and kept for the derivative calls).

use std::cell::Cell;

use brdf_core::{DirPairs, Parametric};
use brdf_models::{ModelConfig, build};
use nalgebra034::{DMatrix, DVector, Dyn, OMatrix, OVector};
use varpro::model::SeparableNonlinearModel;
use varpro::problem::SeparableProblemBuilder;
use varpro::solvers::levmar::LevMarSolver;

use super::{Outcome, PeerError, PeerProblem, timed};

/// The model of a one-channel catalogue model's basis.
struct Basis<'a> {
    model: Box<dyn Parametric>,
    pairs: &'a DirPairs,
    linear: Vec<usize>,
    nonlinear: Vec<usize>,
    a: DVector<f64>,
    phi: DMatrix<f64>,
    /// `dphi[k]`: derivative of the basis with respect to non-linear `k`.
    dphi: Vec<DMatrix<f64>>,
    jacobians: Cell<usize>,
}

#[derive(Debug, thiserror::Error)]
#[error("varpro adapter: {0}")]
struct BasisError(String);

impl Basis<'_> {
    fn refresh(&mut self) {
        let n = self.pairs.len();
        let np = self.model.n_params();
        let mut val = vec![0.0; n];
        let mut jac = vec![0.0; n * np];
        let mut p = self.model.params().to_vec();
        for (u, k) in self.nonlinear.iter().enumerate() {
            p[*k] = self.a[u];
        }
        for t in 0..self.linear.len() {
            for (s, ls) in self.linear.iter().enumerate() {
                p[*ls] = if s == t { 1.0 } else { 0.0 };
            }
            self.model
                .eval_grad_batch_at(&p, self.pairs, &mut val, &mut jac);
            for j in 0..n {
                self.phi[(j, t)] = val[j];
                for (u, k) in self.nonlinear.iter().enumerate() {
                    self.dphi[u][(j, t)] = jac[j * np + k];
                }
            }
        }
    }
}

impl SeparableNonlinearModel for Basis<'_> {
    type ScalarType = f64;
    type Error = BasisError;

    fn parameter_count(&self) -> usize {
        self.nonlinear.len()
    }

    fn base_function_count(&self) -> usize {
        self.linear.len()
    }

    fn output_len(&self) -> usize {
        self.pairs.len()
    }

    fn set_params(&mut self, parameters: OVector<f64, Dyn>) -> Result<(), BasisError> {
        if parameters.len() != self.nonlinear.len() {
            return Err(BasisError(format!(
                "{} parameters, expected {}",
                parameters.len(),
                self.nonlinear.len()
            )));
        }
        self.a = parameters;
        self.refresh();
        Ok(())
    }

    fn params(&self) -> OVector<f64, Dyn> {
        self.a.clone()
    }

    fn eval(&self) -> Result<OMatrix<f64, Dyn, Dyn>, BasisError> {
        Ok(self.phi.clone())
    }

    fn eval_partial_deriv(&self, k: usize) -> Result<OMatrix<f64, Dyn, Dyn>, BasisError> {
        if k == 0 {
            self.jacobians.set(self.jacobians.get() + 1);
        }
        self.dphi
            .get(k)
            .cloned()
            .ok_or_else(|| BasisError(format!("no non-linear parameter {k}")))
    }
}

/// Fit with the crate's defaults (SVD linear solver, the LM crate's
/// default tolerances). Needs a model of the form `[kd per channel, ks per
/// channel, shared non-linear parameters]`.
pub fn fit(prob: &PeerProblem) -> Result<Outcome, PeerError> {
    let nc = prob.channels();
    let n = prob.len();
    let grey = build(&prob.model_name, &ModelConfig::default())?;
    let specs = grey.param_specs();
    let linear: Vec<usize> = (0..specs.len()).filter(|k| specs[*k].linear).collect();
    let nonlinear: Vec<usize> = (0..specs.len()).filter(|k| !specs[*k].linear).collect();
    let nl_full = prob.model.n_params() - linear.len() * nc;
    if linear != (0..linear.len()).collect::<Vec<_>>() || nl_full != nonlinear.len() {
        return Err(PeerError::Usage(format!(
            "{}: the varpro adapter needs the linear parameters first and shared non-linear ones",
            prob.model_name
        )));
    }
    let a0: Vec<f64> = (0..nonlinear.len())
        .map(|u| prob.start[linear.len() * nc + u])
        .collect();
    let y = DMatrix::from_fn(n, nc, |j, c| prob.values[c * n + j]);
    let w = DVector::from_column_slice(&prob.scales);
    let (seconds, cpu_seconds, repeats, (p, evals, jacobians, termination)) = timed(|| {
        let mut basis = Basis {
            model: grey.clone_box(),
            pairs: &prob.pairs,
            linear: linear.clone(),
            nonlinear: nonlinear.clone(),
            a: DVector::from_column_slice(&a0),
            phi: DMatrix::zeros(n, linear.len()),
            dphi: vec![DMatrix::zeros(n, linear.len()); nonlinear.len()],
            jacobians: Cell::new(0),
        };
        basis.refresh();
        let sp = SeparableProblemBuilder::mrhs(basis)
            .observations(y.clone())
            .weights(w.clone())
            .build()
            .map_err(|e| PeerError::Usage(format!("varpro crate: {e}")))?;
        let fit = match LevMarSolver::default().solve(sp) {
            Ok(f) | Err(f) => f,
        };
        let mut p = vec![f64::NAN; prob.model.n_params()];
        if let Some(c) = fit.linear_coefficients() {
            for t in 0..linear.len() {
                for ch in 0..nc {
                    p[t * nc + ch] = c[(t, ch)];
                }
            }
        }
        let a = fit.nonlinear_parameters();
        for u in 0..nonlinear.len() {
            p[linear.len() * nc + u] = a[u];
        }
        let rep = &fit.minimization_report;
        Ok((
            p,
            rep.number_of_evaluations,
            fit.problem.model().jacobians.get(),
            format!("{:?}", rep.termination),
        ))
    })?;
    Ok(Outcome {
        solver: "varpro crate (unbounded, SVD)".into(),
        inside_box: prob.inside_box(&p),
        own_cost: f64::NAN,
        params: p,
        seconds,
        cpu_seconds,
        repeats,
        residual_evals: evals,
        jacobian_evals: Some(jacobians),
        passes: None,
        termination,
    })
}
