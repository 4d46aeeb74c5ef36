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
//! | [`select`] | `select`: the dict of `brdf select --json`, GIL released |
//! | [`fitted`] | `Fit` and `Model` (`eval`, `params`, `export`, `save`, `load`) |
//! | [`model`] | `eval` (vectorised), `export`; model arguments |
//! | [`catalogue`] | `models`, `materials`, `canonical_name`, `data_name` |
//! | [`directions`] | unit-vector arrays, checked row by row |
//! | [`json`] | JSON values to Python objects and back |
//! | [`error`] | `BrdfError`, carrying the Rust message |
//!
//! Build and install in a virtual environment: `pip install ./crates/brdf-py`
//! (maturin is the PEP 517 backend of `pyproject.toml`; the wheel ships the
//! stubs `brdf.pyi` and `py.typed`).
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
pub mod format;
pub mod json;
pub mod model;
pub mod samples;
pub mod select;

use pyo3::prelude::*;

/// Fit analytic BRDF models to measured reflectance data, from Python.
///
/// The fits, models and exports of the ``brdf`` command with NumPy arrays
/// in and out: ``load`` reads a data set, ``fit`` returns a ``Fit`` (its
/// ``model`` evaluates, saves, exports and renders), ``select`` chooses
/// the smallest adequate model, ``eval`` evaluates a
/// catalogue or saved model, ``export`` writes a renderer's material,
/// ``models`` lists the catalogue. Relative data paths that do not exist
/// from the working directory are looked up under ``$BRDF_DATA``. Errors
/// raise ``BrdfError`` with a message naming the argument and the fix.
///
/// Examples
/// --------
/// >>> import numpy as np
/// >>> import brdf
/// >>> brdf.canonical_name("Blinn_Phong")
/// 'blinn-phong'
/// >>> up = np.array([0.0, 0.0, 1.0])
/// >>> float(brdf.eval("lambert", up, up, params={"kd": 0.5})[0])  # kd / pi
/// 0.15915494309189535
#[pymodule]
#[pyo3(name = "brdf")]
fn brdf_module(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // The same results for any thread count, as the `brdf` command.
    brdf_fit::select::sequential_factorisations();
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("BrdfError", m.py().get_type::<error::BrdfError>())?;
    m.add_function(wrap_pyfunction!(samples::load, m)?)?;
    m.add_function(wrap_pyfunction!(samples::save_samples, m)?)?;
    m.add_function(wrap_pyfunction!(fit::fit, m)?)?;
    m.add_function(wrap_pyfunction!(select::select, m)?)?;
    m.add_class::<fitted::PyFit>()?;
    m.add_class::<fitted::PyModel>()?;
    m.add_function(wrap_pyfunction!(model::eval, m)?)?;
    m.add_function(wrap_pyfunction!(model::export, m)?)?;
    m.add_function(wrap_pyfunction!(catalogue::models, m)?)?;
    m.add_function(wrap_pyfunction!(catalogue::materials, m)?)?;
    m.add_function(wrap_pyfunction!(catalogue::canonical_name, m)?)?;
    m.add_function(wrap_pyfunction!(catalogue::data_name, m)?)?;
    m.add_function(wrap_pyfunction!(format::format_number, m)?)?;
    m.add_function(wrap_pyfunction!(format::format_full, m)?)?;
    Ok(())
}
