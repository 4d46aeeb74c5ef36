//! Scale invariance of a fit: data of magnitude `1e-300` or `1e300` (or
//! weights of `1e300`) fit like unit data. Before the fit, the values are
//! divided by their largest magnitude and the weights by their largest
//! value, so the solver sees numbers of at most 1 (squares of `1e300`
//! overflow, squares of `1e-300` underflow, and the solvers' tolerances
//! are meant for numbers near 1). Data `c D`, with `D` of largest
//! magnitude 1, become `D` up to one rounding, so they fit in the same
//! iterations to the same parameters times `c` (bit for bit when `c` is
//! a power of two). Ordinary data and weights (largest magnitude within
//! `2^+-16`) are left untouched, so the study's fits do not change.
//!
//! Values scale only where the model does: for a model that is
//! homogeneous of degree one in its linear parameters (`f(s a, q) = s
//! f(a, q)`, checked numerically on the data's directions), the fit of
//! `D / s` with the linear parameters' boxes divided by `s` gives the
//! fit of `D` after multiplying the linear parameters by `s`. The box of
//! the linear parameters moves with the data ([`BoxedModel::scaled`]), so a box
//! that the unscaled fit would reach (`kd <= 1` for data of `1e300`) is
//! reached by the scaled fit too. The log objective is not scale
//! invariant (`ln(1 + R cos)`), so its values are never scaled.
//!
//! Weights enter every objective either normalised by their sum or as a
//! common factor of all residuals, so dividing them changes nothing but
//! the magnitude the solver sees.

use brdf_core::{DirPairs, ParamSpec, Parametric, SampleSet};

use crate::FitError;
use crate::boxed::BoxedModel;
use crate::objective::Objective;
use crate::summary::FitSummary;

/// Binary exponents within this bound are left unscaled.
const UNSCALED_EXPONENT: i32 = 16;

/// The scale factors of one fit: values and weights were divided by them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DataScale {
    /// Factor of the values (their largest magnitude; 1 when not scaled).
    pub value: f64,
    /// Factor of the weights (their largest value; 1 when not scaled).
    pub weight: f64,
}

impl DataScale {
    /// No scaling.
    pub const IDENTITY: DataScale = DataScale {
        value: 1.0,
        weight: 1.0,
    };

    /// The scales for `data` fitted with `model` under `objective`.
    pub fn choose(data: &SampleSet, model: &dyn Parametric, objective: Objective) -> Self {
        let largest_value = (0..data.channels())
            .flat_map(|c| data.channel(c).iter())
            .filter(|x| x.is_finite())
            .fold(0.0f64, |m, x| m.max(x.abs()));
        let largest_weight = data.weights().iter().fold(0.0f64, |m, w| m.max(*w));
        let value = if !objective.is_transformed() && is_homogeneous(model, data.pairs()) {
            extreme_or_one(largest_value)
        } else {
            1.0
        };
        DataScale {
            value,
            weight: extreme_or_one(largest_weight),
        }
    }

    /// True when nothing is scaled.
    pub fn is_identity(&self) -> bool {
        *self == Self::IDENTITY
    }

    /// The scaling in words, for the report.
    pub fn describe(&self) -> String {
        format!(
            "values divided by {} and weights by {} internally, the result scaled back",
            brdf_io::error::short(self.value),
            brdf_io::error::short(self.weight)
        )
    }

    /// `data` with its values and weights divided by the scales.
    pub fn apply(&self, data: &SampleSet) -> Result<SampleSet, FitError> {
        let mut out = SampleSet::new(
            data.name.clone(),
            data.provenance.clone(),
            data.channel_names.clone(),
        );
        let p = data.pairs();
        let mut row = vec![0.0; data.channels()];
        for j in 0..data.len() {
            for (c, v) in row.iter_mut().enumerate() {
                *v = data.channel(c)[j] / self.value;
            }
            out.push(
                &brdf_core::Direction::new_unchecked(p.l(j)),
                &brdf_core::Direction::new_unchecked(p.v(j)),
                &row,
                data.weights()[j] / self.weight,
            )?;
        }
        Ok(out)
    }

    /// Undo the value scale in a summary of the scaled fit: linear
    /// parameters, their standard errors and every error metric (all are
    /// linear in the values and invariant in the weights) are multiplied
    /// by the value scale. The log objective is never value-scaled.
    pub fn unscale_summary(&self, summary: &mut FitSummary, specs: &[ParamSpec]) {
        let s = self.value;
        if s == 1.0 {
            return;
        }
        for (p, spec) in summary.parameters.iter_mut().zip(specs) {
            if spec.linear {
                p.value *= s;
                p.std_error = p.std_error.map(|e| e * s);
            }
        }
        summary.error *= s;
        summary.ngan_l2 *= s;
        for e in summary
            .error_per_channel
            .iter_mut()
            .chain(summary.ngan_l2_per_channel.iter_mut())
        {
            *e *= s;
        }
    }

    /// The parameters of the unscaled model from those of the scaled fit,
    /// kept inside the model's box (a bound divided and multiplied again
    /// may differ from the bound by a rounding).
    pub fn unscale_params(&self, p: &[f64], specs: &[ParamSpec]) -> Vec<f64> {
        p.iter()
            .zip(specs)
            .map(|(x, s)| {
                if s.linear {
                    (x * self.value).clamp(s.lower, s.upper)
                } else {
                    *x
                }
            })
            .collect()
    }
}

/// `x` itself when it is finite, positive and outside `2^+-16`, else 1.
fn extreme_or_one(x: f64) -> f64 {
    if !(x.is_finite() && x > 0.0) {
        return 1.0;
    }
    if (x.log2().floor() as i32).abs() <= UNSCALED_EXPONENT {
        return 1.0;
    }
    x
}

