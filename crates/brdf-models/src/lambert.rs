//! Lambert (1760): the ideal diffuse reflector.
//!
//! `f(L, V) = kd / pi` above the horizon, 0 below.
//!
//! | parameter | meaning | default box | linear |
//! | --- | --- | --- | --- |
//! | `kd` (per channel) | diffuse albedo | `[0, 1]` | yes |
//!
//! Properties: reciprocal; non-negative; directional albedo is exactly `kd`,
//! so energy conserving for `kd <= 1`.
//!
//! Reference: J. H. Lambert, *Photometria*, 1760.
//!
//! ```
//! use brdf_core::Brdf;
//! use brdf_models::Lambert;
//! use nalgebra::Vector3;
//! let m = Lambert::new(&[0.5]).unwrap();
//! let mut f = [0.0];
//! m.eval(&Vector3::z(), &Vector3::z(), &mut f);
//! assert!((f[0] - 0.5 / std::f64::consts::PI).abs() < 1e-15);
//! ```

use std::f64::consts::FRAC_1_PI;

use brdf_core::params::per_channel_specs;
use brdf_core::{ParamError, ParamSpec, Parametric, impl_brdf_via_params};
use nalgebra::Vector3;

/// The Lambert model, one `kd` per channel.
#[derive(Clone, Debug, PartialEq)]
pub struct Lambert {
    channels: usize,
    specs: Vec<ParamSpec>,
    params: Vec<f64>,
}

impl Lambert {
    /// Name in the catalogue.
    pub const NAME: &'static str = "lambert";

    /// A Lambert model with one `kd` per channel; each must lie in `[0, 1]`.
    pub fn new(kd: &[f64]) -> Result<Self, ParamError> {
        let mut m = Self::with_channels(kd.len())?;
        m.set_params(kd)?;
        Ok(m)
    }

    /// A model with `channels` channels at the default parameters.
    pub fn with_channels(channels: usize) -> Result<Self, ParamError> {
        if channels == 0 {
            return Err(ParamError::Config {
                model: Self::NAME.into(),
                reason: "a model needs at least one channel".into(),
            });
        }
        let specs = per_channel_specs("kd", "diffuse albedo", channels, 0.0, 1.0, 0.5);
        let params = specs.iter().map(|s| s.default).collect();
        Ok(Lambert {
            channels,
            specs,
            params,
        })
    }
}

impl Parametric for Lambert {
    brdf_core::param_accessors!();
    fn name(&self) -> &str {
        Self::NAME
    }
    fn eval_at(&self, p: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        let above = l.z > 0.0 && v.z > 0.0;
        for c in 0..self.channels {
            out[c] = if above { p[c] * FRAC_1_PI } else { 0.0 };
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
        self.eval_at(p, l, v, out);
        let above = l.z > 0.0 && v.z > 0.0;
        let np = self.channels;
        grad[..self.channels * np].iter_mut().for_each(|g| *g = 0.0);
        if above {
            for c in 0..self.channels {
                grad[c * np + c] = FRAC_1_PI;
            }
        }
    }
}

impl_brdf_via_params!(Lambert);
