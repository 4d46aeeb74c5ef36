//! The `levenberg-marquardt` crate (MINPACK's algorithm on nalgebra) on a
//! peer problem: unbounded, all parameters, the same start, residuals and
//! Jacobian from the same [`ModelProblem`] our solvers see (so only the
//! algorithm differs). It knows no box: the outcome says whether it left it.

use std::cell::Cell;

use brdf_solve::{LeastSquaresProblem, ModelProblem};
use nalgebra034::{DMatrix, DVector, Dyn, Owned};

use super::{Outcome, PeerError, PeerProblem, timed};

/// [`ModelProblem`] as the crate's problem type.
struct Adapter<'a> {
    mp: &'a ModelProblem<'a>,
    p: DVector<f64>,
    jacobians: Cell<usize>,
}

impl levenberg_marquardt::LeastSquaresProblem<f64, Dyn, Dyn> for Adapter<'_> {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, Dyn>;
    type ParameterStorage = Owned<f64, Dyn>;

    fn set_params(&mut self, x: &DVector<f64>) {
        self.p.copy_from(x);
    }

    fn params(&self) -> DVector<f64> {
        self.p.clone()
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        let mut r = vec![0.0; self.mp.n_residuals()];
        self.mp.residuals(self.p.as_slice(), &mut r);
        r.iter()
            .all(|x| x.is_finite())
            .then(|| DVector::from_vec(r))
    }

    fn jacobian(&self) -> Option<DMatrix<f64>> {
        self.jacobians.set(self.jacobians.get() + 1);
        let (m, n) = (self.mp.n_residuals(), self.mp.n_params());
        let mut j = vec![0.0; m * n];
        self.mp.jacobian(self.p.as_slice(), &mut j);
        // Ours is row-major, nalgebra's column-major.
        j.iter()
            .all(|x| x.is_finite())
            .then(|| DMatrix::from_row_slice(m, n, &j))
    }
}

/// Fit with the crate's defaults (tolerances `30 eps`, MINPACK scaling).
pub fn fit(prob: &PeerProblem) -> Result<Outcome, PeerError> {
    let mp = prob.model_problem()?;
    let (seconds, cpu_seconds, repeats, (p, report, jacobians)) = timed(|| {
        let a = Adapter {
            mp: &mp,
            p: DVector::from_column_slice(&prob.start),
            jacobians: Cell::new(0),
        };
        let (a, report) = levenberg_marquardt::LevenbergMarquardt::new().minimize(a);
        Ok((a.p.as_slice().to_vec(), report, a.jacobians.get()))
    })?;
    Ok(Outcome {
        solver: "levenberg-marquardt crate (unbounded)".into(),
        inside_box: prob.inside_box(&p),
        own_cost: report.objective_function,
        params: p,
        seconds,
        cpu_seconds,
        repeats,
        residual_evals: report.number_of_evaluations,
        jacobian_evals: Some(jacobians),
        passes: None,
        termination: format!("{:?}", report.termination),
    })
}
