//! Shared by the integration tests: RGB models of the catalogue, their
//! fits, and their samples at fixed quasi-random direction pairs.

// Each test binary compiles this module and uses a part of it.
#![allow(dead_code)]

use std::f64::consts::TAU;

use brdf_core::{Brdf, Direction, Parametric, SampleSet};
use brdf_fit::{Channels, Fit};
use brdf_models::catalogue::{ModelConfig, build};
use nalgebra::Vector3;

/// The catalogue model `name` with three colour channels, at its defaults.
pub fn rgb_model(name: &str) -> Box<dyn Parametric> {
    let cfg = ModelConfig {
        channels: 3,
        ..ModelConfig::default()
    };
    build(name, &cfg).expect("model")
}

/// The RGB principled model at `truth` (base colour r, g, b, metallic,
/// specular, spec_tint, roughness, anisotropic, sheen, sheen_tint,
/// clearcoat, clearcoat_gloss).
pub fn principled_at(truth: &[f64]) -> Box<dyn Parametric> {
    let mut model = rgb_model("principled");
    model.set_params(truth).expect("truth in the box");
    model
}

/// A fit of `name` with every channel's parameters fitted.
pub fn rgb_fit(name: &str) -> Fit {
    Fit::model(name).expect("model").channels(Channels::All)
}

/// A direction of polar angle `1.45 a` (below 83 deg) and azimuth `b`.
pub fn dir(a: f64, b: f64) -> Vector3<f64> {
    let th = a * 1.45;
    Vector3::new(th.sin() * b.cos(), th.sin() * b.sin(), th.cos())
}

/// `model` (3 channels) at `n` quasi-random pairs (golden-ratio and
/// square-root sequences), weight 1.
pub fn rgb_samples(model: &dyn Brdf, n: usize) -> SampleSet {
    let mut s = SampleSet::new(
        "synthetic",
        "test",
        vec!["r".into(), "g".into(), "b".into()],
    );
    let mut f = [0.0; 3];
    for j in 0..n {
        let x = j as f64;
        let l = dir(
            (x * 0.618_033_988_75).fract(),
            TAU * (x * 0.414_213_562_37).fract(),
        );
        let v = dir(
            (x * 0.732_050_807_57).fract(),
            TAU * (x * 0.236_067_977_5).fract(),
        );
        model.eval(&l, &v, &mut f);
        s.push(
            &Direction::try_new(l).expect("unit"),
            &Direction::try_new(v).expect("unit"),
            &f,
            1.0,
        )
        .expect("push");
    }
    s
}
