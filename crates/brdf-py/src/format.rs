//! Numbers as the workspace writes them ([`brdf_core::format::number`] in
//! tables, Rust's `{}` in CSV files), so a Python script writing the same
//! tables as `brdf batch` writes the same strings without a formatter of
//! its own.

use pyo3::prelude::*;

/// A number with ``digits`` significant digits, as the Markdown tables of
/// ``brdf batch`` and the study write it: plain notation from ``1e-4`` up
/// to ``1e6``, scientific outside; ``0`` for zero, ``NaN`` and ``inf`` as
/// Rust prints them.
///
/// Examples
/// --------
/// >>> import brdf
/// >>> brdf.format_number(0.019, 3)
/// '0.0190'
/// >>> brdf.format_number(1.5e-7, 2)
/// '1.5e-7'
#[pyfunction]
pub fn format_number(x: f64, digits: usize) -> String {
    brdf_core::format::number(x, digits)
}

/// A number in full, as the CSV files of ``brdf batch`` hold it (Rust's
/// shortest round-trip digits, no exponent).
///
/// Examples
/// --------
/// >>> import brdf
/// >>> brdf.format_full(0.1)
/// '0.1'
/// >>> brdf.format_full(1e-7)
/// '0.0000001'
#[pyfunction]
pub fn format_full(x: f64) -> String {
    format!("{x}")
}
