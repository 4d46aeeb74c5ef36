//! Deterministic multi-start: starts at the points of a Halton sequence in
//! the box (scrambling-free, so every run gives the same starts), with
//! parameters spanning decades (exponents) sampled on a log scale; every
//! start is solved (in parallel with the `rayon` feature), the best result
//! is kept and the spread of the final costs reported.

use crate::SolveError;
use crate::report::SolverReport;

/// Where starts are drawn from.
#[derive(Clone, Debug, PartialEq)]
pub struct StartBox {
    /// Lower ends (finite).
    pub lower: Vec<f64>,
    /// Upper ends (finite).
    pub upper: Vec<f64>,
    /// Sample this parameter on a log scale (requires `lower > 0`).
    pub log_scale: Vec<bool>,
}

const PRIMES: [u64; 24] = [
    2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47, 53, 59, 61, 67, 71, 73, 79, 83, 89,
];

/// Radical inverse of `i` in base `b`.
fn radical_inverse(mut i: u64, b: u64) -> f64 {
    let inv = 1.0 / b as f64;
    let mut f = inv;
    let mut r = 0.0;
    while i > 0 {
        r += f * (i % b) as f64;
        i /= b;
        f *= inv;
    }
    r
}

impl StartBox {
    /// `count` deterministic starts (Halton points 1..=count).
    pub fn starts(&self, count: usize) -> Result<Vec<Vec<f64>>, SolveError> {
        let d = self.lower.len();
        if d > PRIMES.len() {
            return Err(SolveError::InvalidOption {
                name: "dimension",
                value: d as f64,
                reason: "multi-start supports at most 24 non-linear parameters",
            });
        }
        for k in 0..d {
            let (lo, hi) = (self.lower[k], self.upper[k]);
            if !(lo.is_finite() && hi.is_finite() && lo <= hi) || (self.log_scale[k] && lo <= 0.0) {
                return Err(SolveError::InvalidOption {
                    name: "start box",
                    value: k as f64,
                    reason: "needs finite lower <= upper, and lower > 0 on a log scale",
                });
            }
        }
        Ok((1..=count as u64)
            .map(|i| {
                (0..d)
                    .map(|k| {
                        let t = radical_inverse(i, PRIMES[k]);
                        let (lo, hi) = (self.lower[k], self.upper[k]);
                        if self.log_scale[k] {
                            (lo.ln() + t * (hi.ln() - lo.ln())).exp()
                        } else {
                            lo + t * (hi - lo)
                        }
                    })
                    .collect()
            })
            .collect())
    }
}

/// The best of several solves and how much they disagreed.
#[derive(Clone, Debug)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct MultiStartReport {
    /// The best (lowest residual sum of squares) converged solve, or the best
    /// of all if none converged.
    pub best: SolverReport,
    /// Index of the best start.
    pub best_start: usize,
    /// Final residual sum of squares of every start (NaN for a failed solve).
    pub ssr: Vec<f64>,
    /// Starts whose result is within `1e-6` (relative) of the best.
    pub n_at_best: usize,
    /// Starts that reported convergence.
    pub n_converged: usize,
}

/// Solve from every start and keep the best.
pub fn multistart<F>(starts: &[Vec<f64>], solve: F) -> Result<MultiStartReport, SolveError>
where
    F: Fn(&[f64]) -> Result<SolverReport, SolveError> + Sync,
{
    if starts.is_empty() {
        return Err(SolveError::Empty { what: "starts" });
    }
    summarise(solve_each(starts, |s: &Vec<f64>| solve(s)))
}

/// `solve` from every start (in parallel with the `rayon` feature), the
/// results in the starts' order.
pub(crate) fn solve_each<T: Sync, F>(
    starts: &[T],
    solve: F,
) -> Vec<Result<SolverReport, SolveError>>
where
    F: Fn(&T) -> Result<SolverReport, SolveError> + Sync,
{
    #[cfg(feature = "rayon")]
    {
        use rayon::prelude::*;
        starts.par_iter().map(&solve).collect()
    }
    #[cfg(not(feature = "rayon"))]
    {
        starts.iter().map(&solve).collect()
    }
}

/// The best of the solves `results` (one per start, in the starts' order):
/// the lowest cost among the converged ones, else among all.
pub(crate) fn summarise(
    results: Vec<Result<SolverReport, SolveError>>,
) -> Result<MultiStartReport, SolveError> {
    let ssr: Vec<f64> = results
        .iter()
        .map(|r| r.as_ref().map(|r| r.ssr).unwrap_or(f64::NAN))
        .collect();
    let n_converged = results
        .iter()
        .filter(|r| r.as_ref().is_ok_and(|r| r.termination.is_converged()))
        .count();
    let pick = |need_converged: bool| {
        results
            .iter()
            .enumerate()
            .filter_map(|(i, r)| r.as_ref().ok().map(|r| (i, r)))
            .filter(|(_, r)| r.ssr.is_finite() && (!need_converged || r.termination.is_converged()))
            .min_by(|a, b| a.1.ssr.total_cmp(&b.1.ssr))
            .map(|(i, r)| (i, r.clone()))
    };
    let Some((best_start, best)) = pick(true).or_else(|| pick(false)) else {
        // Every start failed: return the first error.
        return Err(results
            .into_iter()
            .find_map(|r| r.err())
            .unwrap_or(SolveError::Empty {
                what: "no start ends with a finite cost (the residual sum of squares of every start is NaN or overflows: data or weights beyond about 1e150?)",
            }));
    };
    let n_at_best = ssr
        .iter()
        .filter(|s| {
            s.is_finite() && (**s - best.ssr).abs() <= 1e-6 * best.ssr.max(f64::MIN_POSITIVE)
        })
        .count();
    Ok(MultiStartReport {
        best,
        best_start,
        ssr,
        n_at_best,
        n_converged,
    })
}
