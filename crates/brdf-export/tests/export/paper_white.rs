//! The paper_white exports (`tests/reference/paper_white/`, written by its
//! `make.sh` from `brdf fit` of `rgl/paper_white_rgb.bsdf` in GGX and in
//! principled and `brdf export` to the four formats) checked against the
//! renderers' own tools, whose answers `check_exports.sh` stored beside
//! them: Mitsuba 3's evaluation of the XML equals the exported model to
//! 1e-4 relative at 300 pairs and the normal, the Khronos validator finds
//! no error or warning in the glTF, MaterialX's `validate()` accepts the
//! documents. Every file must still be what the exporter writes from the
//! saved models, and every conversion's noted error must be the one
//! recomputed here.

use std::path::PathBuf;

use brdf_core::Parametric;
use brdf_export::{ConvertOptions, Target, WriteOptions, convert, export, export_with};
use brdf_models::saved_model::SavedModel;

const MODELS: [&str; 2] = ["ggx", "principled"];
const TARGETS: [(Target, &str); 4] = [
    (Target::Mitsuba, "xml"),
    (Target::Pbrt, "pbrt"),
    (Target::Gltf, "gltf"),
    (Target::MaterialX, "mtlx"),
];

fn dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/reference/paper_white")
}

/// The files are named after the data, `rgl/paper_white_rgb.bsdf`; the
/// glTF files are material libraries (`--no-mesh`: Cycles renders each
/// material on the judge's sphere; `gltf_mesh.rs` checks the preview mesh).
fn opts_named() -> WriteOptions {
    WriteOptions {
        name: "paper_white_rgb".into(),
        mesh: false,
        ..WriteOptions::default()
    }
}

