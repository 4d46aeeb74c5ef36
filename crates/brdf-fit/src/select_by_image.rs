//! Selection by image error (Bieron and Peers 2020): renderer models each
//! fitted for appearance ([`crate::appearance`]) and judged at the report
//! size ([`brdf_render::judge`]); the least mean FLIP is the choice.

use std::time::Instant;

use brdf_core::progress::Task;
use brdf_models::ModelConfig;
use brdf_render::ImageError;
use rayon::prelude::*;
use serde::Serialize;

use crate::{FitError, FitReport, FitRequest, Material, Metric};

/// A model of [`select_by_image`]: its catalogue name and its number of
/// specular lobes (the models with several: the coloured lobes,
/// Lafortune, Cook-Torrance).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ModelSpec {
    /// Catalogue name (forgiving names resolve).
    pub name: String,
    /// Specular lobes (`ModelConfig::lobes`).
    pub lobes: usize,
}

impl ModelSpec {
    /// `name` with one lobe.
    pub fn named(name: &str) -> Self {
        ModelSpec {
            name: name.to_string(),
            lobes: 1,
        }
    }

    /// The name, with the lobe count when it is not one.
    pub fn label(&self, name: &str) -> String {
        match self.lobes {
            1 => name.to_string(),
            k => format!("{name} ({k} lobes)"),
        }
    }
}

/// One model of [`select_by_image`]: its appearance fit and image errors.
#[derive(Clone, Debug, Serialize)]
pub struct ImageChoice {
    /// Catalogue name.
    pub model: String,
    /// The name with the lobe count where it is not one.
    pub label: String,
    /// Objective of the chosen candidate of this model.
    pub objective: String,
    /// Optional lobes it kept.
    pub lobes: Vec<String>,
    /// Its image errors at the report size.
    pub image: ImageError,
    /// Ngan's L2.
    pub ngan_l2: f64,
    /// Parameters.
    pub parameters: usize,
    /// Seconds of the model's appearance fit.
    pub seconds: f64,
    /// Samples the fit used, of `samples_present`.
    pub samples: usize,
    /// Samples the data holds.
    pub samples_present: usize,
    /// Samples dropped as invalid (NaN, infinite; MERL's negative marker).
    pub dropped_invalid: usize,
    /// Samples dropped beyond `limit_deg`.
    pub dropped_angle: usize,
    /// The angle limit of the BRDF-space candidates (degrees).
    pub limit_deg: f64,
}

/// How [`select_by_image`] fits each model.
#[derive(Clone, Copy, Debug)]
pub struct ByImage {
    /// End each fit with the search on its render's mean FLIP.
    pub polish: bool,
    /// Samples with theta_i or theta_o above this angle (degrees) are
    /// left out of the BRDF-space candidates (the image objective sees
    /// the whole render).
    pub limit_deg: f64,
}

/// Selection by image error (Bieron and Peers 2020): every model of
/// `models` fitted for appearance to `material` as `brdf fit` fits it (a
/// [`FitRequest`] with `how`'s limit, each fit ended by the search on its
/// render's FLIP when `how.polish`), judged against the material's renders at the report size; the index of the least mean FLIP is the choice. The renders are
/// made once for every model, the models fitted in parallel (rows in the
/// order of `models`, each fit the same for any number of threads).
pub fn select_by_image(
    models: &[ModelSpec],
    material: &Material,
    how: ByImage,
    task: &dyn Task,
) -> Result<(Vec<ImageChoice>, usize, FitReport), FitError> {
    // The judge first, so the parallel fits share it instead of racing to
    // make it.
    material.judge()?;
    let fitted: Vec<(ImageChoice, FitReport)> = models
        .par_iter()
        .map(|spec| {
            let entry = crate::resolve(&spec.name)?;
            let label = spec.label(entry.name);
            task.item(&format!("{label} on {}", material.name()));
            let t0 = Instant::now();
            let request = FitRequest {
                metric: Metric::Appearance,
                polish: how.polish,
                limit_deg: how.limit_deg,
                config: ModelConfig {
                    lobes: spec.lobes,
                    ..ModelConfig::default()
                },
                ..FitRequest::new(material, entry)
            };
            let report = request.run()?.into_report()?;
            task.advance(1);
            let chosen = report.candidates.iter().find(|c| c.chosen);
            let row = ImageChoice {
                model: report.summary.model.clone(),
                label,
                objective: chosen.map_or_else(String::new, |c| c.objective.clone()),
                lobes: chosen.map_or_else(Vec::new, |c| c.lobes.clone()),
                image: report
                    .image_error
                    .clone()
                    .ok_or_else(|| FitError::NoImageError {
                        data: material.name().to_string(),
                    })?,
                ngan_l2: report.summary.ngan_l2,
                parameters: report.summary.parameters.len(),
                seconds: t0.elapsed().as_secs_f64(),
                samples: report.summary.samples,
                samples_present: report.samples_present,
                dropped_invalid: report.dropped_invalid,
                dropped_angle: report.dropped_angle,
                limit_deg: report.limit_deg,
            };
            Ok((row, report))
        })
        .collect::<Result<Vec<_>, FitError>>()?;
    let (rows, mut reports): (Vec<ImageChoice>, Vec<FitReport>) = fitted.into_iter().unzip();
    let choice = (0..rows.len())
        .min_by(|a, b| {
            rows[*a]
                .image
                .mean_flip()
                .total_cmp(&rows[*b].image.mean_flip())
        })
        .ok_or(FitError::NoModelToFit)?;
    let report = reports.swap_remove(choice);
    Ok((rows, choice, report))
}
