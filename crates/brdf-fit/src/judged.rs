//! Fits and selections as front ends run them: the fit chosen by image
//! error or the plain fit, judged at the report size, its warnings and
//! notes attached; and what a front end's `--metric` means for a model.

use std::sync::Arc;

use brdf_core::{Brdf, SampleSet};
use brdf_models::ColourStructure;

use crate::appearance::fit_for_appearance;
use crate::image_objective::{ImageTarget, image_terms};
use crate::{Fit, FitError, FitReport, Objective};
use brdf_render::ImageError;
use brdf_render::judge::{FIT_SIZE, Judge, REPORT_SIZE};

/// `outside` of
/// [`DataColourPlane`](brdf_render::image_error::DataColourPlane) above
/// which a fit of a single-colour model carries a note that its colours cannot match. Measured
/// (`results/colour_planes.md`, 128 px, studio): paper_white 0.0005,
/// colodur_napoli 0.0016, vch_golden_yellow 0.0100, cc_iris_purple_gem
/// 0.0205, cc_ibiza_sunset 0.0360. Moving every pixel of the measurement's
/// own Mitsuba render (studio) to the nearest colour of the best plane (in
/// FLIP's linear opponent space) renders at HDR-FLIP 0.036 (golden yellow),
/// 0.180 (iris) and 0.156 (ibiza) against the unmoved render before any
/// error of shape: beyond 0.015 the colours alone cost a film most of what
/// its fits show (their default fits: 0.185, 0.230, 0.216).
pub const COLOUR_PLANE_NOTE: f64 = 0.015;

/// Why a data set gets no image error.
pub const SCATTERED_NOTE: &str = "no image error: the data are scattered samples (CUReT, Cornell, CSV) that cannot be evaluated at the direction pairs of a rendered sphere; RGL `.bsdf` and MERL `.binary` data can";

/// The note of a fit of single-colour model `model` whose data lie off
/// every colour plane by more than [`COLOUR_PLANE_NOTE`].
pub fn colour_plane_note(model: &str, e: &ImageError) -> Option<String> {
    let c = e.colour_plane.as_ref()?;
    let single = brdf_models::entry(model).is_some_and(|e| e.colour == ColourStructure::Single);
    if !single || c.outside <= COLOUR_PLANE_NOTE {
        return None;
    }
    Some(format!(
        "the data's hue changes across the sphere: under the {} light {:.1}% (RMS) of its rendered colour lies off every plane of white and one colour; each `{model}` lobe is white or the base colour, so every `{model}` render lies in such a plane and none comes closer; models with colours per lobe can (e.g. `brdf fit --model sgd`, for Mitsuba exported with `brdf export --tabulate-on`)",
        c.light,
        100.0 * c.outside
    ))
}

/// A fit as front ends run it: chosen by image error when `for_appearance`
/// and the data can be rendered (`dense`, the same measurement as
/// `samples`), else `fit` itself; then its image errors at
/// [`REPORT_SIZE`] pixels and their warnings attached, or the note that
/// none can be formed.
pub fn fit_judged(
    fit: &Fit,
    samples: &SampleSet,
    dense: Option<&dyn Brdf>,
    for_appearance: bool,
) -> Result<FitReport, FitError> {
    let Some(data) = dense else {
        let mut report = fit.run(samples)?;
        report.image_note = Some(SCATTERED_NOTE.to_string());
        return Ok(report);
    };
    // The report's judge (its cells and the data's renders) does not
    // depend on the fit: built beside it, on another thread when there is
    // one.
    let (report, judge) = rayon::join(
        || fit_rendered(fit, samples, data, for_appearance),
        || Judge::with_data(REPORT_SIZE, data),
    );
    let report = report?;
    with_image_errors(report, &judge?)
}