fn read(name: &str) -> String {
    std::fs::read_to_string(dir().join(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn load(name: &str) -> Box<dyn Parametric> {
    SavedModel::load(&dir().join(name))
        .and_then(|s| {
            s.build()
                .map_err(|e| brdf_models::saved_model::SavedModelError::Model {
                    path: name.into(),
                    reason: e.to_string(),
                })
        })
        .unwrap_or_else(|e| panic!("{e}"))
}

/// The model a target's file holds: the converted one where there is one.
fn written(m: &str, t: Target) -> (Box<dyn Parametric>, bool) {
    let conv = format!("{m}.{t}.json");
    if dir().join(&conv).exists() {
        (load(&conv), true)
    } else {
        (load(&format!("{m}.json")), false)
    }
}

#[test]
fn files_are_what_the_exporter_writes_with_the_conversion_error_noted() {
    let mut converted = 0;
    for m in MODELS {
        let source = load(&format!("{m}.json"));
        for (t, ext) in TARGETS {
            let text = read(&format!("{m}.{ext}"));
            let (model, is_conv) = written(m, t);
            if !is_conv {
                assert_eq!(
                    export_with(source.as_ref(), t, None, &opts_named()).unwrap(),
                    text,
                    "{m} -> {t}"
                );
                continue;
            }
            converted += 1;
            // Exact export of a source with a conversion is refused.
            assert!(export(source.as_ref(), t).is_err(), "{m} -> {t}");
            let report: serde_json::Value =
                serde_json::from_str(&read(&format!("{m}.{t}.report.json"))).unwrap();
            let c = &report["conversion"];
            let opts = ConvertOptions {
                pairs: c["samples"].as_u64().unwrap() as usize,
                limit_deg: c["limit_deg"].as_f64().unwrap(),
                ..ConvertOptions::default()
            };
            let e = brdf_export::convert::conversion_error(source.as_ref(), model.as_ref(), &opts)
                .unwrap();
            let rel = c["relative_l2"].as_f64().unwrap();
            assert!(
                (e.relative_l2 - rel).abs() <= 1e-12 * rel,
                "{m} -> {t}: {e:?} vs {rel}"
            );
            assert_eq!(c["via"].as_str().unwrap(), model.name());
            // The note written is the report's, with the recomputed L2; the
            // conversion was forced exactly when its image error is beyond
            // the refusal limits, warned about beyond the warning limits.
            let note = c["note"].as_str().unwrap();
            assert!(note.contains(&format!("relative L2 {:.4e}", e.relative_l2)));
            assert!(note.contains("HDR-FLIP"), "{note}");
            let (flip, delta_e) = (
                c["max_flip"].as_f64().unwrap(),
                c["max_delta_e"].as_f64().unwrap(),
            );
            use brdf_export::convert::{DELTA_E_REFUSE, DELTA_E_WARN, FLIP_REFUSE, FLIP_WARN};
            let within = flip <= FLIP_REFUSE && delta_e <= DELTA_E_REFUSE;
            assert_eq!(c["forced"].as_bool().unwrap(), !within, "{m} -> {t}");
            let quiet = flip <= FLIP_WARN && delta_e <= DELTA_E_WARN;
            assert_eq!(c["warned"].as_bool().unwrap(), !quiet, "{m} -> {t}");
            assert_eq!(
                export_with(model.as_ref(), t, Some(note), &opts_named()).unwrap(),
                text,
                "{m} -> {t}"
            );
            eprintln!("{m} -> {t}: via {}, relative L2 {rel:.4e}", model.name());
        }
    }
    // GGX (height-correlated, Schlick) is exact nowhere; principled only in Mitsuba.
    assert_eq!(converted, 7);
}

#[derive(serde::Deserialize)]
struct MitsubaCase {
    file: String,
    xml: String,
    pairs: Vec<([f64; 3], [f64; 3])>,
    values: Vec<[f64; 3]>,
    peak: [f64; 3],
}

#[derive(serde::Deserialize)]
struct MitsubaValues {
    mitsuba: String,
    cases: Vec<MitsubaCase>,
}

#[test]
fn mitsuba_evaluates_the_exports_as_the_models_do() {
    let mv: MitsubaValues = serde_json::from_str(&read("mitsuba_values.json")).unwrap();
    assert_eq!(mv.cases.len(), MODELS.len());
    for (m, c) in MODELS.iter().zip(&mv.cases) {
        assert_eq!(c.file, format!("paper_white/{m}.xml"));
        assert_eq!(c.xml, read(&format!("{m}.xml")), "rerun check_exports.sh");
        let (model, _) = written(m, Target::Mitsuba);
        let mut f = vec![0.0; model.channels()];
        let mut worst = 0.0f64;
        let n = [0.0, 0.0, 1.0];
        let peak = (n, n);
        for ((wi, wo), v) in c.pairs.iter().zip(&c.values).chain([(&peak, &c.peak)]) {
            model.eval(&(*wo).into(), &(*wi).into(), &mut f);
            for k in 0..3 {
                let ours = f[k.min(f.len() - 1)];
                worst = worst.max((ours - v[k]).abs() / ours.abs().max(1e-3));
            }
        }
        eprintln!(
            "{m}: Mitsuba {} worst relative deviation {worst:.3e}",
            mv.mitsuba
        );
        assert!(worst <= 1e-4, "{m}: {worst}");
    }
}

#[test]
fn khronos_validator_accepts_the_gltf() {
    let v: serde_json::Value = serde_json::from_str(&read("gltf_validation.json")).unwrap();
    let v = v.as_array().unwrap();
    assert_eq!(v.len(), MODELS.len());
    for (m, r) in MODELS.iter().zip(v) {
        assert_eq!(r["text"].as_str().unwrap(), read(&format!("{m}.gltf")));
        let issues = &r["issues"];
        assert_eq!(issues["numErrors"], 0, "{m}: {issues}");
        assert_eq!(issues["numWarnings"], 0, "{m}: {issues}");
    }
}

#[test]
fn materialx_validates_the_documents() {
    let v: serde_json::Value = serde_json::from_str(&read("materialx_validation.json")).unwrap();
    // The gltf_pbr documents (tests/export/targets.rs checks the OpenPBR ones).
    let v: Vec<_> = v
        .as_array()
        .unwrap()
        .iter()
        .filter(|r| !r["file"].as_str().unwrap().ends_with(".openpbr.mtlx"))
        .collect();
    assert_eq!(v.len(), MODELS.len());
    for (m, r) in MODELS.iter().zip(v) {
        assert_eq!(r["text"].as_str().unwrap(), read(&format!("{m}.mtlx")));
        assert_eq!(r["valid"], true, "{m}: {}", r["message"]);
        assert_eq!(r["shaders"], serde_json::json!(["gltf_pbr"]));
    }
}

/// `convert` refuses nonsense options with an error naming them.
#[test]
fn conversion_options_are_checked() {
    let m = brdf_models::build("blinn-phong", &Default::default()).unwrap();
    for opts in [
        ConvertOptions {
            pairs: 3,
            ..Default::default()
        },
        ConvertOptions {
            limit_deg: 95.0,
            ..Default::default()
        },
        ConvertOptions {
            via: Some("no-such-model".into()),
            pairs: 64,
            ..Default::default()
        },
    ] {
        let e = convert(m.as_ref(), Target::Gltf, &opts)
            .err()
            .expect("refused");
        assert!(e.to_string().contains("blinn-phong"), "{e}");
    }
}
