//! What each target does with each model: exact, mapped, or converted by
//! fitting (`brdf export --list`, the README's table).
//!
//! - *exact*: the target's material is the model's BRDF.
//! - *mapped*: the target's material takes the model's parameters under
//!   the same names and meanings, but its BRDF is the renderer's
//!   (UsdPreviewSurface, Blender's Principled BSDF; MaterialX's
//!   `standard_surface` and `open_pbr_surface`): close, not identical.
//! - *converted*: the target has no such material; a model it has is
//!   fitted for appearance ([`crate::convert`](mod@crate::convert)).

use brdf_models::ModelConfig;

use crate::convert::default_via;
use crate::{ExportError, Target, export};

/// How a target writes a model.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Support {
    /// The target's material is the model.
    Exact,
    /// The model's parameters, the renderer's BRDF.
    Mapped,
    /// Converted by fitting this model.
    Converted(String),
    /// The model cannot be written (e.g. not 1 or 3 channels).
    No(String),
}

impl std::fmt::Display for Support {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Support::Exact => f.write_str("exact"),
            Support::Mapped => f.write_str("mapped"),
            Support::Converted(via) => write!(f, "converted ({via})"),
            Support::No(why) => write!(f, "no: {why}"),
        }
    }
}

/// Whether `target`'s exact writes are renderer mappings.
fn maps(target: Target) -> bool {
    matches!(target, Target::Usd | Target::Blender)
}

/// How `target` writes catalogue model `model` (at its default
/// parameters, RGB).
pub fn support(model: &str, target: Target) -> Support {
    let config = ModelConfig {
        channels: 3,
        ..ModelConfig::default()
    };
    let m = match brdf_models::build(model, &config) {
        Ok(m) => m,
        Err(e) => return Support::No(e.to_string()),
    };
    match export(m.as_ref(), target) {
        Ok(_) if maps(target) => Support::Mapped,
        Ok(_) => Support::Exact,
        Err(ExportError::NoEquivalent { .. }) => Support::Converted(default_via(target).into()),
        Err(e) => Support::No(e.to_string()),
    }
}

/// The models of the table: those some target writes exactly, then one
/// for all the others.
pub const MODELS: [&str; 8] = [
    "lambert",
    "principled",
    "gltf",
    "gltf-ext",
    "ggx",
    "ggx-separable",
    "ggx-dielectric",
    "ggx-conductor",
];

/// The markdown table of [`MODELS`] x [`Target::ALL`] (`brdf export
/// --list`).
pub fn markdown() -> String {
    let mut s = String::from("| model |");
    for t in Target::ALL {
        s += &format!(" {t} |");
    }
    s += "\n| --- |";
    s += &" --- |".repeat(Target::ALL.len());
    s += "\n";
    for m in MODELS {
        s += &format!("| `{m}` |");
        for t in Target::ALL {
            s += &format!(" {} |", support(m, t));
        }
        s += "\n";
    }
    s += "| any other |";
    for t in Target::ALL {
        s += &format!(" converted ({}) |", default_via(t));
    }
    s += "\nMaterialX `--surface standard_surface` or `openpbr`: the glTF rows are mapped, not exact.\n";
    s += "Conversions are fitted for appearance and refused above mean HDR-FLIP 0.05 or CIEDE2000 3 (`--force`).\n";
    s
}
