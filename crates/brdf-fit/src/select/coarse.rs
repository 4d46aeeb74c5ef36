//! The coarse-to-fine selection ([`Search::CoarseToFine`]): every candidate
//! is fitted first to ONE shared deterministic stratified subsample of
//! about [`COARSE_SAMPLES`] samples; only the candidates whose coarse error
//! is within [`RACE_FACTOR`]` (1 + tolerance)` of the best coarse error are
//! fitted again to all samples, by the default fit with their coarse
//! optimum as one more start. The others keep a row with their coarse
//! error, marked as screened out, and cannot be chosen.
//!
//! Most candidates of a material are far from the best (a Lambertian fit
//! of a glossy paper, a polynomial of degree 1): their full fits, which
//! cost as much as the good ones', decide nothing.
//!
//! [`Search::CoarseToFine`]: super::Search::CoarseToFine

use brdf_core::{Parametric, SampleSet};
use brdf_solve::{BoundStatus, LmOptions, ModelProblem, SolverReport, bounded_least_squares};
use rayon::prelude::*;

use super::candidates::{Candidate, Todo};
use super::{Fitted, SelectRow, fit_candidate};
use crate::FitError;
use crate::objective::Objective;
use crate::options::FitOptions;
use crate::param_box::box_constraints;
use crate::pipeline::fit;
use crate::summary::FitSummary;
use crate::termination::Termination;

/// Size of the shared coarse subsample (every `k`-th sample of the
/// prepared data, `k = ceil(n / COARSE_SAMPLES)`, as the pipeline's start
/// screening subsamples: 2020 of the 20,196 samples of an RGL file), so
/// that a candidate's coarse fit costs a fraction of its full one. It
/// ranks diffuse materials well (paper_white: coarse and full errors
/// within 1.5% for the candidates near the best) and glossy ones poorly
/// (the highlight is sampled sparsely), which [`RACE_FACTOR`] absorbs.
/// Data of at most this many samples have no coarse stage: every
/// candidate is fitted to all of them.
pub const COARSE_SAMPLES: usize = 2_048;

/// A candidate is fitted to all samples when its coarse error is at most
/// `RACE_FACTOR (1 + tolerance)` times the best coarse error.
///
/// Measured on the five RGL files (`$BRDF_DATA/rgl`, tolerance 0.1, every
/// candidate fitted both ways): the exhaustive choice and the candidate
/// with the best full error need factors of at most 1.25 (cc_ibiza_sunset:
/// the chosen `ggx-aniso` has 1.38 times the best coarse error, that of a
/// 2-lobe Lafortune which the sparse highlight of the subsample flatters
/// by a factor 6), 1.09 (cc_iris_purple_gem), 0.93 (colodur_napoli), 0.98
/// (vch_golden_yellow) and 0.99 (paper_white); 1.35 leaves a margin of 8%
/// above the largest. It refits 2-18 of the 64 candidates there (4 on
/// paper_white), and the choice equals the exhaustive one on all five.
pub const RACE_FACTOR: f64 = 1.35;

/// The rows of every candidate of `todo` (in their order), coarse to fine.
pub(super) fn coarse_to_fine(
    data: &SampleSet,
    tolerance: f64,
    opts: &FitOptions,
    todo: Vec<Todo>,
) -> Vec<Fitted> {
    let (sub, _) = crate::starts::stratified_subsample(data, COARSE_SAMPLES);
    if sub.len() == data.len() {
        return super::fit_all(data, opts, todo);
    }
    // Stage 1: every candidate on the shared subsample (a copy of its
    // model: the fine stage fits the one built for all samples).
    let coarse: Vec<Stage> = todo
        .into_par_iter()
        .map(|t| match t {
            Todo::Fit(c) => {
                let (row, fitted) = fit_candidate(
                    &sub,
                    opts,
                    c.label.clone(),
                    c.name,
                    c.model.clone_box(),
                    false,
                );
                Stage::Coarse(Coarse {
                    candidate: c,
                    fitted,
                    row,
                })
            }
            Todo::Failed(row) => Stage::Failed(row),
        })
        .collect();
    // The bar from the best finite coarse error (a minimum: the same for
    // any order of the rows).
    let best = coarse
        .iter()
        .filter_map(|t| match t {
            Stage::Coarse(c) => Some(c.row.error),
            Stage::Failed(_) => None,
        })
        .filter(|e| e.is_finite())
        .fold(f64::INFINITY, f64::min);
    let bar = RACE_FACTOR * (1.0 + tolerance) * best;
    // Stage 2: the candidates near the best (and those whose coarse fit
    // failed: what cannot be measured cannot be screened out) on all
    // samples.
    coarse
        .into_par_iter()
        .map(|t| match t {
            Stage::Failed(row) => (row, None),
            Stage::Coarse(c) if c.row.error > bar => (c.row.screened(data.len(), bar), None),
            Stage::Coarse(c) => c.fine(data, opts),
        })
        .collect()
}

/// A candidate after the coarse stage.
enum Stage {
    /// Fitted (or failed) on the subsample.
    Coarse(Coarse),
    /// Could not be built: its row.
    Failed(SelectRow),
}

/// A candidate fitted on the coarse subsample.
struct Coarse {
    candidate: Candidate,
    /// The model at its coarse optimum (`None` when the coarse fit failed).
    fitted: Option<Box<dyn Parametric>>,
    row: SelectRow,
}