/// [`fit_judged`] on data that can be rendered, judged by `judge` (the
/// report-size judge holding the data's renders, [`Judge::with_data`] or
/// [`Judge::rendering`]) when several fits of the same data are judged.
pub fn fit_judged_on(
    fit: &Fit,
    samples: &SampleSet,
    data: &dyn Brdf,
    for_appearance: bool,
    judge: &Judge,
) -> Result<FitReport, FitError> {
    with_image_errors(fit_rendered(fit, samples, data, for_appearance)?, judge)
}

/// The fit of [`fit_judged`] on data that can be rendered, before its
/// image errors.
fn fit_rendered(
    fit: &Fit,
    samples: &SampleSet,
    data: &dyn Brdf,
    for_appearance: bool,
) -> Result<FitReport, FitError> {
    if for_appearance {
        let (mut report, candidates) = fit_for_appearance(fit, samples, data)?;
        report.candidates = candidates;
        Ok(report)
    } else if fit.needs_image_target() {
        fit_in_image_objective(fit, samples, data)
    } else {
        fit.run(samples)
    }
}

/// `report` with its image errors by `judge` and their warnings attached.
fn with_image_errors(mut report: FitReport, judge: &Judge) -> Result<FitReport, FitError> {
    let errors = judge.fit_errors(report.model.as_ref())?;
    report.notes.extend(errors.warnings());
    report
        .notes
        .extend(colour_plane_note(report.model.name(), &errors));
    report.image_error = Some(errors);
    Ok(report)
}

/// A fit in the image objective alone (a front end's `--metric image`):
/// `fit` under Ngan's L2, then refined in the image objective at
/// [`FIT_SIZE`] pixels from there (the objective needs a start; its
/// basins trap a cold one). Unlike [`fit_for_appearance`] nothing checks
/// that the result still fits the data's unrendered directions: the
/// render is the whole objective.
pub fn fit_in_image_objective(
    fit: &Fit,
    samples: &SampleSet,
    data: &dyn Brdf,
) -> Result<FitReport, FitError> {
    let start = fit.clone().objective(Objective::Ngan).run(samples)?;
    let target = ImageTarget::new(
        image_terms(FIT_SIZE)?,
        data,
        start.model.channels(),
        start.model.params().to_vec(),
    );
    fit.clone()
        .objective(Objective::Image)
        .image_target(Arc::new(target))
        .run(samples)
}

/// [`crate::select::select_fitted`] and, when the data can be rendered
/// (`dense`, the same measurement as `samples`), the chosen model's image
/// errors at [`REPORT_SIZE`] pixels; the judge's terms and the data's
/// renders do not depend on the choice, so they are made beside the
/// selection.
pub fn select_judged(
    samples: &SampleSet,
    dense: Option<&dyn Brdf>,
    tolerance: f64,
    opts: &crate::FitOptions,
    among: &crate::select::Among,
    search: crate::select::Search,
) -> Result<(crate::select::Selection, Option<ImageError>), FitError> {
    let select = || crate::select::select_fitted(samples, tolerance, opts, among, search);
    let judge = || dense.map(|d| Judge::with_data(REPORT_SIZE, d)).transpose();
    let (selected, judge) = rayon::join(select, judge);
    let selection = selected?;
    let image = match judge? {
        Some(j) => Some(j.fit_errors(selection.model.as_ref())?),
        None => None,
    };
    Ok((selection, image))
}

/// What a front end's `--metric` (or `metric=`) means for `model`:
/// whether to fit for appearance, and the objective of the fit (of the
/// candidates' first, for appearance). `auto` is the appearance fit for a
/// renderer model on data that can be rendered, else Ngan's L2.
pub fn metric_choice<'a>(metric: &'a str, model: &str, renderable: bool) -> (bool, &'a str) {
    match metric {
        "auto" if brdf_models::entry(model).is_some_and(|e| e.renderer) && renderable => {
            (true, "ngan")
        }
        "auto" => (false, "ngan"),
        "appearance" => (true, "ngan"),
        m => (false, m),
    }
}
