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
//!
//! [`markdown`] also prints what was measured on the reference material,
//! the fits of RGL's `paper_white_rgb` committed with their exports in
//! `tests/reference/paper_white/` (written by its `make.sh`, checked by its
//! `check_exports.sh`) and `tests/reference/table/` (the other models'
//! fits): each conversion's image error as the conversion reported it
//! ([`REFERENCE_CONVERSIONS`]), and each export rendered in its renderer
//! against `brdf-render` ([`REFERENCE_RENDERS`]).

use brdf_models::ModelConfig;

use crate::convert::{default_via, via_for};
use crate::{ExportError, Surface, Target, export};

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

/// Whether `target` writes `model` as a mapping onto its own material
/// rather than exactly: USD's and Blender's principled materials take the
/// glTF parameters but evaluate their own BRDF; Blender's sums of closures
/// for the coloured-lobe and thin-film models are exact (Cycles' film
/// integrates the spectrum with its own table, within 1e-3 of the
/// model's), as are USD's MaterialX graphs of them.
fn maps(model: &str, target: Target) -> bool {
    matches!(target, Target::Usd | Target::Blender) && !summed(model)
}

/// Whether `model` is a coloured-lobe or thin-film model: a sum of lobes
/// each target writes exactly where it writes it at all.
fn summed(model: &str) -> bool {
    brdf_models::entry(model).is_some_and(|e| {
        matches!(
            e.form,
            brdf_models::RendererForm::ColouredLobes | brdf_models::RendererForm::ThinFilm
        )
    })
}

/// Whether `target` writes `model` as a mapping onto its own material
/// (with MaterialX's shader `surface`: Standard Surface and OpenPBR take
/// the glTF parameters under their own BRDF) rather than exactly.
pub fn is_mapped(model: &str, target: Target, surface: Surface) -> bool {
    maps(model, target)
        || (target == Target::MaterialX && surface != Surface::GltfPbr && !summed(model))
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
        Ok(_) if maps(model, target) => Support::Mapped,
        Ok(_) => Support::Exact,
        Err(ExportError::NoEquivalent { .. }) => {
            Support::Converted(via_for(m.as_ref(), target).into())
        }
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
    s += &format!(
        "Conversions are fitted for appearance, {} (`--force` exports them anyway; `--exact` refuses every conversion).\n",
        crate::convert::limits_text()
    );
    s += "\n";
    s += &conversions_markdown();
    s += "\n";
    s += &renders_markdown();
    s
}

/// The conversion reports of the reference material: (fitted model, the
/// export's kind, `brdf export --json` report). The ggx and principled
/// fits are those of the committed exports (`tests/reference/paper_white/`),
/// the other rows' fits and conversions are in `tests/reference/table/`
/// (its `make.sh`); a conversion to `gltf` is the one MaterialX, USD and
/// Blender write too.
pub const REFERENCE_CONVERSIONS: [(&str, &str, &str); 23] = [
    (
        "principled",
        "pbrt",
        include_str!("../tests/reference/paper_white/principled.pbrt.report.json"),
    ),
    (
        "principled",
        "gltf",
        include_str!("../tests/reference/paper_white/principled.gltf.report.json"),
    ),
    (
        "principled",
        "materialx",
        include_str!("../tests/reference/paper_white/principled.materialx.report.json"),
    ),
    (
        "principled",
        "openpbr",
        include_str!("../tests/reference/paper_white/principled.openpbr.report.json"),
    ),
    (
        "principled",
        "usd",
        include_str!("../tests/reference/paper_white/principled.usd.report.json"),
    ),
    (
        "principled",
        "blender",
        include_str!("../tests/reference/paper_white/principled.blender.report.json"),
    ),
    (
        "gltf",
        "mitsuba",
        include_str!("../tests/reference/table/gltf.mitsuba.report.json"),
    ),
    (
        "gltf",
        "pbrt",
        include_str!("../tests/reference/table/gltf.pbrt.report.json"),
    ),
    (
        "gltf-ext",
        "mitsuba",
        include_str!("../tests/reference/table/gltf-ext.mitsuba.report.json"),
    ),
    (
        "gltf-ext",
        "pbrt",
        include_str!("../tests/reference/table/gltf-ext.pbrt.report.json"),
    ),
    (
        "ggx",
        "mitsuba",
        include_str!("../tests/reference/paper_white/ggx.mitsuba.report.json"),
    ),
    (
        "ggx",
        "pbrt",
        include_str!("../tests/reference/paper_white/ggx.pbrt.report.json"),
    ),
    (
        "ggx",
        "gltf",
        include_str!("../tests/reference/paper_white/ggx.gltf.report.json"),
    ),
    (
        "ggx",
        "materialx",
        include_str!("../tests/reference/paper_white/ggx.materialx.report.json"),
    ),
    (
        "ggx",
        "openpbr",
        include_str!("../tests/reference/paper_white/ggx.openpbr.report.json"),
    ),
    (
        "ggx",
        "usd",
        include_str!("../tests/reference/paper_white/ggx.usd.report.json"),
    ),
    (
        "ggx",
        "blender",
        include_str!("../tests/reference/paper_white/ggx.blender.report.json"),
    ),
    (
        "ggx-separable",
        "pbrt",
        include_str!("../tests/reference/table/ggx-separable.pbrt.report.json"),
    ),
    (
        "ggx-separable",
        "gltf",
        include_str!("../tests/reference/table/ggx-separable.gltf.report.json"),
    ),
    (
        "ggx-dielectric",
        "mitsuba",
        include_str!("../tests/reference/table/ggx-dielectric.mitsuba.report.json"),
    ),
    (
        "ggx-dielectric",
        "gltf",
        include_str!("../tests/reference/table/ggx-dielectric.gltf.report.json"),
    ),
    (
        "ggx-conductor",
        "mitsuba",
        include_str!("../tests/reference/table/ggx-conductor.mitsuba.report.json"),
    ),
    (
        "ggx-conductor",
        "gltf",
        include_str!("../tests/reference/table/ggx-conductor.gltf.report.json"),
    ),
];

