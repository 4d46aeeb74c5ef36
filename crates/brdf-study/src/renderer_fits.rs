//! The renderer models (GGX, Disney principled, glTF) fitted beside Kurt's
//! nine for the Table 9.3 stand-in and the error against time. They go
//! through the same pipeline; what differs is the reporting: a renderer
//! model's fit that fails is kept as a row saying so (the thesis models
//! never fail on these data, and their tables stay as they were), and the
//! tables state whether each fit converged and which parameters it left on
//! a bound of the renderer's box.

use brdf_core::{Parametric, SampleSet};
use brdf_fit::FitSummary;
use brdf_models::ModelConfig;
use rayon::prelude::*;

use crate::StudyError;
use brdf_fit::report_text::undetermined;

use crate::context::models::{FitHow, fit_model};
use crate::context::progress;
use crate::kurt::common::converged;

/// A fitted model and its summary.
pub type Fitted = (Box<dyn Parametric>, FitSummary);

/// A model of the study: `(label, catalogue name, config)`.
pub type Model = (&'static str, &'static str, ModelConfig);

/// Fit every model to every set with `channels` colour channels, in
/// parallel over the pairs: `[model][set]`, a failed fit kept as its error.
pub fn fit_sets(
    models: &[Model],
    sets: &[SampleSet],
    channels: usize,
    how: FitHow,
    what: &str,
) -> Vec<Vec<Result<Fitted, StudyError>>> {
    let pairs: Vec<(usize, usize)> = (0..models.len())
        .flat_map(|m| (0..sets.len()).map(move |s| (m, s)))
        .collect();
    let bar = progress::bar(pairs.len(), what);
    let mut done: Vec<Result<Fitted, StudyError>> = pairs
        .par_iter()
        .map(|(m, s)| {
            let (_, name, config) = models[*m];
            let r = fit_model(name, ModelConfig { channels, ..config }, &sets[*s], how);
            bar.inc(1);
            r
        })
        .collect();
    bar.finish_and_clear();
    let mut out: Vec<Vec<Result<Fitted, StudyError>>> = Vec::with_capacity(models.len());
    for _ in models {
        let rest = done.split_off(sets.len().min(done.len()));
        out.push(std::mem::replace(&mut done, rest));
    }
    out
}

/// The parameters a fit left on a bound, as `name (lower|upper)`.
pub fn at_bounds(r: &FitSummary) -> Vec<String> {
    r.parameters
        .iter()
        .filter_map(|p| p.at_bound.as_ref().map(|b| format!("{} ({b})", p.name)))
        .collect()
}

/// How one fit ended, in words: converged or the solver's reason, the
/// parameters on a bound, the ones a switched-off lobe leaves undetermined;
/// or the error of a failed fit.
pub fn status<M>(fit: &Result<(M, FitSummary), StudyError>) -> String {
    let r = match fit {
        Ok((_, r)) => r,
        Err(e) => return format!("failed: {e}"),
    };
    let mut words = vec![if converged(r) {
        "converged".to_string()
    } else {
        r.termination.to_string()
    }];
    let bound = at_bounds(r);
    words.push(if bound.is_empty() {
        "no parameter on a bound".into()
    } else {
        format!("on a bound: {}", bound.join(", "))
    });
    let off = undetermined(r);
    if !off.is_empty() {
        words.push(format!("undetermined (lobe off): {}", off.join(", ")));
    }
    words.join("; ")
}

/// How the fits of one procedure over many materials ended, counted.
pub fn tally<'a>(fits: impl IntoIterator<Item = Option<&'a FitSummary>>) -> String {
    let (mut n, mut failed, mut conv, mut bound) = (0, 0, 0, 0);
    for f in fits {
        n += 1;
        match f {
            None => failed += 1,
            Some(r) => {
                conv += usize::from(converged(r));
                bound += usize::from(!at_bounds(r).is_empty());
            }
        }
    }
    format!("{conv}/{n} converged, {bound}/{n} with a parameter on a bound, {failed} failed")
}

#[cfg(test)]
mod tests {
    use super::*;
    use brdf_fit::Termination;

    fn summary(termination: Termination, bounds: &[(&str, Option<&str>)]) -> FitSummary {
        let params = bounds
            .iter()
            .map(|(n, b)| crate::test_support::param(n, 0.5, *b, false))
            .collect();
        crate::test_support::summary(termination, params)
    }

    #[test]
    fn status_names_the_end_and_the_bounds() {
        let free = summary(
            Termination::Solver(brdf_solve::Termination::SmallReduction),
            &[("alpha", None)],
        );
        let ok: Result<((), FitSummary), StudyError> = Ok(((), free.clone()));
        assert_eq!(status(&ok), "converged; no parameter on a bound");
        let stuck = summary(
            Termination::Solver(brdf_solve::Termination::MaxIterations),
            &[
                ("metallic", Some("upper")),
                ("roughness", None),
                ("ior", Some("lower")),
            ],
        );
        let s = status(&Ok(((), stuck.clone())));
        assert_eq!(
            s,
            "NOT converged: iteration cap; on a bound: metallic (upper), ior (lower)"
        );
        let failed: Result<((), FitSummary), StudyError> =
            Err(StudyError::Usage("no samples".into()));
        assert!(
            status(&failed).starts_with("failed: "),
            "{}",
            status(&failed)
        );
        assert_eq!(
            tally([Some(&free), Some(&stuck), None]),
            "1/3 converged, 1/3 with a parameter on a bound, 1 failed"
        );
    }
}
