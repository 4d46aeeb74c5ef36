//! The command's error type: every library crate's error, plus usage and
//! output errors, each with a one-line message a user can act on. The
//! exit code is 1 for every error (and 0 when the reader of the output
//! went away).

use thiserror::Error;

/// Errors of the `brdf` command.
#[derive(Debug, Error)]
pub enum CliError {
    /// Bad command-line input.
    #[error("{0}")]
    Usage(String),
    /// Fitting failed, or a lower crate's error (a parameter, a core
    /// value, reading data, a solver), which [`brdf_fit::FitError`]
    /// already wraps.
    #[error(transparent)]
    Fit(#[from] brdf_fit::FitError),
    /// The study failed.
    #[error(transparent)]
    Study(#[from] brdf_study::StudyError),
    /// A saved model could not be read, written or rebuilt.
    #[error(transparent)]
    SavedModel(#[from] brdf_models::saved_model::SavedModelError),
    /// A model could not be exported.
    #[error(transparent)]
    Export(#[from] brdf_export::ExportError),
    /// A fit for a renderer failed.
    #[error(transparent)]
    ForRenderer(#[from] brdf_export::for_renderer::ForRendererError),
    /// An export job failed.
    #[error(transparent)]
    ExportFile(#[from] brdf_export::file::ExportFileError),
    /// Rendering or writing an image failed.
    #[error(transparent)]
    Render(#[from] brdf_render::RenderError),
    /// A report could not be made.
    #[error(transparent)]
    Report(#[from] brdf_report::ReportError),
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
        $(impl From<$t> for CliError {
            fn from(e: $t) -> Self {
                CliError::Fit(e.into())
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

impl CliError {
    /// Whether this is the reader of standard output going away
    /// (`brdf info x | head`), which ends the command quietly.
    pub fn is_broken_pipe(&self) -> bool {
        matches!(self, CliError::Io { source, .. } if source.kind() == std::io::ErrorKind::BrokenPipe)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lower_errors_through_the_fit_error_keep_their_messages() {
        let e = CliError::from(brdf_core::ParamError::NotFinite {
            name: "kd".into(),
            value: f64::NAN,
        });
        assert!(matches!(e, CliError::Fit(_)));
        assert_eq!(e.to_string(), "parameter `kd` is not finite (NaN)");
        let e = CliError::from(brdf_io::IoError::Unsupported {
            path: "a/b.xyz".into(),
            reason: "unknown data format".into(),
        });
        assert_eq!(e.to_string(), "a/b.xyz: unknown data format");
    }
}
