//! `fit`: the fit `brdf fit` runs, from Python, returning the dict of
//! `brdf fit --json` (built by [`brdf_fit::fit_json`], as the command does).
//! The GIL is released while the data load and the fits run.

use std::path::PathBuf;

use brdf_core::SampleSet;
use brdf_fit::{Channels, Fit, FitReport, Objective, Solver};
use brdf_models::saved_model::SavedModel;
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
///
/// Returns
/// -------
/// Fit
///     ``.model`` (a ``Model``), ``.report`` (the dict ``brdf fit --json``
///     prints), ``.image_error``.
///
/// Raises
/// ------
/// BrdfError
///     With the message of the ``brdf`` command.
#[pyfunction]
#[pyo3(signature = (data, model, *, channels="rgb", metric="auto", limit_deg=80.0,
    starts=12, irls_max_iterations=brdf_fit::options::IRLS_MAX_ITERATIONS, solver="auto",
    lobes=1, order=8, degree=7, save=None, polish=false))]
pub fn fit<'py>(
    py: Python<'py>,
    data: &Bound<'py, PyAny>,
    model: &str,
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
) -> PyResult<PyFit> {
    let (set, name) = data_set(py, data)?;
    let spec = data
        .extract::<PathBuf>()
        .ok()
        .map(|p| p.display().to_string());
    let entry = brdf_fit::resolve(model).map_err(to_py)?;
    // As `brdf fit`: data named by a path that can be rendered get image
    // errors, and renderer models are fitted for appearance under `auto`.
    let dense = match (&spec, channels) {
        (Some(s), "rgb" | "grey") => py.detach(|| brdf_io::load_dense(s)).map_err(to_py)?,
        _ => None,
    };
    let (appearance, metric) = brdf_fit::judged::metric_choice(metric, entry.name, dense.is_some());
    if polish && !appearance {
        return Err(usage(format!(
            "polish=True refines a fit for appearance, which `{model}` with metric=\"{metric}\" on these data is not: use a renderer model (principled, gltf, gltf-ext, ggx) or metric=\"appearance\" on an RGL `.bsdf` or MERL `.binary` path"
        )));
    }
    let fit = Ok::<_, brdf_fit::FitError>(Fit::entry(entry))
        .and_then(|f| Ok(f.objective(Objective::parse(metric)?)))
        .and_then(|f| Ok(f.solver(Solver::parse(solver)?)))
        .map_err(to_py)?
        .starts(starts)
        .irls_max_iterations(irls_max_iterations)
        .limit_deg(limit_deg)
        .lobes(lobes)
        .order(order)
        .degree(degree)
        .polish_on_flip(polish);
    let sets = channel_sets(&set, channels)?;
    if save.is_some() && sets.len() > 1 {
        return Err(usage(
            "save= needs one model: use channels=\"rgb\" or \"grey\"".into(),
        ));
    }
    let judged = (dense.as_deref(), appearance);
    let (reports, saved) = py.detach(|| run_all(&fit, &sets, judged, save.as_ref(), &name))?;
    let report = brdf_fit::fit_json(&reports, &set).map_err(to_py)?;
    Ok(PyFit {
        models: saved.into_iter().map(|saved| PyModel { saved }).collect(),
        report: crate::json::to_py_object(py, &report)?.unbind(),
        data: name,
        spec,
        errors: reports.iter().map(|r| r.summary.ngan_l2).collect(),
    })
}

/// The data set and its name for outputs (relative to `BRDF_DATA`).
pub(crate) fn data_set(py: Python<'_>, data: &Bound<'_, PyAny>) -> PyResult<(SampleSet, String)> {
    if let Ok(d) = data.cast::<PyDict>() {
        let set = crate::samples::from_dict(d)?;
        let name = set.name.clone();
        return Ok((set, name));
    }
    let spec = data_spec(data)?;
    let set = py.detach(|| brdf_io::load(&spec)).map_err(to_py)?;
    Ok((set, brdf_fit::data_name(&spec)))
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

/// The data sets fitted for a channel option, as `brdf fit --channels`.
fn channel_sets(data: &SampleSet, channels: &str) -> PyResult<Vec<(SampleSet, Channels)>> {
    Ok(match channels {
        "rgb" => vec![(data.clone(), Channels::All)],
        "grey" => vec![(data.clone(), Channels::Grey)],
        "per-channel" => (0..data.channels())
            .map(|c| (data.single_channel(c), Channels::All))
            .collect(),
        other => {
            return Err(usage(format!(
                "channels=\"{other}\": expected grey, rgb or per-channel"
            )));
        }
    })
}

/// Run the fit on every set; save the (one) model when asked.
fn run_all(
    fit: &Fit,
    sets: &[(SampleSet, Channels)],
    (dense, appearance): (Option<&dyn brdf_core::Brdf>, bool),
    save: Option<&PathBuf>,
    name: &str,
) -> PyResult<(Vec<FitReport>, Vec<SavedModel>)> {
    let mut reports = Vec::new();
    let mut models = Vec::new();
    for (set, channels) in sets {
        let f = fit.clone().channels(*channels);
        let report = brdf_fit::judged::fit_judged(&f, set, dense, appearance).map_err(to_py)?;
        let saved = report.saved_model(name).map_err(to_py)?;
        if let Some(path) = save {
            saved.save(path).map_err(to_py)?;
        }
        reports.push(report);
        models.push(saved);
    }
    Ok((reports, models))
}
