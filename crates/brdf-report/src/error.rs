//! The report's error type: one line naming the file or input and, where
//! there is one, the fix.

use thiserror::Error;

/// Errors of building or writing a report.
#[derive(Debug, Error)]
pub enum ReportError {
    /// A file could not be read or written.
    #[error("{path}: {source}")]
    Io {
        /// the file
        path: String,
        /// the underlying error
        source: std::io::Error,
    },
    /// The data could not be read.
    #[error(transparent)]
    Data(#[from] brdf_io::IoError),
    /// The saved model could not be read.
    #[error(transparent)]
    Saved(#[from] brdf_models::saved_model::SavedModelError),
    /// The model cannot be rebuilt from what was saved.
    #[error("{what}: the model cannot be rebuilt ({reason}); refit it with `brdf fit --save`")]
    Model {
        /// the saved model or batch line
        what: String,
        /// why
        reason: String,
    },
    /// Rendering, plotting or image encoding failed.
    #[error(transparent)]
    Render(#[from] brdf_render::RenderError),
    /// The image errors could not be computed.
    #[error(transparent)]
    Fit(#[from] brdf_fit::FitError),
    /// The HTML template failed (a bug: the templates are compiled in).
    #[error("HTML template: {0}")]
    Template(#[from] minijinja::Error),
    /// A batch folder or selection file is not what `brdf batch` or
    /// `brdf select --json` writes.
    #[error("{path}: {reason}")]
    Input {
        /// the file or folder
        path: String,
        /// what is wrong and the fix
        reason: String,
    },
}

impl ReportError {
    /// An I/O error on `path`.
    pub fn io(path: &std::path::Path) -> impl FnOnce(std::io::Error) -> ReportError + '_ {
        move |source| ReportError::Io {
            path: path.display().to_string(),
            source,
        }
    }
}
