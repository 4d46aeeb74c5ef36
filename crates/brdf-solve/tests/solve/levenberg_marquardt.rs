//! Levenberg-Marquardt, the bounded solver, LSI and covariance on problems
//! with known answers.

use brdf_solve::covariance::{covariance, standard_errors};
use brdf_solve::strd::{StrdModel, StrdProblem};
use brdf_solve::{
    BoundStatus, Constraints, Damping, LeastSquaresProblem, LmOptions, Termination,
    bounded_least_squares, levenberg_marquardt, lsi,
};
use faer::Mat;

/// Rosenbrock as least squares: r = (10 (y - x^2), 1 - x), minimum (1, 1).
struct Rosenbrock;
impl LeastSquaresProblem for Rosenbrock {
    fn n_params(&self) -> usize {
        2
    }
    fn n_residuals(&self) -> usize {
        2
    }
    fn residuals(&self, p: &[f64], out: &mut [f64]) {
        out[0] = 10.0 * (p[1] - p[0] * p[0]);
        out[1] = 1.0 - p[0];
    }
    fn jacobian(&self, p: &[f64], jac: &mut [f64]) {
        jac.copy_from_slice(&[-20.0 * p[0], 10.0, -1.0, 0.0]);
    }
}

/// The same problem without an analytic Jacobian (finite differences).
struct RosenbrockFd;
impl LeastSquaresProblem for RosenbrockFd {
    fn n_params(&self) -> usize {
        2
    }
    fn n_residuals(&self) -> usize {
        2
    }
    fn residuals(&self, p: &[f64], out: &mut [f64]) {
        Rosenbrock.residuals(p, out)
    }
}

#[test]
fn rosenbrock_from_the_classic_start() {
    for damping in [Damping::Nielsen, Damping::Sopp] {
        let opts = LmOptions {
            damping,
            ..LmOptions::default()
        };
        let rep = levenberg_marquardt(&Rosenbrock, &[-1.2, 1.0], &opts).unwrap();
        assert!(
            rep.termination.is_converged(),
            "{damping:?}: {:?}",
            rep.termination
        );
        assert!((rep.params[0] - 1.0).abs() < 1e-10 && (rep.params[1] - 1.0).abs() < 1e-10);
        assert!(rep.ssr < 1e-20);
    }
    let rep = levenberg_marquardt(&RosenbrockFd, &[-1.2, 1.0], &LmOptions::default()).unwrap();
    assert!((rep.params[0] - 1.0).abs() < 1e-7, "{:?}", rep.params);
}

fn boxbod() -> StrdProblem {
    // NIST StRD BoxBOD data (Box, Hunter & Hunter 1978).
    let x = vec![1.0, 2.0, 3.0, 5.0, 7.0, 10.0];
    let y = vec![109.0, 149.0, 149.0, 191.0, 213.0, 224.0];
    StrdProblem::new(StrdModel::SaturatingExp, x, y).unwrap()
}

#[test]
fn boxbod_plateau_is_not_called_convergence() {
    let rep = levenberg_marquardt(&boxbod(), &[1.0, 1.0], &LmOptions::default()).unwrap();
    // Either it escapes to the certified minimum, or it must not claim
    // convergence on the plateau (SSR far above the certified 1168.0).
    if rep.ssr > 1200.0 {
        assert!(
            !rep.termination.is_converged(),
            "{:?} at ssr {}",
            rep.termination,
            rep.ssr
        );
        assert_eq!(rep.termination, Termination::SingularPlateau);
    } else {
        assert!((rep.ssr - 1.1680088766e3).abs() < 1e-6);
    }
    assert!(rep.params.iter().all(|v| v.is_finite()));
    // From start 2 it converges to the certified values.
    let rep = levenberg_marquardt(&boxbod(), &[100.0, 0.75], &LmOptions::default()).unwrap();
    assert!(rep.termination.is_converged());
    assert!((rep.params[0] / 2.1380940889e2 - 1.0).abs() < 1e-8);
    assert!((rep.params[1] / 5.4723748542e-1 - 1.0).abs() < 1e-8);
    // NIST's certified standard deviations.
    let se = standard_errors(&boxbod(), &rep.params).unwrap();
    assert!((se[0] / 1.2354515176e1 - 1.0).abs() < 1e-6, "{se:?}");
    assert!((se[1] / 1.0455993237e-1 - 1.0).abs() < 1e-6, "{se:?}");
}

#[test]
fn bounded_solution_sits_on_the_bound_and_iterates_stay_feasible() {
    // BoxBOD with b2 <= 0.4 (the free optimum is 0.547): the constrained
    // optimum has b2 = 0.4 and b1 the best value given b2.
    let c = Constraints::boxed(vec![0.0, 0.0], vec![1e3, 0.4]).unwrap();
    let rep = bounded_least_squares(&boxbod(), &[100.0, 0.3], &c, &LmOptions::default()).unwrap();
    assert!(rep.termination.is_converged(), "{:?}", rep.termination);
    assert_eq!(rep.bounds, vec![BoundStatus::Free, BoundStatus::AtUpper]);
    assert!((rep.params[1] - 0.4).abs() < 1e-12);
    // b1 given b2 is linear least squares: b1 = sum g y / sum g^2.
    let x = [1.0, 2.0, 3.0, 5.0, 7.0, 10.0];
    let y = [109.0, 149.0, 149.0, 191.0, 213.0, 224.0];
    let g: Vec<f64> = x.iter().map(|x: &f64| 1.0 - (-0.4 * x).exp()).collect();
    let b1 =
        g.iter().zip(&y).map(|(g, y)| g * y).sum::<f64>() / g.iter().map(|g| g * g).sum::<f64>();
    assert!(
        (rep.params[0] - b1).abs() < 1e-8 * b1,
        "{} vs {b1}",
        rep.params[0]
    );
}

