//! A fitted model on disk (JSON via serde): the catalogue name, the
//! structural configuration and the parameters by name, so `brdf eval
//! --load FILE` rebuilds exactly the fitted model. Parameters are validated
//! against their boxes on loading (a hand-edited file with an impossible
//! value is an error naming the parameter).

use std::path::Path;

use brdf_core::Parametric;
use brdf_core::params::assign_by_name;
use brdf_models::kurt_polynomial::{Pca, PolyVariant};
use brdf_models::{KurtPolynomial, ModelConfig};
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
    /// The PCA transform of a Kurt polynomial (its structure depends on the
    /// data it was fitted to).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pca: Option<Pca>,
}

fn poly_variant(name: &str) -> Option<PolyVariant> {
    match name {
        "polynomial" => Some(PolyVariant::Isotropic),
        "polynomial-aniso" => Some(PolyVariant::Anisotropic),
        _ => None,
    }
}

impl SavedModel {
    /// Capture a model built from the catalogue with `config`; `pairs` are
    /// the directions it was fitted at (needed for Kurt's polynomial, whose
    /// PCA transform is recomputed from them, deterministically).
    pub fn capture(
        model: &dyn Parametric,
        config: &ModelConfig,
        pairs: &brdf_core::DirPairs,
        provenance: String,
    ) -> Result<Self, StudyError> {
        let e = brdf_models::entry(model.name()).ok_or_else(|| {
            StudyError::Usage(format!("`{}` is not a catalogue model", model.name()))
        })?;
        let pca = match (e.build_for_data.is_some(), poly_variant(model.name())) {
            (false, _) => None,
            (true, Some(v)) => Some(Pca::from_pairs(v, pairs)?),
            (true, None) => {
                return Err(StudyError::Usage(format!(
                    "`{}` depends on the fitted data; saving it is not supported",
                    model.name()
                )));
            }
        };
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
            pca,
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
        let mut m: Box<dyn Parametric> = match (&self.pca, poly_variant(&self.model)) {
            (Some(pca), Some(v)) => Box::new(KurtPolynomial::new(
                v,
                self.degree,
                self.channels,
                pca.clone(),
            )?),
            _ => brdf_models::build(&self.model, &config)?,
        };
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
