//! The error type of `brdf-fit`: every lower crate's error, plus invalid
//! requests (an unknown model, a model that does not fit the data), each
//! with a one-line message a user can act on.

use thiserror::Error;

/// Errors of fitting, selecting, saving and loading models.
#[derive(Debug, Error)]
pub enum FitError {
    /// An invalid request: unknown name, mismatched channels, too few
    /// samples, an option out of range.
    #[error("{0}")]
    Usage(String),
    /// A parameter was impossible.
    #[error(transparent)]
    Param(#[from] brdf_core::ParamError),
    /// A core value could not be built.
    #[error(transparent)]
    Core(#[from] brdf_core::CoreError),
    /// Reading data failed.
    #[error(transparent)]
    Data(#[from] brdf_io::IoError),
    /// Rendering or judging a fit failed.
    #[error(transparent)]
    Render(#[from] brdf_render::RenderError),
    /// A solver was misused or given impossible input.
    #[error(transparent)]
    Solve(#[from] brdf_solve::SolveError),
    /// A saved model could not be read or written as JSON.
    #[error("{path}: {reason}")]
    Json {
        /// the file
        path: String,
        /// what serde_json reported
        reason: String,
    },
    /// A fit ended without a finite result.
    #[error(
        "{data}: the fit of `{model}` ended with a non-finite {what} ({value}); the data may be out of any representable range"
    )]
    NonFinite {
        /// the data set
        data: String,
        /// the model
        model: String,
        /// what is not finite
        what: String,
        /// its value
        value: f64,
    },
    /// Reading or writing a file failed.
    #[error("{path}: {source}")]
    Io {
        /// file or folder
        path: String,
        /// the underlying error
        source: std::io::Error,
    },
}
