//! The command line's error type: every lower crate's error (those below
//! `brdf-fit` through [`brdf_fit::FitError`]), plus usage and output
//! errors, each with a message a user can act on.

use thiserror::Error;

/// Errors of the `brdf` command.
#[derive(Debug, Error)]
pub enum StudyError {
    /// Bad command-line input.
    #[error("{0}")]
    Usage(String),
    /// Fitting failed, or a lower crate's error (a parameter, a core
    /// value, reading data, a solver), which [`brdf_fit::FitError`]
    /// already wraps.
    #[error(transparent)]
    Fit(#[from] brdf_fit::FitError),
    /// A saved model could not be read, written or rebuilt.
    #[error(transparent)]
    SavedModel(#[from] brdf_models::saved_model::SavedModelError),
    /// Rendering or writing an image or plot failed.
    #[error(transparent)]
    Render(#[from] brdf_render::RenderError),
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

/// `From` for the errors of the crates below `brdf-fit`, through
/// [`brdf_fit::FitError`] (so `?` works on them and the message is theirs).
macro_rules! through_fit_error {
    ($($t:ty),* $(,)?) => {
        $(impl From<$t> for StudyError {
            fn from(e: $t) -> Self {
                StudyError::Fit(e.into())
            }
        })*
    };
}

through_fit_error!(
    brdf_core::ParamError,
    brdf_core::CoreError,
    brdf_io::IoError,
    brdf_solve::SolveError,
);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lower_errors_through_the_fit_error_keep_their_messages() {
        let e = StudyError::from(brdf_core::ParamError::NotFinite {
            name: "kd".into(),
            value: f64::NAN,
        });
        assert!(matches!(e, StudyError::Fit(_)));
        assert_eq!(e.to_string(), "parameter `kd` is not finite (NaN)");
        let e = StudyError::from(brdf_io::IoError::Unsupported {
            path: "a/b.xyz".into(),
            reason: "unknown data format".into(),
        });
        assert_eq!(e.to_string(), "a/b.xyz: unknown data format");
    }
}
