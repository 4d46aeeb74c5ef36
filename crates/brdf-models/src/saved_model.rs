//! A fitted model on disk: the versioned JSON schema that `brdf fit --save`
//! writes and a renderer reads back with only this crate compiled
//! (feature `serde`).
//!
//! ```json
//! {
//!   "schema": "brdf-fit/saved-model", "version": 1,
//!   "model": "ashikhmin-shirley",
//!   "structure": { "channels": 3, "lobes": 1, "order": 8, "degree": 7 },
//!   "units": { "angles": "radians", "brdf": "1/sr" },
//!   "colour_space": "linear sRGB", "channel_names": ["r", "g", "b"],
//!   "parameters": [ { "name": "kd_r", "value": 0.68, "std_error": 9.5e-5,
//!                     "at_bound": null, "projected": true } ],
//!   "provenance": { "data": "rgl/paper_white_rgb.bsdf", "samples_used": 25308,
//!                   "samples_present": 25308, "objective": "ngan",
//!                   "limit_deg": 80.0, "error": 0.0081, "solver": "...",
//!                   "software": "brdf-fit 0.1.0" }
//! }
//! ```
//!
//! Parameters are objects of the same shape as `brdf fit --json` prints and
//! are validated against their boxes on loading: a hand-edited file with an
//! impossible value is an error naming the file and the parameter. Kurt's
//! polynomial also stores its PCA transform (its structure depends on the
//! data it was fitted to).
//!
//! Version 2 adds `ndf_table`, the normal distribution Dupuy et al.'s model
//! reads off its data (`{ "theta": [...], "d": [...] }`: node angles of
//! the half vector in radians, `D` in 1/sr), which its parameters do not
//! hold. Only files with a table are written as version 2: a reader of
//! version 1 would ignore the table and evaluate another model.
//!
//! Version 3 adds `provenance.termination`, how the fit ended
//! (`{ "converged": true, "reason": "converged: gradient below tolerance" }`),
//! which a reader judges the fit by; files that record it are written as
//! version 3 (they may hold a table too), the others as before. This build
//! reads versions 1 to 3.
//!
//! ```
//! use brdf_core::Brdf;
//! use brdf_models::saved_model::SavedModel;
//! let text = r#"{ "schema": "brdf-fit/saved-model", "version": 1,
//!   "model": "blinn-phong", "structure": { "channels": 1 },
//!   "parameters": [ { "name": "kd", "value": 0.5 }, { "name": "ks", "value": 0.0 },
//!                   { "name": "n", "value": 10.0 } ] }"#;
//! let model = SavedModel::from_json(text, "inline").unwrap().build().unwrap();
//! let mut f = [0.0];
//! model.eval(&nalgebra::Vector3::z(), &nalgebra::Vector3::z(), &mut f);
//! assert!((f[0] - 0.5 / std::f64::consts::PI).abs() < 1e-12);
//! ```

use std::path::Path;

use brdf_core::params::assign_by_name;
use brdf_core::{ParamError, Parametric};
use serde::{Deserialize, Serialize};
use thiserror::Error;

use crate::ModelConfig;

/// The schema name written into every file.
pub const SCHEMA: &str = "brdf-fit/saved-model";
/// The schema version this crate writes for models given by their
/// parameters alone.
pub const VERSION: u32 = 1;
/// The schema version of files holding a data table ([`NdfTable`]).
pub const TABLE_VERSION: u32 = 2;
/// The schema version of files recording how their fit ended
/// ([`Provenance::termination`]); this build reads [`VERSION`] to
/// [`TERMINATION_VERSION`].
pub const TERMINATION_VERSION: u32 = 3;

