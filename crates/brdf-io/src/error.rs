//! The error type of `brdf-io`: every variant names the file and, where it
//! applies, the line (1-based) or byte offset at fault.

use std::path::PathBuf;

use thiserror::Error;

/// Errors of the readers and writers.
#[derive(Debug, Error)]
pub enum IoError {
    /// The file could not be opened, read or written.
    #[error("{path}: {source}")]
    Io {
        /// the file
        path: PathBuf,
        /// the underlying error
        source: std::io::Error,
    },
    /// A field is not a number.
    #[error("{path}:{line}: field {field} `{text}` is not a number")]
    NotANumber {
        /// the file
        path: PathBuf,
        /// 1-based line
        line: usize,
        /// 1-based field on the line
        field: usize,
        /// the text found
        text: String,
    },
    /// A number is NaN or infinite where a finite value is required.
    #[error("{path}:{line}: field {field} is {value}; a finite value is required")]
    NotFinite {
        /// the file
        path: PathBuf,
        /// 1-based line
        line: usize,
        /// 1-based field
        field: usize,
        /// the value
        value: f64,
    },
    /// A line or the file has the wrong number of entries.
    #[error("{path}:{line}: expected {expected}, found {found}")]
    Count {
        /// the file
        path: PathBuf,
        /// 1-based line (0 for the whole file)
        line: usize,
        /// what was expected
        expected: String,
        /// what was found
        found: String,
    },
    /// The content is inconsistent with the format.
    #[error("{path}:{line}: {reason}")]
    Format {
        /// the file
        path: PathBuf,
        /// 1-based line (0 when not line-based)
        line: usize,
        /// what is wrong
        reason: String,
    },
    /// A file this crate cannot read as data (unknown format, a sample or
    /// option that the format does not have).
    #[error("{path}: {reason}")]
    Unsupported {
        /// the file
        path: PathBuf,
        /// what is wrong and what would work
        reason: String,
    },
    /// A requested sample is not in the file.
    #[error("{path}: no sample `{sample}` ({reason})")]
    NoSample {
        /// the file
        path: PathBuf,
        /// the sample asked for
        sample: String,
        /// what exists
        reason: String,
    },
}

/// Parse whitespace-separated numbers of one line, naming the field at fault.
pub(crate) fn parse_fields(
    path: &std::path::Path,
    line_no: usize,
    line: &str,
) -> Result<Vec<f64>, IoError> {
    line.split_whitespace()
        .enumerate()
        .map(|(k, t)| {
            t.parse::<f64>().map_err(|_| IoError::NotANumber {
                path: path.to_path_buf(),
                line: line_no,
                field: k + 1,
                text: t.to_string(),
            })
        })
        .collect()
}

/// A number for a one-line message: at most 6 significant digits, in
/// exponent form when large or small (`{}` of `1e300` prints 301 digits).
pub fn short(x: f64) -> String {
    let a = x.abs();
    if x == 0.0 || !x.is_finite() || (1e-3..1e6).contains(&a) {
        let s = format!("{x:.6}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        if x.is_finite() {
            s.to_string()
        } else {
            format!("{x}")
        }
    } else {
        format!("{x:.5e}")
    }
}
