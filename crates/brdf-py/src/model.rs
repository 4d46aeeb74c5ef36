//! Models from Python: `eval` (vectorised over numpy arrays) and `export`.
//! A model argument is a saved model (a `.json` file written by `fit(...,
//! save=...)` or `brdf fit --save`, or that file's content as a dict) or a
//! catalogue name with `params={name: value}` (the rest at their defaults).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use brdf_core::Parametric;
use brdf_core::params::assign_by_name;
use brdf_models::ModelConfig;
use brdf_models::saved_model::SavedModel;
use numpy::ndarray::Array2;
use numpy::{AllowTypeChange, IntoPyArray, PyArrayLikeDyn};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::error::{to_py, usage};

/// Structure of a catalogue model named in Python (not used for saved
/// models, which carry their own).
#[derive(Clone, Copy, Debug)]
pub struct Structure {
    /// Colour channels.
    pub channels: usize,
    /// Specular lobes.
    pub lobes: usize,
    /// Koenderink order.
    pub order: usize,
    /// Polynomial degree.
    pub degree: usize,
}

/// The model a Python argument names.
pub fn resolve(
    model: &Bound<'_, PyAny>,
    params: Option<BTreeMap<String, f64>>,
    structure: Structure,
) -> PyResult<Box<dyn Parametric>> {
    if let Ok(d) = model.cast::<PyDict>() {
        no_params(&params, "a saved-model dict")?;
        let text = crate::json::to_json_text(d.as_any())?;
        let saved = SavedModel::from_json(&text, "saved-model dict").map_err(to_py)?;
        return saved
            .build()
            .map_err(|e| usage(format!("saved-model dict: {e}")));
    }
    let name: PathBuf = model.extract().map_err(|_| {
        usage("model: expected a catalogue name, a saved-model path or a saved-model dict".into())
    })?;
    if is_saved_model(&name) {
        no_params(&params, &name.display().to_string())?;
        return SavedModel::load_model(&name).map_err(to_py);
    }
    let name = name.display().to_string();
    let entry = brdf_fit::resolve(&name).map_err(to_py)?;
    let config = ModelConfig {
        channels: structure.channels,
        lobes: structure.lobes,
        order: structure.order,
        degree: structure.degree,
    };
    let mut m = (entry.build)(&config).map_err(to_py)?;
    let assignments: Vec<(String, f64)> = params.unwrap_or_default().into_iter().collect();
    let values = assign_by_name(entry.name, m.param_specs(), &assignments).map_err(to_py)?;
    m.set_params(&values).map_err(to_py)?;
    Ok(m)
}

/// A path names a saved model when it ends in `.json` or is a file.
fn is_saved_model(path: &Path) -> bool {
    path.extension().is_some_and(|e| e == "json") || path.is_file()
}

fn no_params(params: &Option<BTreeMap<String, f64>>, what: &str) -> PyResult<()> {
    match params {
        Some(_) => Err(usage(format!(
            "params= sets a catalogue model's parameters; {what} carries its own"
        ))),
        None => Ok(()),
    }
}

/// Evaluate a model at direction pairs (vectorised).
///
/// Parameters
/// ----------
/// model : str, os.PathLike or dict
///     A catalogue name (with ``params``), a saved model's path, or its
///     content as a dict.
/// wi, wo : array_like
///     ``(n, 3)`` unit vectors (local frame, normal +z), or one ``(3,)``
///     vector broadcast against the other.
/// params : dict of str to float, optional
///     A catalogue model's parameters (the rest at their defaults).
/// channels, lobes, order, degree : int
///     A catalogue model's structure.
///
/// Returns
/// -------
/// numpy.ndarray
///     ``(n, channels)`` values in 1/sr, or ``(channels,)`` for two single
///     vectors.
///
/// Examples
/// --------
/// >>> import numpy as np
/// >>> import brdf
/// >>> wi = np.array([[0.0, 0.0, 1.0], [0.6, 0.0, 0.8]])
/// >>> brdf.eval("lambert", wi, np.array([0.0, 0.0, 1.0]), params={"kd": 0.5}).shape
/// (2, 1)
#[pyfunction]
#[pyo3(signature = (model, wi, wo, *, params=None, channels=1, lobes=1, order=8, degree=7))]
pub fn eval<'py>(
    py: Python<'py>,
    model: &Bound<'py, PyAny>,
    wi: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    wo: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    params: Option<BTreeMap<String, f64>>,
    channels: usize,
    lobes: usize,
    order: usize,
    degree: usize,
) -> PyResult<Bound<'py, PyAny>> {
    let structure = Structure {
        channels,
        lobes,
        order,
        degree,
    };
    let m = resolve(model, params, structure)?;
    eval_model(py, m.as_ref(), wi, wo)
}

