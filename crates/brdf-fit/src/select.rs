//! Choosing what a material needs (`brdf select`): fit every candidate —
//! each analytic model (with 1 and 2 lobes where it has lobes), Koenderink
//! orders 2..8, polynomial degrees 1..12 — and pick the one with the fewest
//! stored numbers whose Ngan L2 error is within a relative tolerance of the
//! best. AIC and BIC are reported beside it (Gaussian residuals on Ngan's
//! scaled rows: `AIC = n ln(SSR/n) + 2k`, `BIC = n ln(SSR/n) + k ln n`,
//! `n` = samples x channels, `k` = stored numbers).
//!
//! Stored numbers are the model's parameters; for Kurt's polynomial they
//! include its PCA transform as Kurt counts it (isotropic: the 2 means and
//! 2 numbers of the axes, giving his `2p + 5` per grey fit).

use brdf_core::SampleSet;
use brdf_models::{ModelConfig, catalogue};
use serde::Serialize;

use crate::FitError;
use crate::pipeline::{FitOptions, fit};

/// One candidate's outcome.
#[derive(Clone, Debug, Serialize)]
pub struct SelectRow {
    /// Label (`lafortune (2 lobes)`, `koenderink order 4`, ...).
    pub label: String,
    /// Catalogue name.
    pub model: String,
    /// Stored numbers `k`.
    pub stored_numbers: usize,
    /// Ngan L2 error.
    pub error: f64,
    /// Residual sum of squares on Ngan's rows.
    pub ssr: f64,
    /// Akaike's information criterion.
    pub aic: f64,
    /// Bayes' information criterion.
    pub bic: f64,
    /// Fit time in seconds.
    pub seconds: f64,
    /// The solver's termination.
    pub termination: String,
}

/// The candidates: `(label, model, config)`.
pub fn candidates(channels: usize) -> Vec<(String, &'static str, ModelConfig)> {
    let base = ModelConfig {
        channels,
        ..ModelConfig::default()
    };
    let mut v = Vec::new();
    for e in catalogue() {
        match e.name {
            "koenderink" => {
                for order in 2..=8 {
                    v.push((
                        format!("koenderink order {order}"),
                        e.name,
                        ModelConfig { order, ..base },
                    ));
                }
            }
            "polynomial" => {
                for degree in 1..=12 {
                    v.push((
                        format!("polynomial degree {degree}"),
                        e.name,
                        ModelConfig { degree, ..base },
                    ));
                }
            }
            "polynomial-aniso" => {}
            _ if e.has_lobes => {
                for lobes in 1..=2 {
                    v.push((
                        format!(
                            "{} ({lobes} lobe{})",
                            e.name,
                            if lobes > 1 { "s" } else { "" }
                        ),
                        e.name,
                        ModelConfig { lobes, ..base },
                    ));
                }
            }
            _ => v.push((e.name.to_string(), e.name, base)),
        }
    }
    v
}

/// Which candidates to fit: only these models (forgiving names; all when
/// empty), only those with at most this many stored numbers.
#[derive(Clone, Debug, Default)]
pub struct Among {
    /// Model names (`--models`); every catalogue model when empty.
    pub models: Vec<String>,
    /// The most stored numbers a candidate may have (`--max-parameters`).
    pub max_parameters: Option<usize>,
}

impl Among {
    /// The resolved model names, without repeats; `None` for all.
    fn names(&self) -> Result<Option<Vec<&'static str>>, FitError> {
        if self.models.is_empty() {
            return Ok(None);
        }
        let mut out: Vec<&'static str> = Vec::new();
        for m in &self.models {
            let name = crate::names::resolve(m)?.name;
            if !out.contains(&name) {
                out.push(name);
            }
        }
        Ok(Some(out))
    }
}

/// Stored numbers of a model of `name` with `n_params` parameters: the
/// polynomial's PCA transform and Dupuy's table of `D` count too.
fn stored_numbers(name: &str, n_params: usize) -> usize {
    n_params
        + match name {
            "polynomial" => 4,
            brdf_models::dupuy::NAME => brdf_models::dupuy::DUPUY_NODES,
            _ => 0,
        }
}

