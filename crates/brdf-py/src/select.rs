//! `select`: the model selection `brdf select` runs, from Python, returning
//! the dict of `brdf select --json` (built by [`brdf_fit::select_json`], as
//! the command does). The GIL is released while the data load and the fits
//! run.

use std::path::PathBuf;

use brdf_fit::FitOptions;
use brdf_fit::select::{Among, Search};
use pyo3::prelude::*;

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
///
/// Raises
/// ------
/// BrdfError
///     With the message of the ``brdf`` command.
#[pyfunction]
#[pyo3(signature = (data, *, tolerance=0.1, limit_deg=80.0, grey=false, models=None,
    max_parameters=None, exhaustive=false))]
pub fn select<'py>(
    py: Python<'py>,
    data: &Bound<'py, PyAny>,
    tolerance: f64,
    limit_deg: f64,
    grey: bool,
    models: Option<Vec<String>>,
    max_parameters: Option<usize>,
    exhaustive: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let (set, _) = data_set(py, data)?;
    let spec = data
        .extract::<PathBuf>()
        .ok()
        .map(|p| p.display().to_string());
    if models.as_ref().is_some_and(Vec::is_empty) {
        return Err(usage(
            "models=[]: name at least one model, or leave models out for all".into(),
        ));
    }
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
        let (selection, image) = brdf_fit::appearance::select_judged(
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
