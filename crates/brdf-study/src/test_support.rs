//! Fit summaries made by hand for the unit tests of the study's tables.

use brdf_fit::{FitSummary, FittedParam, Termination};

/// A parameter of a hand-made summary.
pub(crate) fn param(
    name: &str,
    value: f64,
    at_bound: Option<&str>,
    projected: bool,
) -> FittedParam {
    FittedParam {
        name: name.to_string(),
        value,
        std_error: None,
        at_bound: at_bound.map(str::to_string),
        projected,
    }
}

/// A summary that ended with `termination` at `parameters` (every other
/// field empty or zero).
pub(crate) fn summary(termination: Termination, parameters: Vec<FittedParam>) -> FitSummary {
    FitSummary {
        model: String::new(),
        data: String::new(),
        samples: 0,
        parameters,
        objective: "ngan",
        error: 0.0,
        error_per_channel: vec![],
        ngan_l2: 0.0,
        ngan_l2_per_channel: vec![],
        solver: String::new(),
        iterations: 0,
        termination,
        starts: (0, 0, 0),
        seconds: 0.0,
        stored_numbers: 0,
        inert: vec![],
    }
}