#[test]
fn linear_inequality_is_respected() {
    // min (p0 - 2)^2 + (p1 - 2)^2 s.t. p0 + p1 <= 1: solution (0.5, 0.5).
    struct Dist;
    impl LeastSquaresProblem for Dist {
        fn n_params(&self) -> usize {
            2
        }
        fn n_residuals(&self) -> usize {
            2
        }
        fn residuals(&self, p: &[f64], out: &mut [f64]) {
            out[0] = p[0] - 2.0;
            out[1] = p[1] - 2.0;
        }
    }
    let c = Constraints::boxed(vec![0.0, 0.0], vec![f64::INFINITY, f64::INFINITY])
        .unwrap()
        .with_inequality(vec![1.0, 1.0], 1.0)
        .unwrap();
    let rep = bounded_least_squares(&Dist, &[0.1, 0.1], &c, &LmOptions::default()).unwrap();
    assert!(
        (rep.params[0] - 0.5).abs() < 1e-9 && (rep.params[1] - 0.5).abs() < 1e-9,
        "{:?}",
        rep.params
    );
    assert!(rep.params[0] + rep.params[1] <= 1.0 + 1e-12);
    // An infeasible start is refused, not silently moved.
    assert!(bounded_least_squares(&Dist, &[2.0, 2.0], &c, &LmOptions::default()).is_err());
}

#[test]
fn lsi_matches_hand_solution() {
    // min ||x - (1, 2)|| s.t. x0 >= 1.5, -x1 >= -1 (x1 <= 1): x = (1.5, 1).
    let e = Mat::<f64>::identity(2, 2);
    let g = Mat::from_fn(2, 2, |i, j| [[1.0, 0.0], [0.0, -1.0]][i][j]);
    let x = lsi(e.as_ref(), &[1.0, 2.0], g.as_ref(), &[1.5, -1.0]).unwrap();
    assert!(
        (x[0] - 1.5).abs() < 1e-12 && (x[1] - 1.0).abs() < 1e-12,
        "{x:?}"
    );
    // Infeasible: x0 >= 1 and -x0 >= 0.
    let g = Mat::from_fn(2, 2, |i, j| [[1.0, 0.0], [-1.0, 0.0]][i][j]);
    assert!(lsi(e.as_ref(), &[1.0, 2.0], g.as_ref(), &[1.0, 0.0]).is_err());
}

#[test]
fn covariance_of_a_straight_line_matches_the_textbook_formula() {
    // y = a + b x: Cov = s^2 (X^T X)^-1.
    struct Line(Vec<f64>, Vec<f64>);
    impl LeastSquaresProblem for Line {
        fn n_params(&self) -> usize {
            2
        }
        fn n_residuals(&self) -> usize {
            self.0.len()
        }
        fn residuals(&self, p: &[f64], out: &mut [f64]) {
            for i in 0..self.0.len() {
                out[i] = p[0] + p[1] * self.0[i] - self.1[i];
            }
        }
    }
    let x = vec![0.0, 1.0, 2.0, 3.0, 4.0];
    let y = vec![0.1, 0.9, 2.2, 2.8, 4.1];
    let prob = Line(x.clone(), y);
    let rep = levenberg_marquardt(&prob, &[0.0, 0.0], &LmOptions::default()).unwrap();
    let cov = covariance(&prob, &rep.params).unwrap();
    let n = 5.0;
    let sx: f64 = x.iter().sum();
    let sxx: f64 = x.iter().map(|v| v * v).sum();
    let det = n * sxx - sx * sx;
    let s2 = rep.ssr / 3.0;
    let expect = [s2 * sxx / det, -s2 * sx / det, -s2 * sx / det, s2 * n / det];
    for k in 0..4 {
        assert!(
            (cov[k] - expect[k]).abs() < 1e-9 * expect[k].abs().max(1e-3),
            "{cov:?} vs {expect:?}"
        );
    }
}

#[test]
fn bad_input_is_an_error_not_a_panic() {
    let opts = LmOptions::default();
    assert!(levenberg_marquardt(&Rosenbrock, &[f64::NAN, 1.0], &opts).is_err());
    assert!(levenberg_marquardt(&Rosenbrock, &[1.0], &opts).is_err());
    let bad = LmOptions {
        ftol: -1.0,
        ..LmOptions::default()
    };
    assert!(levenberg_marquardt(&Rosenbrock, &[0.0, 0.0], &bad).is_err());
    // Fewer residuals than parameters.
    let one = StrdProblem::new(StrdModel::SaturatingExp, vec![1.0], vec![1.0]).unwrap();
    assert!(levenberg_marquardt(&one, &[1.0, 1.0], &opts).is_err());
    assert!(Constraints::boxed(vec![1.0], vec![0.0]).is_err());
}

#[test]
fn non_finite_residuals_are_rejected_steps_never_nan_parameters() {
    // sqrt(p) - 1 is NaN for p < 0; a big first step into p < 0 must be
    // rejected and the solver must still reach p = 1.
    struct Sqrt;
    impl LeastSquaresProblem for Sqrt {
        fn n_params(&self) -> usize {
            1
        }
        fn n_residuals(&self) -> usize {
            1
        }
        fn residuals(&self, p: &[f64], out: &mut [f64]) {
            out[0] = p[0].sqrt() - 1.0;
        }
        fn jacobian(&self, p: &[f64], jac: &mut [f64]) {
            jac[0] = 0.5 / p[0].sqrt();
        }
    }
    let rep = levenberg_marquardt(&Sqrt, &[100.0], &LmOptions::default()).unwrap();
    assert!(rep.params[0].is_finite());
    assert!((rep.params[0] - 1.0).abs() < 1e-10, "{:?}", rep);
}
