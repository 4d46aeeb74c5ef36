//! glTF 2.0 assets (JSON) with one material.
//!
//! - `gltf`: `pbrMetallicRoughness` with `baseColorFactor`,
//!   `metallicFactor`, `roughnessFactor`.
//! - `gltf-ext`: the same plus `KHR_materials_ior`, `KHR_materials_specular`
//!   and `KHR_materials_clearcoat`, each written where it differs from the
//!   core material (the extension's defaults leave the BRDF unchanged).
//! - `lambert`: a dielectric with `KHR_materials_specular.specularFactor = 0`
//!   (then `F_d = 0` and the material is `base_color / pi`).
//!
//! No exact equivalent (an error): every other model (glTF's BRDF couples
//! diffuse and specular through `1 - F`, which no other catalogue model has).

use serde_json::{Value, json};

use crate::fitted::Fitted;
use crate::{ExportError, Target, WriteOptions};

/// The material object and the extensions it uses.
pub fn material(fit: &Fitted) -> Result<(Value, Vec<&'static str>), ExportError> {
    let (base, metallic, roughness) = match fit.name.as_str() {
        "gltf" | "gltf-ext" => (
            fit.colour("base_color")?,
            fit.get("metallic")?,
            fit.get("roughness")?,
        ),
        "lambert" => (fit.colour("kd")?, 0.0, 1.0),
        _ => {
            return Err(fit.no_equivalent(
                Target::Gltf,
                "glTF's BRDF is the metallic-roughness material; export the `gltf` or `gltf-ext` fit",
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
    if fit.name == "lambert" {
        ext.insert(
            "KHR_materials_specular".into(),
            json!({ "specularFactor": 0.0 }),
        );
        used.push("KHR_materials_specular");
    }
    if fit.name == "gltf-ext" {
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
    // Serialising a Value cannot fail.
    Ok(serde_json::to_string_pretty(&asset).unwrap_or_default() + "\n")
}
