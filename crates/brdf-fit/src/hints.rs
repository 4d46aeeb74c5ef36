//! Advice a fit prints: each hint is a command that, run as printed, does
//! what the hint says of it (CI runs the hints of the default fit of every
//! shared RGL file and checks their image errors). A hint is given only
//! where the fit's own figures show the need: its renders lie in one
//! colour plane while the data do not, or its image error is high.

use brdf_models::ModelEntry;

use brdf_models::ColourStructure;
use brdf_render::ImageError;
use brdf_render::image_error::FLIP_WARN;

use crate::judged::COLOUR_PLANE_NOTE;

/// How a hint starts, so a reader (or a test) finds it among the notes.
pub const HINT: &str = "hint: ";

/// The model a single-colour fit is pointed to when the data's hues leave
/// its plane: glTF with `KHR_materials_specular`, whose specular colour is
/// a second colour, fitted for appearance in seconds and exported exactly.
pub const SECOND_COLOUR_MODEL: &str = "gltf-ext";

/// The hints for a fit of `model` to the data `spec`, given its image
/// errors; `default_fit` when the fit is the one `brdf select` makes of
/// its model (for appearance, default structure and options), which select
/// then never does worse than.
pub fn hints(spec: &str, model: &ModelEntry, default_fit: bool, image: &ImageError) -> Vec<String> {
    let data = quoted(spec);
    let mut out = Vec::new();
    let off_plane = image
        .colour_plane
        .as_ref()
        .is_some_and(|c| c.outside > COLOUR_PLANE_NOTE);
    if off_plane && model.colour == ColourStructure::Single {
        out.push(format!(
            "{HINT}`brdf fit --data {data} --model {SECOND_COLOUR_MODEL}` renders closer: its specular colour is a second colour, off the plane of white and the base colour"
        ));
    }
    let default_fit = default_fit && brdf_models::by_image_models().contains(&model.name);
    let high = image.lights.iter().any(|l| l.flip > FLIP_WARN);
    if high && default_fit {
        out.push(format!(
            "{HINT}`brdf select --data {data}` fits every renderer model for appearance and keeps the one of least image error, never worse than this fit"
        ));
    }
    out
}

/// `spec` as a shell word: quoted when it holds a character the shell
/// would split or expand.
fn quoted(spec: &str) -> String {
    let plain = spec
        .chars()
        .all(|c| c.is_ascii_alphanumeric() || "/._-#:+=,@".contains(c));
    if plain {
        spec.to_string()
    } else {
        format!("'{}'", spec.replace('\'', r"'\''"))
    }
}

#[cfg(test)]
mod tests {
    use super::quoted;

    #[test]
    fn specs_are_shell_words() {
        assert_eq!(
            quoted("rgl/paper_white_rgb.bsdf"),
            "rgl/paper_white_rgb.bsdf"
        );
        assert_eq!(quoted("curet/abrdf.dat#25"), "curet/abrdf.dat#25");
        assert_eq!(quoted("my data/x.bsdf"), "'my data/x.bsdf'");
        assert_eq!(quoted("it's.bsdf"), r"'it'\''s.bsdf'");
    }
}
