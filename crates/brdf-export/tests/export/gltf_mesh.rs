//! The glTF export's preview sphere: one mesh whose primitive uses the
//! material, POSITION and NORMAL of equal counts, unit normals, indices in
//! range, triangles facing outwards, in a node of the default scene; and
//! `mesh: false` writes the material alone. The buffer is decoded here from
//! its `data:` URI by the accessors' own offsets, not by the writer's code.

use base64::Engine;
use brdf_export::{Target, WriteOptions, export_with};
use serde_json::Value;

fn asset(mesh: bool) -> Value {
    let opts = WriteOptions {
        name: "swatch".into(),
        mesh,
        ..WriteOptions::default()
    };
    let m = brdf_models::build("gltf", &brdf_models::ModelConfig::default()).unwrap();
    serde_json::from_str(&export_with(m.as_ref(), Target::Gltf, None, &opts).unwrap()).unwrap()
}

fn buffer(a: &Value) -> Vec<u8> {
    let uri = a["buffers"][0]["uri"].as_str().unwrap();
    let b64 = uri
        .strip_prefix("data:application/octet-stream;base64,")
        .expect("embedded buffer");
    let bytes = base64::engine::general_purpose::STANDARD
        .decode(b64)
        .unwrap();
    assert_eq!(
        bytes.len() as u64,
        a["buffers"][0]["byteLength"].as_u64().unwrap()
    );
    bytes
}

/// The bytes of accessor `k` (tightly packed: no byteStride is written).
fn view<'a>(a: &Value, bytes: &'a [u8], k: u64) -> (&'a [u8], usize) {
    let acc = &a["accessors"][k as usize];
    let bv = &a["bufferViews"][acc["bufferView"].as_u64().unwrap() as usize];
    assert!(bv.get("byteStride").is_none());
    let off = bv["byteOffset"].as_u64().unwrap() as usize;
    let len = bv["byteLength"].as_u64().unwrap() as usize;
    (
        &bytes[off..off + len],
        acc["count"].as_u64().unwrap() as usize,
    )
}

fn vec3s(raw: &[u8], count: usize) -> Vec<[f64; 3]> {
    assert_eq!(raw.len(), count * 12);
    raw.chunks_exact(12)
        .map(|c| {
            let f = |i: usize| f64::from(f32::from_le_bytes(c[i..i + 4].try_into().unwrap()));
            [f(0), f(4), f(8)]
        })
        .collect()
}

#[test]
fn the_preview_sphere_is_a_valid_mesh_using_the_material() {
    let a = asset(true);
    assert_eq!(a["meshes"].as_array().unwrap().len(), 1);
    let prim = &a["meshes"][0]["primitives"][0];
    assert_eq!(prim["material"], 0);
    assert_eq!(a["materials"][0]["name"], "swatch");
    assert_eq!(
        a["scenes"][a["scene"].as_u64().unwrap() as usize]["nodes"],
        serde_json::json!([0])
    );
    assert_eq!(a["nodes"][0]["mesh"], 0);
    let bytes = buffer(&a);
    let (praw, np) = view(&a, &bytes, prim["attributes"]["POSITION"].as_u64().unwrap());
    let (nraw, nn) = view(&a, &bytes, prim["attributes"]["NORMAL"].as_u64().unwrap());
    assert_eq!(np, nn);
    let (pos, nor) = (vec3s(praw, np), vec3s(nraw, nn));
    for n in &nor {
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        assert!((len - 1.0).abs() < 1e-6, "normal length {len}");
    }
    // POSITION's min and max are the data's (the validator checks them too).
    let acc = &a["accessors"][prim["attributes"]["POSITION"].as_u64().unwrap() as usize];
    for k in 0..3 {
        let lo = pos.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min);
        let hi = pos.iter().map(|p| p[k]).fold(f64::NEG_INFINITY, f64::max);
        assert_eq!(acc["min"][k].as_f64().unwrap(), lo);
        assert_eq!(acc["max"][k].as_f64().unwrap(), hi);
    }
    let ik = prim["indices"].as_u64().unwrap() as usize;
    assert_eq!(a["accessors"][ik]["componentType"], 5123, "unsigned short");
    let (iraw, ni) = view(&a, &bytes, ik as u64);
    assert_eq!(iraw.len(), 2 * ni);
    assert_eq!(ni % 3, 0);
    let idx: Vec<usize> = iraw
        .chunks_exact(2)
        .map(|c| usize::from(u16::from_le_bytes([c[0], c[1]])))
        .collect();
    assert!(idx.iter().all(|&i| i < np), "indices in range");
    let mut area = 0.0;
    for t in idx.chunks_exact(3) {
        let (p, q, r) = (pos[t[0]], pos[t[1]], pos[t[2]]);
        let u = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
        let v = [r[0] - p[0], r[1] - p[1], r[2] - p[2]];
        let c = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        let centroid = [p[0] + q[0] + r[0], p[1] + q[1] + r[1], p[2] + q[2] + r[2]];
        let out = c[0] * centroid[0] + c[1] * centroid[1] + c[2] * centroid[2];
        assert!(out > 0.0, "triangle {t:?} faces inwards or is degenerate");
        area += 0.5 * (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
    }
    // The faceted sphere's area approaches 4 pi from below.
    let four_pi = 4.0 * std::f64::consts::PI;
    assert!(area < four_pi && area > 0.98 * four_pi, "area {area}");
}

