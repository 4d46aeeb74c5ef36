//! glTF 2.0 assets (JSON) with one material.
//!
//! - `gltf`: `pbrMetallicRoughness` with `baseColorFactor`,
//!   `metallicFactor`, `roughnessFactor`.
//! - `gltf-ext`: the same plus `KHR_materials_ior`, `KHR_materials_specular`
//!   and `KHR_materials_clearcoat`, each written where it differs from the
//!   core material (the extension's defaults leave the BRDF unchanged).
//! - `gltf-iridescence`: `gltf-ext`'s plus `KHR_materials_iridescence`
//!   (`iridescenceFactor`, `iridescenceIor`, `iridescenceThicknessMaximum`;
//!   no thickness texture, so the film is that thick everywhere).
//! - `lambert`: a dielectric with `KHR_materials_specular.specularFactor = 0`
//!   (then `F_d = 0` and the material is `base_color / pi`).
//!
//! No exact equivalent (an error): every other model (glTF's BRDF couples
//! diffuse and specular through `1 - F`, which no other catalogue model has).
//!
//! By default the asset also holds a preview: a unit UV sphere (positions,
//! normals, 16-bit indices, in one buffer embedded as a `data:` URI) in a
//! node of the default scene, using the material, so a viewer opening the
//! file shows the material at once. [`WriteOptions::mesh`] `false` writes a
//! material library (the material alone) for importing into a scene.

use base64::Engine;
use serde_json::{Value, json};

use crate::fitted::Fitted;
use crate::{ExportError, Target, WriteOptions};
use brdf_models::RendererForm;

/// The material object and the extensions it uses.
pub fn material(fit: &Fitted) -> Result<(Value, Vec<&'static str>), ExportError> {
    let (base, metallic, roughness) = match fit.form {
        RendererForm::Gltf { .. } | RendererForm::GltfIridescence => (
            fit.colour("base_color")?,
            fit.get("metallic")?,
            fit.get("roughness")?,
        ),
        RendererForm::Diffuse => (fit.colour("kd")?, 0.0, 1.0),
        _ => {
            return Err(fit.no_equivalent(
                Target::Gltf,
                "glTF's BRDF is the metallic-roughness material; export the `gltf`, `gltf-ext` or `gltf-iridescence` fit",
            ));
        }
    };
    let mut m = json!({
        "name": "fitted",
        "pbrMetallicRoughness": {
            "baseColorFactor": [base[0], base[1], base[2], 1.0],
            "metallicFactor": metallic,
            "roughnessFactor": roughness,
        }
    });
    let mut ext = serde_json::Map::new();
    let mut used = Vec::new();
    if fit.form == RendererForm::Diffuse {
        ext.insert(
            "KHR_materials_specular".into(),
            json!({ "specularFactor": 0.0 }),
        );
        used.push("KHR_materials_specular");
    }
    let extended = matches!(
        fit.form,
        RendererForm::Gltf { extended: true } | RendererForm::GltfIridescence
    );
    if extended {
        let ior = fit.get("ior")?;
        if ior != 1.5 {
            ext.insert("KHR_materials_ior".into(), json!({ "ior": ior }));
            used.push("KHR_materials_ior");
        }
        let (s, c) = (fit.get("specular")?, fit.colour("specular_color")?);
        if s != 1.0 || c != [1.0; 3] {
            ext.insert(
                "KHR_materials_specular".into(),
                json!({ "specularFactor": s, "specularColorFactor": c }),
            );
            used.push("KHR_materials_specular");
        }
        let cc = fit.get("clearcoat")?;
        if cc != 0.0 {
            ext.insert(
                "KHR_materials_clearcoat".into(),
                json!({ "clearcoatFactor": cc, "clearcoatRoughnessFactor": fit.get("clearcoat_roughness")? }),
            );
            used.push("KHR_materials_clearcoat");
        }
    }
    if fit.form == RendererForm::GltfIridescence {
        // Without a thickness texture the film is the maximum thick.
        ext.insert(
            "KHR_materials_iridescence".into(),
            json!({
                "iridescenceFactor": fit.get("iridescence")?,
                "iridescenceIor": fit.get("iridescence_ior")?,
                "iridescenceThicknessMaximum": fit.get("iridescence_thickness")?,
            }),
        );
        used.push("KHR_materials_iridescence");
    }
    if !ext.is_empty() {
        m["extensions"] = Value::Object(ext);
    }
    Ok((m, used))
}

/// A glTF 2.0 asset holding the material (named `opts.name`), with `note`
/// in `asset.extras`.
pub fn write(fit: &Fitted, note: Option<&str>, opts: &WriteOptions) -> Result<String, ExportError> {
    let (mut m, used) = material(fit)?;
    m["name"] = json!(opts.name);
    let mut asset = json!({
        "asset": { "version": "2.0", "generator": "brdf-export" },
        "materials": [m],
    });
    if let Some(n) = note {
        asset["asset"]["extras"] = json!({ "note": n });
    }
    if !used.is_empty() {
        asset["extensionsUsed"] = json!(used);
    }
    if opts.mesh {
        add_sphere(&mut asset, &opts.name);
    }
    // Serialising a Value cannot fail.
    Ok(serde_json::to_string_pretty(&asset).unwrap_or_default() + "\n")
}

