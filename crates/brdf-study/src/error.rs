//! The command line's error type: every lower crate's error, plus usage
//! errors, each with a message a user can act on.

use thiserror::Error;

/// Errors of the `brdf` command.
#[derive(Debug, Error)]
pub enum StudyError {
    /// Bad command-line input.
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
    /// A solver was misused or given impossible input.
    #[error(transparent)]
    Solve(#[from] brdf_solve::SolveError),
    /// Fitting failed.
    #[error(transparent)]
    Fit(#[from] brdf_fit::FitError),
    /// A saved model could not be read, written or rebuilt.
    #[error(transparent)]
    SavedModel(#[from] brdf_models::saved_model::SavedModelError),
    /// A model could not be exported.
    #[error(transparent)]
    Export(#[from] brdf_export::ExportError),
    /// JSON output failed.
    #[error("JSON: {0}")]
    Json(#[from] serde_json::Error),
    /// Writing output failed.
    #[error("{path}: {source}")]
    Io {
        /// file or folder
        path: String,
        /// the underlying error
        source: std::io::Error,
    },
}
