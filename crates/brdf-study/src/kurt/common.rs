//! What the Kurt tables and figures share: Kurt's published values, the
//! five materials of Table 9.2, the error a table reports, convergence,
//! and the note on Lafortune's box.

use brdf_fit::FitSummary;

/// Kurt's Table 9.2 (RGB CUReT), rows in the order of
/// [`crate::context::models::nine_models`]: felt, orange peel, quarry tile,
/// slate a, slate b.
pub const KURT_9_2: [[f64; 5]; 9] = [
    [0.0190, 0.0217, 0.0165, 0.0121, 0.0223],
    [0.0518, 0.0626, 0.0369, 0.0196, 0.0586],
    [0.0229, 0.0213, 0.0136, 0.0107, 0.0236],
    [0.0170, 0.0245, 0.0117, 0.0070, 0.0184],
    [0.0571, 0.0740, 0.0429, 0.0249, 0.0711],
    [0.0385, 0.0420, 0.0241, 0.0124, 0.0383],
    [0.0238, 0.0219, 0.0137, 0.0109, 0.0243],
    [0.0087, 0.0126, 0.0069, 0.0059, 0.0068],
    [0.0161, 0.0306, 0.0108, 0.0069, 0.0189],
];

/// The five materials of Table 9.2: (CUReT number, name).
pub const TABLE_9_2_MATERIALS: [(u32, &str); 5] = [
    (1, "felt"),
    (55, "orange peel"),
    (25, "quarry tile"),
    (33, "slate a"),
    (34, "slate b"),
];

/// Index of a model label in the nine models (for Kurt's values).
pub fn nine_index(label: &str) -> Option<usize> {
    crate::context::models::nine_models(1)
        .iter()
        .position(|(l, _, _)| *l == label)
}

/// The error a table reports: the objective's (Ngan's L2 by default).
pub fn err(r: &FitSummary) -> f64 {
    r.error
}

/// Whether a fit ended converged (or was a direct solve).
pub fn converged(r: &FitSummary) -> bool {
    r.termination.is_converged()
}

/// Note on how Lafortune was fitted.
pub fn lafortune_note(lbox: crate::context::spec::LafortuneBox) -> &'static str {
    match lbox {
        crate::context::spec::LafortuneBox::Kurt => {
            "Lafortune in Kurt's box (Cxy in [-1, 0], Cz in [0, 1], as every value of his Appendix 3); `lafortune_box.md` compares it with the wide box [-1, 1]."
        }
        crate::context::spec::LafortuneBox::Wide => {
            "Lafortune in the wide box (Cxy, Cz in [-1, 1], back-scattering lobes allowed), NOT Kurt's box; `lafortune_box.md` states the difference."
        }
    }
}

#[cfg(test)]
mod tests {
    use super::converged;
    use brdf_fit::{FitSummary, Termination};
    use brdf_solve::{IrlsTermination, Termination as SolverEnd};

    fn ended(termination: Termination) -> FitSummary {
        crate::test_support::summary(termination, vec![])
    }

    /// "NOT converged" contains the word "converged": only the start of the
    /// description counts (the count of Table 9.4 once took it as converged).
    #[test]
    fn converged_reads_the_start_of_the_description() {
        assert!(converged(&ended(Termination::Solver(
            SolverEnd::SmallReduction
        ))));
        assert!(converged(&ended(Termination::DirectSolve)));
        assert!(!converged(&ended(Termination::Solver(
            SolverEnd::MaxIterations
        ))));
        assert!(converged(&ended(Termination::Irls(
            IrlsTermination::CoefficientTest
        ))));
        assert!(!converged(&ended(Termination::Irls(
            IrlsTermination::IterationCap
        ))));
    }
}
