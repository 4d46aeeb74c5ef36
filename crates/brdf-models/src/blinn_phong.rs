//! Blinn-Phong (Blinn 1977, "Models of light reflection for computer
//! synthesized pictures"), with the `(n+2)/(2 pi)` normalisation used by Ngan
//! et al. (2005) and Kurt (2007).
//!
//! `f = kd/pi + ks (n+2)/(2 pi) cos^n(delta)`, `delta` the angle between the
//! normal and `H = (L + V)/|L + V|`, i.e. `cos delta = H.z`.
//!
//! | parameter | meaning | default box | linear |
//! | --- | --- | --- | --- |
//! | `kd` (per channel) | diffuse albedo | `[0, 1]` | yes |
//! | `ks` (per channel) | specular strength | `[0, 1]` | yes |
//! | `n` | exponent | `[0, 1e6]` | no |
//!
//! Properties: reciprocal; non-negative. This normalisation does not make the
//! model energy conserving for every `n` and `ks`: the half-vector lobe
//! `cos^n(delta)` is about four times wider in `V` than a Phong lobe of the
//! same exponent, so for large `n` the lobe's albedo at normal incidence tends
//! to about `4 ks` (exceeding 1 for `ks > 1/4`). Plausible domain:
//! `kd + 4 ks <= 1`, which conserves energy at every exponent and incidence
//! (tested in `tests/models/energy.rs`, with a point just outside that does not).
//!
//! ```
//! use brdf_core::Brdf;
//! use brdf_models::BlinnPhong;
//! use nalgebra::Vector3;
//! let m = BlinnPhong::new(&[0.5], &[0.0], &[10.0]).unwrap();
//! let mut f = [0.0];
//! m.eval(&Vector3::z(), &Vector3::x(), &mut f);
//! assert_eq!(f[0], 0.0); // V on the horizon
//! m.eval(&Vector3::z(), &Vector3::z(), &mut f);
//! assert!((f[0] - 0.5 / std::f64::consts::PI).abs() < 1e-15);
//! ```

use std::f64::consts::PI;

use brdf_core::ParamSpec;
use nalgebra::Vector3;

use crate::combinators::{DiffuseLobe, Lobe, pow_clamped};

/// The Blinn-Phong lobe `(n+2)/(2 pi) (N.H)^n`.
#[derive(Clone, Debug, PartialEq)]
pub struct BlinnPhongLobe;

impl Lobe for BlinnPhongLobe {
    const NAME: &'static str = "blinn-phong";
    fn specs() -> Vec<ParamSpec> {
        vec![ParamSpec::new("n", "exponent", 0.0, 1e6, 20.0, false)]
    }
    fn shape(q: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, dq: Option<&mut [f64]>) -> f64 {
        let n = q[0];
        let h = l + v;
        let hn = h.norm();
        let c = if hn > 0.0 { h.z / hn } else { 0.0 };
        let (p, dp) = pow_clamped(c, n);
        let norm = (n + 2.0) / (2.0 * PI);
        if let Some(d) = dq {
            d[0] = p / (2.0 * PI) + norm * dp;
        }
        norm * p
    }
}

/// Blinn-Phong: `kd/pi + ks (n+2)/(2 pi) (N.H)^n`.
pub type BlinnPhong = DiffuseLobe<BlinnPhongLobe>;
