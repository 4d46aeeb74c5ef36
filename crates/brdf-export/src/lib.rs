//! # brdf-export
//!
//! Writes a fitted model as a material a renderer loads: a Mitsuba 3
//! `<bsdf>` snippet or judge scene, a pbrt-v4 material, a glTF 2.0 asset, a
//! MaterialX document (`gltf_pbr`, `standard_surface`, `open_pbr_surface`),
//! a USD material (`UsdPreviewSurface`, or a MaterialX graph) and a Blender script.
//! A material is written only where the target's BSDF equals the fitted
//! BRDF; otherwise [`export`] returns [`ExportError::NoEquivalent`] naming
//! why, and [`export_or_convert`] fits a model the target has to the
//! model's values ([`convert()`]) and writes that, with the conversion error
//! in the file itself (a comment, or glTF's `extras`) and in its answer:
//! never a silently different material.
//!
//! | target | module | models written |
//! | --- | --- | --- |
//! | Mitsuba 3 | [`mitsuba`] | `principled`; `lambert`; `ggx*-separable` (blend of `diffuse`, `roughconductor`, metallic `principled`); `lobes*-mitsuba` ([`lobes_mitsuba`]) |
//! | pbrt-v4 | [`pbrt`] | `lambert`; `ggx-conductor*` / `ggx-dielectric*` (height-correlated; `mix` of `diffuse` and `conductor`) |
//! | glTF 2.0 | [`gltf`] | `gltf`, `gltf-ext` (with `KHR_materials_ior`, `_specular`, `_clearcoat`); `lambert` |
//! | MaterialX | [`materialx`] | `gltf`, `gltf-ext`, `lambert` as `gltf_pbr` (mapped as `standard_surface`, `open_pbr_surface`); `lobes*-materialx`, `film*-materialx` exact ([`lobes_materialx`]: pbrlib BSDF nodes summed by `add`) |
//! | USD | [`usd`] | `gltf`, `gltf-ext`, `lambert` mapped to `UsdPreviewSurface`; `lobes*-materialx`, `film*-materialx` exact (their MaterialX graph as UsdShade prims, render context `mtlx`) |
//! | Blender | [`blender`] | `gltf`, `gltf-ext`, `lambert` mapped to the Principled BSDF; `lobes*-cycles` exact ([`lobes_blender`]: Diffuse, Glossy, Metallic BSDFs summed) |
//!
//! *Mapped* ([`table`]): the renderer's material takes the model's
//! parameters under the same meaning, but its BRDF is the renderer's own.
//!
//! Any model is also written for Mitsuba 3 as a `measured` BSDF tabulated
//! on an RGL measurement's grid ([`mod@measured`], `--tabulate-on`).
//!
//! Any other model is converted by fitting (see [`mod@convert`] for the model
//! each target gets).
//!
//! ```
//! use brdf_export::{Target, export};
//! let m = brdf_models::build("principled", &brdf_models::ModelConfig::default()).unwrap();
//! let xml = export(m.as_ref(), Target::Mitsuba).unwrap();
//! // A paste-in snippet: no `version`, an id to reference.
//! assert!(xml.contains(r#"<bsdf id="fitted" type="principled">"#));
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
//! (`brdf-cli`) call it. It never renders; its tests check the exports by
//! rendering them in the renderers (`tests/reference/check_exports.sh`:
//! Mitsuba 3, Blender Cycles through `bpy`) beside `brdf-render`'s render
//! of the same model (`tests/export/render_check.rs`).
//!
//! ## Crate features
//!
//! None.

pub mod blender;
pub mod convert;
pub mod file;
pub mod fitted;
pub mod for_renderer;
pub mod gltf;
pub mod lobes_blender;
pub mod lobes_fit;
pub mod lobes_materialx;
pub mod lobes_mitsuba;
pub mod materialx;
pub mod measured;
pub mod mitsuba;
mod mitsuba_nodes;
pub mod pbrt;
pub mod pbrt_mix;
mod python_literal;
pub mod table;
pub mod usd;
pub mod usd_materialx;
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
    /// USD layer (`.usda`) with a `Material`: a `UsdPreviewSurface`, or the
    /// MaterialX graph of a coloured-lobe or thin-film fit.
    Usd,
    /// Blender Python script building a Principled BSDF material.
    Blender,
}

