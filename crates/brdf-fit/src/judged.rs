//! A fit of data that can be rendered as [`crate::FitRequest`] runs it:
//! chosen by image error or the plain fit (or the image objective alone),
//! judged at the report size, its warnings and notes attached; and what a
//! fit of scattered data says instead.

use std::sync::Arc;

use brdf_core::{Brdf, SampleSet};
use brdf_models::ColourStructure;

use crate::appearance::fit_for_appearance_with;
use crate::image_objective::{ImageTarget, image_terms};
use crate::{Fit, FitError, FitReport, Objective};
use brdf_render::ImageError;
use brdf_render::judge::{FIT_SIZE, Judge};

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
        "the data's hue changes across the sphere: under the {} light {:.1}% (RMS) of its rendered colour lies off every plane of white and one colour; each `{model}` lobe is white or the base colour, so every `{model}` render lies in such a plane and none comes closer; models with a second colour can: `brdf fit --for` with `mitsuba`, `blender`, `materialx` or `gltf` fits the coloured lobes and thin films that renderer shows exactly",
        c.light,
        100.0 * c.outside
    ))
}

/// A fit of data that can be rendered, before its image errors: chosen by
/// image error when `for_appearance` (the refinement's L2 growth limited
/// to `refine_l2_growth`), else `fit` itself.
pub(crate) fn fit_rendered(
    fit: &Fit,
    samples: &SampleSet,
    data: &dyn Brdf,
    for_appearance: bool,
    refine_l2_growth: f64,
) -> Result<FitReport, FitError> {
    if for_appearance {
        let (mut report, candidates) =
            fit_for_appearance_with(fit, samples, data, refine_l2_growth)?;
        report.candidates = candidates;
        Ok(report)
    } else if fit.needs_image_target() {
        fit_in_image_objective(fit, samples, data)
    } else {
        fit.run(samples)
    }
}

/// `report` with its image errors by `judge` and their warnings attached.
pub(crate) fn with_image_errors(
    mut report: FitReport,
    judge: &Judge,
) -> Result<FitReport, FitError> {
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
/// basins trap a cold one). Unlike [`fit_for_appearance`](crate::appearance::fit_for_appearance) nothing checks
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