/// Errors of reading, writing and rebuilding saved models; each names the
/// file.
#[derive(Debug, Error)]
pub enum SavedModelError {
    /// The file could not be read or written.
    #[error("{path}: {source}")]
    Io {
        /// the file
        path: String,
        /// the underlying error
        source: std::io::Error,
    },
    /// Not valid JSON of this schema.
    #[error("{path}: not a saved model ({reason})")]
    Json {
        /// the file
        path: String,
        /// what the JSON reader reported (line and column)
        reason: String,
    },
    /// Another schema or a version this crate cannot read.
    #[error(
        "{path}: schema `{schema}` version {version}; this build reads `{SCHEMA}` versions {VERSION} to {TERMINATION_VERSION}"
    )]
    Version {
        /// the file
        path: String,
        /// the schema found
        schema: String,
        /// the version found
        version: u32,
    },
    /// The model cannot be rebuilt (unknown name, wrong parameters).
    #[error("{path}: {reason}")]
    Model {
        /// the file
        path: String,
        /// what is wrong
        reason: String,
    },
}

/// Structural configuration of the saved model (see [`ModelConfig`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Structure {
    /// Colour channels.
    pub channels: usize,
    /// Specular lobes (default 1).
    #[serde(default = "one")]
    pub lobes: usize,
    /// Koenderink order (default 8).
    #[serde(default = "eight")]
    pub order: usize,
    /// Polynomial degree (default 7).
    #[serde(default = "seven")]
    pub degree: usize,
}

fn one() -> usize {
    1
}
fn eight() -> usize {
    8
}
fn seven() -> usize {
    7
}

impl From<&ModelConfig> for Structure {
    fn from(c: &ModelConfig) -> Self {
        Structure {
            channels: c.channels,
            lobes: c.lobes,
            order: c.order,
            degree: c.degree,
        }
    }
}

impl From<Structure> for ModelConfig {
    fn from(s: Structure) -> Self {
        ModelConfig {
            channels: s.channels,
            lobes: s.lobes,
            order: s.order,
            degree: s.degree,
        }
    }
}

/// Units of the stored values.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Units {
    /// Angles (always `radians`).
    pub angles: String,
    /// BRDF values (always `1/sr`).
    pub brdf: String,
}

impl Default for Units {
    fn default() -> Self {
        Units {
            angles: "radians".into(),
            brdf: "1/sr".into(),
        }
    }
}

/// One parameter, as `brdf fit --json` prints it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SavedParam {
    /// Name as in the model's documentation.
    pub name: String,
    /// Value.
    pub value: f64,
    /// Standard error at the fit, if computed.
    #[serde(default)]
    pub std_error: Option<f64>,
    /// `lower` or `upper` when on that bound.
    #[serde(default)]
    pub at_bound: Option<String>,
    /// Whether the fit projected it out (linear).
    #[serde(default)]
    pub projected: bool,
}

/// Where a saved model came from.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Provenance {
    /// The data set (relative to `BRDF_DATA` where it lies inside it).
    pub data: String,
    /// Samples the fit used.
    pub samples_used: usize,
    /// Samples the data set holds (before invalid and angle-limit drops).
    pub samples_present: usize,
    /// Objective name (`ngan`, `sopp`, ...).
    pub objective: String,
    /// Angle limit in degrees.
    pub limit_deg: f64,
    /// Error in the objective's metric.
    pub error: f64,
    /// Solver description.
    pub solver: String,
    /// Software and version that wrote the file.
    pub software: String,
    /// The fit's image errors against the data under the standard light
    /// sets (empty when the data cannot be rendered: scattered samples).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub image_error: Vec<RenderedError>,
    /// How the fit ended (version 3; `None` in older files and where no
    /// fit produced the model).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub termination: Option<SavedTermination>,
}

/// How the fit of a saved model ended.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SavedTermination {
    /// Whether the fit ended at a (local) minimum.
    pub converged: bool,
    /// Why it stopped, as the fit report says it.
    pub reason: String,
}

/// A fit's image error under one light set (see `brdf_fit::appearance`).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct RenderedError {
    /// Light set (`sky`, `studio`).
    pub light: String,
    /// Mean HDR-FLIP (0: identical).
    pub flip: f64,
    /// PSNR in dB after the data's exposure.
    pub psnr: f64,
    /// CIEDE2000 between the mean sphere colours.
    pub delta_e: f64,
}

