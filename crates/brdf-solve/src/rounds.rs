//! Multi-start in two rounds: every start solved under a small iteration
//! cap, then only the promising ones that were still going solved again
//! under the full cap.
//!
//! A bounded solve from a poor start often creeps: it uses every iteration
//! of its cap and ends orders of magnitude above the best cost (on the
//! coloured-lobe models with a conductor lobe, a third to a half of the
//! starts do, and they took most of the search's time). The least-squares
//! cost never rises along a solve, so a start whose cost after the first
//! round is far above the best of all starts' cannot become the best;
//! one close above still can, and is carried on. A carried start is
//! solved again from the start, not resumed where it stopped: a resumed
//! solve begins with fresh damping and scaling and takes another path, and
//! redoing the first round's few iterations makes a carried start end
//! exactly where a single round would have taken it. Both rounds solve
//! their starts in parallel and decide in the starts' order, so the
//! result is the same for any thread count.
//!
//! ```
//! use brdf_solve::rounds::{Rounds, multistart_in_rounds};
//! use brdf_solve::{BoundStatus, SolverReport, Termination};
//!
//! // A "solve" that moves halfway to 0 per iteration and stops at 1e-3.
//! let solve = |p: &[f64], cap: usize| -> Result<SolverReport, brdf_solve::SolveError> {
//!     let (mut x, mut k) = (p[0], 0);
//!     while x.abs() > 1e-3 && k < cap {
//!         x *= 0.5;
//!         k += 1;
//!     }
//!     let done = x.abs() <= 1e-3;
//!     Ok(SolverReport {
//!         params: vec![x],
//!         ssr: x * x,
//!         termination: if done { Termination::SmallReduction } else { Termination::MaxIterations },
//!         iterations: k,
//!         evaluations: k + 1,
//!         gradient_norm: 0.0,
//!         damping: 0.0,
//!         bounds: vec![BoundStatus::Free],
//!     })
//! };
//! let rounds = Rounds { first: 5, carry: 1, within: 1e4 };
//! let r = multistart_in_rounds(&[vec![0.01], vec![1.0], vec![1e9]], 100, &rounds, solve).unwrap();
//! // The start at 1e9 is still far away after 5 iterations and is dropped;
//! // the one at 1.0 is close enough after 5 and is solved again to the end.
//! assert_eq!(r.n_converged, 2);
//! assert!(r.ssr[2] > 1e12);
//! ```

use crate::SolveError;
use crate::multistart::{MultiStartReport, solve_each, summarise};
use crate::report::{SolverReport, Termination};

/// How [`multistart_in_rounds`] splits its iterations.
#[derive(Clone, Debug, PartialEq)]
pub struct Rounds {
    /// Iteration cap of the first round.
    pub first: usize,
    /// Most starts carried into the second round (the lowest costs among
    /// those the first round stopped at its cap).
    pub carry: usize,
    /// A start is carried only when its cost after the first round is at
    /// most this many times the least cost of the round.
    pub within: f64,
}

/// Solve every start in two rounds ([`Rounds`]), the second under `cap`
/// iterations, and keep the best as [`multistart`](crate::multistart::multistart) does.
/// `solve(p, cap)` solves from the start `p` under an iteration cap. A
/// carried start's report is its second solve's, its iterations and
/// evaluations those of both rounds (the work done).
pub fn multistart_in_rounds<F>(
    starts: &[Vec<f64>],
    cap: usize,
    rounds: &Rounds,
    solve: F,
) -> Result<MultiStartReport, SolveError>
where
    F: Fn(&[f64], usize) -> Result<SolverReport, SolveError> + Sync,
{
    if starts.is_empty() {
        return Err(SolveError::Empty { what: "starts" });
    }
    let first_cap = cap.min(rounds.first);
    let mut results = solve_each(starts, |s| solve(s, first_cap));
    let carried = carried(&results, rounds);
    if first_cap == cap || carried.is_empty() {
        return summarise(results);
    }
    let again = solve_each(&carried, |i| solve(&starts[*i], cap));
    for (i, second) in carried.into_iter().zip(again) {
        if let (Ok(first), Ok(second)) = (&results[i], second) {
            results[i] = Ok(joined(first, second));
        }
    }
    summarise(results)
}

