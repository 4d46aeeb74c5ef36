//! The paper_white exports to USD, Blender, MaterialX `open_pbr_surface`
//! and complete Mitsuba scenes (`tests/reference/paper_white/`, written by
//! its `make.sh`), checked by the real tools, whose answers
//! `check_exports.sh` stored beside them: USD opens each `.usda` as a
//! `Material` with a `UsdPreviewSurface` whose inputs are all in the
//! specification's table; Blender's `bpy` runs each script, saves a
//! `.blend` and reads back the Principled BSDF's inputs as written;
//! MaterialX validates the `open_pbr_surface` documents; Mitsuba loads and
//! renders each scene. Every file must still be what the exporter writes.

use std::path::PathBuf;

use brdf_core::Parametric;
use brdf_export::{Surface, Target, WriteOptions, export_with};
use brdf_models::saved_model::SavedModel;

const MODELS: [&str; 2] = ["ggx", "principled"];

fn dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/reference/paper_white")
}

fn read(name: &str) -> String {
    std::fs::read_to_string(dir().join(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn json(name: &str) -> serde_json::Value {
    serde_json::from_str(&read(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn load(name: &str) -> Box<dyn Parametric> {
    let saved = SavedModel::load(&dir().join(name)).unwrap_or_else(|e| panic!("{e}"));
    saved.build().unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// The file `m.ext` of `kind` is what the exporter writes from the model
/// it holds (the conversion where there is one, with its report's note).
fn assert_written(m: &str, kind: &str, file: &str, target: Target, opts: &WriteOptions) {
    let conv = format!("{m}.{kind}.json");
    let text = if dir().join(&conv).exists() {
        let report = json(&format!("{m}.{kind}.report.json"));
        let c = &report["conversion"];
        let within = c["max_flip"].as_f64().unwrap() <= brdf_export::convert::FLIP_REFUSE;
        assert!(within || c["forced"].as_bool().unwrap(), "{m}.{kind}");
        let note = c["note"].as_str().unwrap();
        export_with(load(&conv).as_ref(), target, Some(note), opts).unwrap()
    } else {
        export_with(load(&format!("{m}.json")).as_ref(), target, None, opts).unwrap()
    };
    assert_eq!(
        text,
        read(file),
        "{file}: exporter output changed; rerun make.sh"
    );
}

fn named() -> WriteOptions {
    WriteOptions {
        name: "paper_white_rgb".into(),
        ..WriteOptions::default()
    }
}

#[test]
fn usd_opens_the_materials() {
    let v = json("usd_validation.json");
    let v = v.as_array().unwrap();
    assert_eq!(v.len(), MODELS.len());
    for (m, r) in MODELS.iter().zip(v) {
        assert_written(m, "usd", &format!("{m}.usda"), Target::Usd, &named());
        assert_eq!(r["text"].as_str().unwrap(), read(&format!("{m}.usda")));
        assert_eq!(r["valid"], true, "{m}: {}", r["problems"]);
        assert_eq!(r["material"], "/paper_white_rgb");
        assert_eq!(r["shader"], "UsdPreviewSurface");
    }
}

#[test]
fn blender_builds_the_principled_materials() {
    let v = json("blender_check.json");
    let v = v.as_array().unwrap();
    assert_eq!(v.len(), MODELS.len());
    for (m, r) in MODELS.iter().zip(v) {
        assert_written(m, "blender", &format!("{m}.py"), Target::Blender, &named());
        assert_eq!(r["text"].as_str().unwrap(), read(&format!("{m}.py")));
        assert_eq!(r["blend_written"], true);
        assert_eq!(r["material"], "paper_white_rgb");
        assert_eq!(r["principled_nodes"], 1);
        assert_eq!(r["surface_linked"], true);
        assert_eq!(r["distribution"], "GGX");
        let (got, want) = (&r["inputs"], &r["expected"]);
        for (k, w) in want.as_object().unwrap() {
            assert_eq!(&got[k], w, "{m}: Blender holds {k} = {} not {w}", got[k]);
        }
    }
}

#[test]
fn materialx_validates_open_pbr() {
    let v = json("materialx_validation.json");
    let open: Vec<_> = v
        .as_array()
        .unwrap()
        .iter()
        .filter(|r| r["file"].as_str().unwrap().ends_with(".openpbr.mtlx"))
        .collect();
    assert_eq!(open.len(), MODELS.len());
    let opts = WriteOptions {
        surface: Surface::OpenPbr,
        ..named()
    };
    for (m, r) in MODELS.iter().zip(open) {
        let file = format!("{m}.openpbr.mtlx");
        assert_written(m, "openpbr", &file, Target::MaterialX, &opts);
        assert_eq!(r["text"].as_str().unwrap(), read(&file));
        assert_eq!(r["valid"], true, "{m}: {}", r["message"]);
        assert_eq!(r["shaders"], serde_json::json!(["open_pbr_surface"]));
        assert_eq!(r["unknown_inputs"], serde_json::json!([]));
    }
}

#[test]
fn mitsuba_loads_and_renders_the_scenes() {
    let v = json("mitsuba_scenes.json");
    let v = v.as_array().unwrap();
    assert_eq!(v.len(), MODELS.len());
    let opts = WriteOptions {
        scene: true,
        ..named()
    };
    for (m, r) in MODELS.iter().zip(v) {
        let file = format!("{m}.scene.xml");
        assert_written(m, "scene", &file, Target::Mitsuba, &opts);
        assert_eq!(r["text"].as_str().unwrap(), read(&file));
        assert_eq!(r["sphere_bsdf"], "Principled BSDF");
        assert_eq!(r["emitters"], 2, "studio: fill and key");
        assert_eq!(r["finite"], true);
        let mean = r["mean"].as_array().unwrap();
        assert!(
            mean.iter().all(|x| x.as_f64().unwrap() > 0.01),
            "{m}: {mean:?}"
        );
    }
}
