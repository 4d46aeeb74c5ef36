//! The colour plane of the image errors (`brdf_render::image_error::DataColourPlane`):
//! under the white studio light every render of a single-colour model
//! (`principled`, `gltf`) keeps its colours in one plane of white and its
//! base colour, whatever its parameters, so the bound is 0 on their own
//! renders; a model with a second colour (`gltf-ext`'s specular colour)
//! leaves that plane, so the bound is not 0 there and the note names only
//! the single-colour models.

use brdf_core::Parametric;
use brdf_fit::judged::{COLOUR_PLANE_NOTE, colour_plane_note};
use brdf_render::{ImageError, Judge};

use crate::common;
use common::rgb_model;

/// `name` (RGB) with the parameters `set` (by name) and the rest at
/// their defaults.
fn model_with(name: &str, set: &[(&str, f64)]) -> Box<dyn Parametric> {
    let mut m = rgb_model(name);
    let mut p = m.params().to_vec();
    for (k, spec) in m.param_specs().iter().enumerate() {
        if let Some((_, v)) = set.iter().find(|(n, _)| *n == spec.name) {
            p[k] = *v;
        }
    }
    m.set_params(&p).expect("in the box");
    m
}

/// The image errors of `m` against its own render (24 px).
fn own_errors(m: &dyn Parametric) -> ImageError {
    Judge::with_data(24, m)
        .and_then(|j| j.fit_errors(m))
        .expect("judge")
}

#[test]
fn renders_of_a_single_colour_model_lie_in_one_colour_plane() {
    let principled = [
        // a saturated blue dielectric with every lobe on, tinted
        vec![
            ("base_color_r", 0.02),
            ("base_color_g", 0.1),
            ("base_color_b", 0.6),
            ("spec_tint", 0.7),
            ("sheen", 0.8),
            ("sheen_tint", 0.5),
            ("clearcoat", 1.0),
            ("clearcoat_gloss", 0.6),
            ("roughness", 0.2),
        ],
        // a half-metallic orange
        vec![
            ("base_color_r", 0.9),
            ("base_color_g", 0.4),
            ("base_color_b", 0.05),
            ("metallic", 0.5),
            ("roughness", 0.35),
        ],
    ];
    for set in &principled {
        let e = own_errors(model_with("principled", set).as_ref());
        let c = e.colour_plane.as_ref().expect("studio is white");
        assert_eq!(c.light, "studio");
        assert!(c.outside < 1e-9, "{set:?}: {c:?}");
    }
    let gltf = model_with(
        "gltf",
        &[
            ("base_color_r", 0.7),
            ("base_color_g", 0.1),
            ("base_color_b", 0.5),
            ("metallic", 0.3),
            ("roughness", 0.25),
        ],
    );
    let c = own_errors(gltf.as_ref()).colour_plane.expect("plane");
    assert!(c.outside < 1e-9, "{c:?}");
    // The plane's colour is the base colour's hue: (0.7, 0.1, 0.5) shifted
    // to a zero minimum and scaled, (1, 0, 2/3).
    for (k, want) in [1.0, 0.0, 2.0 / 3.0].iter().enumerate() {
        assert!((c.colour[k] - want).abs() < 1e-6, "{c:?}");
    }
}

#[test]
fn a_second_colour_leaves_the_plane_and_only_single_colour_models_get_the_note() {
    // gltf-ext: a blue body under a yellow specular colour (a glossy
    // highlight of another hue than the body, as a colour-shifting film's).
    let m = model_with(
        "gltf-ext",
        &[
            ("base_color_r", 0.05),
            ("base_color_g", 0.1),
            ("base_color_b", 0.6),
            ("roughness", 0.2),
            ("specular_color_r", 2.0),
            ("specular_color_g", 1.6),
            ("specular_color_b", 0.0),
        ],
    );
    let e = own_errors(m.as_ref());
    let c = e.colour_plane.as_ref().expect("plane");
    assert!(c.outside > COLOUR_PLANE_NOTE, "{c:?}");
    let colour = brdf_models::entry("gltf-ext").map(|e| e.colour);
    assert_eq!(colour, Some(brdf_models::ColourStructure::PerLobe));
    assert!(colour_plane_note("gltf-ext", &e).is_none());
    // The same data fitted by principled: the note, with the figure.
    let note = colour_plane_note("principled", &e).expect("note");
    let pct = format!("{:.1}%", 100.0 * c.outside);
    assert!(note.contains(&pct) && note.contains("studio"), "{note}");
    // It names the route that renders such data exactly.
    assert!(note.contains("`brdf fit --for`"), "{note}");
}
