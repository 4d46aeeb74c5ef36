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
}
