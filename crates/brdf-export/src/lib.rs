//! # brdf-export
//!
//! Writes a fitted model as a material a renderer loads: a Mitsuba 3
//! `<bsdf>`, a pbrt-v4 material, a glTF 2.0 asset and a MaterialX document.
//! A material is written only where the target's BSDF equals the fitted
//! BRDF; otherwise [`export`] returns [`ExportError::NoEquivalent`] naming
//! why, and [`export_or_convert`] fits a model the target has to the
//! model's values ([`convert()`]) and writes that, with the conversion error
//! in the file itself (a comment, or glTF's `extras`) and in its answer:
//! never a silently different material.
//!
//! | target | module | models written |
//! | --- | --- | --- |
//! | Mitsuba 3 | [`mitsuba`] | `principled`; `lambert`; `ggx*-separable` (blend of `diffuse`, `roughconductor`, metallic `principled`) |
//! | pbrt-v4 | [`pbrt`] | `lambert`; `ggx-conductor*` / `ggx-dielectric*` (height-correlated; `mix` of `diffuse` and `conductor`) |
//! | glTF 2.0 | [`gltf`] | `gltf`, `gltf-ext` (with `KHR_materials_ior`, `_specular`, `_clearcoat`); `lambert` |
//! | MaterialX | [`materialx`] | `gltf`, `gltf-ext`, `lambert` as `gltf_pbr` |
//!
//! Any other model is converted by fitting (see [`mod@convert`] for the model
//! each target gets).
//!
//! ```
//! use brdf_export::{Target, export};
//! let m = brdf_models::build("principled", &brdf_models::ModelConfig::default()).unwrap();
//! let xml = export(m.as_ref(), Target::Mitsuba).unwrap();
//! assert!(xml.contains(r#"<bsdf version="3.0.0" type="principled">"#));
//! // The height-correlated GGX has no Mitsuba equivalent:
//! let g = brdf_models::build("ggx", &brdf_models::ModelConfig::default()).unwrap();
//! assert!(export(g.as_ref(), Target::Mitsuba).is_err());
//! ```
//!
//! [`file::run`] is the whole `brdf export` job: read a saved model, write
//! the material file, optionally save the converted model.
//!
//! ## Layering
//!
//! `brdf-export` sits on `brdf-models` (the models it writes) and
//! `brdf-fit` (conversion by fitting); `brdf-study` and the `brdf` command
//! (`brdf-cli`) call it. It never renders.
//!
//! ## Crate features
//!
//! None.

pub mod convert;
pub mod file;
pub mod fitted;
pub mod gltf;
pub mod materialx;
pub mod mitsuba;
pub mod pbrt;
pub mod pbrt_mix;
mod xml;

use brdf_core::Parametric;
use thiserror::Error;

pub use convert::{Conversion, ConversionError, ConvertOptions, convert};
pub use fitted::{Fitted, GgxFit, LobeFit, LobeFresnel};

/// An export format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// Mitsuba 3 scene-description XML (one `<bsdf>`).
    Mitsuba,
    /// pbrt-v4 scene-description material statements.
    Pbrt,
    /// glTF 2.0 asset (JSON) with one material.
    Gltf,
    /// MaterialX document with one material.
    MaterialX,
}

impl std::str::FromStr for Target {
    type Err = ExportError;
    fn from_str(s: &str) -> Result<Self, ExportError> {
        match s {
            "mitsuba" => Ok(Target::Mitsuba),
            "pbrt" => Ok(Target::Pbrt),
            "gltf" => Ok(Target::Gltf),
            "materialx" => Ok(Target::MaterialX),
            _ => Err(ExportError::UnknownTarget(s.to_string())),
        }
    }
}

impl std::fmt::Display for Target {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Target::Mitsuba => "mitsuba",
            Target::Pbrt => "pbrt",
            Target::Gltf => "gltf",
            Target::MaterialX => "materialx",
        })
    }
}

/// Why a model could not be exported.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ExportError {
    /// The target has no material equal to the model.
    #[error("model `{model}` has no exact equivalent in {target}: {reason}")]
    NoEquivalent {
        /// catalogue name
        model: String,
        /// the target
        target: Target,
        /// why
        reason: String,
    },
    /// The model lacks a parameter the exporter expects.
    #[error("model `{model}` has no parameter `{name}`")]
    MissingParameter {
        /// catalogue name
        model: String,
        /// the parameter
        name: String,
    },
    /// Only grey (1) and RGB (3) models can be exported.
    #[error("model `{model}` has {channels} channels; renderers take 1 (grey) or 3 (linear sRGB)")]
    Channels {
        /// catalogue name
        model: String,
        /// its channel count
        channels: usize,
    },
    /// A target name that is not one of mitsuba, pbrt, gltf, materialx.
    #[error("unknown export target `{0}` (mitsuba, pbrt, gltf, materialx)")]
    UnknownTarget(String),
    /// Conversion by fitting failed.
    #[error("converting `{model}` to {target} by fitting `{via}`: {reason}")]
    Conversion {
        /// the source's catalogue name
        model: String,
        /// the target
        target: Target,
        /// the model fitted
        via: String,
        /// what went wrong
        reason: String,
    },
}

/// A material in a target's format, and the conversion it took (if any).
pub struct Exported {
    /// The file's text.
    pub text: String,
    /// `None` when the material equals the model exactly.
    pub conversion: Option<Conversion>,
}

/// Write `model` (its catalogue name, parameter names and current values)
/// in `target`'s format.
pub fn export(model: &dyn Parametric, target: Target) -> Result<String, ExportError> {
    export_noted(model, target, None)
}

/// [`export`] with `note` (one line) written into the file: an XML comment
/// (Mitsuba, MaterialX), a `#` comment (pbrt), `asset.extras.note` (glTF).
pub fn export_noted(
    model: &dyn Parametric,
    target: Target,
    note: Option<&str>,
) -> Result<String, ExportError> {
    let fit = Fitted::new(model)?;
    match target {
        Target::Mitsuba => mitsuba::write(&fit, note),
        Target::Pbrt => pbrt::write(&fit, note),
        Target::Gltf => gltf::write(&fit, note),
        Target::MaterialX => materialx::write(&fit, note),
    }
}

/// Write `model` exactly where `target` has its equivalent, otherwise
/// convert it by fitting ([`convert()`]) and write the conversion with its
/// error noted in the file. Errors other than
/// [`ExportError::NoEquivalent`] are not converted around.
///
/// ```
/// use brdf_export::{ConvertOptions, Target, export_or_convert};
/// let m = brdf_models::build("lambert", &brdf_models::ModelConfig::default()).unwrap();
/// // Lambert is exact in glTF: no conversion.
/// let e = export_or_convert(m.as_ref(), Target::Gltf, &ConvertOptions::default()).unwrap();
/// assert!(e.conversion.is_none());
/// ```
pub fn export_or_convert(
    model: &dyn Parametric,
    target: Target,
    opts: &ConvertOptions,
) -> Result<Exported, ExportError> {
    match export(model, target) {
        Ok(text) => Ok(Exported {
            text,
            conversion: None,
        }),
        Err(ExportError::NoEquivalent { .. }) => {
            let c = convert(model, target, opts)?;
            let text = export_noted(c.model.as_ref(), target, Some(&c.note()))?;
            Ok(Exported {
                text,
                conversion: Some(c),
            })
        }
        Err(e) => Err(e),
    }
}
