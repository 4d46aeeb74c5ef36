//! Compass search: a derivative-free minimiser of a scalar function in a
//! box, for objectives no least-squares solver can take (a perceptual
//! image metric such as FLIP has no useful Jacobian: it filters, takes
//! maxima over exposures and thresholds).
//!
//! The method (Kolda, Lewis and Torczon 2003, "Optimization by direct
//! search", SIAM Review 45(3), section 3, with the coordinate directions
//! `±e_i`): each free coordinate `i` has a step `d_i`; a sweep tries
//! `x + d_i e_i`, then `x - d_i e_i`, clamped into the box, and moves to
//! the first that lowers the value (simple decrease). A sweep that moves
//! nowhere multiplies every step by [`CompassOptions::shrink`]. It stops
//! when every step is below [`CompassOptions::min_step`] (relative to its
//! scale) or after [`CompassOptions::max_evaluations`] values, and says
//! which. A coordinate whose box is one value is held.
//!
//! The result is never worse than the start, is deterministic (the same
//! sweeps in the same order) and stays in the box.
//!
//! ```
//! use brdf_solve::compass::{CompassOptions, CompassTermination, compass_search};
//! // (x - 0.3)^2 + (y - 2)^2 in [0, 1] x [0, 1]: the minimum is at (0.3, 1).
//! let f = |x: &[f64]| (x[0] - 0.3).powi(2) + (x[1] - 2.0).powi(2);
//! let r = compass_search(f, &[0.9, 0.1], &[0.0, 0.0], &[1.0, 1.0], &CompassOptions::default())
//!     .unwrap();
//! assert!((r.x[0] - 0.3).abs() < 1e-3 && r.x[1] == 1.0);
//! assert_eq!(r.termination, CompassTermination::StepBelowTolerance);
//! assert_eq!(r.at_upper, vec![1]);
//! ```

use crate::SolveError;

/// Settings of [`compass_search`].
#[derive(Clone, Copy, Debug)]
pub struct CompassOptions {
    /// First step of each coordinate as a share of its scale (the box's
    /// width, or `max(|x_i|, 1)` where the box is unbounded).
    pub initial_step: f64,
    /// Factor applied to every step after a sweep that found no decrease.
    pub shrink: f64,
    /// Stop when every step is below this share of its scale.
    pub min_step: f64,
    /// Stop after this many evaluations (the start's included).
    pub max_evaluations: usize,
}

impl Default for CompassOptions {
    fn default() -> Self {
        Self {
            initial_step: 0.05,
            shrink: 0.5,
            min_step: 1e-4,
            max_evaluations: 2000,
        }
    }
}

/// Why [`compass_search`] stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CompassTermination {
    /// Every step fell below `min_step`: no coordinate move of that size
    /// lowers the value (a local minimum at that resolution).
    StepBelowTolerance,
    /// The evaluation budget ran out while steps still lowered the value.
    EvaluationBudget,
}

impl CompassTermination {
    /// The reason in words, for reports.
    pub fn describe(&self) -> &'static str {
        match self {
            Self::StepBelowTolerance => {
                "converged: no coordinate step above the tolerance lowers it"
            }
            Self::EvaluationBudget => "stopped at the evaluation budget, still improving",
        }
    }
}

/// Result of [`compass_search`].
#[derive(Clone, Debug)]
pub struct CompassReport {
    /// The best point found.
    pub x: Vec<f64>,
    /// The value there.
    pub value: f64,
    /// The value at the start.
    pub start_value: f64,
    /// Evaluations spent (the start's included).
    pub evaluations: usize,
    /// Sweeps that moved the point.
    pub moves: usize,
    /// Why it stopped.
    pub termination: CompassTermination,
    /// Free coordinates that end on their lower bound.
    pub at_lower: Vec<usize>,
    /// Free coordinates that end on their upper bound.
    pub at_upper: Vec<usize>,
}

/// Minimise `f` over the box `[lower, upper]` from `x0` by compass search
/// (see the module doc). `f` may return `+inf` for a point it cannot
/// evaluate; such a point is never accepted.
///
/// # Errors
/// [`SolveError`] when the lengths differ, a bound is NaN or crossed,
/// `x0` is outside the box, the start's value is not finite, or an option
/// is out of range.
pub fn compass_search(
    mut f: impl FnMut(&[f64]) -> f64,
    x0: &[f64],
    lower: &[f64],
    upper: &[f64],
    opts: &CompassOptions,
) -> Result<CompassReport, SolveError> {
    check(x0, lower, upper, opts)?;
    let scale: Vec<f64> = (0..x0.len())
        .map(|i| {
            let w = upper[i] - lower[i];
            if w.is_finite() {
                w
            } else {
                x0[i].abs().max(1.0)
            }
        })
        .collect();
    let free: Vec<usize> = (0..x0.len()).filter(|&i| upper[i] > lower[i]).collect();
    let mut step: Vec<f64> = scale.iter().map(|s| opts.initial_step * s).collect();
    let mut x = x0.to_vec();
    let start_value = f(&x);
    if !start_value.is_finite() {
        return Err(SolveError::InvalidOption {
            name: "start",
            value: start_value,
            reason: "the objective is not finite at the start point",
        });
    }
    let (mut value, mut evaluations, mut moves) = (start_value, 1, 0);
    let termination = loop {
        if free.iter().all(|&i| step[i] < opts.min_step * scale[i]) {
            break CompassTermination::StepBelowTolerance;
        }
        let mut moved = false;
        'coordinates: for &i in &free {
            for sign in [1.0, -1.0] {
                if evaluations >= opts.max_evaluations {
                    break 'coordinates;
                }
                let trial = (x[i] + sign * step[i]).clamp(lower[i], upper[i]);
                if trial == x[i] {
                    continue;
                }
                let old = std::mem::replace(&mut x[i], trial);
                let v = f(&x);
                evaluations += 1;
                if v < value {
                    value = v;
                    moved = true;
                    continue 'coordinates;
                }
                x[i] = old;
            }
        }
        if evaluations >= opts.max_evaluations {
            break CompassTermination::EvaluationBudget;
        }
        if moved {
            moves += 1;
        } else {
            step.iter_mut().for_each(|s| *s *= opts.shrink);
        }
    };
    Ok(CompassReport {
        at_lower: free.iter().copied().filter(|&i| x[i] == lower[i]).collect(),
        at_upper: free.iter().copied().filter(|&i| x[i] == upper[i]).collect(),
        x,
        value,
        start_value,
        evaluations,
        moves,
        termination,
    })
}

