//! Choosing what a material needs (`brdf select`): fit every candidate —
//! each analytic model (with 1 and 2 lobes where it has lobes), Koenderink
//! orders 2..8, polynomial degrees 1..12 ([`candidates`]) — and pick the
//! one with the fewest stored numbers whose Ngan L2 error is within a
//! relative tolerance of the best. AIC and BIC are reported beside it
//! (Gaussian residuals on Ngan's scaled rows: `AIC = n ln(SSR/n) + 2k`,
//! `BIC = n ln(SSR/n) + k ln n`, `n` = samples x channels, `k` = stored
//! numbers; an error below the data's rounding level, `eps` times their
//! largest value, counts as that level, so their differences do not
//! depend on the data's unit).
//!
//! By default the candidates are fitted coarse to fine ([`coarse`]): all
//! of them on one shared subsample, then only those near the best on all
//! samples; [`Search::Exhaustive`] fits every candidate to all samples.
//! The candidates are fitted in parallel and the rows come back in
//! candidate order, every decision taken from order-free reductions: the
//! same rows and choice for any number of threads.
//!
//! Stored numbers are the model's parameters; for Kurt's polynomial they
//! include its PCA transform as Kurt counts it (isotropic: the 2 means and
//! 2 numbers of the axes, giving his `2p + 5` per grey fit).

use brdf_core::{Parametric, SampleSet};
use rayon::prelude::*;

use crate::FitError;
use crate::options::FitOptions;
use crate::pipeline::fit;

mod candidates;
pub mod coarse;
mod row;
mod table;

pub use candidates::{Among, candidates};
pub use coarse::{COARSE_SAMPLES, RACE_FACTOR};
pub use row::SelectRow;
pub use table::table;

use candidates::Todo;

/// How the candidates are fitted.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Search {
    /// All candidates on a shared coarse subsample, those near the best
    /// again on all samples ([`coarse`]).
    #[default]
    CoarseToFine,
    /// Every candidate on all samples (`--exhaustive`).
    Exhaustive,
}

/// Fit every candidate to `data` coarse to fine and return the rows and
/// the index of the choice (fewest stored numbers with error `<= (1 +
/// tolerance) best`).
pub fn select(
    data: &SampleSet,
    tolerance: f64,
    opts: &FitOptions,
) -> Result<(Vec<SelectRow>, usize), FitError> {
    select_among(data, tolerance, opts, &Among::default())
}

/// [`select`] among the candidates `among` admits.
pub fn select_among(
    data: &SampleSet,
    tolerance: f64,
    opts: &FitOptions,
    among: &Among,
) -> Result<(Vec<SelectRow>, usize), FitError> {
    select_with(data, tolerance, opts, among, Search::default())
}

/// [`select_among`] with the candidates fitted as `search` says. The
/// choice is made among the candidates fitted to all samples.
pub fn select_with(
    data: &SampleSet,
    tolerance: f64,
    opts: &FitOptions,
    among: &Among,
    search: Search,
) -> Result<(Vec<SelectRow>, usize), FitError> {
    let s = select_fitted(data, tolerance, opts, among, search)?;
    Ok((s.rows, s.choice))
}

/// A selection: every candidate's row, the choice, and the chosen model.
pub struct Selection {
    /// One row per candidate, in candidate order.
    pub rows: Vec<SelectRow>,
    /// Index of the choice in `rows`.
    pub choice: usize,
    /// The chosen model at its fitted parameters.
    pub model: Box<dyn Parametric>,
}

/// [`select_with`], with the chosen model at its fitted parameters (to
/// render it, save it, judge its image error).
pub fn select_fitted(
    data: &SampleSet,
    tolerance: f64,
    opts: &FitOptions,
    among: &Among,
    search: Search,
) -> Result<Selection, FitError> {
    if !(tolerance >= 0.0 && tolerance.is_finite()) {
        return Err(FitError::OutOfRange {
            option: "--tolerance",
            value: tolerance,
            range: ">= 0",
        });
    }
    let todo = candidates::admitted(data, among)?;
    let fitted = match search {
        Search::Exhaustive => fit_all(data, opts, todo),
        Search::CoarseToFine => coarse::coarse_to_fine(data, tolerance, opts, todo),
    };
    let (rows, mut models): (Vec<SelectRow>, Vec<Option<Box<dyn Parametric>>>) =
        fitted.into_iter().unzip();
    let choice = choose(&data.name, &rows, tolerance)?;
    // A row fitted to all samples with a finite error has its model.
    let model = models[choice]
        .take()
        .ok_or_else(|| FitError::ChoiceWithoutModel {
            data: data.name.clone(),
            label: rows[choice].label.clone(),
        })?;
    Ok(Selection {
        rows,
        choice,
        model,
    })
}

