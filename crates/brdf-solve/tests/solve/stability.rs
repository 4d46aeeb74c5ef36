//! The bounded solver never
//! evaluates the problem outside its feasible set — not only the final
//! point, every point it asks for (trial steps included) — from starts on
//! the corners of the box, with either damping schedule and with geodesic
//! acceleration; and stiff problems from both certified NIST starts end
//! either at the certified values or in a termination that says they did
//! not converge.

use std::sync::Mutex;

use brdf_solve::strd::{StrdModel, StrdProblem, lre};
use brdf_solve::{
    Constraints, Damping, LeastSquaresProblem, LmOptions, bounded_least_squares,
    levenberg_marquardt,
};

/// A problem that records every parameter vector it is evaluated at.
struct Recording<'a, P: LeastSquaresProblem> {
    inner: &'a P,
    points: Mutex<Vec<Vec<f64>>>,
    residual_points: Mutex<Vec<Vec<f64>>>,
}

impl<'a, P: LeastSquaresProblem> Recording<'a, P> {
    fn new(inner: &'a P) -> Self {
        Recording {
            inner,
            points: Mutex::new(Vec::new()),
            residual_points: Mutex::new(Vec::new()),
        }
    }
    fn record(&self, p: &[f64]) {
        self.points.lock().unwrap().push(p.to_vec());
    }
}

impl<P: LeastSquaresProblem + Sync> LeastSquaresProblem for Recording<'_, P> {
    fn n_params(&self) -> usize {
        self.inner.n_params()
    }
    fn n_residuals(&self) -> usize {
        self.inner.n_residuals()
    }
    fn residuals(&self, p: &[f64], out: &mut [f64]) {
        self.record(p);
        self.residual_points.lock().unwrap().push(p.to_vec());
        self.inner.residuals(p, out)
    }
    fn jacobian(&self, p: &[f64], jac: &mut [f64]) {
        self.record(p);
        self.inner.jacobian(p, jac)
    }
}

fn boxbod() -> StrdProblem {
    // NIST StRD BoxBOD data (Box, Hunter & Hunter 1978).
    let x = vec![1.0, 2.0, 3.0, 5.0, 7.0, 10.0];
    let y = vec![109.0, 149.0, 149.0, 191.0, 213.0, 224.0];
    StrdProblem::new(StrdModel::SaturatingExp, x, y).unwrap()
}

fn rat43() -> StrdProblem {
    // NIST StRD Rat43 (Ratkowsky 1983), as in brdf-io's fixture.
    let y = vec![
        16.08, 33.83, 65.80, 97.20, 191.55, 326.20, 386.87, 520.53, 590.03, 651.92, 724.93, 699.56,
        689.96, 637.56, 717.41,
    ];
    let x = (1..=15).map(f64::from).collect();
    StrdProblem::new(StrdModel::Rat43, x, y).unwrap()
}

fn option_sets() -> Vec<(&'static str, LmOptions)> {
    vec![
        ("Nielsen", LmOptions::default()),
        ("Sopp", LmOptions::sopp()),
        (
            "Nielsen + geodesic",
            LmOptions {
                geodesic_acceleration: true,
                ..LmOptions::default()
            },
        ),
        (
            "Sopp damping",
            LmOptions {
                damping: Damping::Sopp,
                ..LmOptions::default()
            },
        ),
    ]
}

fn corners(c: &Constraints) -> Vec<Vec<f64>> {
    let n = c.len();
    (0..1usize << n)
        .map(|mask| {
            (0..n)
                .map(|k| {
                    if mask >> k & 1 == 1 {
                        c.upper()[k]
                    } else {
                        c.lower()[k]
                    }
                })
                .collect()
        })
        .collect()
}

/// Every recorded point lies in the box (exactly) and satisfies the
/// linear inequalities to rounding (relative 1e-9).
fn assert_feasible(points: &[Vec<f64>], c: &Constraints, what: &str) {
    assert!(!points.is_empty(), "{what}: nothing evaluated");
    for (i, p) in points.iter().enumerate() {
        for k in 0..p.len() {
            assert!(
                p[k] >= c.lower()[k] && p[k] <= c.upper()[k],
                "{what}: evaluation {i} has p[{k}] = {} outside [{}, {}]",
                p[k],
                c.lower()[k],
                c.upper()[k]
            );
        }
        for ineq in c.inequalities() {
            let ax: f64 = ineq.a.iter().zip(p).map(|(a, x)| a * x).sum();
            assert!(
                ax <= ineq.b + 1e-9 * ineq.b.abs().max(1.0),
                "{what}: evaluation {i} violates {ax} <= {}",
                ineq.b
            );
        }
    }
}

#[test]
fn every_evaluation_of_the_bounded_solver_is_inside_the_box() {
    let problem = boxbod();
    // The box cuts the optimum (b2 = 0.547) off: the iterates press on it.
    let c = Constraints::boxed(vec![1.0, 0.01], vec![1e3, 0.4]).unwrap();
    let mut starts = corners(&c);
    starts.push(vec![100.0, 0.3]);
    let mut runs = 0;
    for (label, opts) in option_sets() {
        for s in &starts {
            let rec = Recording::new(&problem);
            let rep = bounded_least_squares(&rec, s, &c, &opts).unwrap();
            let what = format!("{label} from {s:?}");
            assert_feasible(&rec.points.lock().unwrap(), &c, &what);
            assert!(rep.params.iter().all(|x| x.is_finite()), "{what}");
            // Wherever it ends, it claims convergence only at the
            // constrained optimum (b2 on its bound 0.4).
            if rep.termination.is_converged() {
                assert!(
                    (rep.params[1] - 0.4).abs() < 1e-9,
                    "{what}: {:?}",
                    rep.params
                );
            }
            runs += 1;
        }
    }
    assert_eq!(runs, 4 * 5);
}

