//! Selection by image error (Bieron and Peers 2020): renderer models each
//! fitted for appearance ([`crate::appearance`]) and judged at the report
//! size ([`brdf_render::judge`]); the least mean FLIP is the choice.

use std::time::Instant;

use brdf_core::{Brdf, SampleSet};
use brdf_render::ImageError;
use brdf_render::judge::{Judge, REPORT_SIZE};
use serde::Serialize;

use crate::judged::fit_judged_on;
use crate::{Fit, FitError};

/// One model of [`select_by_image`]: its appearance fit and image errors.
#[derive(Clone, Debug, Serialize)]
pub struct ImageChoice {
    /// Catalogue name.
    pub model: String,
    /// Objective of the chosen candidate of this model.
    pub objective: String,
    /// Optional lobes it kept.
    pub lobes: Vec<String>,
    /// Its image errors at [`REPORT_SIZE`] pixels.
    pub image: ImageError,
    /// Ngan's L2.
    pub ngan_l2: f64,
    /// Parameters.
    pub parameters: usize,
    /// Seconds of the model's appearance fit.
    pub seconds: f64,
}

/// Selection by image error (Bieron and Peers 2020): every model of
/// `models` fitted for appearance to `samples` (each fit ended by the
/// search on its render's FLIP when `polish`, [`Fit::polish_on_flip`]),
/// judged against `data` at [`REPORT_SIZE`] pixels; the index of the least
/// mean FLIP is the choice.
pub fn select_by_image(
    models: &[&str],
    samples: &SampleSet,
    data: &dyn Brdf,
    polish: bool,
) -> Result<(Vec<ImageChoice>, usize), FitError> {
    // The data rendered once at the report size for every model; the
    // models fitted in parallel (rows in the order of `models`, each fit
    // the same for any number of threads).
    let judge = Judge::with_data(REPORT_SIZE, data)?;
    use rayon::prelude::*;
    let rows = models
        .par_iter()
        .map(|name| {
            let t0 = Instant::now();
            let fit = Fit::model(name)?.polish_on_flip(polish);
            let report = fit_judged_on(&fit, samples, data, true, &judge)?;
            let chosen = report.candidates.iter().find(|c| c.chosen);
            Ok(ImageChoice {
                model: report.summary.model.clone(),
                objective: chosen.map_or_else(String::new, |c| c.objective.clone()),
                lobes: chosen.map_or_else(Vec::new, |c| c.lobes.clone()),
                image: report
                    .image_error
                    .clone()
                    .ok_or_else(|| FitError::NoImageError {
                        data: samples.name.clone(),
                    })?,
                ngan_l2: report.summary.ngan_l2,
                parameters: report.summary.parameters.len(),
                seconds: t0.elapsed().as_secs_f64(),
            })
        })
        .collect::<Result<Vec<_>, FitError>>()?;
    let choice = (0..rows.len())
        .min_by(|a, b| {
            rows[*a]
                .image
                .mean_flip()
                .total_cmp(&rows[*b].image.mean_flip())
        })
        .ok_or(FitError::NoModelToFit)?;
    Ok((rows, choice))
}
