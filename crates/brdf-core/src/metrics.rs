//! Error metrics between measured values `R` and model values `M`.
//!
//! All sample metrics take channel-major arrays (`[c * n + j]`, the order of
//! [`crate::SampleSet::values_channel_major`] and of model batch output), the
//! `cos theta_i` of each sample and per-sample weights, and return the total
//! and the per-channel values.
//!
//! Every root-mean-square here is formed without spurious underflow or
//! overflow (`root_mean_square`): data of 1e-300 have squared residuals
//! below the smallest `f64`, data of 1e200 above the largest, and a
//! textbook `sqrt(sum r^2 / n)` returns 0 or infinity for them.

use crate::CoreError;

/// Smallest mean square taken as formed: below it the squares may have
/// lost digits to gradual underflow, so the scaled form is used.
const SAFE_MEAN_SQUARE: f64 = f64::MIN_POSITIVE / f64::EPSILON;

/// `sqrt( sum_j w(j) t(j)^2 / divisor )` over `j < n`.
///
/// The textbook sum, bit for bit, when it and its mean are finite and at
/// least [`SAFE_MEAN_SQUARE`] (all ordinary data); otherwise, as LAPACK's
/// `dnrm2` does, the terms divided by their largest magnitude and the
/// weights by theirs, squared, summed and scaled back, so a residual of
/// 1e-302 gives 1e-302, not 0, and one of 1e200 not infinity. A NaN term
/// gives NaN, as in the textbook sum.
fn root_mean_square(
    n: usize,
    weight: impl Fn(usize) -> f64,
    term: impl Fn(usize) -> f64,
    divisor: f64,
) -> f64 {
    let plain: f64 = (0..n)
        .map(|j| {
            let t = term(j);
            weight(j) * t * t
        })
        .sum();
    let mean = plain / divisor;
    if plain.is_nan() || (plain.is_finite() && mean.is_finite() && mean >= SAFE_MEAN_SQUARE) {
        return mean.sqrt();
    }
    let live = |j: &usize| weight(*j) != 0.0;
    let tmax = (0..n)
        .filter(live)
        .map(|j| term(j).abs())
        .fold(0.0, f64::max);
    let wmax = (0..n)
        .filter(live)
        .map(|j| weight(j).abs())
        .fold(0.0, f64::max);
    if tmax == 0.0 || !tmax.is_finite() || !wmax.is_finite() {
        return if tmax == 0.0 { 0.0 } else { f64::INFINITY };
    }
    let scaled: f64 = (0..n)
        .filter(live)
        .map(|j| {
            let t = term(j) / tmax;
            (weight(j) / wmax) * t * t
        })
        .sum();
    // divisor / wmax, then the square root, so neither factor overflows.
    tmax * (scaled / (divisor / wmax)).sqrt()
}

/// A metric's value over all channels and per channel.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct MetricValue {
    /// Over all channels (squared terms averaged over channels).
    pub total: f64,
    /// Per channel.
    pub per_channel: Vec<f64>,
}

fn check(measured: &[f64], model: &[f64], n: usize, other: &[&[f64]]) -> Result<usize, CoreError> {
    if n == 0 {
        return Err(CoreError::Empty { what: "sample set" });
    }
    if measured.len() != model.len() {
        return Err(CoreError::LengthMismatch {
            what: "measured vs model values",
            left: measured.len(),
            right: model.len(),
        });
    }
    if !measured.len().is_multiple_of(n) {
        return Err(CoreError::LengthMismatch {
            what: "values vs samples x channels",
            left: measured.len(),
            right: n,
        });
    }
    for o in other {
        if o.len() != n {
            return Err(CoreError::LengthMismatch {
                what: "per-sample array vs samples",
                left: o.len(),
                right: n,
            });
        }
    }
    Ok(measured.len() / n)
}

