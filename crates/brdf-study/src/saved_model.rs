//! A fitted model on disk (JSON via serde): the catalogue name, the
//! structural configuration and the parameters by name, so `brdf eval
//! --load FILE` rebuilds exactly the fitted model. Parameters are validated
//! against their boxes on loading (a hand-edited file with an impossible
//! value is an error naming the parameter).

use std::path::Path;

use brdf_core::Parametric;
use brdf_core::params::assign_by_name;
use brdf_models::ModelConfig;
use serde::{Deserialize, Serialize};

use crate::StudyError;

/// The saved form.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SavedModel {
    /// Catalogue name.
    pub model: String,
    /// Channels.
    pub channels: usize,
    /// Lobes.
    pub lobes: usize,
    /// Koenderink order.
    pub order: usize,
    /// Polynomial degree.
    pub degree: usize,
    /// Parameters by name.
    pub parameters: Vec<(String, f64)>,
    /// Where it came from (data set, objective, error).
    pub provenance: String,
}

impl SavedModel {
    /// Capture a model built from the catalogue with `config`.
    pub fn capture(
        model: &dyn Parametric,
        config: &ModelConfig,
        provenance: String,
    ) -> Result<Self, StudyError> {
        let e = brdf_models::entry(model.name()).ok_or_else(|| {
            StudyError::Usage(format!("`{}` is not a catalogue model", model.name()))
        })?;
        if e.build_for_data.is_some() {
            return Err(StudyError::Usage(format!(
                "`{}` depends on the fitted data (its PCA transform); saving it is not supported",
                model.name()
            )));
        }
        Ok(Self {
            model: model.name().to_string(),
            channels: config.channels,
            lobes: config.lobes,
            order: config.order,
            degree: config.degree,
            parameters: model
                .param_specs()
                .iter()
                .map(|s| s.name.clone())
                .zip(model.params().iter().copied())
                .collect(),
            provenance,
        })
    }

    /// Rebuild the model.
    pub fn build(&self) -> Result<Box<dyn Parametric>, StudyError> {
        let config = ModelConfig {
            channels: self.channels,
            lobes: self.lobes,
            order: self.order,
            degree: self.degree,
        };
        let mut m = brdf_models::build(&self.model, &config)?;
        if self.parameters.len() != m.n_params() {
            return Err(StudyError::Usage(format!(
                "saved `{}` has {} parameters, the model has {}",
                self.model,
                self.parameters.len(),
                m.n_params()
            )));
        }
        let p = assign_by_name(&self.model, m.param_specs(), &self.parameters)?;
        m.set_params(&p)?;
        Ok(m)
    }

    /// Write as pretty JSON.
    pub fn save(&self, path: &Path) -> Result<(), StudyError> {
        let text = serde_json::to_string_pretty(self)?;
        std::fs::write(path, text).map_err(|e| StudyError::Io {
            path: path.display().to_string(),
            source: e,
        })
    }

    /// Read.
    pub fn load(path: &Path) -> Result<Self, StudyError> {
        let text = std::fs::read_to_string(path).map_err(|e| StudyError::Io {
            path: path.display().to_string(),
            source: e,
        })?;
        Ok(serde_json::from_str(&text)?)
    }
}