impl Coarse {
    /// The candidate fitted to all samples, from its coarse optimum too.
    fn fine(self, data: &SampleSet, opts: &FitOptions) -> Fitted {
        let Candidate { label, name, model } = self.candidate;
        let coarse_error = self.row.error.is_finite().then_some(self.row.error);
        let (model, from_coarse) = match self.fitted {
            Some(m) => (m, true),
            None => (model, false),
        };
        let (mut row, fitted) = fit_candidate(data, opts, label, name, model, from_coarse);
        row.seconds += self.row.seconds;
        row.coarse_error = coarse_error;
        (row, fitted)
    }
}

/// The default fit of `m` to `d`, with `m`'s current parameters (the
/// coarse optimum) as one more start, treated as the pipeline treats its
/// own: solved on all samples to the search tolerance, and, when that
/// beats the default fit's Ngan cost, polished to the full tolerances and
/// kept. The result is never worse than the default starts' alone. Only
/// for the Ngan objective (the one selection compares) and models with a
/// non-linear parameter (an all-linear model's direct solve has no
/// start). The search keeps the solver's own iteration cap, not the
/// model's polish factor: measured on paper_white, SGD's joint problem
/// crept for 71 s at the polish cap from its coarse optimum.
pub(super) fn fit_from_current(
    m: &mut dyn Parametric,
    d: &SampleSet,
    opts: &FitOptions,
) -> Result<FitSummary, FitError> {
    let start = m.params().to_vec();
    let summary = fit(m, d, opts)?;
    if opts.objective != Objective::Ngan || m.param_specs().iter().all(|s| s.linear) {
        return Ok(summary);
    }
    // A failed extra start leaves the default fit standing.
    match extra_start(&*m, d, opts, &start, summary.ngan_l2) {
        Ok(Some(better)) => adopt(m, d, opts, summary, better),
        Ok(None) | Err(_) => Ok(summary),
    }
}

/// The solve of `m`'s Ngan problem on `d` from `start` (see
/// [`fit_from_current`]): its report when it ends below `default_cost`
/// (Ngan L2).
fn extra_start(
    m: &dyn Parametric,
    d: &SampleSet,
    opts: &FitOptions,
    start: &[f64],
    default_cost: f64,
) -> Result<Option<SolverReport>, FitError> {
    let values = d.values_channel_major();
    let scales = Objective::Ngan.row_scales(d);
    let problem = ModelProblem::new(m, d.pairs(), &values, &scales)?;
    let full = box_constraints(m)?;
    let t = opts.search_tolerance;
    let search = LmOptions {
        ftol: opts.lm.ftol.max(t),
        xtol: opts.lm.xtol.max(t),
        gtol: opts.lm.gtol.max(t),
        ..opts.lm.clone()
    };
    let found = bounded_least_squares(&problem, start, &full, &search)?;
    if !(ngan(m, d, &found.params)? < default_cost) {
        return Ok(None);
    }
    let factor = brdf_models::polish_factor(m);
    let polish_lm = LmOptions {
        max_iterations: opts.lm.max_iterations * factor,
        max_evaluations: opts.lm.max_evaluations * factor,
        ..opts.lm.clone()
    };
    let polish = bounded_least_squares(&problem, &found.params, &full, &polish_lm)?;
    let iterations = found.iterations + polish.iterations;
    let kept = if polish.ssr <= found.ssr {
        polish
    } else {
        found
    };
    Ok(Some(SolverReport { iterations, ..kept }))
}

/// Ngan's L2 of `m` at `p` on `d`.
fn ngan(m: &dyn Parametric, d: &SampleSet, p: &[f64]) -> Result<f64, FitError> {
    Ok(ngan_of(d, &values_at(m, d, p))?.total)
}

/// `m`'s values at `p` on `d`'s pairs (channel-major).
fn values_at(m: &dyn Parametric, d: &SampleSet, p: &[f64]) -> Vec<f64> {
    let mut fitted = vec![0.0; d.len() * m.channels()];
    m.eval_batch_at(p, d.pairs(), &mut fitted);
    fitted
}

/// Ngan's L2 of the values `fitted` against `d`.
fn ngan_of(d: &SampleSet, fitted: &[f64]) -> Result<brdf_core::MetricValue, FitError> {
    Ok(brdf_core::metrics::ngan_l2(
        &d.values_channel_major(),
        fitted,
        &d.pairs().lz,
        d.weights(),
    )?)
}

/// The default fit's summary with the extra start's result `rep` in its
/// place (and `m` set to it).
fn adopt(
    m: &mut dyn Parametric,
    d: &SampleSet,
    opts: &FitOptions,
    mut summary: FitSummary,
    rep: SolverReport,
) -> Result<FitSummary, FitError> {
    let p = rep.params;
    m.set_params(&p)?;
    let fitted = values_at(m, d, &p);
    let err = opts.objective.error(d, &fitted)?;
    let ngan = ngan_of(d, &fitted)?;
    let status = box_constraints(m)?.status(&p);
    for ((fp, v), s) in summary.parameters.iter_mut().zip(&p).zip(&status) {
        fp.value = *v;
        fp.std_error = None;
        fp.at_bound = match s {
            BoundStatus::Free => None,
            BoundStatus::AtLower => Some("lower".into()),
            BoundStatus::AtUpper => Some("upper".into()),
        };
    }
    let default_cost = summary.ngan_l2;
    summary.error = err.total;
    summary.error_per_channel = err.per_channel;
    summary.ngan_l2 = ngan.total;
    summary.ngan_l2_per_channel = ngan.per_channel;
    summary.iterations = rep.iterations;
    summary.termination = Termination::FromCoarseOptimum {
        end: rep.termination,
        default_cost,
    };
    summary.solver = format!(
        "{}; the coarse-subsample optimum solved on all samples as one more start",
        summary.solver
    );
    Ok(summary)
}
