//! The box a model's parameters are fitted in, as the solver's
//! constraints: every stage of the pipeline solves inside it.

use brdf_core::Parametric;
use brdf_solve::Constraints;

use crate::FitError;

/// Box constraints of a model's parameters (open lower ends moved inside by
/// `1e-9` of the box width).
pub fn box_constraints(model: &dyn Parametric) -> Result<Constraints, FitError> {
    let specs = model.param_specs();
    let lower = specs
        .iter()
        .map(|s| {
            if s.lower_open {
                s.lower + 1e-9 * (s.upper - s.lower).min(1.0)
            } else {
                s.lower
            }
        })
        .collect();
    Ok(Constraints::boxed(
        lower,
        specs.iter().map(|s| s.upper).collect(),
    )?)
}
