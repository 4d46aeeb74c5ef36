//! The crate's error type: writing an image or plot failed, or an argument
//! (size, light, image shapes) cannot be rendered or compared.

use thiserror::Error;

/// Errors of `brdf-render`.
#[derive(Debug, Error)]
pub enum RenderError {
    /// Writing output failed.
    #[error("{path}: {source}")]
    Io {
        /// file or folder
        path: String,
        /// the underlying error
        source: std::io::Error,
    },
    /// An argument that cannot be rendered or compared, with the fix.
    #[error("{0}")]
    Invalid(String),
    /// A light-set name that is not one of the light sets.
    #[error("light set `{name}` is unknown: use one of {choices}")]
    UnknownLightSet {
        /// the name given
        name: String,
        /// the valid names, comma separated
        choices: String,
    },
    /// Two images that must have the same shape do not.
    #[error(
        "{what}: images are {a} and {b} (width x height x channels): render both at the same size"
    )]
    ShapeMismatch {
        /// the comparison that needed equal shapes
        what: &'static str,
        /// shape of the first image
        a: String,
        /// shape of the second image
        b: String,
    },
    /// Writing or reading an OpenEXR file failed.
    #[error("{path}: OpenEXR: {message}")]
    Exr {
        /// file
        path: String,
        /// what the `exr` crate reported
        message: String,
    },
}
