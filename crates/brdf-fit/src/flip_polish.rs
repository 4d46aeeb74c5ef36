//! The last step of a fit for appearance, on request
//! ([`crate::Fit::polish_on_flip`]): a search on the judge's own metric.
//!
//! The image objective ([`crate::image_objective`]) is a least-squares
//! stand-in for what the judge measures: log residuals of the pixels.
//! HDR-FLIP, the judge's metric, filters the images by the eye's contrast
//! sensitivity, weighs edges and points, and takes the worst of several
//! exposures; it has no Jacobian a least-squares solver could use. So the
//! fit chosen by [`crate::appearance::fit_for_appearance`] is moved by
//! compass search ([`brdf_solve::compass`], derivative-free, in the fit's
//! own boxes: held parameters stay held) to lower the mean FLIP of its
//! renders at the fitting size ([`brdf_render::judge::FIT_SIZE`]).
//!
//! Measured (`brdf fit --model principled --polish` on the shared RGL
//! files; brdf-render's judge at 128 px, sky / studio, before -> after):
//! cc_iris_purple_gem 0.319 / 0.230 -> 0.286 / 0.231 (Mitsuba's judge:
//! sky 0.330 -> 0.299), colodur_napoli 0.072 / 0.049 -> 0.071 / 0.047,
//! cc_ibiza_sunset 0.306 / 0.217 -> 0.305 / 0.217 (its mean colour, 3.3
//! from the data's, bounds the search), vch_golden_yellow 0.228 / 0.183
//! -> 0.226 / 0.177; on paper_white the searched point is not kept (its
//! Ngan's L2 grew from 0.015 to 2.8: a lobe the 32-px renders do not
//! see). Without the colour limit the search took the iris film's colour
//! difference from 1.5 to 4.2. The search costs one render per
//! evaluation, so at most [`POLISH_EVALUATIONS`] of them.
//!
//! The polished fit's report is the fit's own pipeline summarising the
//! point (Ngan's L2, standard errors, notes on bounds), its solver and
//! termination those of the search.

use std::sync::Arc;

use brdf_core::SampleSet;
use brdf_render::{ImageError, Judge};
use brdf_solve::{CompassOptions, LmOptions, compass_search};

use crate::image_objective::ImageTarget;
use crate::termination::Termination;
use crate::{Fit, FitError, FitReport, Objective};

/// Evaluation budget of the search (each one renders the fit under every
/// light set at [`brdf_render::judge::FIT_SIZE`] pixels, about 25 ms on
/// two cores). The default principled fits of the shared films converge
/// within it (cc_iris_purple_gem, the longest, in 196 evaluations; with
/// 150 it stopped at the budget at the same mean FLIP to four digits).
pub const POLISH_EVALUATIONS: usize = 200;

/// First step of each parameter, a share of its box's width.
pub const POLISH_STEP: f64 = 0.05;

/// Smallest step, a share of its box's width: finer moves do not change
/// a 32-pixel render's FLIP in its third digit.
pub const POLISH_MIN_STEP: f64 = 1e-3;

/// Mean-colour CIEDE2000 (worst light set) the search may reach when the
/// start's is lower: a just-noticeable difference (Sharma 2003: 2.3).
pub const COLOUR_DRIFT: f64 = 2.3;

/// `report` (a fit of `fit`, with its lobes set, in the image objective
/// of `target`; `start` its image errors under `judge`) moved to a lower
/// mean FLIP under `judge`; `None` when no step lowered it.
pub(crate) fn polish(
    fit: &Fit,
    report: &FitReport,
    start: &ImageError,
    target: &ImageTarget,
    judge: &Judge,
    samples: &SampleSet,
) -> Result<Option<FitReport>, FitError> {
    let mut model = report.model.clone_box();
    let specs = model.param_specs().to_vec();
    let lower: Vec<f64> = specs.iter().map(|s| s.lower).collect();
    let upper: Vec<f64> = specs.iter().map(|s| s.upper).collect();
    // A point the model refuses (an open bound) or the judge cannot
    // render is never taken, nor one whose mean colour drifts beyond
    // COLOUR_DRIFT (FLIP alone let cc_iris_purple_gem's colour difference
    // grow from 1.5 to 4.2 for a sky FLIP 0.04 lower).
    let colour_limit = start.max_delta_e().max(COLOUR_DRIFT);
    let mean_flip = |p: &[f64]| -> f64 {
        if model.set_params(p).is_err() {
            return f64::INFINITY;
        }
        match judge.fit_errors(model.as_ref()) {
            Ok(e) if e.max_delta_e() <= colour_limit => e.mean_flip(),
            _ => f64::INFINITY,
        }
    };
    let opts = CompassOptions {
        initial_step: POLISH_STEP,
        shrink: 0.5,
        min_step: POLISH_MIN_STEP,
        max_evaluations: POLISH_EVALUATIONS,
    };
    let found = compass_search(mean_flip, report.model.params(), &lower, &upper, &opts)?;
    if found.moves == 0 {
        return Ok(None);
    }
    // The fit's own pipeline summarises the point: the image objective
    // started there and given no iteration.
    let at = ImageTarget {
        start: found.x.clone(),
        ..target.clone()
    };
    let mut out = fit
        .clone()
        .objective(Objective::Image)
        .image_target(Arc::new(at))
        .lm_options(LmOptions {
            max_iterations: 0,
            ..LmOptions::default()
        })
        .run(samples)?;
    out.summary.solver = format!(
        "compass search on the mean HDR-FLIP of brdf-render's renders ({} light sets, {} px; at most {POLISH_EVALUATIONS} renders), from the fit in the image objective",
        judge.lights(),
        judge.size()
    );
    out.summary.iterations = found.evaluations;
    out.summary.termination = Termination::FlipSearch {
        end: found.termination,
        mean_flip: found.value,
        from: found.start_value,
    };
    Ok(Some(out))
}