impl Target {
    /// Every target, in the order of `brdf export --list`.
    pub const ALL: [Target; 6] = [
        Target::Mitsuba,
        Target::Pbrt,
        Target::Gltf,
        Target::MaterialX,
        Target::Usd,
        Target::Blender,
    ];

    /// The usual file extension of the target's files.
    pub fn extension(self) -> &'static str {
        match self {
            Target::Mitsuba => "xml",
            Target::Pbrt => "pbrt",
            Target::Gltf => "gltf",
            Target::MaterialX => "mtlx",
            Target::Usd => "usda",
            Target::Blender => "py",
        }
    }

    /// How a user puts `file`, written for this target, to use: one line
    /// the commands print after writing it (the details are in
    /// `docs/export.md`).
    pub fn usage(self, file: &str) -> String {
        match self {
            Target::Mitsuba => format!(
                "use it: paste the `<bsdf>` of {file} into a Mitsuba 3 scene and refer to it by its id (`brdf export --to mitsuba --scene` writes a whole judge scene)"
            ),
            Target::Pbrt => format!(
                "use it: `Include \"{file}\"` in a pbrt-v4 scene, then `NamedMaterial` its name before a shape"
            ),
            Target::Gltf => format!(
                "use it: open {file} in a glTF 2.0 viewer, or import it into Blender (File > Import > glTF 2.0)"
            ),
            Target::MaterialX => format!(
                "use it: `MaterialXView --material {file}`, or load it where MaterialX is read (USD, Houdini, Maya, Blender's importers)"
            ),
            Target::Usd => format!(
                "use it: reference {file} from a scene (`references = @{file}@`) and bind it to a shape; `usdview` shows it"
            ),
            Target::Blender => format!(
                "use it: `blender -b -P {file} -- --blend material.blend` (or `python {file} --blend material.blend` with pip's bpy), or run it in Blender's Scripting workspace"
            ),
        }
    }
}

/// A light set of the judge scene (`docs/appearance.md`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Light {
    /// A dim constant surround and a square key light.
    #[default]
    Studio,
    /// Mitsuba's `sunsky`, the sun at (0.5, 0.64, 0.58).
    Sky,
}

impl std::str::FromStr for Light {
    type Err = ExportError;
    fn from_str(s: &str) -> Result<Self, ExportError> {
        match s {
            "studio" => Ok(Light::Studio),
            "sky" => Ok(Light::Sky),
            _ => Err(ExportError::UnknownOption {
                option: "--light",
                value: s.to_string(),
                expected: "studio or sky",
            }),
        }
    }
}

/// The surface shader of a MaterialX document.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Surface {
    /// Khronos's `gltf_pbr` (the glTF material itself).
    #[default]
    GltfPbr,
    /// Autodesk Standard Surface (`standard_surface`).
    StandardSurface,
    /// OpenPBR Surface (`open_pbr_surface`, MaterialX 1.39).
    OpenPbr,
}

impl std::str::FromStr for Surface {
    type Err = ExportError;
    fn from_str(s: &str) -> Result<Self, ExportError> {
        match s {
            "gltf_pbr" | "gltf-pbr" | "gltf" => Ok(Surface::GltfPbr),
            "standard_surface" | "standard-surface" | "standard" => Ok(Surface::StandardSurface),
            "openpbr" | "open_pbr_surface" | "open-pbr" => Ok(Surface::OpenPbr),
            _ => Err(ExportError::UnknownOption {
                option: "--surface",
                value: s.to_string(),
                expected: "gltf_pbr, standard_surface or openpbr",
            }),
        }
    }
}

