//! `select`: the model selection `brdf select` runs, from Python, returning
//! the dict of `brdf select --json` (built by [`brdf_fit::select_json`], as
//! the command does), or with `by_image=True` that of `brdf select
//! --by-image --json` (built by [`brdf_fit::select_by_image_json`]). The GIL
//! is released while the data load and the fits run.

use std::path::PathBuf;

use brdf_fit::FitOptions;
use brdf_fit::select::{Among, Search};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::error::{to_py, usage};
use crate::fit::data_set;

/// Fit the candidate models and choose the smallest adequate one, as
/// ``brdf select``.
///
/// Every catalogue model (or those of ``models``) is fitted, coarse to fine
/// by default: all on a shared subsample of about 2048 samples, those near
/// the best again on all samples. The choice is the candidate with the
/// fewest stored numbers whose Ngan L2 is within ``(1 + tolerance)`` times
/// the best. On data named by a path that can be rendered (RGL ``.bsdf``,
/// MERL ``.binary``) the choice's image errors under the standard light
/// sets are reported too.
///
/// With ``by_image=True``, as ``brdf select --by-image``, the renderer
/// models (principled, glTF, glTF + KHR, GGX; or those of ``models``) are
/// each fitted for appearance and the one of least mean HDR-FLIP against
/// the data's renders is chosen (Bieron and Peers 2020). This needs data
/// named by a path that can be rendered (RGL ``.bsdf``, MERL ``.binary``),
/// and it ignores ``tolerance``, ``limit_deg``, ``grey``,
/// ``max_parameters`` and ``exhaustive``, as the command ignores their
/// options.
///
/// Parameters
/// ----------
/// data : str, os.PathLike or dict
///     A data path (relative paths are also looked up under
///     ``BRDF_DATA``), or a dict of arrays as ``load`` returns.
/// tolerance : float
///     Accept errors up to ``(1 + tolerance)`` times the best.
/// limit_deg : float
///     Drop samples with theta_i or theta_o above this angle.
/// grey : bool
///     Fit the mean of the channels instead of every channel.
/// models : list of str, optional
///     Only these models (forgiving names; repeats count once).
/// max_parameters : int, optional
///     Only candidates with at most this many stored numbers.
/// exhaustive : bool
///     Fit every candidate to all samples.
/// by_image : bool
///     Choose among the renderer models by their image error instead
///     (``brdf select --by-image``); data must be a path to RGL ``.bsdf``
///     or MERL ``.binary`` data.
/// polish : bool
///     With ``by_image=True``: end each model's fit with a search on the
///     mean HDR-FLIP of its renders, as ``fit(..., polish=True)``
///     (``brdf select --by-image --polish``).
///
/// Returns
/// -------
/// dict
///     What ``brdf select --json`` prints: ``choice`` (its row),
///     ``candidates`` (every row: ``label``, ``model``, ``stored_numbers``,
///     ``error``, ``aic``, ``bic``, ``seconds``, ``termination``,
///     ``screened_out``, ...), ``choice_image_error`` (``None`` on
///     scattered data, with ``image_note`` saying why), ``data``,
///     ``samples``, ``tolerance``, ``search``. Fit the choice with
///     ``fit(data, result["choice"]["model"])`` to get its ``Model``.
///     With ``by_image=True``, what ``brdf select --by-image --json``
///     prints instead: ``data``, ``choice`` (its row) and ``candidates``
///     (every row: ``model``, ``objective``, ``lobes``, ``image`` (the
///     image errors per light set), ``ngan_l2``, ``parameters``,
///     ``seconds``).
///
/// Raises
/// ------
/// BrdfError
///     With the message of the ``brdf`` command.
#[pyfunction]
#[pyo3(signature = (data, *, tolerance=0.1, limit_deg=80.0, grey=false, models=None,
    max_parameters=None, exhaustive=false, by_image=false, polish=false))]
pub fn select<'py>(
    py: Python<'py>,
    data: &Bound<'py, PyAny>,
    tolerance: f64,
    limit_deg: f64,
    grey: bool,
    models: Option<Vec<String>>,
    max_parameters: Option<usize>,
    exhaustive: bool,
    by_image: bool,
    polish: bool,
) -> PyResult<Bound<'py, PyAny>> {
    if polish && !by_image {
        return Err(usage(
            "polish=True refines fits for appearance: use it with by_image=True (renderer models on RGL `.bsdf` or MERL `.binary` data)".into(),
        ));
    }
    if models.as_ref().is_some_and(Vec::is_empty) {
        return Err(usage(
            "models=[]: name at least one model, or leave models out for all".into(),
        ));
    }
    if by_image {
        return select_by_image(py, data, models, polish);
    }
    let (set, _) = data_set(py, data)?;
    let spec = data
        .extract::<PathBuf>()
        .ok()
        .map(|p| p.display().to_string());
    let among = Among {
        models: models.unwrap_or_default(),
        max_parameters,
    };
    let search = if exhaustive {
        Search::Exhaustive
    } else {
        Search::CoarseToFine
    };
    let report = py.detach(|| {
        let set = brdf_fit::select::prepare(&set, limit_deg, grey)?;
        let dense = match &spec {
            Some(s) => brdf_io::load_dense(s)?,
            None => None,
        };
        let (selection, image) = brdf_fit::judged::select_judged(
            &set,
            dense.as_deref(),
            tolerance,
            &FitOptions::default(),
            &among,
            search,
        )?;
        brdf_fit::select_json(
            &set,
            tolerance,
            search,
            &selection.rows,
            selection.choice,
            image.as_ref(),
        )
    });
    crate::json::to_py_object(py, &report.map_err(to_py)?)
}

/// `select(..., by_image=True)`: what `brdf select --by-image` does, on the
/// data path resolved as [`data_set`] resolves it (relative paths also
/// under `BRDF_DATA`, by [`brdf_io::load`] and [`brdf_io::load_dense`]).
fn select_by_image<'py>(
    py: Python<'py>,
    data: &Bound<'py, PyAny>,
    models: Option<Vec<String>>,
    polish: bool,
) -> PyResult<Bound<'py, PyAny>> {
    // Arrays hold samples only: there is nothing to render them from.
    if data.cast::<PyDict>().is_ok() {
        return Err(usage(
            "by_image=True: data given as arrays holds scattered samples that cannot be rendered; pass the path of RGL `.bsdf` or MERL `.binary` data, or select without by_image=True".into(),
        ));
    }
    let spec = crate::fit::data_spec(data)?;
    let names: Vec<String> = models.unwrap_or_else(|| {
        brdf_models::by_image_models()
            .iter()
            .map(|m| m.to_string())
            .collect()
    });
    let report = py.detach(|| -> PyResult<serde_json::Value> {
        let samples = brdf_io::load(&spec).map_err(to_py)?;
        let Some(dense) = brdf_io::load_dense(&spec).map_err(to_py)? else {
            return Err(usage(format!(
                "by_image=True: `{spec}` holds scattered samples that cannot be rendered; use RGL `.bsdf` or MERL `.binary` data, or select without by_image=True"
            )));
        };
        let names: Vec<&str> = names.iter().map(String::as_str).collect();
        let (rows, choice) =
            brdf_fit::select_by_image::select_by_image(&names, &samples, dense.as_ref(), polish)
                .map_err(to_py)?;
        brdf_fit::select_by_image_json(&samples.name, &rows, choice).map_err(to_py)
    });
    crate::json::to_py_object(py, &report?)
}