/// The checks by rendering of the reference material's exports
/// (`tests/reference/render_check.py`).
pub const REFERENCE_RENDERS: &str =
    include_str!("../tests/reference/paper_white/render_check.json");

/// `x` to three significant digits (`2.73`, `0.0755`).
fn sig3(x: f64) -> String {
    if !x.is_finite() || x == 0.0 {
        return format!("{x}");
    }
    let decimals = (2 - x.abs().log10().floor() as i32).max(0) as usize;
    format!("{x:.decimals$}")
}

fn num(v: &serde_json::Value) -> f64 {
    v.as_f64().unwrap_or(f64::NAN)
}

/// The image error of each conversion of the reference material's fits.
pub fn conversions_markdown() -> String {
    let mut s = String::from(
        "Conversions of the reference material's fits (RGL `paper_white_rgb`, `brdf fit --metric ngan` in each model), image error at 128 px (MaterialX, USD and Blender write the `gltf` conversion):\n\n",
    );
    s += "| fit | target | converted to | HDR-FLIP sky | HDR-FLIP studio | CIEDE2000 (max) | relative L2 |\n";
    s += "| --- | --- | --- | --- | --- | --- | --- |\n";
    for (model, kind, text) in REFERENCE_CONVERSIONS {
        let Ok(report) = serde_json::from_str::<serde_json::Value>(text) else {
            continue;
        };
        let c = &report["conversion"];
        let flip = |light: &str| {
            c["image"]["lights"]
                .as_array()
                .and_then(|v| v.iter().find(|l| l["light"] == light))
                .map_or(f64::NAN, |l| num(&l["flip"]))
        };
        s += &format!(
            "| `{model}` | {kind} | `{}` | {:.4} | {:.4} | {:.2} | {} |\n",
            c["via"].as_str().unwrap_or("?"),
            flip("sky"),
            flip("studio"),
            num(&c["max_delta_e"]),
            sig3(num(&c["relative_l2"]))
        );
    }
    s
}

/// Each reference export rendered in its renderer beside `brdf-render`.
pub fn renders_markdown() -> String {
    let Ok(r) = serde_json::from_str::<serde_json::Value>(REFERENCE_RENDERS) else {
        return String::new();
    };
    let mut s = String::from(
        "Checks by rendering: each export rendered in its renderer (Mitsuba 3; Blender Cycles, the `.usda` and `.gltf` through Blender's importers; MaterialX's GLSL renderer) against `brdf-render`'s render of the model it holds, studio light, HDR-FLIP (bounds: Mitsuba 0.02, Cycles 0.03, MaterialX 0.025), and against the fit itself for conversions:\n\n",
    );
    s +=
        "| file | renderer | holds | HDR-FLIP vs brdf-render | renderer re-seeded | vs the fit |\n";
    s += "| --- | --- | --- | --- | --- | --- |\n";
    for c in r["checks"].as_array().into_iter().flatten() {
        let l = &c["lights"]["studio"];
        let file = c["file"].as_str().unwrap_or("?");
        let holds = c["model"].as_str().unwrap_or("?");
        s += &format!(
            "| `{}` | {} | `{}` | {:.4} | {:.4} | {:.4} |\n",
            file.trim_start_matches("paper_white/"),
            c["renderer"].as_str().unwrap_or("?"),
            holds.trim_start_matches("paper_white/"),
            num(&l["flip_held"]),
            num(&l["flip_reseeded"]),
            num(&l["flip_source"])
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sums_of_lobes_are_exact_where_principled_materials_are_mapped() {
        let gltf_pbr = Surface::GltfPbr;
        assert!(is_mapped("gltf", Target::Usd, gltf_pbr));
        assert!(is_mapped("gltf", Target::Blender, gltf_pbr));
        assert!(!is_mapped("gltf", Target::MaterialX, gltf_pbr));
        assert!(is_mapped("gltf", Target::MaterialX, Surface::OpenPbr));
        assert!(!is_mapped("lobes-materialx", Target::Usd, gltf_pbr));
        assert!(!is_mapped(
            "film-materialx",
            Target::MaterialX,
            Surface::OpenPbr
        ));
        assert!(!is_mapped("lobes-cycles", Target::Blender, gltf_pbr));
    }
}