/// How a material file is written (beyond the model).
#[derive(Clone, Debug, PartialEq)]
pub struct WriteOptions {
    /// The material's name (an identifier: letters, digits, `_`).
    pub name: String,
    /// Mitsuba: a complete judge scene instead of a `<bsdf>` snippet.
    pub scene: bool,
    /// Mitsuba scene: its light set.
    pub light: Light,
    /// MaterialX: the surface shader.
    pub surface: Surface,
    /// glTF: a preview sphere using the material in the default scene
    /// (`false`: the material alone, a material library).
    pub mesh: bool,
}

impl Default for WriteOptions {
    fn default() -> Self {
        WriteOptions {
            name: "fitted".into(),
            scene: false,
            light: Light::Studio,
            surface: Surface::GltfPbr,
            mesh: true,
        }
    }
}

/// `text` as an identifier every target accepts (USD prim, MaterialX
/// node, Mitsuba id, Python string): other characters become `_`, a
/// leading digit gets a `m_` prefix, empty becomes `fitted`.
pub fn identifier(text: &str) -> String {
    let s: String = text
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    match s.chars().next() {
        None => "fitted".into(),
        Some(c) if c.is_ascii_digit() => format!("m_{s}"),
        Some(_) => s,
    }
}

impl std::str::FromStr for Target {
    type Err = ExportError;
    fn from_str(s: &str) -> Result<Self, ExportError> {
        match s {
            "mitsuba" => Ok(Target::Mitsuba),
            "pbrt" => Ok(Target::Pbrt),
            "gltf" => Ok(Target::Gltf),
            "materialx" | "mtlx" => Ok(Target::MaterialX),
            "usd" | "usda" => Ok(Target::Usd),
            "blender" => Ok(Target::Blender),
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
            Target::Usd => "usd",
            Target::Blender => "blender",
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
    /// A target name that is not one of mitsuba, pbrt, gltf, materialx, usd, blender.
    #[error("unknown export target `{0}`: use --to mitsuba, pbrt, gltf, materialx, usd or blender")]
    UnknownTarget(String),
    /// An option value that is not one of its choices.
    #[error("unknown {option} `{value}`: use {expected}")]
    UnknownOption {
        /// the option
        option: &'static str,
        /// the value given
        value: String,
        /// its choices
        expected: &'static str,
    },
    /// The converted material renders as another material (see
    /// [`convert::FLIP_REFUSE`], [`convert::DELTA_E_REFUSE`]).
    #[error(
        "converting `{model}` to {target} as `{via}` makes another material (HDR-FLIP {flip:.3} under one light set, refused above {flip_limit}; CIEDE2000 {delta_e:.2}, refused above {de_limit}): fit the target's model directly: {fit} and export that, or pass {force} to export the conversion anyway",
        flip_limit = convert::FLIP_REFUSE,
        de_limit = convert::DELTA_E_REFUSE,
        fit = .front.fit_hint(via),
        force = .front.force_option()
    )]
    LooksDifferent {
        /// the source's catalogue name
        model: String,
        /// the target
        target: Target,
        /// the model fitted
        via: String,
        /// largest HDR-FLIP over the light sets
        flip: f64,
        /// largest mean-colour CIEDE2000
        delta_e: f64,
        /// whose options the message names (see [`ExportError::for_front_end`])
        front: FrontEnd,
    },
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

/// The front end an error's advice is written for: the options to name
/// differ (`--force` on the command line, `force=True` in Python).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FrontEnd {
    /// The `brdf` command.
    #[default]
    Cli,
    /// The Python module.
    Python,
}

impl FrontEnd {
    /// The option that exports a conversion beyond the limits.
    pub fn force_option(self) -> &'static str {
        match self {
            FrontEnd::Cli => "--force",
            FrontEnd::Python => "force=True",
        }
    }

    /// How to fit RGB data (the option that fits colour).
    pub fn rgb_option(self) -> &'static str {
        match self {
            FrontEnd::Cli => "`--channels rgb`",
            FrontEnd::Python => "`channels=\"rgb\"`",
        }
    }

    /// How to fit the data for `target` (`--for`).
    pub fn for_hint(self, target: Target) -> String {
        match self {
            FrontEnd::Cli => format!("`brdf fit --data DATA --for {target} --out FILE`"),
            FrontEnd::Python => format!("`brdf.fit(data, for_renderer=\"{target}\")`"),
        }
    }

    /// How to fit the model `via` to the data directly.
    pub fn fit_hint(self, via: &str) -> String {
        match self {
            FrontEnd::Cli => format!("`brdf fit --model {via} ...`"),
            FrontEnd::Python => format!("`brdf.fit(data, \"{via}\")`"),
        }
    }
}

