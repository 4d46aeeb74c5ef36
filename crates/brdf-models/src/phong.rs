//! Modified Phong (Phong 1975; normalised as Lafortune & Willems 1994,
//! "Using the modified Phong reflectance model for physically based
//! rendering").
//!
//! `f = kd/pi + ks (n+2)/(2 pi) cos^n(alpha_r)`, `alpha_r` the angle between
//! the mirror direction `R = (-Lx, -Ly, Lz)` of `L` and `V`, the cosine
//! clamped at 0.
//!
//! | parameter | meaning | default box | linear |
//! | --- | --- | --- | --- |
//! | `kd` (per channel) | diffuse albedo | `[0, 1]` | yes |
//! | `ks` (per channel) | specular strength | `[0, 1]` | yes |
//! | `n` | Phong exponent | `[0, 1e6]` | no |
//!
//! Properties: reciprocal (`R.V` is symmetric in `L` and `V`);
//! non-negative. The lobe's directional albedo is
//! `int (n+2)/(2 pi) cos^n(alpha_r) cos_o dV`, which equals 1 at normal
//! incidence (`(n+2) int_0^1 mu^(n+1) dmu = 1`) and is smaller elsewhere
//! (part of the lobe falls below the horizon, and `cos_o < 1` away from the
//! normal; Lafortune & Willems 1994), so `kd + ks <= 1` conserves energy.
//!
//! ```
//! use brdf_core::Brdf;
//! use brdf_models::Phong;
//! use nalgebra::Vector3;
//! let m = Phong::new(&[0.0], &[1.0], &[2.0]).unwrap();
//! let mut f = [0.0];
//! // Mirror configuration at normal incidence: cos alpha_r = 1.
//! m.eval(&Vector3::z(), &Vector3::z(), &mut f);
//! assert!((f[0] - 4.0 / (2.0 * std::f64::consts::PI)).abs() < 1e-15);
//! ```

use std::f64::consts::PI;

use brdf_core::ParamSpec;
use nalgebra::Vector3;

use crate::combinators::{DiffuseLobe, Lobe, pow_clamped};

/// The Phong lobe `(n+2)/(2 pi) cos^n(alpha_r)`.
#[derive(Clone, Debug, PartialEq)]
pub struct PhongLobe;

impl Lobe for PhongLobe {
    const NAME: &'static str = "phong";
    fn specs() -> Vec<ParamSpec> {
        vec![ParamSpec::new("n", "Phong exponent", 0.0, 1e6, 20.0, false)]
    }
    fn shape(q: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, dq: Option<&mut [f64]>) -> f64 {
        let n = q[0];
        let c = -l.x * v.x - l.y * v.y + l.z * v.z;
        let (p, dp) = pow_clamped(c, n);
        let norm = (n + 2.0) / (2.0 * PI);
        if let Some(d) = dq {
            d[0] = p / (2.0 * PI) + norm * dp;
        }
        norm * p
    }
}

/// Modified Phong: `kd/pi + ks (n+2)/(2 pi) cos^n(alpha_r)`.
pub type Phong = DiffuseLobe<PhongLobe>;
