//! Feasible sets of the bounded solver: a box `lower <= p <= upper`
//! (infinite bounds allowed) and optional linear inequalities `a . p <= b`
//! (e.g. `kd + ks <= 1`).

use crate::SolveError;
use crate::report::BoundStatus;

/// One linear inequality `a . p <= b`.
#[derive(Clone, Debug, PartialEq)]
pub struct LinearInequality {
    /// Coefficients, one per parameter.
    pub a: Vec<f64>,
    /// Right-hand side.
    pub b: f64,
}

/// Box bounds and linear inequalities on the parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct Constraints {
    lower: Vec<f64>,
    upper: Vec<f64>,
    linear: Vec<LinearInequality>,
}

impl Constraints {
    /// No constraints on `n` parameters.
    pub fn unbounded(n: usize) -> Self {
        Self {
            lower: vec![f64::NEG_INFINITY; n],
            upper: vec![f64::INFINITY; n],
            linear: Vec::new(),
        }
    }

    /// A box. Bounds may be infinite but not NaN, and `lower <= upper`.
    pub fn boxed(lower: Vec<f64>, upper: Vec<f64>) -> Result<Self, SolveError> {
        if lower.len() != upper.len() {
            return Err(SolveError::Dimension {
                what: "lower vs upper bounds",
                left: lower.len(),
                right: upper.len(),
            });
        }
        for (k, (lo, hi)) in lower.iter().zip(&upper).enumerate() {
            if lo.is_nan() || hi.is_nan() || lo > hi {
                return Err(SolveError::InvalidOption {
                    name: "bounds",
                    value: k as f64,
                    reason: "parameter k (value) has a NaN bound or lower > upper",
                });
            }
        }
        Ok(Self {
            lower,
            upper,
            linear: Vec::new(),
        })
    }

    /// Add the inequality `a . p <= b`.
    pub fn with_inequality(mut self, a: Vec<f64>, b: f64) -> Result<Self, SolveError> {
        if a.len() != self.lower.len() {
            return Err(SolveError::Dimension {
                what: "inequality coefficients vs parameters",
                left: a.len(),
                right: self.lower.len(),
            });
        }
        if !b.is_finite() || a.iter().any(|v| !v.is_finite()) {
            return Err(SolveError::InvalidOption {
                name: "inequality",
                value: b,
                reason: "coefficients and right-hand side must be finite",
            });
        }
        self.linear.push(LinearInequality { a, b });
        Ok(self)
    }

    /// Number of parameters.
    pub fn len(&self) -> usize {
        self.lower.len()
    }

    /// True for zero parameters.
    pub fn is_empty(&self) -> bool {
        self.lower.is_empty()
    }

    /// Lower bounds.
    pub fn lower(&self) -> &[f64] {
        &self.lower
    }

    /// Upper bounds.
    pub fn upper(&self) -> &[f64] {
        &self.upper
    }

    /// The linear inequalities.
    pub fn inequalities(&self) -> &[LinearInequality] {
        &self.linear
    }

    /// True when there is nothing to enforce.
    pub fn is_unconstrained(&self) -> bool {
        self.linear.is_empty()
            && self.lower.iter().all(|v| *v == f64::NEG_INFINITY)
            && self.upper.iter().all(|v| *v == f64::INFINITY)
    }

    /// Whether `p` satisfies every constraint (linear ones up to `tol`).
    pub fn is_feasible(&self, p: &[f64], tol: f64) -> bool {
        p.iter()
            .zip(self.lower.iter().zip(&self.upper))
            .all(|(v, (lo, hi))| v >= lo && v <= hi)
            && self.linear.iter().all(|c| dot(&c.a, p) <= c.b + tol)
    }

    /// Clamp `p` into the box (used only to remove rounding after a step
    /// that the subproblem already kept feasible).
    pub fn clamp(&self, p: &mut [f64]) {
        for (k, v) in p.iter_mut().enumerate() {
            *v = v.clamp(self.lower[k], self.upper[k]);
        }
    }

    /// Bound status of every parameter of `p` (relative tolerance `1e-10`).
    pub fn status(&self, p: &[f64]) -> Vec<BoundStatus> {
        p.iter()
            .enumerate()
            .map(|(k, v)| {
                let tol = 1e-10 * v.abs().max(1.0);
                if self.lower[k].is_finite() && *v - self.lower[k] <= tol {
                    BoundStatus::AtLower
                } else if self.upper[k].is_finite() && self.upper[k] - *v <= tol {
                    BoundStatus::AtUpper
                } else {
                    BoundStatus::Free
                }
            })
            .collect()
    }

    /// The constraints on a step `d` from `p` as rows `G d >= h`.
    pub(crate) fn step_rows(&self, p: &[f64]) -> (Vec<Vec<f64>>, Vec<f64>) {
        let n = p.len();
        let mut g = Vec::new();
        let mut h = Vec::new();
        for k in 0..n {
            if self.lower[k].is_finite() {
                let mut row = vec![0.0; n];
                row[k] = 1.0;
                g.push(row);
                h.push(self.lower[k] - p[k]);
            }
            if self.upper[k].is_finite() {
                let mut row = vec![0.0; n];
                row[k] = -1.0;
                g.push(row);
                h.push(p[k] - self.upper[k]);
            }
        }
        for c in &self.linear {
            g.push(c.a.iter().map(|v| -v).collect());
            h.push(dot(&c.a, p) - c.b);
        }
        (g, h)
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}
