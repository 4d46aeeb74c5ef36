//! The Python exception of the module: every Rust error (a file that cannot
//! be read, a bad option, an impossible parameter) becomes a `brdf.BrdfError`
//! (a `ValueError`) carrying the Rust message, which names the file, line,
//! parameter or argument at fault.

use pyo3::PyErr;
use pyo3::create_exception;
use pyo3::exceptions::PyValueError;

create_exception!(
    brdf,
    BrdfError,
    PyValueError,
    "An error of the brdf library; the message names the file, line or parameter at fault."
);

/// A Rust error as a `BrdfError` with its message.
pub fn to_py<E: std::fmt::Display>(e: E) -> PyErr {
    BrdfError::new_err(e.to_string())
}

/// A `BrdfError` with the given message (bad arguments found here).
pub fn usage(message: String) -> PyErr {
    BrdfError::new_err(message)
}

/// Issue `message` as a Python `UserWarning` (shown once per call site by
/// Python's default filter; `warnings.catch_warnings` captures it), for
/// what the library did that the caller should know but that is no error.
pub fn warn(py: pyo3::Python<'_>, message: &str) -> pyo3::PyResult<()> {
    // Messages are the library's one-line texts; a NUL would only cut it.
    let text = std::ffi::CString::new(message.replace('\0', " "))
        .map_err(|e| usage(format!("warning text: {e}")))?;
    let category = py.get_type::<pyo3::exceptions::PyUserWarning>();
    PyErr::warn(py, category.as_any(), &text, 1)
}
