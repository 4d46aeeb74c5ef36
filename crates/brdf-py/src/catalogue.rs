//! What there is to fit and name: the model catalogue (as `brdf models
//! --json`), the materials a path stands for (as `brdf batch --data`),
//! canonical model names and data names for outputs.

use brdf_models::ModelConfig;
use pyo3::prelude::*;
use serde_json::{Value, json};

use crate::error::to_py;

/// The catalogue: a list of dicts (name, family, summary, paper,
/// reciprocal, parameters with their boxes, linear flags and defaults), as
/// `brdf models --json` prints it for the same structure options.
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

/// The catalogue name a forgiving model name stands for ("Blinn-Phong" ->
/// "blinn-phong"); an unknown name is an error suggesting the nearest.
#[pyfunction]
pub fn canonical_name(name: &str) -> PyResult<&'static str> {
    brdf_fit::resolve(name).map(|e| e.name).map_err(to_py)
}

/// A data set's name in outputs: relative to `BRDF_DATA` when inside it.
#[pyfunction]
pub fn data_name(spec: &str) -> String {
    brdf_fit::data_name(spec)
}

/// The data sets a path stands for, sorted, as `brdf batch --data` reads
/// it: a folder gives every file of a known format in it, a CUReT
/// `abrdf.dat` without `#N` every sample (`abrdf.dat#N`), anything else
/// itself.
#[pyfunction]
pub fn materials(py: Python<'_>, path: std::path::PathBuf) -> PyResult<Vec<String>> {
    let spec = path.display().to_string();
    py.detach(|| brdf_io::materials(&spec)).map_err(to_py)
}
