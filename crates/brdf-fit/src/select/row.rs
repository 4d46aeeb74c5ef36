//! One candidate's outcome ([`SelectRow`]): its Ngan L2 error, SSR and
//! information criteria on the samples it was fitted to, and which stage
//! of the selection it reached.

use brdf_core::SampleSet;
use serde::Serialize;

use super::candidates::stored_numbers;
use crate::summary::FitSummary;

/// One candidate's outcome.
#[derive(Clone, Debug, Serialize)]
pub struct SelectRow {
    /// Label (`lafortune (2 lobes)`, `koenderink order 4`, ...).
    pub label: String,
    /// Catalogue name.
    pub model: String,
    /// Stored numbers `k`.
    pub stored_numbers: usize,
    /// Ngan L2 error on the row's [`samples`](SelectRow::samples): on the
    /// coarse subsample when the row is
    /// [`screened_out`](SelectRow::screened_out), else on all samples.
    pub error: f64,
    /// Residual sum of squares on Ngan's rows (of the same samples as the
    /// error).
    pub ssr: f64,
    /// Akaike's information criterion (NaN, `null` in JSON, for a
    /// screened-out row: criteria compare fits of the same samples).
    pub aic: f64,
    /// Bayes' information criterion (NaN for a screened-out row).
    pub bic: f64,
    /// Fit time in seconds (both stages for a refitted candidate).
    pub seconds: f64,
    /// The solver's termination; for a screened-out row, that it was
    /// screened out on the coarse subsample and why.
    pub termination: String,
    /// Samples the error was computed on.
    pub samples: usize,
    /// Whether the candidate was screened out on the coarse subsample and
    /// never fitted to all samples (its error is the coarse one; it cannot
    /// be chosen).
    pub screened_out: bool,
    /// The candidate's error on the coarse subsample (`None` without a
    /// coarse stage, or when its coarse fit failed).
    pub coarse_error: Option<f64>,
}

impl SelectRow {
    /// A candidate that could not be built or fitted: NaN errors and why.
    pub(super) fn failed(
        label: String,
        name: &str,
        n_params: usize,
        samples: usize,
        why: &dyn std::fmt::Display,
    ) -> Self {
        SelectRow {
            label,
            model: name.to_string(),
            stored_numbers: n_params,
            error: f64::NAN,
            ssr: f64::NAN,
            aic: f64::NAN,
            bic: f64::NAN,
            seconds: 0.0,
            termination: format!("failed: {why}"),
            samples,
            screened_out: false,
            coarse_error: None,
        }
    }

    /// The row of a fit `r` of a model of `name` with `n_params`
    /// parameters to `data`. AIC and BIC assume Gaussian residuals on
    /// Ngan's scaled rows: `AIC = n ln(SSR/n) + 2k`, `BIC = n ln(SSR/n) +
    /// k ln n`, `n` = samples x channels, `k` = stored numbers.
    pub(super) fn fitted(
        label: String,
        name: &str,
        n_params: usize,
        data: &SampleSet,
        r: &FitSummary,
    ) -> Self {
        let n = (data.len() * data.channels()) as f64;
        let k = stored_numbers(name, n_params);
        // SSR on Ngan's rows: E^2 times the weight sum (per channel averaged).
        let wsum: f64 = data.weights().iter().sum();
        let ssr = r.ngan_l2 * r.ngan_l2 * wsum * data.channels() as f64;
        // ln(SSR / n) from the error itself: SSR of data near 1e300
        // overflows, its logarithm does not. The error is floored at the
        // data's rounding level (an exact fit's error is 0): a floor at
        // the smallest normal number instead cut every candidate's
        // ln(SSR / n) alike on data of 1e-300, and AIC and BIC then ranked
        // the candidates by their stored numbers alone.
        let e = if r.ngan_l2.is_nan() {
            f64::NAN
        } else {
            r.ngan_l2.max(rounding_level(data))
        };
        let ll = n * (2.0 * e.ln() + (wsum * data.channels() as f64 / n).ln());
        SelectRow {
            label,
            model: name.to_string(),
            stored_numbers: k,
            error: r.ngan_l2,
            ssr,
            aic: ll + 2.0 * k as f64,
            bic: ll + k as f64 * n.ln(),
            seconds: r.seconds,
            termination: r.termination.to_string(),
            samples: data.len(),
            screened_out: false,
            coarse_error: None,
        }
    }

    /// This coarse row, screened out: it keeps its coarse error and says
    /// so (`of` = all samples, `bar` = the error it had to reach).
    pub(super) fn screened(self, of: usize, bar: f64) -> Self {
        SelectRow {
            aic: f64::NAN,
            bic: f64::NAN,
            termination: format!(
                "screened out on the coarse subsample ({} of {of} samples): coarse error {:.4e} > {:.4e}; coarse fit: {}",
                self.samples, self.error, bar, self.termination
            ),
            screened_out: true,
            coarse_error: Some(self.error),
            ..self
        }
    }
}

/// The error of an exact fit to `data` at rounding: `eps` times the
/// largest finite magnitude of the data (the smallest normal number for
/// data that are all 0).
fn rounding_level(data: &SampleSet) -> f64 {
    let largest = (0..data.channels())
        .flat_map(|c| data.channel(c).iter())
        .filter(|x| x.is_finite())
        .fold(0.0f64, |m, x| m.max(x.abs()));
    if largest > 0.0 {
        f64::EPSILON * largest
    } else {
        f64::MIN_POSITIVE
    }
}
