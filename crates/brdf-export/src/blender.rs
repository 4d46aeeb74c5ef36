//! Blender Python scripts that build a material whose surface is one
//! Principled BSDF (Blender 4.x names), named after the data.
//!
//! Run in Blender (`blender -b -P material.py`) or with the `bpy` module
//! (`python material.py`); `-- --blend OUT.blend` (Blender) or
//! `--blend OUT.blend` (`bpy`) also saves a `.blend`.
//!
//! The glTF fits are *mapped*, as Blender's own glTF importer maps them:
//!
//! - the distribution is `GGX`, Blender's single-scatter GGX, as glTF's
//!   (not `MULTI_GGX`, which adds the energy lost to multiple scattering);
//! - `Roughness` is the perceptual roughness (`alpha = roughness^2`), as
//!   glTF's; `Base Color`, `Metallic`, `IOR` carry over;
//! - `Specular IOR Level` scales F0 by twice its value, so glTF's
//!   `KHR_materials_specular.specularFactor` is `2 x` the level (0.5 =
//!   F0 from the IOR), and `Specular Tint` is `specularColorFactor`;
//! - `Coat Weight`, `Coat Roughness` are the clear coat (IOR 1.5).
//! - `lambert` is the base colour with `Specular IOR Level = 0`.
//!
//! The coloured-lobe models with height-correlated masking
//! (`lobes*-cycles`) are written exactly as sums of Cycles BSDFs instead:
//! [`crate::lobes_blender`].
//!
//! Blender's Principled BSDF layers its lobes by albedo and its diffuse is
//! Lambert: close to glTF's `1 - F` mix, not identical. Every other model
//! is converted by fitting `gltf`.

use crate::fitted::Fitted;
use crate::python_literal::py_str;
use crate::{ExportError, Target, WriteOptions};
use brdf_models::RendererForm;

/// A Principled BSDF input: its Blender name and Python value.
type Input = (&'static str, String);

fn rgba(c: [f64; 3]) -> String {
    format!("({}, {}, {}, 1.0)", c[0], c[1], c[2])
}

/// The Principled BSDF inputs of `fit`.
pub fn inputs(fit: &Fitted) -> Result<Vec<Input>, ExportError> {
    let f = |n: &'static str, v: f64| (n, format!("{v:?}"));
    let v = match fit.form {
        RendererForm::Diffuse => vec![
            ("Base Color", rgba(fit.colour("kd")?)),
            f("Metallic", 0.0),
            f("Roughness", 1.0),
            f("Specular IOR Level", 0.0),
        ],
        RendererForm::Gltf { extended } => {
            let mut v = vec![
                ("Base Color", rgba(fit.colour("base_color")?)),
                f("Metallic", fit.get("metallic")?),
                f("Roughness", fit.get("roughness")?),
            ];
            if extended {
                v.extend([
                    f("IOR", fit.get("ior")?),
                    f("Specular IOR Level", 0.5 * fit.get("specular")?),
                    ("Specular Tint", rgba(fit.colour("specular_color")?)),
                    f("Coat Weight", fit.get("clearcoat")?),
                    f("Coat Roughness", fit.get("clearcoat_roughness")?),
                    f("Coat IOR", 1.5),
                ]);
            } else {
                v.extend([f("IOR", 1.5), f("Specular IOR Level", 0.5)]);
            }
            v
        }
        _ => {
            return Err(fit.no_equivalent(
                Target::Blender,
                "the Principled BSDF takes the glTF material's parameters; export the `gltf` fit",
            ));
        }
    };
    Ok(v)
}

const BODY: &str = r#"


def build(name=NAME):
    mat = bpy.data.materials.get(name) or bpy.data.materials.new(name)
    # Kept in a saved .blend without an object using it (a library material).
    mat.use_fake_user = True
    if mat.node_tree is None:
        # Blender before 5 makes a material's node tree only on request
        # (`use_nodes`, deprecated in Blender 5, where every material has one).
        mat.use_nodes = True
    nodes = mat.node_tree.nodes
    nodes.clear()
    bsdf = nodes.new("ShaderNodeBsdfPrincipled")
    out = nodes.new("ShaderNodeOutputMaterial")
    out.location = (300, 0)
    mat.node_tree.links.new(bsdf.outputs["BSDF"], out.inputs["Surface"])
    # Single-scatter GGX, as glTF's (MULTI_GGX would add multiple scattering).
    bsdf.distribution = "GGX"
    for key, value in INPUTS.items():
        bsdf.inputs[key].default_value = value
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

/// The Blender script for `fit`, with `note` in its docstring.
pub fn write(fit: &Fitted, note: Option<&str>, opts: &WriteOptions) -> Result<String, ExportError> {
    if let Some(lobes) = fit.lobes()? {
        let terms = crate::lobes_blender::terms(fit, &lobes)?;
        return crate::lobes_blender::write(fit, &terms, note, opts);
    }
    if fit.form == RendererForm::ThinFilm {
        let terms = crate::lobes_blender::film_terms(fit)?;
        return crate::lobes_blender::write(fit, &terms, note, opts);
    }
    let inputs = inputs(fit)?;
    let mut s =
        String::from("\"\"\"Principled BSDF material written by `brdf export --to blender`.\n\n");
    s += "Run: blender -b -P THIS.py [-- --blend OUT.blend], or python THIS.py [--blend OUT.blend] with bpy.\n";
    if let Some(n) = note {
        s += &format!("\n{}\n", n.replace('\\', "/").replace("\"\"\"", "'''"));
    }
    s += "\"\"\"\n\nimport os\nimport sys\n\nimport bpy\n\n";
    s += &format!("NAME = {}\nINPUTS = {{\n", py_str(&opts.name));
    for (k, v) in inputs {
        s += &format!("    {}: {v},\n", py_str(k));
    }
    s += "}";
    s += BODY;
    Ok(s)
}
