//! `gltf-iridescence` (glTF with `KHR_materials_iridescence`) against
//! `tests/reference/gltf_iridescence.py`, an independent NumPy
//! transcription of the extension's formulas (its GLSL of the film, the
//! appendix's GGX in slope form), whose output `gltf_iridescence.json` is
//! committed beside it: one and three channels, six parameter sets each
//! across the box, seven direction pairs among them the pole, a grazing
//! pair and one below the horizon. Derivatives, finiteness and the
//! declared non-reciprocity are the catalogue-wide tests'
//! (`tests/properties.rs`, `tests/reciprocity.rs`).

use brdf_models::{ModelConfig, build};
use nalgebra::Vector3;

#[derive(serde::Deserialize)]
struct Case {
    channels: usize,
    params: Vec<f64>,
    wi: [f64; 3],
    wo: [f64; 3],
    values: Vec<f64>,
}

#[test]
fn values_match_the_independent_numpy_script() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/reference/gltf_iridescence.json"
    ))
    .expect("reference file");
    let cases: Vec<Case> = serde_json::from_str(&text).expect("reference JSON");
    assert_eq!(cases.len(), 84);
    let mut worst: f64 = 0.0;
    for c in &cases {
        let config = ModelConfig {
            channels: c.channels,
            ..ModelConfig::default()
        };
        let mut m = build("gltf-iridescence", &config).expect("a catalogue model");
        m.set_params(&c.params).expect("in the box");
        let mut f = vec![f64::NAN; c.channels];
        m.eval(&Vector3::from(c.wi), &Vector3::from(c.wo), &mut f);
        for (&a, &b) in f.iter().zip(&c.values) {
            let dev = (a - b).abs() / b.abs().max(1e-12);
            worst = worst.max(dev);
            assert!(
                (a - b).abs() <= 1e-10 * b.abs() + 1e-15,
                "at wi {:?} wo {:?}: {a} vs reference {b} (params {:?})",
                c.wi,
                c.wo,
                c.params
            );
        }
    }
    eprintln!("largest relative deviation {worst:.2e}");
}
