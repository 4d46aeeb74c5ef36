//! `fit`: the fit `brdf fit` runs, from Python, returning the dict of
//! `brdf fit --json` (built by [`brdf_fit::fit_json`], as the command does).
//! The GIL is released while the data load and the fits run; the fit is
//! the same [`FitRequest`] the command runs.

use std::path::PathBuf;

use brdf_fit::{ChannelMode, FitRequest, Material, Metric, Solver};
use brdf_models::ModelConfig;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::error::{to_py, usage};
use crate::fitted::{PyFit, PyModel};

/// Fit a model to measured data from automatic starts, as ``brdf fit``.
///
/// Parameters
/// ----------
/// data : str, os.PathLike or dict
///     A data path such as ``"curet/abrdf.dat#25"`` (relative paths are
///     also looked up under ``BRDF_DATA``), or a dict of arrays as
///     ``load`` returns.
/// model : str
///     Catalogue name (forgiving: ``"Blinn-Phong"``, ``"blinn_phong"``).
/// channels : str
///     ``"rgb"`` (shared non-linear, per-channel linear parameters),
///     ``"grey"`` or ``"per-channel"``.
/// metric : str
///     auto (as ``brdf fit``: the appearance fit for renderer models on data
///     that can be rendered, else ngan), appearance, ngan, sopp,
///     sopp-unweighted, lafortune, log, cube-root, relative or image.
/// limit_deg : float
///     Drop samples with theta_i or theta_o above this angle.
/// starts : int
///     Multi-start count.
/// irls_max_iterations : int
///     Reweighting cap of a robust (IRLS) fit (50 is MATLAB's
///     ``robustfit``'s); a fit whose reweighting cycles stops earlier and
///     says so.
/// solver : str
///     auto, sqp, lm, sopp, ols, irls or irls:WEIGHT.
/// lobes, order, degree : int
///     Structure: specular lobes, Koenderink order, polynomial degree.
/// save : str or os.PathLike, optional
///     Also write the fitted model (JSON) here.
/// polish : bool
///     End the fit for appearance with a search on the judge's mean
///     HDR-FLIP (as ``brdf fit --polish``): a lower image error for a few
///     seconds more. Only for fits for appearance.
/// for_renderer : str, optional
///     Instead of ``model``: among the models this renderer (``"mitsuba"``,
///     ``"blender"``, ``"gltf"``, ``"materialx"``, ``"usd"``, ``"pbrt"``)
///     renders exactly, the one whose render is closest to the data, fitted
///     for appearance (as ``brdf fit --for``); write it with
///     ``fit.model.export(for_renderer, path)``. It honours ``limit_deg``,
///     ``polish`` and ``save``; the options it decides itself
///     (``channels``, ``metric``, ``starts``, ``solver``, ...) raise when
///     given other values than their defaults.
///
/// Returns
/// -------
/// Fit
///     ``.model`` (a ``Model``), ``.report`` (the dict ``brdf fit --json``
///     prints; with ``for_renderer``, that of ``brdf fit --for --json``),
///     ``.image_error``.
///
/// Raises
/// ------
/// BrdfError
///     With the message of the ``brdf`` command.
#[pyfunction]
#[pyo3(signature = (data, model=None, *, channels="rgb", metric="auto", limit_deg=80.0,
    starts=12, irls_max_iterations=brdf_fit::options::IRLS_MAX_ITERATIONS, solver="auto",
    lobes=1, order=8, degree=7, save=None, polish=false, for_renderer=None))]