#[test]
fn every_evaluation_respects_a_linear_inequality() {
    // Rat43 with b1 + 100 b4 <= 800 (the certified b1 = 699.6, b4 = 1.28
    // gives 827.6: the constraint is active).
    let problem = rat43();
    let c = Constraints::boxed(vec![1.0, 0.0, 0.01, 0.1], vec![1e3, 20.0, 2.0, 5.0])
        .unwrap()
        .with_inequality(vec![1.0, 0.0, 0.0, 100.0], 800.0)
        .unwrap();
    for (label, opts) in option_sets() {
        for s in [vec![600.0, 5.0, 0.75, 1.0], vec![100.0, 10.0, 1.0, 1.0]] {
            let rec = Recording::new(&problem);
            let rep = bounded_least_squares(&rec, &s, &c, &opts).unwrap();
            let what = format!("{label} from {s:?}");
            for (i, p) in rec.points.lock().unwrap().iter().enumerate() {
                for k in 0..4 {
                    assert!(
                        p[k] >= c.lower()[k] && p[k] <= c.upper()[k],
                        "{what}: evaluation {i}: p[{k}] = {}",
                        p[k]
                    );
                }
                // The box holds exactly; the inequality to the rounding of
                // the LSI step on this badly conditioned Jacobian (a trial
                // point 1.5e-7 = 2e-10 relative beyond it was observed).
                assert!(
                    p[0] + 100.0 * p[3] <= 800.0 * (1.0 + 1e-9),
                    "{what}: evaluation {i}: b1 + 100 b4 = {}",
                    p[0] + 100.0 * p[3]
                );
            }
            assert!(rep.params.iter().all(|x| x.is_finite()), "{what}");
        }
    }
}

#[test]
fn stiff_nist_problems_from_both_starts_converge_to_the_certificate_or_say_not() {
    // Rat43: certified values (NIST), both certified starts.
    let certified = [6.9964151270e2, 5.2771253025, 7.5962938329e-1, 1.2792483859];
    let starts = [[100.0, 10.0, 1.0, 1.0], [700.0, 5.0, 0.75, 1.3]];
    let problem = rat43();
    let mut converged = 0;
    for s in starts {
        let rep = levenberg_marquardt(&problem, &s, &LmOptions::default()).unwrap();
        let min_lre = rep
            .params
            .iter()
            .zip(certified)
            .map(|(e, c)| lre(*e, c))
            .fold(f64::INFINITY, f64::min);
        if rep.termination.is_converged() {
            assert!(min_lre > 6.0, "from {s:?}: converged with LRE {min_lre}");
            assert!((rep.ssr / 8.7864049080e3 - 1.0).abs() < 1e-8, "{}", rep.ssr);
            converged += 1;
        }
        assert!(rep.params.iter().all(|x| x.is_finite()));
    }
    // Start 2 is the easy one.
    assert!(converged >= 1);
    // BoxBOD from start 1 sits on a plateau; from start 2 it converges.
    let rep = levenberg_marquardt(&boxbod(), &[100.0, 0.75], &LmOptions::default()).unwrap();
    assert!(rep.termination.is_converged(), "{:?}", rep.termination);
    assert!(lre(rep.params[0], 2.1380940889e2) > 6.0);
    assert!(lre(rep.params[1], 5.4723748542e-1) > 6.0);
}

/// `r(p) = p`, one parameter: with Marquardt scaling the damped step from
/// `p` is `-p / (1 + lambda)`, so every accepted step multiplies `p` by
/// `lambda / (1 + lambda)` and the trial points spell out the damping.
struct Identity1;
impl LeastSquaresProblem for Identity1 {
    fn n_params(&self) -> usize {
        1
    }
    fn n_residuals(&self) -> usize {
        1
    }
    fn residuals(&self, p: &[f64], out: &mut [f64]) {
        out[0] = p[0];
    }
    fn jacobian(&self, _p: &[f64], jac: &mut [f64]) {
        jac[0] = 1.0;
    }
}

#[test]
fn sopp_damping_constants_are_pinned() {
    // Sopp (fitting.md): start at 1e-3, halve on an accepted step down to
    // 1e-4 (every step of this problem is accepted).
    let rec = Recording::new(&Identity1);
    levenberg_marquardt(&rec, &[1.0], &LmOptions::sopp()).unwrap();
    let points = rec.residual_points.lock().unwrap();
    let lambdas = [1e-3, 5e-4, 2.5e-4, 1.25e-4, 1e-4, 1e-4];
    let mut expected = 1.0f64;
    assert_eq!(points[0], vec![1.0]);
    let compared = points.len().min(lambdas.len() + 1) - 1;
    assert!(compared >= 5, "only {} trial points", points.len());
    for (k, lambda) in lambdas.iter().take(compared).enumerate() {
        expected *= lambda / (1.0 + lambda);
        let got = points[k + 1][0];
        assert!(
            (got / expected - 1.0).abs() < 1e-8,
            "step {}: {got} vs {expected} (lambda {lambda})",
            k + 1
        );
    }
}