/// The normal distribution a model read off its data (Dupuy et al.'s
/// tabulated `D`), saved beside its parameters.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct NdfTable {
    /// Polar angles of the half vector at the nodes, radians
    /// (`theta_max (j / (n - 1))^2`, see [`crate::dupuy`]).
    pub theta: Vec<f64>,
    /// `D` at the nodes, 1/sr (`integral D cos dm = 1`).
    pub d: Vec<f64>,
}

/// The saved form.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SavedModel {
    /// Always [`SCHEMA`].
    pub schema: String,
    /// Schema version ([`VERSION`]).
    pub version: u32,
    /// Catalogue name.
    pub model: String,
    /// Structural configuration.
    pub structure: Structure,
    /// Units of the values.
    #[serde(default)]
    pub units: Units,
    /// Colour space of the channels (`linear sRGB`, `grey`, ...).
    #[serde(default)]
    pub colour_space: String,
    /// Channel names.
    #[serde(default)]
    pub channel_names: Vec<String>,
    /// Parameters by name.
    pub parameters: Vec<SavedParam>,
    /// Where it came from.
    #[serde(default)]
    pub provenance: Provenance,
    /// The normal distribution of a model read off its data (version 2).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ndf_table: Option<NdfTable>,
    /// The PCA transform of a Kurt polynomial.
    #[cfg(feature = "polynomial")]
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pca: Option<crate::kurt_polynomial::Pca>,
}

/// The model of a saved table: Dupuy's, the one catalogue model read off
/// its data.
#[cfg(feature = "microfacet")]
fn table_model(channels: usize, t: &NdfTable) -> Result<Box<dyn Parametric>, ParamError> {
    Ok(Box::new(crate::Dupuy::from_saved_table(
        channels, &t.theta, &t.d,
    )?))
}

#[cfg(not(feature = "microfacet"))]
fn table_model(_: usize, _: &NdfTable) -> Result<Box<dyn Parametric>, ParamError> {
    Err(ParamError::Config {
        model: "dupuy".into(),
        reason: "this build has no microfacet models (feature `microfacet`)".into(),
    })
}

#[cfg(feature = "polynomial")]
fn poly_variant(name: &str) -> Option<crate::kurt_polynomial::PolyVariant> {
    use crate::kurt_polynomial::PolyVariant;
    match name {
        "polynomial" => Some(PolyVariant::Isotropic),
        "polynomial-aniso" => Some(PolyVariant::Anisotropic),
        _ => None,
    }
}