/// Evaluate `m` at the direction pairs `wi`, `wo` (as [`eval`]).
pub fn eval_model<'py>(
    py: Python<'py>,
    m: &dyn Parametric,
    wi: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    wo: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
) -> PyResult<Bound<'py, PyAny>> {
    let (wi, wi_single) = crate::directions::parse(wi.as_array(), "wi")?;
    let (wo, wo_single) = crate::directions::parse(wo.as_array(), "wo")?;
    let n = match (wi_single, wo_single) {
        (true, _) => wo.len(),
        (false, true) => wi.len(),
        (false, false) if wi.len() == wo.len() => wi.len(),
        _ => {
            return Err(usage(format!(
                "wi has {} rows, wo {}: give the same number, or one (3,) vector",
                wi.len(),
                wo.len()
            )));
        }
    };
    let nc = m.channels();
    let out = py.detach(|| {
        let mut out = Array2::zeros((n, nc));
        let mut f = vec![0.0; nc];
        for j in 0..n {
            let l = wi[if wi_single { 0 } else { j }];
            let v = wo[if wo_single { 0 } else { j }];
            m.eval(l.vector(), v.vector(), &mut f);
            out.row_mut(j).assign(&numpy::ndarray::ArrayView1::from(&f));
        }
        out
    });
    if wi_single && wo_single {
        return Ok(out.row(0).to_owned().into_pyarray(py).into_any());
    }
    Ok(out.into_pyarray(py).into_any())
}

/// The CLI's `brdf export` options, as keyword arguments.
#[derive(Clone, Debug)]
pub struct ExportOptions<'a> {
    /// Mitsuba: a complete judge scene instead of a `<bsdf>` snippet.
    pub scene: bool,
    /// Mitsuba scene: `"studio"` or `"sky"`.
    pub light: &'a str,
    /// MaterialX: `"gltf_pbr"`, `"standard_surface"` or `"openpbr"`.
    pub surface: &'a str,
    /// The material's name (made an identifier).
    pub name: &'a str,
    /// Convert by fitting where the target has no exact equivalent.
    pub convert: bool,
    /// Write a conversion even when it renders unlike the model.
    pub force: bool,
    /// glTF: the preview sphere (false: the material alone).
    pub mesh: bool,
}

