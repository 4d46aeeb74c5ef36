//! Why a fit stopped ([`Termination`]), typed from the solver that ended
//! it to every report: [`Termination::is_converged`] answers whether the
//! result is a (local) minimum, and its `Display` is the sentence the
//! reports print. It serialises as that sentence, so JSON reports read as
//! before, and a sentence read back from one (a `fits.jsonl` line) parses
//! to the same value ([`str::parse`]).

use std::fmt;
use std::str::FromStr;

use brdf_solve::{CompassTermination, IrlsTermination};
use serde::{Serialize, Serializer};

/// Why a fit stopped.
#[derive(Clone, Debug, PartialEq)]
pub enum Termination {
    /// An all-linear model solved directly (no iteration to end).
    DirectSolve,
    /// The bounded solver's own reason.
    Solver(brdf_solve::Termination),
    /// The solver stopped on a plateau with a singular Jacobian where a
    /// term of the model has vanished and `lost`, the parameters only that
    /// term used, have no influence at all: a degenerate but genuine fit.
    Degenerate {
        /// How the term vanished.
        cause: VanishedTerm,
        /// The parameters without influence.
        lost: Vec<String>,
    },
    /// The robust (IRLS) fit's reason (the first channel's that did not
    /// converge, else the last's).
    Irls(IrlsTermination),
    /// The search on the judge's mean FLIP ([`crate::flip_polish`]).
    FlipSearch {
        /// Why the compass search stopped.
        end: CompassTermination,
        /// Mean FLIP at the end.
        mean_flip: f64,
        /// Mean FLIP at the start.
        from: f64,
    },
    /// The solve from the coarse-subsample optimum that a selection kept
    /// over the default starts' fit ([`crate::select`]).
    FromCoarseOptimum {
        /// The solver's reason.
        end: brdf_solve::Termination,
        /// Ngan's L2 of the default starts' fit.
        default_cost: f64,
    },
}

/// How a term of a degenerate fit vanished.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VanishedTerm {
    /// A linear coefficient sits at 0, its lower bound.
    LinearTermZero,
    /// Parameters on their bounds switch the term off (principled's
    /// dielectric lobe at `metallic = 1`).
    SwitchedOffByBounds,
}

impl Termination {
    /// Whether the fit ended at a (local) minimum: the solvers' converged
    /// reasons, a degenerate fit, a direct solve, a FLIP search whose
    /// steps all fell below tolerance.
    pub fn is_converged(&self) -> bool {
        match self {
            Termination::DirectSolve | Termination::Degenerate { .. } => true,
            Termination::Solver(t) | Termination::FromCoarseOptimum { end: t, .. } => {
                t.is_converged()
            }
            Termination::Irls(t) => t.is_converged(),
            Termination::FlipSearch { end, .. } => *end == CompassTermination::StepBelowTolerance,
        }
    }
}

impl fmt::Display for Termination {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Termination::DirectSolve => f.write_str("direct solve"),
            Termination::Solver(t) => f.write_str(t.describe()),
            Termination::Degenerate {
                cause: VanishedTerm::LinearTermZero,
                lost,
            } => write!(
                f,
                "converged to a degenerate fit: a linear term is 0, so {} have no influence",
                lost.join(", ")
            ),
            Termination::Degenerate {
                cause: VanishedTerm::SwitchedOffByBounds,
                lost,
            } => write!(
                f,
                "converged to a degenerate fit: parameters on their bounds switch off the term of {}, which then have no influence",
                lost.join(", ")
            ),
            Termination::Irls(t) => write!(f, "IRLS {}", t.describe()),
            Termination::FlipSearch {
                end,
                mean_flip,
                from,
            } => write!(
                f,
                "{}; mean FLIP {mean_flip:.4} from {from:.4}",
                end.describe()
            ),
            Termination::FromCoarseOptimum { end, default_cost } => write!(
                f,
                "{} (from the coarse optimum, below the default starts' {default_cost:.4e})",
                end.describe()
            ),
        }
    }
}

