//! Oren-Nayar (1994, "Generalization of Lambert's reflectance model",
//! SIGGRAPH): the qualitative model fitted in Kurt's thesis ([`OrenNayar`])
//! and the full model with the interreflection term ([`OrenNayarFull`]).
//!
//! ## Qualitative
//!
//! `f = kd/pi (A + B max(0, cos(phi_o - phi_i)) sin(alpha) tan(beta))`,
//! `A = 1 - 0.5 s2/(s2 + 0.33)`, `B = 0.45 s2/(s2 + 0.09)`, `s2 = sigma^2`,
//! `alpha = max(theta_i, theta_o)`, `beta = min(theta_i, theta_o)`.
//!
//! | parameter | meaning | default box | linear |
//! | --- | --- | --- | --- |
//! | `kd` (per channel) | diffuse albedo | `[0, 1]` | yes |
//! | `sigma` | facet slope standard deviation (radians) | `[0, 0.999]` | no |
//!
//! Energy: at `kd = 1` the albedo exceeds 1 near grazing incidence (the
//! `tan(beta)` term), for the full model too; both conserve energy for
//! `kd <= 0.95` (tested in `tests/models/energy.rs`).
//!
//! Properties: reciprocal (`alpha`, `beta` and `cos(dphi)` are symmetric);
//! non-negative (`A >= 1/2`, the `B` term is `>= 0`); `sigma = 0` is
//! Lambert. Finite above the horizon: `tan(beta) <= tan(pi/2 - 1e-6)`-ish
//! within `1e-6` of the horizon, never infinite for `theta < pi/2`.
//!
//! ## Full
//!
//! `f = max(0, f1 + f2)`,
//! `f1 = kd/pi [C1 + cos(dphi) C2 tan(beta) + (1 - |cos dphi|) C3 tan((alpha+beta)/2)]`,
//! `C1 = 1 - 0.5 s2/(s2+0.33)`,
//! `C2 = 0.45 s2/(s2+0.09) sin(alpha)` if `cos dphi >= 0`, else
//! `0.45 s2/(s2+0.09) (sin(alpha) - (2 beta/pi)^3)`,
//! `C3 = 0.125 s2/(s2+0.09) (4 alpha beta / pi^2)^2`,
//! `f2 = 0.17 kd^2/pi s2/(s2+0.13) [1 - cos(dphi) (2 beta/pi)^2]`.
//!
//! | parameter | meaning | default box | linear |
//! | --- | --- | --- | --- |
//! | `kd` (per channel) | diffuse albedo | `[0, 1]` | **no** (`kd^2` in `f2`) |
//! | `sigma` | facet slope standard deviation (radians) | `[0, 0.999]` | no |
//!
//! Properties: reciprocal; `sigma = 0` is Lambert. The published formula is
//! **negative** in part of the domain: in back-scatter geometry
//! (`cos dphi < 0`) near grazing the term `cos(dphi) C2 tan(beta)` exceeds
//! `C1` (e.g. `sigma = 0.999`, `theta_i = theta_o = 89 deg`, `dphi = pi`:
//! `C2 tan(beta) -> 0.45 s2/(s2+0.09) 6/pi ~ 0.79 > C1 ~ 0.62`), and for
//! small `kd` the positive `kd^2` interreflection term cannot make up for it
//! (`kd = 0.3` there gives `f1 + f2 ~ -0.007`). A BRDF cannot
//! be negative, so the model clamps at 0 (derivatives 0 there);
//! [`OrenNayarFull::unclamped`] gives the published value, and the tests
//! check both that the clamp is active there and that it is inactive
//! elsewhere.
//!
//! ```
//! use brdf_core::{Brdf, spherical_to_cartesian};
//! use brdf_models::OrenNayarFull;
//! // sigma = 0 is Lambert; the interreflection term vanishes with sigma.
//! let m = OrenNayarFull::new(&[0.6], 0.0).unwrap();
//! let mut f = [0.0];
//! m.eval(&spherical_to_cartesian(0.7, 0.0), &spherical_to_cartesian(0.4, 2.0), &mut f);
//! assert!((f[0] - 0.6 / std::f64::consts::PI).abs() < 1e-15);
//! ```
//!
//! ```
//! use brdf_core::Brdf;
//! use brdf_models::OrenNayar;
//! use nalgebra::Vector3;
//! // sigma = 0 is Lambert.
//! let m = OrenNayar::new(&[0.5], 0.0).unwrap();
//! let mut f = [0.0];
//! m.eval(&Vector3::new(0.6, 0.0, 0.8), &Vector3::z(), &mut f);
//! assert!((f[0] - 0.5 / std::f64::consts::PI).abs() < 1e-15);
//! ```