pub fn fit<'py>(
    py: Python<'py>,
    data: &Bound<'py, PyAny>,
    model: Option<&str>,
    channels: &str,
    metric: &str,
    limit_deg: f64,
    starts: usize,
    irls_max_iterations: usize,
    solver: &str,
    lobes: usize,
    order: usize,
    degree: usize,
    save: Option<PathBuf>,
    polish: bool,
    for_renderer: Option<&str>,
) -> PyResult<PyFit> {
    let model = match (model, for_renderer) {
        (Some(m), None) => m,
        (None, Some(target)) => {
            // What --for decides itself is refused when given, not ignored.
            let given = [
                ("channels", channels != "rgb"),
                ("metric", !["auto", "appearance"].contains(&metric)),
                ("starts", starts != 12),
                (
                    "irls_max_iterations",
                    irls_max_iterations != brdf_fit::options::IRLS_MAX_ITERATIONS,
                ),
                ("solver", solver != "auto"),
                ("lobes", lobes != 1),
                ("order", order != 8),
                ("degree", degree != 7),
            ];
            if let Some((name, _)) = given.iter().find(|(_, on)| *on) {
                return Err(usage(format!(
                    "{name}= has no use with for_renderer=: each of the renderer's models is fitted for appearance with its own settings; leave {name}= out"
                )));
            }
            return fit_for(py, data, target, (limit_deg, polish), save);
        }
        _ => {
            return Err(usage(
                "fit: give model=NAME or for_renderer=RENDERER (one of them)".into(),
            ));
        }
    };
    let channels = ChannelMode::parse(channels).map_err(|_| {
        usage(format!(
            "channels=\"{channels}\": expected grey, rgb or per-channel"
        ))
    })?;
    let material = material(py, data)?;
    let request = FitRequest {
        metric: Metric::parse(metric).map_err(to_py)?,
        channels,
        solver: Solver::parse(solver).map_err(to_py)?,
        starts,
        irls_max_iterations,
        limit_deg,
        config: ModelConfig {
            lobes,
            order,
            degree,
            ..ModelConfig::default()
        },
        polish,
        ..FitRequest::new(&material, brdf_fit::resolve(model).map_err(to_py)?)
    };
    if polish && !request.resolved_metric().0 {
        return Err(usage(format!(
            "polish=True refines a fit for appearance, which `{model}` with metric=\"{metric}\" on these data is not: use a renderer model (principled, gltf, gltf-ext, ggx) or metric=\"appearance\" on an RGL `.bsdf` or MERL `.binary` path"
        )));
    }
    if save.is_some() && channels.models(material.samples()) > 1 {
        return Err(usage(
            "save= needs one model: use channels=\"rgb\" or \"grey\"".into(),
        ));
    }
    let outcome = py.detach(|| request.run()).map_err(to_py)?;
    let saved = outcome
        .reports
        .iter()
        .map(|r| r.saved_model(material.name()))
        .collect::<Result<Vec<_>, _>>()
        .map_err(to_py)?;
    if let (Some(path), [one]) = (&save, saved.as_slice()) {
        one.save(path).map_err(to_py)?;
    }
    let report = brdf_fit::fit_json(&outcome.reports, material.samples()).map_err(to_py)?;
    Ok(PyFit {
        models: saved.into_iter().map(|saved| PyModel { saved }).collect(),
        report: crate::json::to_py_object(py, &report)?.unbind(),
        data: material.name().to_string(),
        spec: path_spec(data),
        errors: outcome.reports.iter().map(|r| r.summary.ngan_l2).collect(),
    })
}

/// The material `data` names: a path (str or os.PathLike, relative paths
/// also under `BRDF_DATA`), loaded with the GIL released, or a dict of
/// arrays as `load` returns (scattered samples, nothing to render).
pub(crate) fn material(py: Python<'_>, data: &Bound<'_, PyAny>) -> PyResult<Material> {
    if let Ok(d) = data.cast::<PyDict>() {
        let set = crate::samples::from_dict(d)?;
        let name = set.name.clone();
        return Ok(Material::new(&name, set, None));
    }
    let spec = data_spec(data)?;
    let material = py.detach(|| Material::load(&spec)).map_err(to_py)?;
    for n in &material.samples().notes {
        crate::error::warn(py, n)?;
    }
    Ok(material)
}

/// The data spec of `data` when given as a path.
fn path_spec(data: &Bound<'_, PyAny>) -> Option<String> {
    data.extract::<PathBuf>()
        .ok()
        .map(|p| p.display().to_string())
}

/// The data spec of `data` given as a path (str or os.PathLike), as the
/// `brdf` command takes it (relative paths also under `BRDF_DATA`).
pub(crate) fn data_spec(data: &Bound<'_, PyAny>) -> PyResult<String> {
    let path: PathBuf = data.extract().map_err(|_| {
        usage(
            "data: expected a path (str or os.PathLike) or a dict of arrays as load() returns"
                .into(),
        )
    })?;
    Ok(path.display().to_string())
}

/// `fit(data, for_renderer=...)`: the renderer's exact models fitted for
/// appearance, the closest kept (as `brdf fit --for`).
fn fit_for(
    py: Python<'_>,
    data: &Bound<'_, PyAny>,
    target: &str,
    (limit_deg, polish): (f64, bool),
    save: Option<PathBuf>,
) -> PyResult<PyFit> {
    let target: brdf_export::Target = target.parse().map_err(to_py)?;
    let material = material(py, data)?;
    let request = brdf_fit::SelectRequest {
        limit_deg,
        polish,
        ..brdf_fit::SelectRequest::new(&material)
    };
    let done = py
        .detach(|| {
            brdf_export::for_renderer::fit_for(
                &request,
                target,
                &brdf_export::WriteOptions::default(),
            )
        })
        .map_err(|e| usage(e.to_string()))?;
    let saved = done.report.saved_model(material.name()).map_err(to_py)?;
    if let Some(path) = &save {
        saved.save(path).map_err(to_py)?;
    }
    let report = brdf_fit::select_by_image_json(&material.samples().name, &done.rows, done.choice)
        .map_err(to_py)?;
    Ok(PyFit {
        models: vec![PyModel { saved }],
        report: crate::json::to_py_object(py, &report)?.unbind(),
        data: material.name().to_string(),
        spec: path_spec(data),
        errors: vec![done.report.summary.ngan_l2],
    })
}
