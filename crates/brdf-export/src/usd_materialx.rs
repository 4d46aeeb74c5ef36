//! A MaterialX graph written as UsdShade prims: the USD layer of the
//! coloured-lobe and thin-film fits that MaterialX renders exactly
//! ([`crate::lobes_materialx`]), for pipelines that take USD.
//!
//! The layer follows the convention USD's MaterialX support reads (the
//! `usdMtlx` plugin writes it, Hydra's MaterialX network reads it back):
//! each MaterialX node is a `Shader` prim under the `Material`, named as
//! the node, whose `info:id` is the node's MaterialX node definition
//! (`ND_generalized_schlick_bsdf`, `ND_add_bsdf`, `ND_surface`, ...); a
//! value is an input of the USD type of its MaterialX type (`color3` as
//! `color3f`, `vector2` as `float2`, `float`, `string`), a link is a
//! connection to the source's `outputs:out` (BSDF and shader values are
//! `token`s in USD), and the material's `outputs:mtlx:surface` (the
//! `mtlx` render context) is connected to the `surface` node. The graph
//! is the MaterialX document's, node for node and value for value, so it
//! renders what MaterialX renders wherever USD is shaded by MaterialX
//! (Storm, Karma, RenderMan, Arnold). A renderer without MaterialX finds
//! no surface for the universal context: the `gltf` fit's
//! UsdPreviewSurface layer ([`crate::usd`]) is the one it reads.

use crate::xml::Node;
use crate::{ExportError, Target};

/// A USD string literal.
pub(crate) fn quoted(s: &str) -> String {
    format!("\"{}\"", s.replace('\\', "\\\\").replace('"', "\\\""))
}

/// The USD type of a MaterialX input type.
fn usd_type(mtlx: &str) -> Option<&'static str> {
    Some(match mtlx {
        "color3" => "color3f",
        "vector2" => "float2",
        "float" => "float",
        "string" => "string",
        "BSDF" | "surfaceshader" => "token",
        _ => return None,
    })
}

/// The MaterialX node definition of a node of `tag` and output `kind`
/// (the standard library's naming: `ND_<node>` for the BSDF nodes, the
/// output type appended where the node is defined for several).
fn node_def(tag: &str, kind: &str) -> Option<String> {
    match (tag, kind) {
        (t, "BSDF") if t.ends_with("_bsdf") => Some(format!("ND_{t}")),
        ("add", "BSDF") => Some("ND_add_bsdf".into()),
        ("surface", "surfaceshader") => Some("ND_surface".into()),
        _ => None,
    }
}

/// A value written as USD writes its type: tuples in parentheses, strings
/// quoted.
fn usd_value(kind: &str, value: &str) -> String {
    match kind {
        "color3f" | "float2" => format!("({value})"),
        "string" => format!("\"{value}\""),
        _ => value.to_string(),
    }
}

/// The `Shader` prim of MaterialX node `node` under `/material`.
fn shader(node: &Node, material: &str) -> Result<String, ExportError> {
    let kind = node.get("type").unwrap_or("");
    let id = node_def(node.tag(), kind).ok_or_else(|| untranslated(node.tag()))?;
    let mut s = format!("    def Shader \"{}\"\n    {{\n", node.name());
    s += &format!("        uniform token info:id = \"{id}\"\n");
    for input in node.children() {
        let name = input.name();
        let mtlx_type = input.get("type").unwrap_or("");
        let ty = usd_type(mtlx_type).ok_or_else(|| untranslated(mtlx_type))?;
        match (input.get("value"), input.get("nodename")) {
            (Some(v), _) => {
                // MaterialX's enumerated strings are uniform in USD.
                let uniform = if ty == "string" { "uniform " } else { "" };
                s += &format!(
                    "        {uniform}{ty} inputs:{name} = {}\n",
                    usd_value(ty, v)
                );
            }
            (None, Some(source)) => {
                s += &format!(
                    "        {ty} inputs:{name}.connect = </{material}/{source}.outputs:out>\n"
                );
            }
            (None, None) => return Err(untranslated(name)),
        }
    }
    s += "        token outputs:out\n    }\n";
    Ok(s)
}

/// An element of the graph this writer has no USD form for: the graphs
/// come from [`crate::lobes_materialx`], so this names a node or type that
/// module added without teaching this one.
fn untranslated(what: &str) -> ExportError {
    ExportError::NoEquivalent {
        model: "MaterialX graph".into(),
        target: Target::Usd,
        reason: format!("`{what}` has no UsdShade form here"),
    }
}

/// The `.usda` layer of MaterialX document `doc` (whose `surfacematerial`
/// names the material), with `note` as the layer's `doc`.
pub(crate) fn layer(doc: &Node, note: &str) -> Result<String, ExportError> {
    let material = doc
        .children()
        .iter()
        .find(|n| n.tag() == "surfacematerial")
        .ok_or_else(|| untranslated("a document without a surfacematerial"))?;
    let name = material.name();
    let surface = material
        .children()
        .iter()
        .find_map(|i| i.get("nodename"))
        .ok_or_else(|| untranslated("a surfacematerial without a shader"))?;
    let mut s = format!("#usda 1.0\n(\n    defaultPrim = {}\n", quoted(name));
    s += &format!("    doc = {}\n)\n\n", quoted(note));
    s += &format!("def Material {}\n{{\n", quoted(name));
    s += &format!("    token outputs:mtlx:surface.connect = </{name}/{surface}.outputs:out>\n");
    for node in doc
        .children()
        .iter()
        .filter(|n| n.tag() != "surfacematerial")
    {
        s += "\n";
        s += &shader(node, name)?;
    }
    s += "}\n";
    Ok(s)
}
