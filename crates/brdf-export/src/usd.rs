//! USD layers (`.usda`) holding one `Material` whose surface is a
//! `UsdPreviewSurface` shader, the layer's default prim (so another layer
//! references it with `references = @material.usda@`).
//!
//! The glTF fits are *mapped* (UsdPreviewSurface's specification fixes
//! the parameters, not the BRDF, which each renderer implements; Storm and
//! most path tracers use GGX with Schlick Fresnel and a Lambert base):
//!
//! - `gltf`, and `gltf-ext` at the core specular: the metalness workflow
//!   (`diffuseColor` = base colour, `metallic`, `roughness` = glTF's
//!   perceptual roughness, `ior`, `clearcoat`, `clearcoatRoughness`).
//! - `gltf-ext` with `KHR_materials_specular` away from its defaults and
//!   `metallic = 0`: the specular workflow, `specularColor` =
//!   `F0 = ((ior - 1) / (ior + 1))^2 specular specular_color`.
//! - `lambert`: the specular workflow with a black `specularColor`.
//!
//! The coloured-lobe and thin-film fits MaterialX renders exactly (their
//! `-materialx` configurations) are written exactly, as their MaterialX
//! graph in UsdShade prims ([`crate::usd_materialx`]); their Cycles and
//! Mitsuba configurations are converted by fitting the `-materialx` twin.
//! Every other model is converted by fitting `gltf`.

use crate::fitted::Fitted;
use crate::usd_materialx::quoted;
use crate::{ExportError, Target, WriteOptions};
use brdf_models::RendererForm;

/// A shader input: USD type, name, value text.
type Input = (&'static str, &'static str, String);

fn colour(c: [f64; 3]) -> String {
    format!("({}, {}, {})", c[0], c[1], c[2])
}

fn float(name: &'static str, v: f64) -> Input {
    ("float", name, v.to_string())
}

/// The UsdPreviewSurface inputs of `fit`.
pub fn inputs(fit: &Fitted) -> Result<Vec<Input>, ExportError> {
    let specular = |c: [f64; 3], roughness: f64| -> Vec<Input> {
        vec![
            ("int", "useSpecularWorkflow", "1".into()),
            ("color3f", "specularColor", colour(c)),
            float("roughness", roughness),
        ]
    };
    let mut v: Vec<Input> = Vec::new();
    match fit.form {
        RendererForm::Diffuse => {
            v.push(("color3f", "diffuseColor", colour(fit.colour("kd")?)));
            v.extend(specular([0.0; 3], 1.0));
        }
        RendererForm::Gltf { extended: ext } => {
            let base = fit.colour("base_color")?;
            let (m, r) = (fit.get("metallic")?, fit.get("roughness")?);
            v.push(("color3f", "diffuseColor", colour(base)));
            let ior = if ext { fit.get("ior")? } else { 1.5 };
            let (s, sc) = if ext {
                (fit.get("specular")?, fit.colour("specular_color")?)
            } else {
                (1.0, [1.0; 3])
            };
            if (s != 1.0 || sc != [1.0; 3]) && m == 0.0 {
                let f0 = ((ior - 1.0) / (ior + 1.0)).powi(2) * s;
                v.extend(specular(sc.map(|x| (x * f0).min(1.0)), r));
            } else {
                v.push(("int", "useSpecularWorkflow", "0".into()));
                v.push(float("metallic", m));
                v.push(float("roughness", r));
            }
            v.push(float("ior", ior));
            if ext {
                v.push(float("clearcoat", fit.get("clearcoat")?));
                v.push(float("clearcoatRoughness", fit.get("clearcoat_roughness")?));
            }
        }
        _ => {
            return Err(fit.no_equivalent(
                Target::Usd,
                "UsdPreviewSurface takes the glTF material's parameters; export the `gltf` fit",
            ));
        }
    }
    Ok(v)
}

/// The `.usda` layer for `fit`, with `note` as the layer's `doc`.
pub fn write(fit: &Fitted, note: Option<&str>, opts: &WriteOptions) -> Result<String, ExportError> {
    if let Some(graph) = crate::materialx::lobe_graph(fit, Target::Usd, opts)? {
        let doc = note.unwrap_or(
            "exported exactly by brdf-export (the MaterialX graph as UsdShade prims, render context mtlx)",
        );
        return crate::usd_materialx::layer(&graph, doc);
    }
    let name = &opts.name;
    let mut s = format!("#usda 1.0\n(\n    defaultPrim = {}\n", quoted(name));
    let doc = note.unwrap_or("exported exactly by brdf-export (UsdPreviewSurface mapping)");
    s += &format!("    doc = {}\n)\n\n", quoted(doc));
    s += &format!("def Material {}\n{{\n", quoted(name));
    s += &format!(
        "    token outputs:surface.connect = </{name}/PreviewSurface.outputs:surface>\n\n"
    );
    s += "    def Shader \"PreviewSurface\"\n    {\n";
    s += "        uniform token info:id = \"UsdPreviewSurface\"\n";
    for (kind, input, value) in inputs(fit)? {
        s += &format!("        {kind} inputs:{input} = {value}\n");
    }
    s += "        token outputs:surface\n    }\n}\n";
    Ok(s)
}
