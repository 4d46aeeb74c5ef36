//! Phong with exact Fresnel transmission (Sopp 2017, car paint under a
//! clear coat): the specular lobe is weakened by the light the coat
//! reflects at incidence:
//!
//! `f = cd/pi + (ns+2)/(2 pi) cs (R.V)^ns (1 - Fr(theta_i))`,
//!
//! `Fr` the exact unpolarised Fresnel reflectance for refractive index
//! `eta`: `theta_t = asin(sin(theta_i)/eta)`,
//! `rs = sin(theta_i - theta_t)/sin(theta_i + theta_t)`,
//! `rp = tan(theta_i - theta_t)/tan(theta_i + theta_t)`, `Fr = (rs^2 + rp^2)/2`
//! (`Fr(0) = ((eta-1)/(eta+1))^2`; evaluated in the equivalent cosine form).
//!
//! | parameter | meaning | default box | linear |
//! | --- | --- | --- | --- |
//! | `cd` (per channel) | diffuse colour | `[0, 1]` | yes |
//! | `cs` (per channel) | specular colour | `[0, 1]` | yes |
//! | `ns` | Phong exponent | `[0, 1e6]` | no |
//! | `eta` | refractive index of the coat | `[1, 3]` | no |
//!
//! Properties: non-negative; finite above the horizon. **Not reciprocal**:
//! `1 - Fr(theta_i)` depends on the incident direction only (as published);
//! `f(L, V) - cd/pi` divided by `1 - Fr(theta_i)` is reciprocal, which the
//! tests check. Energy conserving where modified Phong is
//! (`cd + cs <= 1`), since `1 - Fr <= 1`.
//!
//! ```
//! use brdf_core::Brdf;
//! use brdf_models::PhongFresnel;
//! use nalgebra::Vector3;
//! // Normal incidence and view: R.V = 1, Fr = ((eta-1)/(eta+1))^2 = 0.04.
//! let m = PhongFresnel::new(&[0.0], &[1.0], &[10.0, 1.5]).unwrap();
//! let mut f = [0.0];
//! m.eval(&Vector3::z(), &Vector3::z(), &mut f);
//! assert!((f[0] - 12.0 / (2.0 * std::f64::consts::PI) * 0.96).abs() < 1e-12);
//! ```

use std::f64::consts::PI;

use brdf_core::ParamSpec;
use brdf_core::fresnel::fresnel_dielectric_d_eta;
use nalgebra::Vector3;

use crate::combinators::{DiffuseLobe, Lobe, pow_clamped};

/// The lobe `(ns+2)/(2 pi) (R.V)^ns (1 - Fr(theta_i; eta))`.
#[derive(Clone, Debug, PartialEq)]
pub struct PhongFresnelLobe;

impl Lobe for PhongFresnelLobe {
    const NAME: &'static str = "phong-fresnel";
    const DIFFUSE: &'static str = "cd";
    const SPECULAR: &'static str = "cs";
    fn specs() -> Vec<ParamSpec> {
        vec![
            ParamSpec::new("ns", "Phong exponent", 0.0, 1e6, 20.0, false),
            ParamSpec::new(
                "eta",
                "refractive index of the clear coat",
                1.0,
                3.0,
                1.5,
                false,
            ),
        ]
    }
    fn shape(q: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, dq: Option<&mut [f64]>) -> f64 {
        let (n, eta) = (q[0], q[1]);
        let c = -l.x * v.x - l.y * v.y + l.z * v.z;
        let (p, dp) = pow_clamped(c, n);
        let norm = (n + 2.0) / (2.0 * PI);
        let (fr, dfr) = fresnel_dielectric_d_eta(l.z, eta);
        let t = 1.0 - fr;
        if let Some(d) = dq {
            d[0] = (p / (2.0 * PI) + norm * dp) * t;
            d[1] = -norm * p * dfr;
        }
        norm * p * t
    }
    fn reciprocal() -> bool {
        false
    }
}

/// Sopp's Phong with Fresnel: `cd`, `cs` per channel, `ns`, `eta`.
pub type PhongFresnel = DiffuseLobe<PhongFresnelLobe>;