impl ExportError {
    /// The error with its advice naming `front`'s options (errors are
    /// made with the command line's).
    pub fn for_front_end(self, front: FrontEnd) -> Self {
        match self {
            ExportError::LooksDifferent {
                model,
                target,
                via,
                flip,
                delta_e,
                ..
            } => ExportError::LooksDifferent {
                model,
                target,
                via,
                flip,
                delta_e,
                front,
            },
            e => e,
        }
    }
}

/// A material in a target's format, and the conversion it took (if any).
pub struct Exported {
    /// The file's text.
    pub text: String,
    /// `None` when the material equals the model exactly.
    pub conversion: Option<Conversion>,
    /// What the material does not say that the user should know (see
    /// [`warnings`]), one line each, for the front end to print.
    pub warnings: Vec<String>,
}

/// Warnings for writing `model` as a `target` material, with the fix in
/// `front`'s options. Every target writes colours (RGB), so a one-channel
/// (grey) fit becomes a grey material whose colour was never fitted: a
/// grey metal or a grey plastic where the data may have been coloured.
pub fn warnings(model: &dyn Parametric, target: Target, front: FrontEnd) -> Vec<String> {
    let mut w = Vec::new();
    if model.channels() == 1 {
        w.push(format!(
            "`{}` has one channel: its colour was never fitted, so the {target} material is grey; fit RGB data with {} for a coloured material",
            model.name(),
            front.rgb_option()
        ));
    }
    w
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
    export_with(model, target, note, &WriteOptions::default())
}

/// [`export_noted`] with the material's name and the target's options.
pub fn export_with(
    model: &dyn Parametric,
    target: Target,
    note: Option<&str>,
    opts: &WriteOptions,
) -> Result<String, ExportError> {
    let fit = Fitted::new(model)?;
    match target {
        Target::Mitsuba => mitsuba::write(&fit, note, opts),
        Target::Pbrt => pbrt::write(&fit, note),
        Target::Gltf => gltf::write(&fit, note, opts),
        Target::MaterialX => materialx::write(&fit, note, opts),
        Target::Usd => usd::write(&fit, note, opts),
        Target::Blender => blender::write(&fit, note, opts),
    }
}

/// Write `model` exactly where `target` has its equivalent, otherwise
/// convert it by fitting ([`convert()`]) and write the conversion with its
/// error noted in the file and a warning where it renders differently; a
/// conversion that renders as another material is refused
/// ([`ExportError::LooksDifferent`]) unless `opts.force`. Errors
/// other than
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
    export_or_convert_with(model, target, opts, &WriteOptions::default())
}

/// [`export_or_convert`] with the material's name and the target's options.
pub fn export_or_convert_with(
    model: &dyn Parametric,
    target: Target,
    opts: &ConvertOptions,
    write: &WriteOptions,
) -> Result<Exported, ExportError> {
    let warnings = warnings(model, target, FrontEnd::Cli);
    match export_with(model, target, None, write) {
        Ok(text) => Ok(Exported {
            text,
            conversion: None,
            warnings,
        }),
        Err(ExportError::NoEquivalent { .. }) => {
            let c = convert(model, target, opts)?;
            if !opts.force {
                c.check(target)?;
            }
            let mut warnings = warnings;
            warnings.extend(for_renderer::conversion_warning(&c, target, FrontEnd::Cli));
            let text = export_with(c.model.as_ref(), target, Some(&c.note()), write)?;
            Ok(Exported {
                text,
                conversion: Some(c),
                warnings,
            })
        }
        Err(e) => Err(e),
    }
}
