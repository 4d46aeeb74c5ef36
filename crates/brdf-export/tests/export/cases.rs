//! The fitted models whose Mitsuba export is checked against Mitsuba 3.

use brdf_core::Parametric;

/// `(model, channels, lobes, parameters)`.
pub fn cases() -> Vec<(&'static str, usize, usize, Vec<f64>)> {
    vec![
        ("lambert", 3, 1, vec![0.2, 0.5, 0.7]),
        (
            "principled",
            3,
            1,
            vec![0.9, 0.5, 0.1, 0.3, 0.7, 0.6, 0.4, 0.5, 0.8, 0.3, 0.6, 0.9],
        ),
        (
            "principled",
            3,
            1,
            vec![0.2, 0.6, 0.9, 0.0, 0.5, 0.0, 0.3, 0.0, 0.0, 0.0, 0.0, 0.0],
        ),
        (
            "principled",
            1,
            1,
            vec![0.5, 1.0, 0.5, 0.0, 0.25, 0.5, 0.0, 0.0, 0.0, 0.0],
        ),
        (
            "ggx-conductor-separable",
            3,
            1,
            vec![0.1, 0.2, 0.3, 0.5, 0.6, 0.4, 0.2, 0.2, 3.0],
        ),
        (
            "ggx-dielectric-aniso-separable",
            1,
            1,
            vec![0.3, 0.6, 0.1, 0.4, 1.5],
        ),
        (
            "ggx-separable",
            1,
            2,
            vec![0.2, 0.3, 0.1, 0.05, 0.4, 0.4, 0.9],
        ),
        (
            "ggx-aniso-separable",
            3,
            1,
            vec![0.4, 0.3, 0.2, 0.5, 0.5, 0.5, 0.3, 0.1, 0.04],
        ),
    ]
}

/// The model with its parameters set.
pub fn build(name: &str, channels: usize, lobes: usize, p: &[f64]) -> Box<dyn Parametric> {
    let config = brdf_models::ModelConfig {
        channels,
        lobes,
        ..brdf_models::ModelConfig::default()
    };
    let mut m = brdf_models::build(name, &config).unwrap_or_else(|e| panic!("{e}"));
    m.set_params(p).unwrap_or_else(|e| panic!("{e}"));
    m
}
