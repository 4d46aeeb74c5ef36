//! Blender Python scripts of the coloured-lobe models with
//! height-correlated masking (the `lobes*-cycles` configurations of
//! `brdf_models::coloured_lobes`), exact in Cycles: each term is a Cycles
//! BSDF node with the same formula and Add Shader nodes sum them.
//!
//! - the Lambert term is a Diffuse BSDF (Roughness 0: Lambert);
//! - a lobe of Fresnel law none is a Glossy BSDF with distribution `GGX`
//!   (single scattering, height-correlated Smith `G`, no Fresnel), Color
//!   the lobe's colour;
//! - a conductor lobe is a Metallic BSDF, `GGX`, Fresnel type
//!   `PHYSICAL_CONDUCTOR`, IOR `eta`, Extinction `kappa` (per channel);
//! - an F82-tint lobe is a Metallic BSDF, `GGX`, Fresnel type `F82`, Base
//!   Color `f0`, Edge Tint `tint` (Cycles' F82 law is the model's: the
//!   value at `cos = 1/7` is the tint times Schlick's);
//! - the coat is a Metallic BSDF, `PHYSICAL_CONDUCTOR`, IOR `coat_ior`,
//!   Extinction 0: the conductor Fresnel at zero extinction is the
//!   dielectric's.
//!
//! Cycles' Roughness `r` is the GGX width's square root (`alpha = r^2`), so
//! each node gets `sqrt(alpha)`. `MULTI_GGX` is never used: it adds the
//! energy of multiple scattering, which the model does not have.
//!
//! The script runs in Blender (`blender -b -P material.py`) or with the
//! `bpy` module (`python material.py`), as [`crate::blender`]'s; it reads
//! the material's node tree where Blender made one and switches nodes on
//! (`use_nodes`, deprecated in Blender 5) only where it did not.
//!
//! The separable (`-mitsuba`) configurations have no Cycles equivalent
//! (Cycles' GGX is height-correlated): an error naming the `-cycles`
//! configuration to fit.

use crate::fitted::Fitted;
use crate::lobes_fit::{LobeColour, LobesFit};
use crate::python_literal::py_str;
use crate::{ExportError, Target, WriteOptions};

/// One BSDF node of the sum: its Blender type, enum properties and inputs
/// (Python values).
#[derive(Clone, Debug, PartialEq)]
pub struct ShaderTerm {
    /// Node type identifier (`ShaderNodeBsdfDiffuse`, ...).
    pub node: &'static str,
    /// Enum properties, `(name, value)`.
    pub props: Vec<(&'static str, &'static str)>,
    /// Socket inputs, `(name, Python value)`.
    pub inputs: Vec<(&'static str, String)>,
    /// The term's weight, when not 1: a Mix Shader with nothing on its
    /// other input scales the closure by its factor exactly.
    pub weight: Option<f64>,
}

fn rgba(c: &[f64; 3]) -> String {
    format!("({:?}, {:?}, {:?}, 1.0)", c[0], c[1], c[2])
}

fn vec3(c: &[f64; 3]) -> String {
    format!("({:?}, {:?}, {:?})", c[0], c[1], c[2])
}

fn roughness(alpha: f64) -> (&'static str, String) {
    ("Roughness", format!("{:?}", alpha.sqrt()))
}

fn metallic(fresnel: &'static str, inputs: Vec<(&'static str, String)>) -> ShaderTerm {
    ShaderTerm {
        node: "ShaderNodeBsdfMetallic",
        props: vec![("distribution", "GGX"), ("fresnel_type", fresnel)],
        inputs,
        weight: None,
    }
}