impl Serialize for Termination {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

/// Every reason of the bounded solver, to read its sentence back.
const SOLVER_ENDS: [brdf_solve::Termination; 9] = {
    use brdf_solve::Termination as T;
    [
        T::ZeroResidual,
        T::SmallGradient,
        T::SmallReduction,
        T::SmallStep,
        T::SingularPlateau,
        T::MaxIterations,
        T::MaxEvaluations,
        T::DampingLimit,
        T::NonFiniteStart,
    ]
};

/// Every reason of the robust fit, to read its sentence back.
const IRLS_ENDS: [IrlsTermination; 5] = [
    IrlsTermination::CoefficientTest,
    IrlsTermination::DevianceTest,
    IrlsTermination::ExactFit,
    IrlsTermination::IterationCap,
    IrlsTermination::Cycle,
];

/// Every reason of the compass search, to read its sentence back.
const COMPASS_ENDS: [CompassTermination; 2] = [
    CompassTermination::StepBelowTolerance,
    CompassTermination::EvaluationBudget,
];

/// A sentence that is not one [`Termination`] prints.
#[derive(Debug, thiserror::Error)]
#[error("`{0}` is not how a fit ends")]
pub struct UnknownTermination(pub String);

impl FromStr for Termination {
    type Err = UnknownTermination;

    /// The termination whose `Display` is `s`.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let unknown = || UnknownTermination(s.to_string());
        if s == "direct solve" {
            return Ok(Termination::DirectSolve);
        }
        if let Some(t) = SOLVER_ENDS.into_iter().find(|t| t.describe() == s) {
            return Ok(Termination::Solver(t));
        }
        if let Some(t) = s
            .strip_prefix("IRLS ")
            .and_then(|r| IRLS_ENDS.into_iter().find(|t| t.describe() == r))
        {
            return Ok(Termination::Irls(t));
        }
        let degenerate = [
            (
                VanishedTerm::LinearTermZero,
                "converged to a degenerate fit: a linear term is 0, so ",
                " have no influence",
            ),
            (
                VanishedTerm::SwitchedOffByBounds,
                "converged to a degenerate fit: parameters on their bounds switch off the term of ",
                ", which then have no influence",
            ),
        ];
        for (cause, head, tail) in degenerate {
            if let Some(lost) = s.strip_prefix(head).and_then(|r| r.strip_suffix(tail)) {
                let lost = lost.split(", ").map(str::to_string).collect();
                return Ok(Termination::Degenerate { cause, lost });
            }
        }
        if let Some((end, rest)) = s.split_once("; mean FLIP ") {
            let end = COMPASS_ENDS
                .into_iter()
                .find(|t| t.describe() == end)
                .ok_or_else(unknown)?;
            let (at, from) = rest.split_once(" from ").ok_or_else(unknown)?;
            return Ok(Termination::FlipSearch {
                end,
                mean_flip: at.parse().map_err(|_| unknown())?,
                from: from.parse().map_err(|_| unknown())?,
            });
        }
        if let Some((end, rest)) =
            s.split_once(" (from the coarse optimum, below the default starts' ")
        {
            let end = SOLVER_ENDS
                .into_iter()
                .find(|t| t.describe() == end)
                .ok_or_else(unknown)?;
            let cost = rest.strip_suffix(')').ok_or_else(unknown)?;
            return Ok(Termination::FromCoarseOptimum {
                end,
                default_cost: cost.parse().map_err(|_| unknown())?,
            });
        }
        Err(unknown())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every kind of termination reads back from its sentence (the
    /// numbers to the digits the sentence keeps).
    #[test]
    fn sentences_read_back() {
        let mut all: Vec<Termination> = vec![Termination::DirectSolve];
        all.extend(SOLVER_ENDS.map(Termination::Solver));
        all.extend(IRLS_ENDS.map(Termination::Irls));
        for cause in [
            VanishedTerm::LinearTermZero,
            VanishedTerm::SwitchedOffByBounds,
        ] {
            all.push(Termination::Degenerate {
                cause,
                lost: vec!["specular".into(), "spec_tint".into()],
            });
        }
        all.extend(COMPASS_ENDS.map(|end| Termination::FlipSearch {
            end,
            mean_flip: 0.251,
            from: 0.26,
        }));
        all.push(Termination::FromCoarseOptimum {
            end: brdf_solve::Termination::SmallStep,
            default_cost: 1.5e-3,
        });
        for t in all {
            let back: Termination = t.to_string().parse().expect("parses");
            assert_eq!(back, t, "{t}");
            assert_eq!(back.is_converged(), t.is_converged());
        }
        assert!("not recorded".parse::<Termination>().is_err());
    }
}