use std::f64::consts::FRAC_1_PI;

use brdf_core::params::per_channel_specs;
use brdf_core::trig::cos_dphi;
use brdf_core::{ParamError, ParamSpec, Parametric, impl_brdf_via_params};
use nalgebra::Vector3;

/// The qualitative Oren-Nayar model.
#[derive(Clone, Debug, PartialEq)]
pub struct OrenNayar {
    channels: usize,
    specs: Vec<ParamSpec>,
    params: Vec<f64>,
}

impl OrenNayar {
    /// Name in the catalogue.
    pub const NAME: &'static str = "oren-nayar";

    /// At default parameters.
    pub fn with_channels(channels: usize) -> Result<Self, ParamError> {
        if channels == 0 {
            return Err(ParamError::Config {
                model: Self::NAME.into(),
                reason: "a model needs at least one channel".into(),
            });
        }
        let mut specs = per_channel_specs("kd", "diffuse albedo", channels, 0.0, 1.0, 0.5);
        specs.push(ParamSpec::new(
            "sigma",
            "facet slope standard deviation (radians)",
            0.0,
            0.999,
            0.3,
            false,
        ));
        let params = specs.iter().map(|s| s.default).collect();
        Ok(OrenNayar {
            channels,
            specs,
            params,
        })
    }

    /// With per-channel `kd` and `sigma`, validated.
    pub fn new(kd: &[f64], sigma: f64) -> Result<Self, ParamError> {
        let mut m = Self::with_channels(kd.len())?;
        let p: Vec<f64> = kd.iter().copied().chain([sigma]).collect();
        m.set_params(&p)?;
        Ok(m)
    }

    /// `(A + B g, d/dsigma)` with `g = max(0, cos dphi) sin(alpha) tan(beta)`.
    fn shape(sigma: f64, l: &Vector3<f64>, v: &Vector3<f64>) -> (f64, f64) {
        let s2 = sigma * sigma;
        let a = 1.0 - 0.5 * s2 / (s2 + 0.33);
        let b = 0.45 * s2 / (s2 + 0.09);
        let da = -0.5 * 2.0 * sigma * 0.33 / ((s2 + 0.33) * (s2 + 0.33));
        let db = 0.45 * 2.0 * sigma * 0.09 / ((s2 + 0.09) * (s2 + 0.09));
        let c = cos_dphi(l, v).max(0.0);
        // alpha = max(theta), beta = min(theta): the smaller cosine is alpha's.
        let (ca, cb) = if l.z < v.z { (l.z, v.z) } else { (v.z, l.z) };
        let sin_a = (1.0 - ca * ca).max(0.0).sqrt();
        let tan_b = (1.0 - cb * cb).max(0.0).sqrt() / cb;
        let g = c * sin_a * tan_b;
        (a + b * g, da + db * g)
    }
}

impl Parametric for OrenNayar {
    brdf_core::param_accessors!();
    fn name(&self) -> &str {
        Self::NAME
    }
    fn eval_at(&self, p: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        let nc = self.channels;
        if !(l.z > 0.0 && v.z > 0.0) {
            out[..nc].iter_mut().for_each(|x| *x = 0.0);
            return;
        }
        let (s, _) = Self::shape(p[nc], l, v);
        for c in 0..nc {
            out[c] = p[c] * FRAC_1_PI * s;
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
        let np = nc + 1;
        grad[..nc * np].iter_mut().for_each(|g| *g = 0.0);
        if !(l.z > 0.0 && v.z > 0.0) {
            out[..nc].iter_mut().for_each(|x| *x = 0.0);
            return;
        }
        let (s, ds) = Self::shape(p[nc], l, v);
        for c in 0..nc {
            out[c] = p[c] * FRAC_1_PI * s;
            grad[c * np + c] = FRAC_1_PI * s;
            grad[c * np + nc] = p[c] * FRAC_1_PI * ds;
        }
    }
}

impl_brdf_via_params!(OrenNayar);

/// The full Oren-Nayar model with the interreflection term (see the module
/// documentation).
#[derive(Clone, Debug, PartialEq)]
pub struct OrenNayarFull {
    channels: usize,
    specs: Vec<ParamSpec>,
    params: Vec<f64>,
}

impl OrenNayarFull {
    /// Name in the catalogue.
    pub const NAME: &'static str = "oren-nayar-full";