/// The starts the first round stopped at its cap whose cost is within
/// `rounds.within` of the round's least, at most `rounds.carry` of them,
/// lowest cost first (ties by index).
fn carried(results: &[Result<SolverReport, SolveError>], rounds: &Rounds) -> Vec<usize> {
    let best = results
        .iter()
        .filter_map(|r| r.as_ref().ok())
        .map(|r| r.ssr)
        .filter(|s| s.is_finite())
        .fold(f64::INFINITY, f64::min);
    let mut going: Vec<(f64, usize)> = results
        .iter()
        .enumerate()
        .filter_map(|(i, r)| r.as_ref().ok().map(|r| (i, r)))
        .filter(|(_, r)| {
            r.termination == Termination::MaxIterations
                && r.ssr.is_finite()
                && r.ssr <= rounds.within * best
        })
        .map(|(i, r)| (r.ssr, i))
        .collect();
    going.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    going
        .into_iter()
        .take(rounds.carry)
        .map(|(_, i)| i)
        .collect()
}

/// A start's second solve, with the work of both rounds.
fn joined(first: &SolverReport, second: SolverReport) -> SolverReport {
    SolverReport {
        iterations: first.iterations + second.iterations,
        evaluations: first.evaluations + second.evaluations,
        ..second
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A solve that halves `x` per iteration down to `stop`.
    fn halving(p: &[f64], cap: usize) -> Result<SolverReport, SolveError> {
        let (mut x, mut k) = (p[0], 0);
        while x.abs() > 1e-3 && k < cap {
            x *= 0.5;
            k += 1;
        }
        let done = x.abs() <= 1e-3;
        Ok(SolverReport {
            params: vec![x],
            ssr: x * x,
            iterations: k,
            evaluations: k + 1,
            termination: if done {
                Termination::SmallReduction
            } else {
                Termination::MaxIterations
            },
            gradient_norm: 0.0,
            damping: 0.0,
            bounds: vec![crate::BoundStatus::Free],
        })
    }

    #[test]
    fn carried_starts_end_where_one_round_would() {
        let starts = vec![vec![3.0], vec![0.5], vec![2.0]];
        let one = crate::multistart(&starts, |s| halving(s, 100)).unwrap();
        let rounds = Rounds {
            first: 3,
            carry: 3,
            within: f64::INFINITY,
        };
        let two = multistart_in_rounds(&starts, 100, &rounds, halving).unwrap();
        assert_eq!(one.ssr, two.ssr);
        assert_eq!(one.best_start, two.best_start);
        assert_eq!(one.best.params, two.best.params);
        assert_eq!(one.n_converged, two.n_converged);
        // Every start was still going after 3 iterations and was solved
        // again: the best one's report counts those 3 besides its own.
        assert_eq!(two.best.iterations, one.best.iterations + 3);
    }

    #[test]
    fn far_or_surplus_starts_stop_after_the_first_round() {
        // After 2 iterations: 0.25 (converges later), 1.0, 2.5e8.
        let starts = vec![vec![1.0], vec![4.0], vec![1e9]];
        let rounds = Rounds {
            first: 2,
            carry: 1,
            within: 100.0,
        };
        let r = multistart_in_rounds(&starts, 50, &rounds, halving).unwrap();
        // Only the lowest of those still going is carried.
        assert_eq!(r.n_converged, 1);
        assert_eq!(r.best_start, 0);
        assert_eq!(r.ssr[1], 1.0);
        assert_eq!(r.ssr[2], 2.5e8 * 2.5e8);
        // Its report counts both rounds: 2 halvings, then the 10 from 1.0
        // that reach 1e-3.
        assert_eq!(r.best.iterations, 12);
        assert_eq!(r.best.evaluations, 3 + 11);
    }

    #[test]
    fn no_start_is_an_error() {
        let rounds = Rounds {
            first: 2,
            carry: 1,
            within: 10.0,
        };
        assert!(multistart_in_rounds(&[], 10, &rounds, halving).is_err());
    }
}
