//! Robust regression by iteratively reweighted least squares, as MATLAB's
//! `robustfit` (used by Kurt 2007), with the scale conventions of
//! `fitting.md` selectable by name:
//!
//! 1. `b` = ordinary least squares (column-pivoted QR, [`crate::lstsq`]).
//! 2. Leverages `h` = diagonal of the hat matrix of the unweighted design,
//!    capped at `0.9999`, computed once from its QR (not for statsmodels).
//! 3. Loop: `r = y - X b`; `r_adj = r / sqrt(1 - h)`; scale `s`;
//!    `u = r_adj / (tune s)`; `w = psi_weight(u)`; `b` = weighted least
//!    squares with `w`. Stop when every
//!    `|b - b_old| <= sqrt(eps) max(|b|, |b_old|)` or after the cap (default 50).
//!
//! Scale conventions ([`ScaleConvention`]); `a` = `|r_adj|` sorted with the
//! `p - 1` smallest dropped (`p` = number of coefficients):
//! - `Matlab2004`: MAD about the median of `a`, `median(|a - median(a)|) /
//!   0.6745`; if zero, `0.5 mean(|r_adj|)`;
//! - `Matlab2011`: about zero, `median(a) / 0.6745`, floored at
//!   `1e-6 std(y)`;
//! - `Statsmodels`: `median(|r|) / 0.6745` without leverage adjustment, as
//!   statsmodels `RLM` with `scale_est='mad'` computes it (its
//!   `_estimate_scale` calls `scale.mad(resid, center=0)`; fitting.md's
//!   `median(|r - median(r)|)` is the `mad` function's default centring,
//!   which `RLM` does not use).
//!
//! A zero scale (an exact fit of all but a few points) never divides by
//! zero: the conventions' fallbacks apply, and if the scale is still zero
//! the fit is exact and IRLS stops with the current `b`.

use faer::{Mat, MatRef};

use crate::linear::leverages;
use crate::robust_weights::RobustWeight;
use crate::{LstsqMethod, SolveError, lstsq};

/// How the residual scale is estimated.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum ScaleConvention {
    /// `robustfit` of the 2004 era (closest to Kurt's fits) (default).
    #[default]
    Matlab2004,
    /// `robustfit` 2011 and later.
    Matlab2011,
    /// statsmodels `RLM` (no leverage adjustment).
    Statsmodels,
}

impl ScaleConvention {
    /// Name as used on the command line and in reports.
    pub fn name(self) -> &'static str {
        match self {
            ScaleConvention::Matlab2004 => "matlab2004",
            ScaleConvention::Matlab2011 => "matlab2011",
            ScaleConvention::Statsmodels => "statsmodels",
        }
    }
}

/// Options of [`irls`].
#[derive(Clone, Debug, PartialEq)]
pub struct IrlsOptions {
    /// Weight function (default bisquare).
    pub weight: RobustWeight,
    /// Tuning constant; `None` uses the weight function's default.
    pub tune: Option<f64>,
    /// Scale convention (default Matlab2004).
    pub scale: ScaleConvention,
    /// Iteration cap (default 50).
    pub max_iterations: usize,
}

impl Default for IrlsOptions {
    fn default() -> Self {
        Self {
            weight: RobustWeight::Bisquare,
            tune: None,
            scale: ScaleConvention::Matlab2004,
            max_iterations: 50,
        }
    }
}