/// Weighted root-mean-square of per-sample terms `t(c, j)` per channel, and the
/// total `sqrt(mean_c E_c^2)`.
fn weighted_rms(
    nc: usize,
    weights: &[f64],
    term: impl Fn(usize, usize) -> f64,
) -> Result<MetricValue, CoreError> {
    let n = weights.len();
    let wsum: f64 = weights.iter().sum();
    if !(wsum > 0.0) {
        return Err(CoreError::InvalidOption {
            name: "weights",
            value: wsum,
            reason: "the weights must have a positive sum",
        });
    }
    let per_channel: Vec<f64> = (0..nc)
        .map(|c| root_mean_square(n, |j| weights[j], |j| term(c, j), wsum))
        .collect();
    let total = channel_total(&per_channel);
    Ok(MetricValue { total, per_channel })
}

/// `sqrt(mean_c E_c^2)`.
fn channel_total(per_channel: &[f64]) -> f64 {
    root_mean_square(
        per_channel.len(),
        |_| 1.0,
        |c| per_channel[c],
        per_channel.len() as f64,
    )
}

/// Ngan et al. (2005) / Kurt (2007) L2 metric:
/// `E_c = sqrt( sum_j w_j (cos_i_j (R_cj - M_cj))^2 / sum_j w_j )`,
/// total `sqrt(mean_c E_c^2)`. `w_j = 1` for scattered data, the solid angle
/// for gridded data.
pub fn ngan_l2(
    measured: &[f64],
    model: &[f64],
    cos_i: &[f64],
    weights: &[f64],
) -> Result<MetricValue, CoreError> {
    let n = cos_i.len();
    let nc = check(measured, model, n, &[weights])?;
    weighted_rms(nc, weights, |c, j| {
        cos_i[j] * (measured[c * n + j] - model[c * n + j])
    })
}

/// Lafortune et al. (1997) metric: residuals multiplied by `cos_i cos_o`,
/// `sqrt( sum_j w_j (cos_i cos_o (R - M))^2 / sum_j w_j )`.
pub fn lafortune_l2(
    measured: &[f64],
    model: &[f64],
    cos_i: &[f64],
    cos_o: &[f64],
    weights: &[f64],
) -> Result<MetricValue, CoreError> {
    let n = cos_i.len();
    let nc = check(measured, model, n, &[cos_o, weights])?;
    weighted_rms(nc, weights, |c, j| {
        cos_i[j] * cos_o[j] * (measured[c * n + j] - model[c * n + j])
    })
}

/// Log metric (Matusik et al. 2003; poor near zero, Ngan):
/// `sqrt( sum_j w_j (ln(1 + R cos_i) - ln(1 + M cos_i))^2 / sum_j w_j )`.
/// Arguments of the logarithm are clamped at `-1 + 1e-12` so slightly
/// negative measured values stay finite.
pub fn log_metric(
    measured: &[f64],
    model: &[f64],
    cos_i: &[f64],
    weights: &[f64],
) -> Result<MetricValue, CoreError> {
    let n = cos_i.len();
    let nc = check(measured, model, n, &[weights])?;
    let lg = |x: f64| (x.max(-1.0 + 1e-12)).ln_1p();
    weighted_rms(nc, weights, |c, j| {
        lg(measured[c * n + j] * cos_i[j]) - lg(model[c * n + j] * cos_i[j])
    })
}

/// Cube-root metric (Forés, Ferwerda & Gu 2012, "Toward a perceptually
/// based metric for BRDF modeling"):
/// `sqrt( sum_j w_j (cbrt(R cos_i + d) - cbrt(M cos_i + d))^2 / sum_j w_j )`,
/// negative values clamped at 0; the offset `d >= 0` keeps the fitted
/// objective differentiable at 0 (the fit uses `1e-6 p99(R cos_i)`).
pub fn cube_root_metric(
    measured: &[f64],
    model: &[f64],
    cos_i: &[f64],
    weights: &[f64],
    d: f64,
) -> Result<MetricValue, CoreError> {
    let n = cos_i.len();
    let nc = check(measured, model, n, &[weights])?;
    let cr = |x: f64| (x.max(0.0) + d).cbrt();
    weighted_rms(nc, weights, |c, j| {
        cr(measured[c * n + j] * cos_i[j]) - cr(model[c * n + j] * cos_i[j])
    })
}