impl SavedModel {
    /// Capture a catalogue model built with `config`; `pairs` are the
    /// directions it was fitted at (Kurt's polynomial recomputes its PCA
    /// from them, deterministically). `fitted` carries standard errors and
    /// bound flags when the caller has them; otherwise only values are kept.
    pub fn capture(
        model: &dyn Parametric,
        config: &ModelConfig,
        pairs: &brdf_core::DirPairs,
        fitted: Option<&[SavedParam]>,
        channel_names: &[String],
        provenance: Provenance,
    ) -> Result<Self, ParamError> {
        let model_err = |reason: &str| ParamError::Config {
            model: model.name().to_string(),
            reason: reason.to_string(),
        };
        let e = crate::entry(model.name()).ok_or_else(|| model_err("not a catalogue model"))?;
        let data_bound = "depends on the fitted data; saving it is not supported";
        let ndf_table = model.data_table().map(|(theta, d)| NdfTable {
            theta: theta.to_vec(),
            d: d.to_vec(),
        });
        if e.from_samples.is_some() && ndf_table.is_none() {
            return Err(model_err("is read off its data but gives no table to save"));
        }
        #[cfg(feature = "polynomial")]
        let pca = match (e.build_for_data.is_some(), poly_variant(model.name())) {
            (false, _) => None,
            (true, Some(v)) => Some(crate::kurt_polynomial::Pca::from_pairs(v, pairs)?),
            (true, None) => return Err(model_err(data_bound)),
        };
        #[cfg(not(feature = "polynomial"))]
        if e.build_for_data.is_some() || pairs.is_empty() {
            return Err(model_err(data_bound));
        }
        let parameters = match fitted {
            Some(f) => f.to_vec(),
            None => model
                .param_specs()
                .iter()
                .zip(model.params())
                .map(|(s, v)| SavedParam {
                    name: s.name.clone(),
                    value: *v,
                    std_error: None,
                    at_bound: None,
                    projected: false,
                })
                .collect(),
        };
        let colour_space = match channel_names.len() {
            1 => "grey",
            3 => "linear sRGB",
            _ => "per channel",
        };
        Ok(Self {
            schema: SCHEMA.into(),
            version: if provenance.termination.is_some() {
                TERMINATION_VERSION
            } else if ndf_table.is_some() {
                TABLE_VERSION
            } else {
                VERSION
            },
            model: model.name().to_string(),
            structure: config.into(),
            units: Units::default(),
            colour_space: colour_space.into(),
            channel_names: channel_names.to_vec(),
            parameters,
            provenance,
            ndf_table,
            #[cfg(feature = "polynomial")]
            pca,
        })
    }

    /// Rebuild the model (parameters validated against their boxes).
    pub fn build(&self) -> Result<Box<dyn Parametric>, ParamError> {
        let config: ModelConfig = self.structure.into();
        #[cfg(feature = "polynomial")]
        let built: Option<Box<dyn Parametric>> = match (&self.pca, poly_variant(&self.model)) {
            (Some(pca), Some(v)) => Some(Box::new(crate::KurtPolynomial::new(
                v,
                config.degree,
                config.channels,
                pca.clone(),
            )?)),
            _ => None,
        };
        #[cfg(not(feature = "polynomial"))]
        let built: Option<Box<dyn Parametric>> = None;
        let mut m = match built {
            Some(m) => m,
            None => self.build_structure(&config)?,
        };
        if self.parameters.len() != m.n_params() {
            return Err(ParamError::WrongCount {
                model: self.model.clone(),
                expected: m.n_params(),
                got: self.parameters.len(),
            });
        }
        let named: Vec<(String, f64)> = self
            .parameters
            .iter()
            .map(|p| (p.name.clone(), p.value))
            .collect();
        let p = assign_by_name(&self.model, m.param_specs(), &named)?;
        m.set_params(&p)?;
        Ok(m)
    }

    /// The model at its default parameters: from the saved table for a
    /// model read off its data, else from the catalogue.
    fn build_structure(&self, config: &ModelConfig) -> Result<Box<dyn Parametric>, ParamError> {
        let model_err = |reason: &str| ParamError::Config {
            model: self.model.clone(),
            reason: reason.to_string(),
        };
        let from_data = crate::entry(&self.model).is_some_and(|e| e.from_samples.is_some());
        match (&self.ndf_table, from_data) {
            (Some(t), true) => table_model(config.channels, t),
            (Some(_), _) => Err(model_err(
                "has an `ndf_table`, which only a model read off its data (dupuy) takes; remove it",
            )),
            (None, true) => Err(model_err(
                "is read off its data and the file has no `ndf_table`; save the fit again with `brdf fit --save`",
            )),
            (None, false) => crate::build(&self.model, config),
        }
    }

    /// Parse JSON text; `origin` names the text in errors (a path).
    pub fn from_json(text: &str, origin: &str) -> Result<Self, SavedModelError> {
        #[derive(Deserialize)]
        struct Header {
            #[serde(default)]
            schema: String,
            #[serde(default)]
            version: u32,
        }
        let json_err = |e: serde_json::Error| SavedModelError::Json {
            path: origin.to_string(),
            reason: e.to_string(),
        };
        let h: Header = serde_json::from_str(text).map_err(json_err)?;
        if h.schema != SCHEMA || !(VERSION..=TERMINATION_VERSION).contains(&h.version) {
            return Err(SavedModelError::Version {
                path: origin.to_string(),
                schema: h.schema,
                version: h.version,
            });
        }
        serde_json::from_str(text).map_err(json_err)
    }

