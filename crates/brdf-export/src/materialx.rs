//! MaterialX 1.39 documents with one surface shader ([`Surface`]):
//!
//! - `gltf_pbr` (default) is Khronos's MaterialX definition of the glTF
//!   2.0 material, with the same parameters as `gltf-ext` (`base_color`,
//!   `metallic`, `roughness`, `ior`, `specular`, `specular_color`,
//!   `clearcoat`, `clearcoat_roughness`), so `gltf` and `gltf-ext` fits
//!   are written as it and `lambert` as a `gltf_pbr` with `specular = 0`.
//!   MaterialX evaluates the material with its own node graph (layering by
//!   directional albedo where the glTF appendix writes `1 - max F`); the
//!   glTF specification leaves that choice to implementations, the
//!   material is the same.
//! - `standard_surface` (Autodesk Standard Surface) and `open_pbr_surface`
//!   (OpenPBR 1.x) take the same glTF fits *mapped*, as Khronos and the
//!   OpenPBR specification map glTF: base colour, metalness, specular
//!   roughness and IOR, specular weight and colour, coat weight and
//!   roughness. Their closures are other materials (OpenPBR's metal is
//!   F82-tinted, both layer by albedo, Standard Surface's diffuse is
//!   Oren-Nayar at roughness 0): the mapping keeps the parameters, not the
//!   BRDF, and its difference is not measured here.
//!
//! The coloured-lobe and thin-film models as MaterialX evaluates them
//! (`lobes*-materialx`, `film*-materialx`) are written as a graph of its
//! BSDF nodes instead, exactly
//! ([`crate::lobes_materialx`]; `surface` does not apply to them).
//!
//! No equivalent (an error): every other model (converted by fitting
//! `gltf`).

use brdf_models::RendererForm;

use crate::fitted::{Fitted, rgb_string};
use crate::xml::Node;
use crate::{ExportError, Surface, Target, WriteOptions};

fn input(name: &str, kind: &str, value: String) -> Node {
    Node::new("input")
        .attr("name", name)
        .attr("type", kind)
        .attr("value", value)
}

/// A glTF material's parameters (core defaults where the model lacks one).
struct Gltf {
    base: [f64; 3],
    metallic: f64,
    roughness: f64,
    ior: f64,
    specular: f64,
    specular_color: [f64; 3],
    coat: f64,
    coat_roughness: f64,
}

fn gltf_params(fit: &Fitted) -> Result<Gltf, ExportError> {
    let mut g = Gltf {
        base: [0.0; 3],
        metallic: 0.0,
        roughness: 1.0,
        ior: 1.5,
        specular: 1.0,
        specular_color: [1.0; 3],
        coat: 0.0,
        coat_roughness: 0.0,
    };
    match fit.form {
        RendererForm::Gltf { extended } => {
            g.base = fit.colour("base_color")?;
            g.metallic = fit.get("metallic")?;
            g.roughness = fit.get("roughness")?;
            if extended {
                g.ior = fit.get("ior")?;
                g.specular = fit.get("specular")?;
                g.specular_color = fit.colour("specular_color")?;
                g.coat = fit.get("clearcoat")?;
                g.coat_roughness = fit.get("clearcoat_roughness")?;
            }
        }
        RendererForm::Diffuse => {
            g.base = fit.colour("kd")?;
            g.specular = 0.0;
        }
        _ => {
            return Err(fit.no_equivalent(
                Target::MaterialX,
                "only the glTF material (gltf_pbr) matches a catalogue model exactly",
            ));
        }
    }
    Ok(g)
}

/// The shader node's kind and inputs for `surface`.
fn shader_inputs(fit: &Fitted, g: &Gltf, surface: Surface) -> (&'static str, Vec<Node>) {
    let f = |n: &str, v: f64| input(n, "float", v.to_string());
    let c = |n: &str, v: [f64; 3]| input(n, "color3", rgb_string(&v));
    match surface {
        Surface::GltfPbr => {
            let mut v = vec![
                c("base_color", g.base),
                f("metallic", g.metallic),
                f("roughness", g.roughness),
            ];
            if fit.form == (RendererForm::Gltf { extended: true }) {
                v.extend([
                    f("ior", g.ior),
                    f("specular", g.specular),
                    c("specular_color", g.specular_color),
                    f("clearcoat", g.coat),
                    f("clearcoat_roughness", g.coat_roughness),
                ]);
            } else if fit.form == RendererForm::Diffuse {
                v.push(f("specular", 0.0));
            }
            ("gltf_pbr", v)
        }
        Surface::StandardSurface => (
            "standard_surface",
            vec![
                f("base", 1.0),
                c("base_color", g.base),
                f("metalness", g.metallic),
                f("specular", g.specular),
                c("specular_color", g.specular_color),
                f("specular_roughness", g.roughness),
                f("specular_IOR", g.ior),
                f("coat", g.coat),
                f("coat_roughness", g.coat_roughness),
            ],
        ),
        Surface::OpenPbr => (
            "open_pbr_surface",
            vec![
                f("base_weight", 1.0),
                c("base_color", g.base),
                f("base_metalness", g.metallic),
                f("specular_weight", g.specular),
                c("specular_color", g.specular_color),
                f("specular_roughness", g.roughness),
                f("specular_ior", g.ior),
                f("coat_weight", g.coat),
                f("coat_roughness", g.coat_roughness),
            ],
        ),
    }
}

/// The MaterialX document of a coloured-lobe or thin-film fit for `target`
/// (MaterialX, or USD through MaterialX); `None` for other models.
pub(crate) fn lobe_graph(
    fit: &Fitted,
    target: Target,
    opts: &WriteOptions,
) -> Result<Option<Node>, ExportError> {
    if let Some(lobes) = fit.lobes()? {
        return crate::lobes_materialx::graph(fit, &lobes, target, opts).map(Some);
    }
    if fit.form == RendererForm::ThinFilm {
        return crate::lobes_materialx::film_graph(fit, target, opts).map(Some);
    }
    Ok(None)
}

/// The MaterialX document for `fit`, with `note` as a comment before it.
pub fn write(fit: &Fitted, note: Option<&str>, opts: &WriteOptions) -> Result<String, ExportError> {
    if let Some(graph) = lobe_graph(fit, Target::MaterialX, opts)? {
        return Ok(graph.to_document(true, note));
    }
    let g = gltf_params(fit)?;
    let (kind, inputs) = shader_inputs(fit, &g, opts.surface);
    let shader_name = format!("{}_shader", opts.name);
    let shader = inputs.into_iter().fold(
        Node::new(kind)
            .attr("name", &shader_name)
            .attr("type", "surfaceshader"),
        Node::child,
    );
    let material = Node::new("surfacematerial")
        .attr("name", &opts.name)
        .attr("type", "material")
        .child(
            Node::new("input")
                .attr("name", "surfaceshader")
                .attr("type", "surfaceshader")
                .attr("nodename", &shader_name),
        );
    let doc = Node::new("materialx")
        .attr("version", "1.39")
        .child(shader)
        .child(material);
    Ok(doc.to_document(true, note))
}