/// `m` in `to`'s format as `brdf export` writes it: exact, or (with
/// `opts.convert`) converted for appearance with the conversion's error in
/// the file.
/// What the material does not say (a grey fit's colour never fitted) is
/// issued as a Python `UserWarning`.
pub fn export_text(
    py: Python<'_>,
    m: &dyn Parametric,
    to: &str,
    opts: &ExportOptions<'_>,
) -> PyResult<String> {
    use brdf_export::FrontEnd;
    // The library's advice names the command line's options; here, Python's.
    let to_py = |e: brdf_export::ExportError| to_py(e.for_front_end(FrontEnd::Python));
    let target: brdf_export::Target = to.parse().map_err(to_py)?;
    if opts.scene && target != brdf_export::Target::Mitsuba {
        return Err(usage(format!(
            "scene=True: only Mitsuba scenes are written (to=\"mitsuba\"), not {target}"
        )));
    }
    let write = brdf_export::WriteOptions {
        name: brdf_export::identifier(opts.name),
        scene: opts.scene,
        light: opts.light.parse().map_err(to_py)?,
        surface: opts.surface.parse().map_err(to_py)?,
        mesh: opts.mesh,
    };
    let (text, conversion) = if opts.convert {
        let convert = brdf_export::ConvertOptions {
            force: opts.force,
            ..brdf_export::ConvertOptions::default()
        };
        let e = brdf_export::export_or_convert_with(m, target, &convert, &write).map_err(to_py)?;
        (e.text, e.conversion)
    } else {
        let text = brdf_export::export_with(m, target, None, &write).map_err(to_py)?;
        (text, None)
    };
    let converted = conversion
        .and_then(|c| brdf_export::for_renderer::conversion_warning(&c, target, FrontEnd::Python));
    for w in brdf_export::warnings(m, target, FrontEnd::Python)
        .into_iter()
        .chain(converted)
    {
        crate::error::warn(py, &w)?;
    }
    Ok(text)
}

/// A model as a renderer's material, as ``brdf export`` writes it.
///
/// Parameters
/// ----------
/// model : str, os.PathLike or dict
///     As for ``eval``.
/// to : str
///     ``"mitsuba"``, ``"pbrt"``, ``"gltf"``, ``"materialx"``, ``"usd"`` or
///     ``"blender"``.
/// params : dict of str to float, optional
///     A catalogue model's parameters.
/// channels, lobes, order, degree : int
///     A catalogue model's structure.
/// name : str
///     The material's name (``--name``; made an identifier).
/// scene : bool
///     Mitsuba: a complete judge scene instead of a paste-in ``<bsdf>``
///     snippet (``--scene``).
/// light : str
///     The Mitsuba scene's light set, ``"studio"`` or ``"sky"``.
/// surface : str
///     MaterialX: ``"gltf_pbr"``, ``"standard_surface"`` or ``"openpbr"``.
/// convert : bool
///     Where the target has no exact equivalent, convert by fitting for
///     appearance (the error noted in the file), as ``brdf export`` does;
///     by default such a model is refused (``--exact``).
/// force : bool
///     With ``convert``: write a conversion even when it renders as another
///     material (beyond HDR-FLIP 0.1; between 0.02 and 0.1 it is written
///     with a warning).
/// mesh : bool
///     glTF: a preview sphere using the material in the default scene, so
///     a viewer shows it (``False``: the material alone, ``--no-mesh``).
///
/// Returns
/// -------
/// str
///     The material (for ``"blender"``, a Python script for Blender); a
///     ``BrdfError`` says why when there is no exact equivalent and
///     ``convert`` is false.
///
/// Warns
/// -----
/// UserWarning
///     For a one-channel (grey) model: its colour was never fitted, so the
///     material is grey (fit with ``channels="rgb"`` for a coloured one);
///     for a conversion that renders differently (HDR-FLIP above 0.02):
///     its image error and the route to an exact material.
#[pyfunction]
#[pyo3(signature = (model, to, *, params=None, channels=1, lobes=1, order=8, degree=7,
                    name="fitted", scene=false, light="studio", surface="gltf_pbr",
                    convert=false, force=false, mesh=true))]
pub fn export(
    py: Python<'_>,
    model: &Bound<'_, PyAny>,
    to: &str,
    params: Option<BTreeMap<String, f64>>,
    channels: usize,
    lobes: usize,
    order: usize,
    degree: usize,
    name: &str,
    scene: bool,
    light: &str,
    surface: &str,
    convert: bool,
    force: bool,
    mesh: bool,
) -> PyResult<String> {
    let structure = Structure {
        channels,
        lobes,
        order,
        degree,
    };
    let m = resolve(model, params, structure)?;
    let opts = ExportOptions {
        scene,
        light,
        surface,
        name,
        convert,
        force,
        mesh,
    };
    export_text(py, m.as_ref(), to, &opts)
}