/// The inputs of [`compass_search`], checked.
fn check(
    x0: &[f64],
    lower: &[f64],
    upper: &[f64],
    opts: &CompassOptions,
) -> Result<(), SolveError> {
    for (what, len) in [("lower bounds", lower.len()), ("upper bounds", upper.len())] {
        if len != x0.len() {
            return Err(SolveError::Dimension {
                what,
                left: len,
                right: x0.len(),
            });
        }
    }
    for i in 0..x0.len() {
        if lower[i].is_nan() || upper[i].is_nan() || lower[i] > upper[i] {
            return Err(SolveError::InvalidOption {
                name: "bounds",
                value: lower[i],
                reason: "a lower bound is NaN or above its upper bound",
            });
        }
        if !x0[i].is_finite() || x0[i] < lower[i] || x0[i] > upper[i] {
            return Err(SolveError::InvalidOption {
                name: "start",
                value: x0[i],
                reason: "a start coordinate is not finite or outside its box",
            });
        }
    }
    let valid = opts.initial_step > 0.0
        && opts.shrink > 0.0
        && opts.shrink < 1.0
        && opts.min_step > 0.0
        && opts.max_evaluations > 0;
    if !valid {
        return Err(SolveError::InvalidOption {
            name: "compass options",
            value: opts.shrink,
            reason: "steps must be positive, shrink in (0, 1), the budget at least 1",
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn held_coordinates_do_not_move_and_the_value_never_rises() {
        let f = |x: &[f64]| (x[0] - 0.7).powi(2) + (x[1] - 0.2).powi(2);
        let r = compass_search(
            f,
            &[0.1, 0.5],
            &[0.0, 0.5],
            &[1.0, 0.5],
            &CompassOptions::default(),
        )
        .unwrap();
        assert_eq!(r.x[1], 0.5);
        assert!((r.x[0] - 0.7).abs() < 1e-3, "{:?}", r.x);
        assert!(r.value <= r.start_value);
        assert!(r.at_lower.is_empty() && r.at_upper.is_empty());
    }

    #[test]
    fn rosenbrock_in_a_box_reaches_its_minimum() {
        let f = |x: &[f64]| 100.0 * (x[1] - x[0] * x[0]).powi(2) + (1.0 - x[0]).powi(2);
        let opts = CompassOptions {
            min_step: 1e-9,
            max_evaluations: 200_000,
            ..CompassOptions::default()
        };
        let r = compass_search(f, &[-1.2, 1.0], &[-2.0, -2.0], &[2.0, 2.0], &opts).unwrap();
        assert_eq!(r.termination, CompassTermination::StepBelowTolerance);
        assert!(r.value < 1e-6, "{} at {:?}", r.value, r.x);
        assert!((r.x[0] - 1.0).abs() < 1e-2 && (r.x[1] - 1.0).abs() < 2e-2);
    }

    #[test]
    fn the_budget_is_reported_as_the_reason() {
        let f = |x: &[f64]| (x[0] - 1e3).powi(2);
        let opts = CompassOptions {
            max_evaluations: 10,
            ..CompassOptions::default()
        };
        let r = compass_search(f, &[0.0], &[f64::NEG_INFINITY], &[f64::INFINITY], &opts).unwrap();
        assert_eq!(r.termination, CompassTermination::EvaluationBudget);
        assert_eq!(r.evaluations, 10);
        assert!(r.x[0] > 0.0);
    }

    #[test]
    fn an_unevaluable_point_is_never_accepted() {
        // The value is lower beyond 0.5 but cannot be evaluated there.
        let f = |x: &[f64]| if x[0] > 0.5 { f64::INFINITY } else { -x[0] };
        let r = compass_search(f, &[0.0], &[0.0], &[1.0], &CompassOptions::default()).unwrap();
        assert!(r.x[0] <= 0.5 && r.x[0] > 0.49, "{:?}", r.x);
    }

    #[test]
    fn bad_input_is_a_typed_error() {
        let f = |x: &[f64]| x[0];
        let o = CompassOptions::default();
        assert!(compass_search(f, &[2.0], &[0.0], &[1.0], &o).is_err());
        assert!(compass_search(f, &[0.5], &[1.0], &[0.0], &o).is_err());
        assert!(compass_search(f, &[0.5], &[0.0, 0.0], &[1.0], &o).is_err());
        assert!(compass_search(|_: &[f64]| f64::NAN, &[0.5], &[0.0], &[1.0], &o).is_err());
        let bad = CompassOptions { shrink: 1.0, ..o };
        assert!(compass_search(f, &[0.5], &[0.0], &[1.0], &bad).is_err());
    }
}