/// Rings (from pole to pole) and segments (around) of the preview sphere:
/// smooth under a viewer's default light at a few hundred vertices.
pub const SPHERE_RINGS: usize = 16;
/// See [`SPHERE_RINGS`].
pub const SPHERE_SEGMENTS: usize = 32;

/// A unit UV sphere about the origin, +Y up (glTF's): positions (which are
/// also the normals), and triangles wound counter-clockwise seen from
/// outside (glTF's front faces). The seam and the poles repeat vertices so
/// that every triangle is proper: one triangle per segment at each pole.
pub fn sphere(rings: usize, segments: usize) -> (Vec<[f32; 3]>, Vec<u16>) {
    use std::f64::consts::{PI, TAU};
    let mut positions = Vec::with_capacity((rings + 1) * (segments + 1));
    for r in 0..=rings {
        let theta = PI * r as f64 / rings as f64;
        for s in 0..=segments {
            let phi = TAU * s as f64 / segments as f64;
            let p = [
                theta.sin() * phi.cos(),
                theta.cos(),
                -theta.sin() * phi.sin(),
            ];
            // Unit in f64; rounded to f32 it stays within 1e-7 of unit.
            let n = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
            positions.push([(p[0] / n) as f32, (p[1] / n) as f32, (p[2] / n) as f32]);
        }
    }
    let row = segments + 1;
    let mut indices = Vec::with_capacity(6 * rings * segments);
    // Vertex counts stay far below u16::MAX for the sizes used here.
    let idx = |i: usize| u16::try_from(i).unwrap_or(u16::MAX);
    for r in 0..rings {
        for s in 0..segments {
            let (a, b) = (r * row + s, (r + 1) * row + s);
            let (c, d) = (b + 1, a + 1);
            if r != 0 {
                indices.extend([idx(a), idx(b), idx(d)]);
            }
            if r + 1 != rings {
                indices.extend([idx(d), idx(b), idx(c)]);
            }
        }
    }
    (positions, indices)
}

/// Add the preview sphere to `asset`: one buffer (positions, normals,
/// indices, embedded), its views and accessors, a mesh whose primitive
/// uses material 0, a node named `name` and the default scene.
fn add_sphere(asset: &mut Value, name: &str) {
    let (positions, indices) = sphere(SPHERE_RINGS, SPHERE_SEGMENTS);
    let mut bytes = Vec::new();
    for p in &positions {
        for x in p {
            bytes.extend_from_slice(&x.to_le_bytes());
        }
    }
    let vec_len = bytes.len();
    // On a unit sphere about the origin the normal is the position.
    bytes.extend_from_slice(&bytes.clone());
    for i in &indices {
        bytes.extend_from_slice(&i.to_le_bytes());
    }
    let mut min = [f32::INFINITY; 3];
    let mut max = [f32::NEG_INFINITY; 3];
    for p in &positions {
        for k in 0..3 {
            min[k] = min[k].min(p[k]);
            max[k] = max[k].max(p[k]);
        }
    }
    let as_f64 = |v: [f32; 3]| v.map(f64::from);
    let uri = format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&bytes)
    );
    asset["buffers"] = json!([{ "byteLength": bytes.len(), "uri": uri }]);
    asset["bufferViews"] = json!([
        { "buffer": 0, "byteOffset": 0, "byteLength": vec_len, "target": 34962 },
        { "buffer": 0, "byteOffset": vec_len, "byteLength": vec_len, "target": 34962 },
        { "buffer": 0, "byteOffset": 2 * vec_len, "byteLength": 2 * indices.len(), "target": 34963 },
    ]);
    asset["accessors"] = json!([
        { "bufferView": 0, "componentType": 5126, "count": positions.len(), "type": "VEC3",
          "min": as_f64(min), "max": as_f64(max) },
        { "bufferView": 1, "componentType": 5126, "count": positions.len(), "type": "VEC3" },
        { "bufferView": 2, "componentType": 5123, "count": indices.len(), "type": "SCALAR" },
    ]);
    asset["meshes"] = json!([{
        "name": "preview_sphere",
        "primitives": [{
            "attributes": { "POSITION": 0, "NORMAL": 1 },
            "indices": 2,
            "material": 0,
            "mode": 4,
        }],
    }]);
    asset["nodes"] = json!([{ "name": name, "mesh": 0 }]);
    asset["scenes"] = json!([{ "nodes": [0] }]);
    asset["scene"] = json!(0);
}
