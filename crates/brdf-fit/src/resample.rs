//! Conversion behind `brdf resample`: data or a saved model written as
//! MERL, Sopp's grid or CSV samples. Dense sources (MERL) and saved models
//! are evaluated at the target's nodes (a model written as CSV: at the
//! nodes of Sopp's grid); scattered sources can only be written as CSV
//! samples (resampling scattered data would need an interpolation the
//! project does not invent). Lives here, not in `brdf-io`, because a saved
//! model is rebuilt with `brdf-models`.

use std::path::Path;

use brdf_core::Brdf;
use brdf_core::nalgebra::Vector3;
use brdf_io::{Format, csv_samples, merl, rgl, sopp_grid};
use brdf_models::saved_model::SavedModel;

use crate::FitError;

/// A resampling target.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// MERL's binary half-difference grid.
    Merl,
    /// Sopp's goniometric grid.
    SoppGrid,
    /// CSV samples.
    Csv,
}

impl std::str::FromStr for Target {
    type Err = FitError;
    fn from_str(s: &str) -> Result<Self, FitError> {
        match s {
            "merl" => Ok(Target::Merl),
            "sopp-grid" => Ok(Target::SoppGrid),
            "csv" => Ok(Target::Csv),
            other => Err(FitError::InvalidOption {
                option: "--to",
                value: other.to_string(),
                expected: "merl, sopp-grid or csv",
            }),
        }
    }
}

/// Convert `from` (a data file, or a saved model `.json`) to `to` in
/// `out`. Returns a note for the user when bins were marked invalid.
pub fn resample(from: &str, to: Target, out: &Path) -> Result<Option<String>, FitError> {
    let from_model = from.ends_with(".json");
    let dense: Option<Box<dyn Brdf>> = if from_model {
        let m = SavedModel::load(Path::new(from))?.build()?;
        Some(Box::new(ModelBrdf(m)))
    } else {
        brdf_io::load_dense(from)?
    };
    let (path, _) = brdf_io::split_sample(from);
    let is_rgl = !from_model && brdf_io::format_of(&path)? == Format::Rgl;
    match (to, dense) {
        // RGL onto MERL: bins beyond the measured incidence are invalid
        // (see brdf_io::rgl::MeasuredRange).
        (Target::Merl, Some(_)) if is_rgl => {
            let m = rgl::Rgl::read(&path)?;
            merl::write(out, &merl::Merl::resample(&rgl::MeasuredRange(&m)))?;
            return Ok(Some(format!(
                "note: bins with theta_i or theta_o above {:.2} deg (the largest measured incidence) are marked invalid (-1)",
                m.measured_theta_max().to_degrees()
            )));
        }
        (Target::Merl, Some(b)) => merl::write(out, &merl::Merl::resample(b.as_ref()))?,
        (Target::SoppGrid, Some(b)) => {
            sopp_grid::write(out, &sopp_grid::SoppGrid::resample(b.as_ref()))?
        }
        // A model has no samples of its own: it is written at the nodes of
        // Sopp's goniometric grid (cell weights).
        (Target::Csv, Some(b)) if from_model => {
            let g = sopp_grid::SoppGrid::resample(b.as_ref());
            let name = Path::new(from)
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default();
            csv_samples::write(out, &g.to_samples(&format!("model#{name}"), 90.0, true))?
        }
        (Target::Csv, _) => csv_samples::write(out, &brdf_io::load(from)?)?,
        (Target::Merl | Target::SoppGrid, None) => {
            return Err(FitError::ScatteredToGrid {
                from: from.to_string(),
            });
        }
    }
    Ok(None)
}

/// A parametric model as a plain BRDF.
struct ModelBrdf(Box<dyn brdf_core::Parametric>);

impl Brdf for ModelBrdf {
    fn channels(&self) -> usize {
        self.0.channels()
    }
    fn eval(&self, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        self.0.eval(l, v, out)
    }
}
