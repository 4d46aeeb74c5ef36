//! MaterialX documents with a `gltf_pbr` surface shader.
//!
//! `gltf_pbr` is Khronos's MaterialX definition of the glTF 2.0 material,
//! with the same parameters as `gltf-ext` (`base_color`, `metallic`,
//! `roughness`, `ior`, `specular`, `specular_color`, `clearcoat`,
//! `clearcoat_roughness`), so `gltf` and `gltf-ext` fits are written as it
//! and `lambert` as a `gltf_pbr` with `specular = 0`. MaterialX evaluates the
//! material with its own node graph (layering by directional albedo where
//! the glTF appendix writes `1 - max F`); the glTF specification leaves that
//! choice to implementations, the material is the same.
//!
//! No exact equivalent (an error): every other model (MaterialX's
//! `standard_surface`, `open_pbr_surface` and `disney_principled` are other
//! materials than the catalogue's).

use crate::fitted::{Fitted, rgb_string};
use crate::xml::Node;
use crate::{ExportError, Target};

fn input(name: &str, kind: &str, value: String) -> Node {
    Node::new("input")
        .attr("name", name)
        .attr("type", kind)
        .attr("value", value)
}

/// The MaterialX document for `fit`, with `note` as a comment before it.
pub fn write(fit: &Fitted, note: Option<&str>) -> Result<String, ExportError> {
    let mut shader = Node::new("gltf_pbr")
        .attr("name", "fitted_shader")
        .attr("type", "surfaceshader");
    let f = |n: &str, v: f64| input(n, "float", v.to_string());
    let c = |n: &str, v: [f64; 3]| input(n, "color3", rgb_string(&v));
    match fit.name.as_str() {
        "gltf" | "gltf-ext" => {
            shader = shader
                .child(c("base_color", fit.colour("base_color")?))
                .child(f("metallic", fit.get("metallic")?))
                .child(f("roughness", fit.get("roughness")?));
            if fit.name == "gltf-ext" {
                shader = shader
                    .child(f("ior", fit.get("ior")?))
                    .child(f("specular", fit.get("specular")?))
                    .child(c("specular_color", fit.colour("specular_color")?))
                    .child(f("clearcoat", fit.get("clearcoat")?))
                    .child(f("clearcoat_roughness", fit.get("clearcoat_roughness")?));
            }
        }
        "lambert" => {
            shader = shader
                .child(c("base_color", fit.colour("kd")?))
                .child(f("metallic", 0.0))
                .child(f("roughness", 1.0))
                .child(f("specular", 0.0));
        }
        _ => {
            return Err(fit.no_equivalent(
                Target::MaterialX,
                "only the glTF material (gltf_pbr) matches a catalogue model exactly",
            ));
        }
    }
    let material = Node::new("surfacematerial")
        .attr("name", "fitted")
        .attr("type", "material")
        .child(
            Node::new("input")
                .attr("name", "surfaceshader")
                .attr("type", "surfaceshader")
                .attr("nodename", "fitted_shader"),
        );
    let doc = Node::new("materialx")
        .attr("version", "1.39")
        .child(shader)
        .child(material);
    Ok(doc.to_document(true, note))
}