/// Relative metric: `sqrt( sum_j w_j (s_j (R - M))^2 / sum_j w_j )` with
/// row scales `s_j` (`1 / (mean_c R_j + e)` times `sqrt(w_j)` in the fit, so
/// each sample counts by its ratio to the data).
pub fn relative_metric(
    measured: &[f64],
    model: &[f64],
    scales: &[f64],
    weights: &[f64],
) -> Result<MetricValue, CoreError> {
    let n = scales.len();
    let nc = check(measured, model, n, &[weights])?;
    let wsum: f64 = weights.iter().sum();
    if !(wsum > 0.0) {
        return Err(CoreError::InvalidOption {
            name: "weights",
            value: wsum,
            reason: "the weights must have a positive sum",
        });
    }
    // The scales already hold sqrt(w): average their squared rows with
    // unit weights, normalised by the weights' sum.
    let k = (n as f64 / wsum).sqrt();
    weighted_rms(nc, &vec![1.0; n], |c, j| {
        k * scales[j] * (measured[c * n + j] - model[c * n + j])
    })
}

/// Sopp (2017) error: residuals `r_j = w_j cos_i_j (R_j - M_j) / sum_k w_k`,
/// error `sqrt(sum_j r_j^2)` per channel. With `weighted = false` every
/// `w_j = 1` (so `r_j = cos_i (R - M) / n`): Sopp reports this unweighted
/// value for both weighted and unweighted fits so they can be compared.
/// Total: `sqrt(mean_c E_c^2)`.
pub fn sopp_error(
    measured: &[f64],
    model: &[f64],
    cos_i: &[f64],
    weights: &[f64],
    weighted: bool,
) -> Result<MetricValue, CoreError> {
    let n = cos_i.len();
    let nc = check(measured, model, n, &[weights])?;
    let w = |j: usize| if weighted { weights[j] } else { 1.0 };
    let wsum: f64 = (0..n).map(w).sum();
    if !(wsum > 0.0) {
        return Err(CoreError::InvalidOption {
            name: "weights",
            value: wsum,
            reason: "the weights must have a positive sum",
        });
    }
    let per_channel: Vec<f64> = (0..nc)
        .map(|c| {
            // w_j / sum w first: w_j (R - M) alone overflows for weights
            // and data of 1e300.
            let r = |j: usize| w(j) / wsum * (cos_i[j] * (measured[c * n + j] - model[c * n + j]));
            root_mean_square(n, |_| 1.0, r, 1.0)
        })
        .collect();
    let total = channel_total(&per_channel);
    Ok(MetricValue { total, per_channel })
}

/// Root mean square difference `sqrt(mean (a - b)^2)`.
pub fn rms(a: &[f64], b: &[f64]) -> Result<f64, CoreError> {
    if a.is_empty() {
        return Err(CoreError::Empty { what: "array" });
    }
    if a.len() != b.len() {
        return Err(CoreError::LengthMismatch {
            what: "rms arrays",
            left: a.len(),
            right: b.len(),
        });
    }
    Ok(root_mean_square(
        a.len(),
        |_| 1.0,
        |j| a[j] - b[j],
        a.len() as f64,
    ))
}

/// Relative RMS `sqrt( sum (a - b)^2 / sum b^2 )`, `b` the reference.
/// `+inf` when the reference is all zero and `a` is not; `0` when both are.
pub fn relative_rms(a: &[f64], reference: &[f64]) -> Result<f64, CoreError> {
    let num = rms(a, reference)?;
    let den = root_mean_square(
        reference.len(),
        |_| 1.0,
        |j| reference[j],
        reference.len() as f64,
    );
    Ok(if den > 0.0 {
        num / den
    } else if num == 0.0 {
        0.0
    } else {
        f64::INFINITY
    })
}

/// Peak signal-to-noise ratio between two images (any layout, same length):
/// `PSNR = 10 log10(peak^2 / MSE)` in dB; `+inf` for identical images.
pub fn psnr(a: &[f64], b: &[f64], peak: f64) -> Result<f64, CoreError> {
    if !(peak > 0.0 && peak.is_finite()) {
        return Err(CoreError::InvalidOption {
            name: "peak",
            value: peak,
            reason: "the peak must be positive and finite",
        });
    }
    let r = rms(a, b)?;
    Ok(if r == 0.0 {
        f64::INFINITY
    } else {
        20.0 * (peak / r).log10()
    })
}
