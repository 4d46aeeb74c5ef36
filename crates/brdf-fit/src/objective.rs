//! The fitting objectives: the row scalings and residual transforms of
//! `fitting.md`, and each one's error of a fit.
//!
//! A row-scaling objective (Ngan, Sopp, Lafortune, relative) keeps the
//! residual linear in the linear parameters, so the pipeline projects those
//! out; a transforming one (log, cube root, image) is fitted on all
//! parameters, its residual formed by [`crate::transformed_rows`] (or by
//! [`crate::image_objective`] for the image objective).

use brdf_core::metrics::{
    cube_root_metric, lafortune_l2, log_metric, ngan_l2, relative_metric, sopp_error,
};
use brdf_core::{MetricValue, SampleSet};

use crate::FitError;

/// The fitting objective (see `fitting.md`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Objective {
    /// Ngan's / Kurt's L2: rows `sqrt(w) cos_i (R - M)`.
    Ngan,
    /// Sopp's: rows `w cos_i (R - M) / sum w` (weighting on) or
    /// `cos_i (R - M) / n` (off).
    Sopp {
        /// Solid-angle weighting ("Gewichtung").
        weighted: bool,
    },
    /// Lafortune et al.: rows `sqrt(w) cos_i cos_o (R - M)`.
    Lafortune,
    /// Matusik's log: `ln(1 + M cos_i) - ln(1 + R cos_i)`.
    Log,
    /// Forés et al.'s cube root (2012, "BRDF parameter estimation"):
    /// `sqrt(w) (cbrt(M cos_i + d) - cbrt(R cos_i + d))`, `d = 1e-6 p99(R
    /// cos_i)` keeping the derivative finite at 0. Like lightness, the cube
    /// root compresses the highlight so the body colour weighs.
    CubeRoot,
    /// Relative error: rows `sqrt(w) (M - R) / (mean_c R + e)`, `e = 1e-2
    /// median(mean_c R)`: every sample counts by its ratio to the data, so
    /// the dim body weighs as much as the peak. A row scaling, so the linear
    /// parameters are still projected out.
    Relative,
    /// The image objective ([`crate::image_objective`]): log residuals of
    /// the sphere's pixels under the standard light sets of `brdf-render`,
    /// for data that can be evaluated at any direction pair. Fitted from
    /// the best BRDF-space fits (see [`crate::appearance`]).
    Image,
}

impl Objective {
    /// Parse `ngan|sopp|sopp-unweighted|lafortune|log`.
    pub fn parse(s: &str) -> Result<Self, FitError> {
        Ok(match s {
            "ngan" => Objective::Ngan,
            "sopp" => Objective::Sopp { weighted: true },
            "sopp-unweighted" => Objective::Sopp { weighted: false },
            "lafortune" => Objective::Lafortune,
            "log" => Objective::Log,
            "cube-root" | "cuberoot" | "cube_root" => Objective::CubeRoot,
            "relative" => Objective::Relative,
            "image" => Objective::Image,
            other => {
                return Err(FitError::UnknownChoice {
                    option: "metric",
                    value: other.to_string(),
                    choices: "ngan, sopp, sopp-unweighted, lafortune, log, cube-root, relative or image",
                });
            }
        })
    }

    /// Name in reports.
    pub fn name(self) -> &'static str {
        match self {
            Objective::Ngan => "ngan",
            Objective::Sopp { weighted: true } => "sopp",
            Objective::Sopp { weighted: false } => "sopp-unweighted",
            Objective::Lafortune => "lafortune",
            Objective::Log => "log",
            Objective::CubeRoot => "cube-root",
            Objective::Relative => "relative",
            Objective::Image => "image",
        }
    }

    /// Whether the objective transforms the residual (fitted on all
    /// parameters) rather than scaling its rows.
    pub fn is_transformed(self) -> bool {
        matches!(
            self,
            Objective::Log | Objective::CubeRoot | Objective::Image
        )
    }

    /// Row scales `s_j` (the residual is `s_j (M - R)`); the log objective
    /// uses unit scales and transforms the residual instead.
    pub fn row_scales(self, s: &SampleSet) -> Vec<f64> {
        let p = s.pairs();
        let w = s.weights();
        let n = s.len();
        match self {
            Objective::Ngan => (0..n).map(|j| w[j].sqrt() * p.lz[j]).collect(),
            Objective::Lafortune => (0..n).map(|j| w[j].sqrt() * p.lz[j] * p.vz[j]).collect(),
            Objective::Sopp { weighted: true } => {
                let sw: f64 = w.iter().sum();
                (0..n).map(|j| w[j] * p.lz[j] / sw).collect()
            }
            Objective::Sopp { weighted: false } => (0..n).map(|j| p.lz[j] / n as f64).collect(),
            Objective::Relative => {
                let nc = s.channels();
                let mean: Vec<f64> = (0..n)
                    .map(|j| (0..nc).map(|c| s.channel(c)[j]).sum::<f64>() / nc as f64)
                    .collect();
                let e = relative_floor(&mean);
                (0..n)
                    .map(|j| w[j].sqrt() / (mean[j].max(0.0) + e))
                    .collect()
            }
            Objective::Log | Objective::CubeRoot | Objective::Image => vec![1.0; n],
        }
    }

    /// The objective's error of `fitted` (channel-major) on `s`.
    pub fn error(self, s: &SampleSet, fitted: &[f64]) -> Result<MetricValue, FitError> {
        let m = s.values_channel_major();
        let p = s.pairs();
        Ok(match self {
            Objective::Ngan => ngan_l2(&m, fitted, &p.lz, s.weights())?,
            Objective::Lafortune => lafortune_l2(&m, fitted, &p.lz, &p.vz, s.weights())?,
            Objective::Sopp { weighted } => sopp_error(&m, fitted, &p.lz, s.weights(), weighted)?,
            Objective::Log | Objective::Image => log_metric(&m, fitted, &p.lz, s.weights())?,
            Objective::CubeRoot => {
                cube_root_metric(&m, fitted, &p.lz, s.weights(), cube_root_offset(s))?
            }
            Objective::Relative => {
                let scales = self.row_scales(s);
                relative_metric(&m, fitted, &scales, s.weights())?
            }
        })
    }
}

/// Offset `d` of the cube-root objective: `1e-6 p99(R cos_i)` (1e-300 for
/// all-zero data), so `cbrt'` stays finite at 0.
pub(crate) fn cube_root_offset(s: &SampleSet) -> f64 {
    let n = s.len();
    let mut v: Vec<f64> = (0..s.channels())
        .flat_map(|c| (0..n).map(move |j| (c, j)))
        .map(|(c, j)| (s.channel(c)[j] * s.pairs().lz[j]).abs())
        .filter(|x| x.is_finite())
        .collect();
    v.sort_by(f64::total_cmp);
    let p99 = v
        .get((v.len().saturating_sub(1) * 99) / 100)
        .copied()
        .unwrap_or(0.0);
    (1e-6 * p99).max(1e-300)
}

/// Floor `e` of the relative objective: `1e-2 median(mean_c R)` (1e-300
/// for all-zero data).
fn relative_floor(mean: &[f64]) -> f64 {
    let mut v: Vec<f64> = mean
        .iter()
        .map(|x| x.abs())
        .filter(|x| x.is_finite())
        .collect();
    v.sort_by(f64::total_cmp);
    (1e-2 * v.get(v.len() / 2).copied().unwrap_or(0.0)).max(1e-300)
}