/// Result of [`irls`].
#[derive(Clone, Debug)]
pub struct IrlsSolution {
    /// Coefficients.
    pub coef: Vec<f64>,
    /// Final robust weights, one per observation.
    pub weights: Vec<f64>,
    /// Reweighting iterations done.
    pub iterations: usize,
    /// Whether the coefficient test held (false: the cap was reached).
    pub converged: bool,
    /// The final scale estimate.
    pub scale: f64,
    /// The convention used.
    pub convention: ScaleConvention,
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    let n = v.len();
    if n == 0 {
        0.0
    } else if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

fn std_dev(y: &[f64]) -> f64 {
    let n = y.len() as f64;
    let m = y.iter().sum::<f64>() / n;
    (y.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (n - 1.0).max(1.0)).sqrt()
}

/// The scale of residuals `r` (already leverage-adjusted where the
/// convention asks) for `p` coefficients.
pub fn robust_scale(r: &[f64], p: usize, y: &[f64], convention: ScaleConvention) -> f64 {
    match convention {
        ScaleConvention::Statsmodels => {
            let mut a: Vec<f64> = r.iter().map(|v| v.abs()).collect();
            median(&mut a) / 0.6745
        }
        ScaleConvention::Matlab2004 | ScaleConvention::Matlab2011 => {
            let mut a: Vec<f64> = r.iter().map(|v| v.abs()).collect();
            a.sort_by(|x, y| x.total_cmp(y));
            let drop = p.saturating_sub(1).min(a.len().saturating_sub(1));
            let mut kept = a[drop..].to_vec();
            if convention == ScaleConvention::Matlab2011 {
                (median(&mut kept) / 0.6745).max(1e-6 * std_dev(y))
            } else {
                let med = median(&mut kept.clone());
                let mut dev: Vec<f64> = kept.iter().map(|v| (v - med).abs()).collect();
                let s = median(&mut dev) / 0.6745;
                if s > 0.0 {
                    s
                } else {
                    0.5 * r.iter().map(|v| v.abs()).sum::<f64>() / r.len() as f64
                }
            }
        }
    }
}

/// Robust fit of `y ~ X b`.
pub fn irls(
    x: MatRef<'_, f64>,
    y: &[f64],
    options: &IrlsOptions,
) -> Result<IrlsSolution, SolveError> {
    let (m, p) = (x.nrows(), x.ncols());
    if y.len() != m {
        return Err(SolveError::Dimension {
            what: "rows of X vs length of y",
            left: m,
            right: y.len(),
        });
    }
    if m < p {
        return Err(SolveError::Dimension {
            what: "fewer observations than coefficients",
            left: m,
            right: p,
        });
    }
    let tune = options.tune.unwrap_or(options.weight.default_tune());
    if !(tune > 0.0 && tune.is_finite()) {
        return Err(SolveError::InvalidOption {
            name: "tune",
            value: tune,
            reason: "the tuning constant must be finite and > 0",
        });
    }
    let ym = Mat::from_fn(m, 1, |i, _| y[i]);
    let solve = |w: Option<&[f64]>| -> Result<Vec<f64>, SolveError> {
        let s = lstsq(x, ym.as_ref(), w, LstsqMethod::PivotedQr)?;
        Ok((0..p).map(|k| s.x[(k, 0)]).collect())
    };
    let mut b = solve(None)?;
    let h: Vec<f64> = if options.scale == ScaleConvention::Statsmodels {
        vec![0.0; m]
    } else {
        leverages(x)?.into_iter().map(|v| v.min(0.9999)).collect()
    };
    let adj: Vec<f64> = h.iter().map(|h| 1.0 / (1.0 - h).sqrt()).collect();
    let mut w = vec![1.0; m];
    let mut scale = 0.0;
    let mut r = vec![0.0; m];
    let tol = f64::EPSILON.sqrt();
    for it in 1..=options.max_iterations {
        for i in 0..m {
            let fit: f64 = (0..p).map(|k| x[(i, k)] * b[k]).sum();
            r[i] = (y[i] - fit) * adj[i];
        }
        scale = robust_scale(&r, p, y, options.scale);
        if !(scale > 0.0) {
            // An exact fit of the weighted points: nothing to reweight; the
            // weights that produced it are kept.
            return Ok(IrlsSolution {
                coef: b,
                weights: w,
                iterations: it - 1,
                converged: true,
                scale: 0.0,
                convention: options.scale,
            });
        }
        for i in 0..m {
            w[i] = options.weight.weight(r[i] / (tune * scale));
        }
        if w.iter().all(|v| *v == 0.0) {
            return Err(SolveError::InvalidOption {
                name: "tune",
                value: tune,
                reason: "every observation got weight zero",
            });
        }
        let b_new = solve(Some(&w))?;
        let done = b_new
            .iter()
            .zip(&b)
            .all(|(n, o)| (n - o).abs() <= tol * n.abs().max(o.abs()));
        b = b_new;
        if done {
            return Ok(IrlsSolution {
                coef: b,
                weights: w,
                iterations: it,
                converged: true,
                scale,
                convention: options.scale,
            });
        }
    }
    Ok(IrlsSolution {
        coef: b,
        weights: w,
        iterations: options.max_iterations,
        converged: false,
        scale,
        convention: options.scale,
    })
}