    /// Write as pretty JSON.
    pub fn save(&self, path: &Path) -> Result<(), SavedModelError> {
        let text = serde_json::to_string_pretty(self).map_err(|e| SavedModelError::Json {
            path: path.display().to_string(),
            reason: e.to_string(),
        })?;
        std::fs::write(path, text).map_err(|e| SavedModelError::Io {
            path: path.display().to_string(),
            source: e,
        })
    }

    /// Read and check the schema.
    pub fn load(path: &Path) -> Result<Self, SavedModelError> {
        let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
        let data_ext = ["bsdf", "binary", "brdf", "dat"].contains(&ext);
        let text = std::fs::read_to_string(path).map_err(|e| {
            if data_ext || e.kind() == std::io::ErrorKind::InvalidData {
                SavedModelError::Model {
                    path: path.display().to_string(),
                    reason: "is a data file, not a fitted model; give a model saved by `brdf fit --save`".into(),
                }
            } else {
                SavedModelError::Io {
                    path: path.display().to_string(),
                    source: e,
                }
            }
        })?;
        Self::from_json(&text, &path.display().to_string())
    }

    /// Read a file and rebuild its model; every error names the file.
    pub fn load_model(path: &Path) -> Result<Box<dyn Parametric>, SavedModelError> {
        Self::load(path)?
            .build()
            .map_err(|e| SavedModelError::Model {
                path: path.display().to_string(),
                reason: e.to_string(),
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A version-1 file written before the termination was recorded (a
    /// committed conversion of paper_white) still reads, every field as
    /// written, with no termination.
    #[test]
    fn an_old_version_reads() {
        let text = include_str!("../../brdf-export/tests/reference/paper_white/ggx.pbrt.json");
        let saved = SavedModel::from_json(text, "ggx.pbrt.json").expect("reads");
        assert_eq!(saved.version, VERSION);
        assert_eq!(saved.model, "ggx-dielectric");
        assert_eq!(saved.structure.channels, 3);
        assert_eq!(saved.channel_names, ["r", "g", "b"]);
        assert_eq!(saved.parameters[0].name, "kd_r");
        assert_eq!(saved.parameters[0].value, 0.7940103739598579);
        let p = &saved.provenance;
        assert_eq!(p.data, "rgl/paper_white_rgb.bsdf");
        assert_eq!((p.samples_used, p.samples_present), (2048, 2048));
        assert_eq!(p.objective, "ngan");
        assert_eq!(p.limit_deg, 80.0);
        assert_eq!(p.error, 0.017455689107313214);
        assert_eq!(p.software, "brdf-export 0.1.0");
        assert_eq!(p.termination, None);
    }

    /// A file recording its termination is version 3 and reads back the
    /// same; a version beyond this build's is refused.
    #[test]
    fn the_termination_is_version_3() {
        let text = include_str!("../../brdf-export/tests/reference/paper_white/ggx.pbrt.json");
        let mut saved = SavedModel::from_json(text, "ggx.pbrt.json").expect("reads");
        saved.version = TERMINATION_VERSION;
        saved.provenance.termination = Some(SavedTermination {
            converged: false,
            reason: "NOT converged: iteration cap".into(),
        });
        let written = serde_json::to_string_pretty(&saved).expect("writes");
        let back = SavedModel::from_json(&written, "v3.json").expect("reads");
        assert_eq!(back, saved);
        let future = written.replace("\"version\": 3", "\"version\": 4");
        assert!(SavedModel::from_json(&future, "v4.json").is_err());
    }
}
