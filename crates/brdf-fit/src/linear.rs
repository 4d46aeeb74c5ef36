//! All-linear models (Lambert, Koenderink, Kurt's polynomial) fitted
//! directly, channel by channel: NNLS (Lawson-Hanson) where the box starts
//! at 0, column-pivoted QR otherwise, or robust IRLS.
//!
//! The design matrix comes from the model's own parameter derivatives
//! (`Parametric::eval_grad_batch_at`), never from a named model: for an
//! all-linear model they do not depend on the parameters.

use brdf_core::{Parametric, SampleSet};
use brdf_solve::robust_weights::RobustWeight;
use brdf_solve::{IrlsOptions, IrlsTermination, ScaleConvention, irls};
use faer::{Mat, MatRef};

use crate::FitError;
use crate::options::{FitOptions, Solver};

/// An all-linear fit ([`fit_all_linear`]).
pub(crate) struct LinearFit {
    /// The parameters.
    pub params: Vec<f64>,
    /// The solver, in words.
    pub how: String,
    /// How the robust fit ended, for IRLS.
    pub irls: Option<IrlsEnd>,
}

/// How a robust (IRLS) fit ended over the channels.
pub(crate) struct IrlsEnd {
    /// Reweighting iterations of each fitted channel.
    pub iterations: Vec<usize>,
    /// The termination of the first channel that did not converge, else
    /// of the last: a fit converges only if every channel does.
    pub termination: IrlsTermination,
}

impl IrlsEnd {
    fn add(end: &mut Option<IrlsEnd>, iterations: usize, termination: IrlsTermination) {
        let e = end.get_or_insert(IrlsEnd {
            iterations: Vec::new(),
            termination,
        });
        e.iterations.push(iterations);
        if e.termination.is_converged() {
            e.termination = termination;
        }
    }
}

/// Fit an all-linear model channel by channel on rows scaled by `scales`.
pub(crate) fn fit_all_linear(
    model: &dyn Parametric,
    data: &SampleSet,
    scales: &[f64],
    opts: &FitOptions,
) -> Result<LinearFit, FitError> {
    let solver = opts.solver;
    let specs = model.param_specs();
    let (n, nc, np) = (data.len(), model.channels(), specs.len());
    let zero = vec![0.0; np];
    let mut offset = vec![0.0; nc * n];
    let mut jac = vec![0.0; nc * n * np];
    model.eval_grad_batch_at(&zero, data.pairs(), &mut offset, &mut jac);
    let mut p = zero;
    let mut how = String::new();
    let mut irls_end = None;
    for c in 0..nc {
        let cols = channel_columns(&jac, c, n, np);
        if cols.is_empty() {
            continue;
        }
        let y = data.channel(c);
        let a = Mat::from_fn(n, cols.len(), |j, k| {
            scales[j] * jac[(c * n + j) * np + cols[k]]
        });
        let b: Vec<f64> = (0..n)
            .map(|j| scales[j] * (y[j] - offset[c * n + j]))
            .collect();
        let x: Vec<f64> = match solver {
            Solver::Irls(weight) => fit_irls(a.as_ref(), &b, weight, opts, &mut irls_end)?,
            _ if cols.iter().all(|&k| specs[k].lower == 0.0) => {
                let upper: Vec<f64> = cols.iter().map(|&k| specs[k].upper).collect();
                fit_nnls(a.as_ref(), &b, &upper, &mut how)?
            }
            _ => fit_least_squares(a.as_ref(), &b, &mut how)?,
        };
        for (k, &col) in cols.iter().enumerate() {
            p[col] = x[k];
        }
    }
    if let (Solver::Irls(weight), Some(end)) = (solver, &irls_end) {
        how = irls_description(weight, end);
    }
    Ok(LinearFit {
        params: p,
        how,
        irls: irls_end,
    })
}

/// The parameters that channel `c` depends on (a column of the Jacobian
/// with a non-zero entry): the others, such as another channel's albedo,
/// are left out of its design, which they would make rank-deficient.
fn channel_columns(jac: &[f64], c: usize, n: usize, np: usize) -> Vec<usize> {
    (0..np)
        .filter(|&k| (0..n).any(|j| jac[(c * n + j) * np + k] != 0.0))
        .collect()
}

/// Robust fit of one channel by IRLS with MATLAB 2004's scale convention
/// (the one closest to Kurt's fits), recording how it ended.
fn fit_irls(
    a: MatRef<'_, f64>,
    b: &[f64],
    weight: RobustWeight,
    opts: &FitOptions,
    irls_end: &mut Option<IrlsEnd>,
) -> Result<Vec<f64>, FitError> {
    let s = irls(
        a,
        b,
        &IrlsOptions {
            weight,
            scale: ScaleConvention::Matlab2004,
            max_iterations: opts.irls_max_iterations,
            stop_on_cycle: opts.irls_stop_on_cycle,
            ..IrlsOptions::default()
        },
    )?;
    IrlsEnd::add(irls_end, s.iterations, s.termination);
    Ok(s.coef)
}

/// NNLS for a channel whose parameters all have the lower bound 0; when its
/// solution exceeds an upper bound, least squares within the whole box
/// instead (NNLS knows only the lower bounds).
fn fit_nnls(
    a: MatRef<'_, f64>,
    b: &[f64],
    upper: &[f64],
    how: &mut String,
) -> Result<Vec<f64>, FitError> {
    *how = "NNLS (Lawson-Hanson)".into();
    let s = brdf_solve::nnls(a, b, 3 * upper.len() + 10)?;
    match crate::linear_box::within_upper(a, b, s.x, upper)? {
        (x, true) => {
            *how = "least squares within the box (LSI: NNLS exceeded an upper bound)".into();
            Ok(x)
        }
        (x, false) => Ok(x),
    }
}

/// Unconstrained least squares for one channel by column-pivoted QR, whose
/// rank the description reports (a rank-deficient design is solved by SVD).
fn fit_least_squares(
    a: MatRef<'_, f64>,
    b: &[f64],
    how: &mut String,
) -> Result<Vec<f64>, FitError> {
    let n = a.nrows();
    let bm = Mat::from_fn(n, 1, |j, _| b[j]);
    let s = brdf_solve::lstsq(a, bm.as_ref(), None, brdf_solve::LstsqMethod::PivotedQr)?;
    *how = format!("least squares (column-pivoted QR, rank {})", s.rank);
    Ok((0..a.ncols()).map(|k| s.x[(k, 0)]).collect())
}

/// The solver in words for a robust fit: the weight function and the
/// iterations of each channel.
fn irls_description(weight: RobustWeight, end: &IrlsEnd) -> String {
    let counts: Vec<String> = end.iterations.iter().map(|k| k.to_string()).collect();
    format!(
        "IRLS ({}, MATLAB 2004 scale), {} iterations{}",
        weight.name(),
        counts.join(" / "),
        if counts.len() > 1 {
            " (per channel)"
        } else {
            ""
        }
    )
}