#[test]
fn without_the_mesh_the_material_alone_is_written() {
    let a = asset(false);
    for key in [
        "meshes",
        "nodes",
        "scenes",
        "scene",
        "buffers",
        "bufferViews",
        "accessors",
    ] {
        assert!(a.get(key).is_none(), "{key}");
    }
    assert_eq!(a["materials"].as_array().unwrap().len(), 1);
    // The material itself is the same with and without the mesh.
    assert_eq!(a["materials"], asset(true)["materials"]);
}

/// The Khronos validator's answer on `tests/reference/mesh/FILE`
/// (`check_exports.sh`), checked to be on the file as it is.
fn validated(file: &str, text: &str) -> Value {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/reference");
    let answers = std::fs::read_to_string(dir.join("mesh/gltf_validation.json")).unwrap();
    let v: Value = serde_json::from_str(&answers).unwrap();
    let entry = v
        .as_array()
        .unwrap()
        .iter()
        .find(|e| e["file"] == format!("mesh/{file}"))
        .unwrap_or_else(|| panic!("no validator answer for {file}: rerun check_exports.sh"))
        .clone();
    assert_eq!(
        entry["text"].as_str().unwrap(),
        text,
        "rerun check_exports.sh"
    );
    entry["issues"].clone()
}

/// `tests/reference/mesh/NAME.gltf` is what the exporter writes for the
/// model `model` (a saved model under `tests/reference`), named `NAME`.
fn current_export(model: &str, name: &str) -> String {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/reference");
    let saved = brdf_models::saved_model::SavedModel::load_model(&dir.join(model)).unwrap();
    let opts = WriteOptions {
        name: name.into(),
        ..WriteOptions::default()
    };
    let text = std::fs::read_to_string(dir.join(format!("mesh/{name}.gltf"))).unwrap();
    assert_eq!(
        export_with(saved.as_ref(), Target::Gltf, None, &opts).unwrap(),
        text
    );
    text
}

/// `tests/reference/mesh/paper_white_rgb.gltf` (paper_white's `make.sh`:
/// principled's glTF conversion with its preview sphere) is what the
/// exporter writes, and the Khronos validator (`check_exports.sh`) found
/// no error, warning or note in it as it is.
#[test]
fn khronos_validator_accepts_the_file_with_the_sphere() {
    let text = current_export("paper_white/principled.gltf.json", "paper_white_rgb");
    let issues = validated("paper_white_rgb.gltf", &text);
    assert_eq!(issues["numErrors"], 0, "{issues}");
    assert_eq!(issues["numWarnings"], 0, "{issues}");
    assert_eq!(issues["messages"], serde_json::json!([]), "{issues}");
}

/// glTF's thin film: `mesh/film_iridescence.gltf`, the export of a
/// `gltf-iridescence` model, carries `KHR_materials_iridescence` with the
/// model's film (a texture-free film is `iridescenceThicknessMaximum`
/// thick), and the Khronos validator found nothing to report in it.
#[test]
fn khronos_validator_accepts_the_iridescent_film() {
    let text = current_export("mesh/film_iridescence.json", "film_iridescence");
    let a: Value = serde_json::from_str(&text).unwrap();
    let film = &a["materials"][0]["extensions"]["KHR_materials_iridescence"];
    assert_eq!(film["iridescenceFactor"], 1.0);
    assert_eq!(film["iridescenceIor"], 2.09);
    assert_eq!(film["iridescenceThicknessMaximum"], 281.0);
    assert!(
        a["extensionsUsed"]
            .as_array()
            .unwrap()
            .contains(&Value::from("KHR_materials_iridescence"))
    );
    let issues = validated("film_iridescence.gltf", &text);
    assert_eq!(issues["numErrors"], 0, "{issues}");
    assert_eq!(issues["numWarnings"], 0, "{issues}");
    assert_eq!(issues["messages"], serde_json::json!([]), "{issues}");
}