/// A candidate's row and, when it was fitted to all samples, its model.
type Fitted = (SelectRow, Option<Box<dyn Parametric>>);

/// Every candidate of `todo` fitted to all of `data`, in parallel, rows in
/// candidate order.
fn fit_all(data: &SampleSet, opts: &FitOptions, todo: Vec<Todo>) -> Vec<Fitted> {
    todo.into_par_iter()
        .map(|t| match t {
            Todo::Fit(c) => fit_candidate(data, opts, c.label, c.name, c.model, false),
            Todo::Failed(row) => (row, None),
        })
        .collect()
}

/// The choice among the rows fitted to all samples: the fewest stored
/// numbers with error `<= (1 + tolerance)` times the best, ties to the
/// smaller error.
fn choose(data: &str, rows: &[SelectRow], tolerance: f64) -> Result<usize, FitError> {
    let full = |r: &&SelectRow| !r.screened_out && r.error.is_finite();
    let best = rows
        .iter()
        .filter(full)
        .map(|r| r.error)
        .fold(f64::INFINITY, f64::min);
    rows.iter()
        .enumerate()
        .filter(|(_, r)| full(r) && r.error <= (1.0 + tolerance) * best)
        .min_by(|a, b| {
            a.1.stored_numbers
                .cmp(&b.1.stored_numbers)
                .then(a.1.error.total_cmp(&b.1.error))
        })
        .map(|(i, _)| i)
        .ok_or_else(|| {
            FitError::NoCandidateFitted {
                data: data.to_string(),
                why: rows.first()
                    .map(|r| format!("{}: {}", r.label, r.termination))
                    .unwrap_or_else(|| "no candidate has fewer parameters than samples, or within --models and --max-parameters".into()),
            }
        })
}

/// One candidate's fit to `data` as a row (a failed fit is a row with NaN
/// errors saying why) and the fitted model. `from_current`: the model's
/// current parameters are one more start ([`coarse::fit_from_current`]).
fn fit_candidate(
    data: &SampleSet,
    opts: &FitOptions,
    label: String,
    name: &'static str,
    model: Box<dyn Parametric>,
    from_current: bool,
) -> (SelectRow, Option<Box<dyn Parametric>>) {
    let n_params = model.n_params();
    let scaled = crate::scaling::fit_scaled(model, data, opts.objective, |m, d, _| {
        if from_current {
            coarse::fit_from_current(m, d, opts)
        } else {
            fit(m, d, opts)
        }
    });
    match scaled {
        Ok((m, r, _)) => (SelectRow::fitted(label, name, n_params, data, &r), Some(m)),
        Err(e) => (
            SelectRow::failed(label, name, n_params, data.len(), &e),
            None,
        ),
    }
}

/// Make faer's dense factorisations sequential for the whole process:
/// [`brdf_solve::sequential_factorisations`] (the `brdf` command and the
/// Python module call it at start).
pub use brdf_solve::sequential_factorisations;

/// The measured data `brdf select` fits: invalid samples and those beyond
/// `limit_deg` dropped, the mean of the channels when `grey`.
pub fn prepare(data: &SampleSet, limit_deg: f64, grey: bool) -> Result<SampleSet, FitError> {
    if !(limit_deg > 0.0 && limit_deg <= 90.0) {
        return Err(FitError::OutOfRange {
            option: "--limit",
            value: limit_deg,
            range: "in (0, 90] degrees",
        });
    }
    let (data, _) = data.filter_invalid(false);
    let (data, _) = data.filter_angle_limit(limit_deg.to_radians());
    Ok(if grey { data.mean_channel() } else { data })
}