/// Whether `f(2 a, q) = 2 f(a, q)` for the linear parameters `a` (at
/// mid-box values) and the default non-linear `q`, on up to 64 of the
/// data's direction pairs. Models without linear parameters, and models
/// whose linear parameters interact (Oren-Nayar's squared `kd`), are not.
fn is_homogeneous(model: &dyn Parametric, pairs: &DirPairs) -> bool {
    let specs = model.param_specs();
    if !specs.iter().any(|s| s.linear) {
        return false;
    }
    let mut p: Vec<f64> = specs.iter().map(|s| s.default).collect();
    for (k, s) in specs.iter().enumerate() {
        if s.linear {
            p[k] = 0.25 * (1 + k % 3) as f64;
        }
    }
    let doubled: Vec<f64> = p
        .iter()
        .zip(specs)
        .map(|(x, s)| if s.linear { 2.0 * x } else { *x })
        .collect();
    let nc = model.channels();
    let (mut a, mut b) = (vec![0.0; nc], vec![0.0; nc]);
    let mut largest = 0.0f64;
    for j in (0..pairs.len()).step_by(pairs.len().div_ceil(64).max(1)) {
        let (l, v) = (pairs.l(j), pairs.v(j));
        model.eval_at(&p, &l, &v, &mut a);
        model.eval_at(&doubled, &l, &v, &mut b);
        for c in 0..nc {
            if !(a[c].is_finite() && b[c].is_finite()) {
                return false;
            }
            largest = largest.max(a[c].abs());
            if (b[c] - 2.0 * a[c]).abs() > 1e-12 * b[c].abs().max(1e-300) {
                return false;
            }
        }
    }
    largest > 0.0
}

/// Fit `model` to `data` through the scaling: choose the scales, wrap the
/// model if its values scale, run `fit` on the scaled data (`fit` gets the
/// model, the data it sees and the value scale), and return the unwrapped
/// model at the unscaled parameters, the unscaled summary and the scales.
pub fn fit_scaled<F>(
    model: Box<dyn Parametric>,
    data: &SampleSet,
    objective: Objective,
    fit: F,
) -> Result<(Box<dyn Parametric>, FitSummary, DataScale), FitError>
where
    F: FnOnce(&mut dyn Parametric, &SampleSet, f64) -> Result<FitSummary, FitError>,
{
    let scale = DataScale::choose(data, model.as_ref(), objective);
    if scale.is_identity() {
        let mut model = model;
        let summary = fit(model.as_mut(), data, 1.0)?;
        return Ok((model, summary, scale));
    }
    let scaled = scale.apply(data)?;
    let (model, mut summary) = if scale.value != 1.0 {
        let mut wrapped = BoxedModel::scaled(model, scale.value);
        let mut summary = fit(&mut wrapped, &scaled, scale.value)?;
        let p = wrapped.params().to_vec();
        for ((fp, spec), v) in summary
            .parameters
            .iter_mut()
            .zip(wrapped.param_specs())
            .zip(&p)
        {
            if spec.linear {
                fp.at_bound = bound_status(*v, spec);
            }
        }
        let mut inner = wrapped.into_inner();
        let p = scale.unscale_params(&p, inner.param_specs());
        inner.set_params(&p)?;
        (inner, summary)
    } else {
        let mut model = model;
        let summary = fit(model.as_mut(), &scaled, 1.0)?;
        (model, summary)
    };
    scale.unscale_summary(&mut summary, model.param_specs());
    for (fp, v) in summary.parameters.iter_mut().zip(model.params()) {
        fp.value = *v;
    }
    Ok((model, summary, scale))
}

/// Whether `v` sits on a bound of `spec`'s box (scaled domain). The
/// tolerance is relative to the value, floored at the box width up to 1:
/// the pipeline's test floors at 1, which would put every linear
/// parameter of a box `[0, 1e-300]` on its lower bound.
fn bound_status(v: f64, spec: &ParamSpec) -> Option<String> {
    let width = spec.upper - spec.lower;
    let tol = 1e-10 * v.abs().max(width.min(1.0));
    if spec.lower.is_finite() && v - spec.lower <= tol {
        Some("lower".into())
    } else if spec.upper.is_finite() && spec.upper - v <= tol {
        Some("upper".into())
    } else {
        None
    }
}

/// Ngan's L2 of `model` on `data` computed on values divided by a power
/// of two near their largest (and weights by their largest), then scaled
/// back: finite for data whose squares overflow (`1e300` fitted under the
/// log objective, which is never value-scaled).
pub fn ngan_l2_rescaled(
    model: &dyn Parametric,
    data: &SampleSet,
) -> Result<brdf_core::MetricValue, FitError> {
    let values = data.values_channel_major();
    let largest = values
        .iter()
        .filter(|x| x.is_finite())
        .fold(0.0f64, |m, x| m.max(x.abs()));
    let s = if largest > 0.0 {
        2f64.powi(largest.log2().floor() as i32)
    } else {
        1.0
    };
    let mut fitted = vec![0.0; values.len()];
    model.eval_batch_at(model.params(), data.pairs(), &mut fitted);
    let wmax = data.weights().iter().fold(0.0f64, |m, w| m.max(*w));
    let w: Vec<f64> = data
        .weights()
        .iter()
        .map(|x| if wmax > 0.0 { x / wmax } else { *x })
        .collect();
    let v: Vec<f64> = values.iter().map(|x| x / s).collect();
    let f: Vec<f64> = fitted.iter().map(|x| x / s).collect();
    let mut m = brdf_core::metrics::ngan_l2(&v, &f, &data.pairs().lz, &w)?;
    m.total *= s;
    for x in &mut m.per_channel {
        *x *= s;
    }
    Ok(m)
}