    /// At default parameters.
    pub fn with_channels(channels: usize) -> Result<Self, ParamError> {
        let mut q = OrenNayar::with_channels(channels).map_err(|e| match e {
            ParamError::Config { reason, .. } => ParamError::Config {
                model: Self::NAME.into(),
                reason,
            },
            other => other,
        })?;
        // kd enters squared in the interreflection term: not linear.
        for s in q.specs.iter_mut().take(channels) {
            s.linear = false;
        }
        Ok(Self {
            channels,
            specs: q.specs,
            params: q.params,
        })
    }

    /// With per-channel `kd` and `sigma`, validated.
    pub fn new(kd: &[f64], sigma: f64) -> Result<Self, ParamError> {
        let mut m = Self::with_channels(kd.len())?;
        let p: Vec<f64> = kd.iter().copied().chain([sigma]).collect();
        m.set_params(&p)?;
        Ok(m)
    }

    /// The published (unclamped) value for one channel with albedo `kd`, and
    /// its derivatives `(d/dkd, d/dsigma)`.
    pub fn unclamped(kd: f64, sigma: f64, l: &Vector3<f64>, v: &Vector3<f64>) -> (f64, f64, f64) {
        use std::f64::consts::PI;
        let s2 = sigma * sigma;
        let ds2 = 2.0 * sigma;
        let c1 = 1.0 - 0.5 * s2 / (s2 + 0.33);
        let dc1 = -0.5 * 0.33 * ds2 / ((s2 + 0.33) * (s2 + 0.33));
        let b = s2 / (s2 + 0.09);
        let db = 0.09 * ds2 / ((s2 + 0.09) * (s2 + 0.09));
        let g = s2 / (s2 + 0.13);
        let dg = 0.13 * ds2 / ((s2 + 0.13) * (s2 + 0.13));
        let cphi = cos_dphi(l, v);
        let (ca, cb) = if l.z < v.z { (l.z, v.z) } else { (v.z, l.z) };
        let alpha = ca.clamp(-1.0, 1.0).acos();
        let beta = cb.clamp(-1.0, 1.0).acos();
        let sin_a = (1.0 - ca * ca).max(0.0).sqrt();
        let tan_b = (1.0 - cb * cb).max(0.0).sqrt() / cb;
        let x2 = if cphi >= 0.0 {
            sin_a
        } else {
            sin_a - (2.0 * beta / PI).powi(3)
        };
        let y3 = (4.0 * alpha * beta / (PI * PI)).powi(2);
        let t3 = (0.5 * (alpha + beta)).tan();
        let w = 1.0 - cphi.abs();
        let bracket = c1 + cphi * 0.45 * b * x2 * tan_b + w * 0.125 * b * y3 * t3;
        let dbracket = dc1 + cphi * 0.45 * db * x2 * tan_b + w * 0.125 * db * y3 * t3;
        let inter = 1.0 - cphi * (2.0 * beta / PI).powi(2);
        let f1 = kd / PI * bracket;
        let f2 = 0.17 * kd * kd / PI * g * inter;
        let d_kd = bracket / PI + 2.0 * 0.17 * kd / PI * g * inter;
        let d_sigma = kd / PI * dbracket + 0.17 * kd * kd / PI * dg * inter;
        (f1 + f2, d_kd, d_sigma)
    }
}

impl Parametric for OrenNayarFull {
    brdf_core::param_accessors!();
    fn name(&self) -> &str {
        Self::NAME
    }
    fn eval_at(&self, p: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        let nc = self.channels;
        for c in 0..nc {
            out[c] = if l.z > 0.0 && v.z > 0.0 {
                Self::unclamped(p[c], p[nc], l, v).0.max(0.0)
            } else {
                0.0
            };
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
        let np = nc + 1;
        grad[..nc * np].iter_mut().for_each(|g| *g = 0.0);
        for c in 0..nc {
            out[c] = 0.0;
            if !(l.z > 0.0 && v.z > 0.0) {
                continue;
            }
            let (f, dk, ds) = Self::unclamped(p[c], p[nc], l, v);
            if f > 0.0 {
                out[c] = f;
                grad[c * np + c] = dk;
                grad[c * np + nc] = ds;
            }
        }
    }
}

impl_brdf_via_params!(OrenNayarFull);
