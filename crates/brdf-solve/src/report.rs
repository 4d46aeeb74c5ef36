//! What a non-linear solver reports: where it stopped, why, at what cost,
//! and which parameters sit on a bound.

/// Why a solver stopped. Only [`Termination::is_converged`] reasons claim a
/// minimum.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Termination {
    /// The residual vanished (`||r|| <= tiny`): an exact fit.
    ZeroResidual,
    /// The scaled (projected) gradient fell below `gtol`.
    SmallGradient,
    /// Actual and predicted relative reductions of the cost both fell below
    /// `ftol`.
    SmallReduction,
    /// The scaled step fell below `xtol` relative to the scaled parameters.
    SmallStep,
    /// A stopping test held, but the Jacobian (scaled by the largest column
    /// norms seen) is numerically singular there: the point is a plateau
    /// where some parameter has lost its influence (BoxBOD from start 1 is
    /// the classic case), not a certified minimum.
    SingularPlateau,
    /// The iteration cap was reached.
    MaxIterations,
    /// The cap on residual evaluations was reached.
    MaxEvaluations,
    /// No step reduced the cost even at the largest damping allowed (Sopp's
    /// schedule caps the damping at 1).
    DampingLimit,
    /// The residuals or Jacobian at the start are not finite.
    NonFiniteStart,
}

impl Termination {
    /// True for the reasons that certify a (local) minimum.
    pub fn is_converged(self) -> bool {
        matches!(
            self,
            Termination::ZeroResidual
                | Termination::SmallGradient
                | Termination::SmallReduction
                | Termination::SmallStep
        )
    }

    /// A short human-readable description.
    pub fn describe(self) -> &'static str {
        match self {
            Termination::ZeroResidual => "converged: zero residual",
            Termination::SmallGradient => "converged: gradient below tolerance",
            Termination::SmallReduction => "converged: relative reduction below tolerance",
            Termination::SmallStep => "converged: step below tolerance",
            Termination::SingularPlateau => {
                "NOT converged: stopped on a plateau with a singular Jacobian"
            }
            Termination::MaxIterations => "NOT converged: iteration cap",
            Termination::MaxEvaluations => "NOT converged: evaluation cap",
            Termination::DampingLimit => "NOT converged: damping limit reached without progress",
            Termination::NonFiniteStart => "NOT converged: residuals not finite at the start",
        }
    }
}

/// Where a parameter sits relative to its bounds at the solution.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum BoundStatus {
    /// Strictly inside its box.
    Free,
    /// On (within rounding of) its lower bound.
    AtLower,
    /// On its upper bound.
    AtUpper,
}

/// The report of a non-linear least-squares solve.
#[derive(Clone, Debug)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SolverReport {
    /// The parameters at the end (always finite).
    pub params: Vec<f64>,
    /// Residual sum of squares `||r||^2` at `params`.
    pub ssr: f64,
    /// Why it stopped.
    pub termination: Termination,
    /// Outer iterations (Jacobian evaluations).
    pub iterations: usize,
    /// Residual evaluations.
    pub evaluations: usize,
    /// Infinity norm of the (projected) gradient `J^T r` at the end.
    pub gradient_norm: f64,
    /// The damping parameter at the end.
    pub damping: f64,
    /// Bound status per parameter (all `Free` without bounds).
    pub bounds: Vec<BoundStatus>,
}

impl SolverReport {
    /// Indices of the parameters on a bound.
    pub fn at_bound(&self) -> Vec<usize> {
        self.bounds
            .iter()
            .enumerate()
            .filter(|(_, b)| **b != BoundStatus::Free)
            .map(|(k, _)| k)
            .collect()
    }
}
