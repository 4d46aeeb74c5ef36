//! `select`: the model selection `brdf select` runs, from Python, returning
//! the dict of `brdf select --json` (built by [`brdf_fit::select_json`], as
//! the command does), or with `by_image=True` that of `brdf select
//! --by-image --json` (built by [`brdf_fit::select_by_image_json`]). The GIL
//! is released while the data load and the fits run.

use brdf_fit::select::{Among, Search};
use brdf_fit::{SelectBy, SelectRequest};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::error::{to_py, usage};
use crate::fit::material;

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
/// By image (the default on data that can be rendered), the renderer
/// models (principled, glTF, glTF + KHR, GGX; or those of ``models``) are
/// each fitted for appearance and the one of least mean HDR-FLIP against
/// the data's renders is chosen (Bieron and Peers 2020). This needs data
/// named by a path that can be rendered (RGL ``.bsdf``, MERL ``.binary``);
/// ``limit_deg`` limits the samples of each fit's BRDF-space candidates,
/// and ``tolerance``, ``grey``, ``max_parameters`` and ``exhaustive``,
/// which only a selection by L2 reads, raise when given.
///
/// Parameters
/// ----------
/// data : str, os.PathLike or dict
///     A data path (relative paths are also looked up under
///     ``BRDF_DATA``), or a dict of arrays as ``load`` returns.
/// tolerance : float, optional
///     Accept errors up to ``(1 + tolerance)`` times the best (default
///     0.1).
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
/// by_image : bool, optional
///     ``None`` (default): by image error on data that can be rendered
///     (a path to RGL ``.bsdf`` or MERL ``.binary`` data), else by L2, as
///     ``brdf select``; ``True``: by image error (``--by-image``);
///     ``False``: by L2 (``--by-l2``).
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
#[pyo3(signature = (data, *, tolerance=None, limit_deg=80.0, grey=false, models=None,
    max_parameters=None, exhaustive=false, by_image=None, polish=false))]
pub fn select<'py>(
    py: Python<'py>,
    data: &Bound<'py, PyAny>,
    tolerance: Option<f64>,
    limit_deg: f64,
    grey: bool,
    models: Option<Vec<String>>,
    max_parameters: Option<usize>,
    exhaustive: bool,
    by_image: Option<bool>,
    polish: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let by = match by_image {
        None => SelectBy::Auto,
        Some(true) => SelectBy::Image,
        Some(false) => SelectBy::L2,
    };
    let arrays = data.cast::<PyDict>().is_ok();
    if polish && (by == SelectBy::L2 || arrays) {
        return Err(usage(
            "polish=True refines fits for appearance: use it with by_image=True (renderer models on RGL `.bsdf` or MERL `.binary` data)".into(),
        ));
    }
    if models.as_ref().is_some_and(Vec::is_empty) {
        return Err(usage(
            "models=[]: name at least one model, or leave models out for all".into(),
        ));
    }
    // Arrays hold samples only: there is nothing to render them from.
    if by == SelectBy::Image && arrays {
        return Err(usage(
            "by_image=True: data given as arrays holds scattered samples that cannot be rendered; pass the path of RGL `.bsdf` or MERL `.binary` data, or select without by_image=True".into(),
        ));
    }
    let material = material(py, data)?;
    if polish && !material.is_renderable() {
        return Err(usage(
            "polish=True refines fits for appearance: use it with by_image=True (renderer models on RGL `.bsdf` or MERL `.binary` data)".into(),
        ));
    }
    if by == SelectBy::Image && !material.is_renderable() {
        return Err(usage(format!(
            "by_image=True: `{}` holds scattered samples that cannot be rendered; use RGL `.bsdf` or MERL `.binary` data, or select without by_image=True",
            material.spec()
        )));
    }
    if by == SelectBy::Image || (by == SelectBy::Auto && material.is_renderable()) {
        let given = [
            ("tolerance", tolerance.is_some()),
            ("grey", grey),
            ("max_parameters", max_parameters.is_some()),
            ("exhaustive", exhaustive),
        ];
        if let Some((name, _)) = given.iter().find(|(_, on)| *on) {
            return Err(usage(format!(
                "{name}= applies to a selection by L2, and `{}` can be rendered, so select chooses by image (every renderer model fitted for appearance on all channels): pass by_image=False, or leave {name}= out",
                material.spec()
            )));
        }
    }
    let request = SelectRequest {
        by,
        tolerance: tolerance.unwrap_or(0.1),
        limit_deg,
        grey,
        among: Among {
            models: models.unwrap_or_default(),
            max_parameters,
        },
        search: if exhaustive {
            Search::Exhaustive
        } else {
            Search::CoarseToFine
        },
        polish,
        ..SelectRequest::new(&material)
    };
    let report = py.detach(|| request.run().and_then(|outcome| outcome.json()));
    crate::json::to_py_object(py, &report.map_err(to_py)?)
}
