//! The fitting pipeline (the linear part): fit any model whose parameters are
//! all linear (Lambert, Koenderink, Kurt's polynomial) to a sample set by
//! weighted least squares on Ngan's objective
//! `sum_j w_j (cos_i_j (R_j - M_j))^2`, per channel.
//!
//! The design matrix comes from the model's own parameter derivatives
//! (`Parametric::eval_grad_batch_at`), never from a named model: for an
//! all-linear model they do not depend on the parameters. Parameters whose
//! box starts at 0 make the fit non-negative (Lawson-Hanson NNLS); otherwise
//! column-scaled pivoted QR. A solution outside a parameter's box is an
//! error naming the parameter, never silently clamped.

use std::time::Instant;

use brdf_core::metrics::ngan_l2;
use brdf_core::{MetricValue, Parametric, SampleSet};

use crate::FitError;

/// The outcome of a fit.
#[derive(Clone, Debug, serde::Serialize)]
pub struct FitReport {
    /// model name
    pub model: String,
    /// sample set name
    pub data: String,
    /// samples used
    pub samples: usize,
    /// parameter names and values
    pub parameters: Vec<(String, f64)>,
    /// Ngan's L2 metric (total and per channel)
    pub ngan_l2: f64,
    /// per-channel Ngan L2
    pub ngan_l2_per_channel: Vec<f64>,
    /// solver used
    pub solver: String,
    /// numerical rank of the design (minimum over channels)
    pub rank: usize,
    /// wall-clock fit time in seconds
    pub seconds: f64,
}

/// Fit an all-linear model to `samples` (same channel count) on Ngan's
/// objective; `model` is left at the fitted parameters.
pub fn fit_linear(model: &mut dyn Parametric, samples: &SampleSet) -> Result<FitReport, FitError> {
    let start = Instant::now();
    let specs = model.param_specs().to_vec();
    if let Some(s) = specs.iter().find(|s| !s.linear) {
        return Err(FitError::Usage(format!(
            "model `{}` has the non-linear parameter `{}`: only all-linear models can be fitted so far",
            model.name(),
            s.name
        )));
    }
    let (n, nc, np) = (samples.len(), model.channels(), specs.len());
    if nc != samples.channels() {
        return Err(FitError::Usage(format!(
            "model has {nc} channels but `{}` has {}",
            samples.name,
            samples.channels()
        )));
    }
    if n < np / nc.max(1) {
        return Err(FitError::Usage(format!(
            "{n} samples are fewer than the {} parameters per channel of `{}`",
            np / nc.max(1),
            model.name()
        )));
    }
    let pairs = samples.pairs();
    let scales = crate::pipeline::Objective::Ngan.row_scales(samples);
    let crate::pipeline::LinearFit {
        params: p,
        how: solver,
        rank,
        ..
    } = crate::pipeline::fit_all_linear(
        model,
        samples,
        &scales,
        &crate::pipeline::FitOptions {
            solver: crate::pipeline::Solver::Ols,
            ..Default::default()
        },
    )?;
    model.set_params(&p)?;
    let seconds = start.elapsed().as_secs_f64();
    let mut fitted = vec![0.0; nc * n];
    model.eval_batch_at(&p, pairs, &mut fitted);
    let MetricValue { total, per_channel } = ngan_l2(
        &samples.values_channel_major(),
        &fitted,
        &pairs.lz,
        samples.weights(),
    )?;
    Ok(FitReport {
        model: model.name().to_string(),
        data: samples.name.clone(),
        samples: n,
        parameters: specs.iter().map(|s| s.name.clone()).zip(p).collect(),
        ngan_l2: total,
        ngan_l2_per_channel: per_channel,
        solver,
        rank,
        seconds,
    })
}
