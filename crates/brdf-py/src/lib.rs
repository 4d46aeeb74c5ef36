//! # brdf (Python)
//!
//! The Python module `brdf`, built with maturin from this crate: the fits of
//! [`brdf_fit`] from Python, with numpy arrays in and out.
//!
//! ```python
//! import brdf
//! d = brdf.load("curet/abrdf.dat#25")        # dict of numpy arrays
//! r = brdf.fit(d, "blinn-phong", save="fit.json")  # a brdf.Fit
//! r.model.eval(d["wi"], d["wo"]); r.report       # the dict of `brdf fit --json`
//! f = brdf.eval("fit.json", d["wi"], d["wo"])  # (n, channels)
//! xml = brdf.export("principled", "mitsuba")
//! ```
//!
//! | module | what |
//! | --- | --- |
//! | [`samples`] | `load`, `save_samples`: data sets as numpy arrays and back |
//! | [`fit`] | `fit`: a `Fit` (model, `brdf fit --json` report), GIL released |
//! | [`fitted`] | `Fit` and `Model` (`eval`, `params`, `export`, `save`, `load`) |
//! | [`model`] | `eval` (vectorised), `export`; model arguments |
//! | [`catalogue`] | `models`, `materials`, `canonical_name`, `data_name` |
//! | [`directions`] | unit-vector arrays, checked row by row |
//! | [`json`] | JSON values to Python objects and back |
//! | [`error`] | `BrdfError`, carrying the Rust message |
//!
//! Build and install: `pip install maturin && maturin build --release -m
//! crates/brdf-py/Cargo.toml`, then `pip install` the wheel it names (or
//! `maturin develop --release` inside a virtual environment).
//!
//! ## Layering
//!
//! A top crate beside the `brdf` command (`brdf-cli`): it calls
//! `brdf-fit`, `brdf-io`, `brdf-models` and `brdf-export` as the command
//! does, with the same model-name resolver ([`brdf_fit::names::resolve`]),
//! and nothing depends on it.

pub mod catalogue;
pub mod directions;
pub mod error;
pub mod fit;
pub mod fitted;
pub mod json;
pub mod model;
pub mod samples;

use pyo3::prelude::*;

/// The module `brdf`.
#[pymodule]
#[pyo3(name = "brdf")]
fn brdf_module(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("BrdfError", m.py().get_type::<error::BrdfError>())?;
    m.add_function(wrap_pyfunction!(samples::load, m)?)?;
    m.add_function(wrap_pyfunction!(samples::save_samples, m)?)?;
    m.add_function(wrap_pyfunction!(fit::fit, m)?)?;
    m.add_class::<fitted::PyFit>()?;
    m.add_class::<fitted::PyModel>()?;
    m.add_function(wrap_pyfunction!(model::eval, m)?)?;
    m.add_function(wrap_pyfunction!(model::export, m)?)?;
    m.add_function(wrap_pyfunction!(catalogue::models, m)?)?;
    m.add_function(wrap_pyfunction!(catalogue::materials, m)?)?;
    m.add_function(wrap_pyfunction!(catalogue::canonical_name, m)?)?;
    m.add_function(wrap_pyfunction!(catalogue::data_name, m)?)?;
    Ok(())
}
