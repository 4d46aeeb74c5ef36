//! JSON values to Python objects and back, through Python's `json` module:
//! the Rust side writes shortest round-trip numbers, which `json.loads`
//! reads back exactly, so a report has the same numbers in both languages.

use pyo3::prelude::*;

use crate::error::to_py;

/// A serialisable Rust value as the Python object of its JSON.
pub fn to_py_object<'py, T: serde::Serialize + ?Sized>(
    py: Python<'py>,
    value: &T,
) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value).map_err(to_py)?;
    py.import("json")?.call_method1("loads", (text,))
}

/// A Python object (dict, list, numbers, strings) as JSON text.
pub fn to_json_text(object: &Bound<'_, PyAny>) -> PyResult<String> {
    object
        .py()
        .import("json")?
        .call_method1("dumps", (object,))?
        .extract()
}
