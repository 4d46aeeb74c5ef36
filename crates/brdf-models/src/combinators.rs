//! Generic combinators that assemble models from named parts.
//!
//! [`DiffuseLobe`] is `f_c = kd_c / pi + ks_c S(L, V; q)`: a Lambertian term
//! and one specular lobe shape `S` with non-linear parameters `q` shared by
//! all channels. `kd` and `ks` (per channel) enter linearly. Phong,
//! Blinn-Phong, Ward and Ward-Duer are such models; each lobe lives in its
//! model's file and implements [`Lobe`].

use std::f64::consts::FRAC_1_PI;

use brdf_core::params::per_channel_specs;
use brdf_core::{Brdf, ParamError, ParamSpec, Parametric};
use nalgebra::Vector3;

/// A specular lobe shape `S(L, V; q)` with its derivatives.
pub trait Lobe: Clone + Send + Sync + 'static {
    /// Catalogue name of the model `kd/pi + ks S`.
    const NAME: &'static str;
    /// Descriptions of the lobe's non-linear parameters `q`.
    fn specs() -> Vec<ParamSpec>;
    /// `S` at `q`, writing `dS/dq_k` into `dq` when it is `Some`. Called only
    /// for directions above the horizon.
    fn shape(q: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, dq: Option<&mut [f64]>) -> f64;
    /// Whether `S(L, V) = S(V, L)`.
    fn reciprocal() -> bool {
        true
    }
}

/// `f_c = kd_c / pi + ks_c S(L, V; q)`.
#[derive(Clone, Debug, PartialEq)]
pub struct DiffuseLobe<S: Lobe> {
    pub(crate) channels: usize,
    specs: Vec<ParamSpec>,
    params: Vec<f64>,
    _lobe: std::marker::PhantomData<S>,
}

impl<S: Lobe> DiffuseLobe<S> {
    /// The model with `channels` channels at its default parameters.
    pub fn with_channels(channels: usize) -> Result<Self, ParamError> {
        if channels == 0 {
            return Err(ParamError::Config {
                model: S::NAME.into(),
                reason: "a model needs at least one channel".into(),
            });
        }
        let mut specs = per_channel_specs("kd", "diffuse albedo", channels, 0.0, 1.0, 0.3);
        specs.extend(per_channel_specs(
            "ks",
            "specular strength",
            channels,
            0.0,
            1.0,
            0.2,
        ));
        specs.extend(S::specs());
        let params = specs.iter().map(|s| s.default).collect();
        Ok(DiffuseLobe {
            channels,
            specs,
            params,
            _lobe: std::marker::PhantomData,
        })
    }

    /// The model with the given per-channel `kd`, `ks` (same length) and lobe
    /// parameters, validated against their boxes.
    pub fn new(kd: &[f64], ks: &[f64], q: &[f64]) -> Result<Self, ParamError> {
        if kd.len() != ks.len() {
            return Err(ParamError::Config {
                model: S::NAME.into(),
                reason: format!("kd has {} channels but ks has {}", kd.len(), ks.len()),
            });
        }
        let mut m = Self::with_channels(kd.len())?;
        let p: Vec<f64> = kd.iter().chain(ks).chain(q).copied().collect();
        m.set_params(&p)?;
        Ok(m)
    }
}

impl<S: Lobe> Brdf for DiffuseLobe<S> {
    fn channels(&self) -> usize {
        self.channels
    }
    fn eval(&self, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        self.eval_at(&self.params, l, v, out)
    }
}

impl<S: Lobe> Parametric for DiffuseLobe<S> {
    brdf_core::param_accessors!();
    fn name(&self) -> &str {
        S::NAME
    }
    fn eval_at(&self, p: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        let nc = self.channels;
        if !(l.z > 0.0 && v.z > 0.0) {
            out[..nc].iter_mut().for_each(|x| *x = 0.0);
            return;
        }
        let s = S::shape(&p[2 * nc..], l, v, None);
        for c in 0..nc {
            out[c] = p[c] * FRAC_1_PI + p[nc + c] * s;
        }
    }
    fn eval_grad_at(
        &self,
        p: &[f64],
        l: &Vector3<f64>,
        v: &Vector3<f64>,
        out: &mut [f64],
        grad: &mut [f64],
    ) {
        let nc = self.channels;
        let np = self.specs.len();
        let nq = np - 2 * nc;
        grad[..nc * np].iter_mut().for_each(|g| *g = 0.0);
        if !(l.z > 0.0 && v.z > 0.0) {
            out[..nc].iter_mut().for_each(|x| *x = 0.0);
            return;
        }
        let mut dq = [0.0; 8];
        let s = S::shape(&p[2 * nc..], l, v, Some(&mut dq[..nq]));
        for c in 0..nc {
            let ks = p[nc + c];
            out[c] = p[c] * FRAC_1_PI + ks * s;
            let row = &mut grad[c * np..(c + 1) * np];
            row[c] = FRAC_1_PI;
            row[nc + c] = s;
            for k in 0..nq {
                row[2 * nc + k] = ks * dq[k];
            }
        }
    }
    fn is_reciprocal(&self) -> bool {
        S::reciprocal()
    }
}

/// `c^n` and `d(c^n)/dn = c^n ln c` for a cosine `c` clamped at 0, computed
/// as `exp(n ln c)` so exponents up to `1e6` neither overflow nor give NaN
/// (`0^n = 0` for every `n`, with derivative 0).
#[inline]
pub fn pow_clamped(c: f64, n: f64) -> (f64, f64) {
    if c <= 0.0 {
        return (0.0, 0.0);
    }
    let lc = c.min(1.0).ln();
    let v = (n * lc).exp();
    (v, v * lc)
}

/// Names the lobe type of a [`DiffuseLobe`] model (used by the catalogue).
pub trait HasLobe {
    /// The lobe.
    type L: Lobe;
}

impl<S: Lobe> HasLobe for DiffuseLobe<S> {
    type L = S;
}