/// The BSDF nodes of `lobes`, in the model's order; an error for a
/// configuration Cycles lacks.
pub fn terms(fit: &Fitted, lobes: &LobesFit) -> Result<Vec<ShaderTerm>, ExportError> {
    if lobes.separable() {
        let twin = lobes.variant.name.replace("-mitsuba", "-cycles");
        return Err(fit.no_equivalent(
            Target::Blender,
            format!(
                "Cycles' GGX uses the height-correlated Smith G, this configuration the separable one; fit `{twin}` for an exact Blender export"
            ),
        ));
    }
    if lobes.variant.compensated {
        let twin = lobes.variant.name.replace("-materialx", "-cycles");
        return Err(fit.no_equivalent(
            Target::Blender,
            format!(
                "this configuration carries MaterialX's GGX energy compensation, which Cycles' GGX nodes lack; fit `{twin}` for an exact Blender export"
            ),
        ));
    }
    let mut v = vec![ShaderTerm {
        node: "ShaderNodeBsdfDiffuse",
        props: vec![],
        inputs: vec![("Color", rgba(&lobes.kd)), ("Roughness", "0.0".to_string())],
        weight: None,
    }];
    for lobe in &lobes.lobes {
        let r = roughness(lobe.alpha);
        v.push(match lobe.colour {
            LobeColour::Plain(ks) => ShaderTerm {
                node: "ShaderNodeBsdfAnisotropic",
                props: vec![("distribution", "GGX")],
                inputs: vec![("Color", rgba(&ks)), r, ("Anisotropy", "0.0".into())],
                weight: None,
            },
            LobeColour::Conductor { eta, kappa } => metallic(
                "PHYSICAL_CONDUCTOR",
                vec![("IOR", vec3(&eta)), ("Extinction", vec3(&kappa)), r],
            ),
            LobeColour::F82 { f0, tint } => metallic(
                "F82",
                vec![("Base Color", rgba(&f0)), ("Edge Tint", rgba(&tint)), r],
            ),
        });
    }
    if let Some(c) = lobes.coat {
        v.push(coat(c.ior, c.alpha));
    }
    Ok(v)
}

/// The white dielectric coat: a conductor of zero extinction.
fn coat(ior: f64, alpha: f64) -> ShaderTerm {
    metallic(
        "PHYSICAL_CONDUCTOR",
        vec![
            ("IOR", vec3(&[ior; 3])),
            ("Extinction", vec3(&[0.0; 3])),
            roughness(alpha),
        ],
    )
}

/// The BSDF nodes of a thin-film model (`brdf_models::thin_film`): the
/// Lambert term, the film lobe as a Metallic BSDF of the base's index and
/// zero extinction carrying Cycles' thin film, weighted by `w`, and the
/// coat. A one-channel fit is the film's luminance, which no Cycles node
/// shows: an error asking for an RGB fit.
pub fn film_terms(fit: &Fitted) -> Result<Vec<ShaderTerm>, ExportError> {
    if let Some(stem) = fit.name.strip_suffix("-materialx") {
        return Err(fit.no_equivalent(
            Target::Blender,
            format!(
                "this is MaterialX's film (its Airy series and GGX energy compensation), not Cycles'; fit `{stem}-cycles` for an exact Blender export"
            ),
        ));
    }
    if fit.channels != 3 {
        return Err(fit.no_equivalent(
            Target::Blender,
            "a one-channel thin film is the film's luminance, Cycles' film is coloured; fit RGB data",
        ));
    }
    let n3 = fit.get("base_ior")?;
    let mut film = metallic(
        "PHYSICAL_CONDUCTOR",
        vec![
            ("IOR", vec3(&[n3; 3])),
            ("Extinction", vec3(&[0.0; 3])),
            roughness(fit.get("alpha")?),
            ("Thin Film Thickness", format!("{:?}", fit.get("film_d")?)),
            ("Thin Film IOR", format!("{:?}", fit.get("film_ior")?)),
        ],
    );
    film.weight = Some(fit.get("w")?);
    let mut v = vec![
        ShaderTerm {
            node: "ShaderNodeBsdfDiffuse",
            props: vec![],
            inputs: vec![
                ("Color", rgba(&fit.colour("kd")?)),
                ("Roughness", "0.0".to_string()),
            ],
            weight: None,
        },
        film,
    ];
    if fit.params.iter().any(|(n, _)| n == "coat_ior") {
        v.push(coat(fit.get("coat_ior")?, fit.get("coat_alpha")?));
    }
    Ok(v)
}