/// Fit every candidate to `data` and return the rows and the index of the
/// choice (fewest stored numbers with error `<= (1 + tolerance) best`).
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
    if !(tolerance >= 0.0 && tolerance.is_finite()) {
        return Err(FitError::Usage(format!(
            "--tolerance {tolerance} must be >= 0"
        )));
    }
    let names = among.names()?;
    // The admitted candidates, then their fits in parallel (rows in
    // candidate order: the same table for any number of threads).
    let mut todo = Vec::new();
    for (label, name, config) in candidates(data.channels()) {
        if names.as_ref().is_some_and(|v| !v.contains(&name)) {
            continue;
        }
        let Some(e) = brdf_models::entry(name) else {
            continue;
        };
        // A model read off the data (Dupuy's table) may not be buildable
        // from these samples (too few back-scattering ones): a failed row.
        let model = match e.build_from(&config, data) {
            Ok(m) => m,
            Err(err) if e.from_samples.is_some() => {
                todo.push(Err(SelectRow {
                    label,
                    model: name.to_string(),
                    stored_numbers: 0,
                    error: f64::NAN,
                    ssr: f64::NAN,
                    aic: f64::NAN,
                    bic: f64::NAN,
                    seconds: 0.0,
                    termination: format!("failed: {err}"),
                }));
                continue;
            }
            Err(err) => return Err(err.into()),
        };
        if model.n_params() >= data.len() * data.channels() {
            continue;
        }
        if among
            .max_parameters
            .is_some_and(|m| stored_numbers(name, model.n_params()) > m)
        {
            continue;
        }
        todo.push(Ok((label, name, model)));
    }
    use rayon::prelude::*;
    let rows: Vec<SelectRow> = todo
        .into_par_iter()
        .map(|t| match t {
            Ok((label, name, model)) => select_row(data, opts, label, name, model),
            Err(failed) => failed,
        })
        .collect();
    let best = rows
        .iter()
        .map(|r| r.error)
        .filter(|e| e.is_finite())
        .fold(f64::INFINITY, f64::min);
    let choice = rows
        .iter()
        .enumerate()
        .filter(|(_, r)| r.error.is_finite() && r.error <= (1.0 + tolerance) * best)
        .min_by(|a, b| {
            a.1.stored_numbers
                .cmp(&b.1.stored_numbers)
                .then(a.1.error.total_cmp(&b.1.error))
        })
        .map(|(i, _)| i)
        .ok_or_else(|| {
            FitError::Usage(format!(
                "`{}`: no candidate could be fitted ({})",
                data.name,
                rows.first()
                    .map(|r| format!("{}: {}", r.label, r.termination))
                    .unwrap_or_else(|| "no candidate has fewer parameters than samples, or within --models and --max-parameters".into())
            ))
        })?;
    Ok((rows, choice))
}

/// One candidate's fit as a row of [`select_among`] (a failed fit is a
/// row with NaN errors saying why).
fn select_row(
    data: &SampleSet,
    opts: &FitOptions,
    label: String,
    name: &'static str,
    model: Box<dyn brdf_core::Parametric>,
) -> SelectRow {
    let n = (data.len() * data.channels()) as f64;
    let n_params = model.n_params();
    let scaled = crate::scaling::fit_scaled(model, data, opts.objective, |m, d, _| fit(m, d, opts));
    let r = match scaled {
        Ok((_, r, _)) => r,
        Err(e) => {
            return SelectRow {
                label,
                model: name.to_string(),
                stored_numbers: n_params,
                error: f64::NAN,
                ssr: f64::NAN,
                aic: f64::NAN,
                bic: f64::NAN,
                seconds: 0.0,
                termination: format!("failed: {e}"),
            };
        }
    };
    let k = stored_numbers(name, n_params);
    // SSR on Ngan's rows: E^2 times the weight sum (per channel averaged).
    let wsum: f64 = data.weights().iter().sum();
    let ssr = r.ngan_l2 * r.ngan_l2 * wsum * data.channels() as f64;
    // ln(SSR / n) from the error itself: SSR of data near 1e300
    // overflows, its logarithm does not.
    let ll = n
        * (2.0 * r.ngan_l2.ln() + (wsum * data.channels() as f64 / n).ln())
            .max(f64::MIN_POSITIVE.ln());
    SelectRow {
        label,
        model: name.to_string(),
        stored_numbers: k,
        error: r.ngan_l2,
        ssr,
        aic: ll + 2.0 * k as f64,
        bic: ll + k as f64 * n.ln(),
        seconds: r.seconds,
        termination: r.termination,
    }
}

/// The measured data `brdf select` fits: invalid samples and those beyond
/// `limit_deg` dropped, the mean of the channels when `grey`.
pub fn prepare(data: &SampleSet, limit_deg: f64, grey: bool) -> Result<SampleSet, FitError> {
    if !(limit_deg > 0.0 && limit_deg <= 90.0) {
        return Err(FitError::Usage(format!(
            "--limit {limit_deg} must be in (0, 90] degrees"
        )));
    }
    let (data, _) = data.filter_invalid(false);
    let (data, _) = data.filter_angle_limit(limit_deg.to_radians());
    Ok(if grey { data.mean_channel() } else { data })
}

/// The candidates as a table, smallest first, the chosen one marked, with
/// a note saying why it was chosen.
pub fn table(name: &str, rows: &[SelectRow], choice: usize, tolerance: f64) -> crate::table::Table {
    use crate::table::{Cell, Table};
    let mut t = Table::new(
        &format!("Candidates for {name}"),
        &[
            "candidate",
            "stored numbers",
            "Ngan L2",
            "AIC",
            "BIC",
            "time (s)",
            "termination",
        ],
    );
    let mut order: Vec<usize> = (0..rows.len()).collect();
    order.sort_by(|a, b| {
        rows[*a]
            .stored_numbers
            .cmp(&rows[*b].stored_numbers)
            .then(rows[*a].error.total_cmp(&rows[*b].error))
    });
    for i in order {
        let r = &rows[i];
        let label = if i == choice {
            format!("**{}** (chosen)", r.label)
        } else {
            r.label.clone()
        };
        t.rows.push(vec![
            Cell::Text(label),
            Cell::Text(r.stored_numbers.to_string()),
            Cell::Num(r.error, 4),
            Cell::Num(r.aic, 5),
            Cell::Num(r.bic, 5),
            Cell::Num(r.seconds, 3),
            Cell::Text(r.termination.clone()),
        ]);
    }
    if let Some(c) = rows.get(choice) {
        t.note = format!(
            "Chosen: {} ({} stored numbers, error {:.4e}): the fewest stored numbers within {} of the best error.",
            c.label, c.stored_numbers, c.error, tolerance
        );
    }
    t
}
