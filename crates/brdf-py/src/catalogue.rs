//! What there is to fit and name: the model catalogue (as `brdf models
//! --json`), the materials a path stands for (as `brdf batch --data`),
//! canonical model names and data names for outputs.

use brdf_models::ModelConfig;
use pyo3::prelude::*;
use serde_json::{Value, json};

use crate::error::to_py;

/// The model catalogue, as ``brdf models --json`` prints it.
///
/// Parameters
/// ----------
/// channels, lobes, order, degree : int
///     Structure the parameter lists are given for.
///
/// Returns
/// -------
/// list of dict
///     Name, family, summary, paper, reciprocity, and the parameters with
///     their boxes, linear flags and defaults.
#[pyfunction]
#[pyo3(signature = (*, channels=1, lobes=1, order=8, degree=7))]
pub fn models(
    py: Python<'_>,
    channels: usize,
    lobes: usize,
    order: usize,
    degree: usize,
) -> PyResult<Bound<'_, PyAny>> {
    let config = ModelConfig {
        channels,
        lobes,
        order,
        degree,
    };
    let mut out = Vec::new();
    for e in brdf_models::catalogue() {
        let m = (e.build)(&config).map_err(to_py)?;
        let parameters: Vec<Value> = m
            .param_specs()
            .iter()
            .map(|s| {
                json!({
                    "name": s.name, "meaning": s.meaning, "lower": s.lower,
                    "upper": s.upper, "lower_open": s.lower_open,
                    "linear": s.linear, "default": s.default,
                })
            })
            .collect();
        out.push(json!({
            "name": e.name, "family": e.family, "summary": e.summary,
            "paper": e.paper, "reciprocal": m.is_reciprocal(),
            "parameters": parameters,
        }));
    }
    crate::json::to_py_object(py, &out)
}

/// The catalogue name a forgiving model name stands for.
///
/// Parameters
/// ----------
/// name : str
///     E.g. ``"Blinn-Phong"`` or ``"blinn_phong"``.
///
/// Returns
/// -------
/// str
///     The catalogue name (``"blinn-phong"``); a ``BrdfError`` suggesting
///     the nearest names for an unknown one.
///
/// Examples
/// --------
/// >>> import brdf
/// >>> brdf.canonical_name("GGX")
/// 'ggx'
#[pyfunction]
pub fn canonical_name(name: &str) -> PyResult<&'static str> {
    brdf_fit::resolve(name).map(|e| e.name).map_err(to_py)
}

/// A data set's name in outputs.
///
/// Parameters
/// ----------
/// spec : str
///     A data path, ``PATH`` or ``PATH#SAMPLE``.
///
/// Returns
/// -------
/// str
///     Relative to ``BRDF_DATA`` when inside it, as given when relative,
///     the file name otherwise.
#[pyfunction]
pub fn data_name(spec: &str) -> String {
    brdf_fit::data_name(spec)
}

/// The data sets a path stands for, as ``brdf batch --data`` reads it.
///
/// Parameters
/// ----------
/// path : str or os.PathLike
///     A folder (every file of a known format in it), a CUReT
///     ``abrdf.dat`` (every sample, ``abrdf.dat#N``) or one file.
///
/// Returns
/// -------
/// list of str
///     Sorted, without repeats.
#[pyfunction]
pub fn materials(py: Python<'_>, path: std::path::PathBuf) -> PyResult<Vec<String>> {
    let spec = path.display().to_string();
    py.detach(|| brdf_io::materials(&spec)).map_err(to_py)
}