const BODY: &str = r#"


def build(name=NAME):
    mat = bpy.data.materials.get(name) or bpy.data.materials.new(name)
    # Kept in a saved .blend without an object using it (a library material).
    mat.use_fake_user = True
    if mat.node_tree is None:
        # Blender before 5 makes a material's node tree only on request.
        mat.use_nodes = True
    tree = mat.node_tree
    tree.nodes.clear()
    out = tree.nodes.new("ShaderNodeOutputMaterial")
    out.location = (300 * (len(TERMS) + 1), 0)
    total = None
    for i, (kind, props, inputs, weight) in enumerate(TERMS):
        node = tree.nodes.new(kind)
        node.location = (300 * i, -250)
        for key, value in props.items():
            setattr(node, key, value)
        for key, value in inputs.items():
            node.inputs[key].default_value = value
        term = node.outputs["BSDF"]
        if weight is not None:
            # Mix Shader is fac * B + (1 - fac) * A; with A unlinked it is
            # the term scaled by fac.
            mix = tree.nodes.new("ShaderNodeMixShader")
            mix.location = (300 * i + 75, -450)
            mix.inputs["Fac"].default_value = weight
            tree.links.new(term, mix.inputs[2])
            term = mix.outputs["Shader"]
        if total is None:
            total = term
            continue
        # Add Shader sums its two closures exactly.
        add = tree.nodes.new("ShaderNodeAddShader")
        add.location = (300 * i + 150, 0)
        tree.links.new(total, add.inputs[0])
        tree.links.new(term, add.inputs[1])
        total = add.outputs["Shader"]
    tree.links.new(total, out.inputs["Surface"])
    return mat


if __name__ == "__main__":
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
    build()
    if "--blend" in argv:
        i = argv.index("--blend")
        if i + 1 >= len(argv):
            sys.exit("--blend needs a file name: --blend OUT.blend")
        bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(argv[i + 1]))
"#;

/// The Blender script of `terms`, the BSDF nodes of `fit`, with `note` in
/// its docstring.
pub(crate) fn write(
    fit: &Fitted,
    terms: &[ShaderTerm],
    note: Option<&str>,
    opts: &WriteOptions,
) -> Result<String, ExportError> {
    let mut s = format!(
        "\"\"\"Cycles material of `{}` written by `brdf export --to blender`: the model's terms as Diffuse, Glossy (GGX) and Metallic (GGX) BSDFs joined by Add Shader nodes, exact in Cycles.\n\n",
        fit.name
    );
    s += "Run: blender -b -P THIS.py [-- --blend OUT.blend], or python THIS.py [--blend OUT.blend] with bpy.\n";
    if let Some(n) = note {
        s += &format!("\n{}\n", n.replace('\\', "/").replace("\"\"\"", "'''"));
    }
    s += "\"\"\"\n\nimport os\nimport sys\n\nimport bpy\n\n";
    s += &format!(
        "NAME = {}\n# (node type, properties, inputs, weight) of each term of the sum.\nTERMS = [\n",
        py_str(&opts.name)
    );
    for t in terms {
        s += &format!("    (\n        {},\n        {{", py_str(t.node));
        s += &t
            .props
            .iter()
            .map(|(k, v)| format!("{}: {}", py_str(k), py_str(v)))
            .collect::<Vec<_>>()
            .join(", ");
        s += "},\n        {";
        s += &t
            .inputs
            .iter()
            .map(|(k, v)| format!("{}: {v}", py_str(k)))
            .collect::<Vec<_>>()
            .join(", ");
        s += &format!(
            "}},\n        {},\n    ),\n",
            t.weight.map_or("None".to_string(), |w| format!("{w:?}"))
        );
    }
    s += "]";
    s += BODY;
    Ok(s)
}
