//! Cook-Torrance (Cook & Torrance 1982, "A reflectance model for computer
//! graphics", ACM TOG 1(1)) with `K` lobes and the Beckmann distribution:
//!
//! `f = kd/pi + sum_k ks_k/pi D_k G F_k(V.H) / ((N.L)(N.V))`,
//! `D = exp(-(tan(delta)/m)^2) / (m^2 cos^4(delta))`,
//! `G = min(1, 2 (N.H)(N.V)/(V.H), 2 (N.H)(N.L)/(V.H))`, Schlick `F`.
//!
//! | parameter | meaning | default box | linear |
//! | --- | --- | --- | --- |
//! | `kd` (per channel) | diffuse albedo | `[0, 1]` | yes |
//! | `ks{k}` (per channel) | strength of lobe `k` | `[0, 1]` | yes |
//! | `m{k}` | Beckmann RMS slope of lobe `k` | `(0, 0.999]` | no |
//! | `f0_{k}` | Fresnel reflectance at normal incidence of lobe `k` | `[0, 0.999]` | no |
//!
//! Properties: reciprocal; non-negative; finite above the horizon (`D` is
//! evaluated as 0 once `exp(-tan^2/m^2)` underflows, before `cos^4` can
//! vanish). Not energy conserving for every `ks`: each lobe's albedo
//! approaches `4 F0`, so the domain is `kd + 4 sum_k ks_k <= 1` (tested in
//! `tests/models/energy.rs`). Fits with 1 and 2
//! lobes (Ngan).
//!
//! ```
//! use brdf_core::{Brdf, Parametric};
//! use brdf_models::CookTorrance;
//! use nalgebra::Vector3;
//! let mut m = CookTorrance::new(1, 1).unwrap();
//! // kd, ks1, m1, f0_1
//! m.set_params(&[0.0, 1.0, 0.3, 0.5]).unwrap();
//! let mut f = [0.0];
//! m.eval(&Vector3::z(), &Vector3::z(), &mut f);
//! // delta = 0: D = 1/m^2, G = 1, F = F0: f = F0 / (pi m^2).
//! assert!((f[0] - 0.5 / (std::f64::consts::PI * 0.09)).abs() < 1e-12);
//! ```

use std::f64::consts::FRAC_1_PI;

use brdf_core::ParamSpec;
use nalgebra::Vector3;

use crate::ashikhmin_shirley::f0_spec;
use crate::combinators::{Lobe, MultiLobe};
use crate::microfacet::facet_lobe;

/// One Cook-Torrance lobe `D G F / (pi N.L N.V)`, parameters `m`, `f0`.
#[derive(Clone, Debug, PartialEq)]
pub struct CtLobe;

impl Lobe for CtLobe {
    const NAME: &'static str = "cook-torrance";
    fn specs() -> Vec<ParamSpec> {
        vec![
            ParamSpec::new("m", "Beckmann RMS slope", 0.0, 0.999, 0.2, false).open_below(),
            f0_spec(),
        ]
    }
    fn shape(q: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, dq: Option<&mut [f64]>) -> f64 {
        facet_lobe(q, l, v, dq, |g, m| {
            if !(g.nh > 0.0) {
                return None;
            }
            let c2 = g.nh * g.nh;
            let tan2 = (1.0 - c2).max(0.0) / c2;
            // exp underflows to 0 before cos^4 can vanish.
            let d = FRAC_1_PI * (-tan2 / (m * m)).exp() / (m * m * c2 * c2);
            Some((d, (2.0 * tan2 / (m * m) - 2.0) / m))
        })
    }
}

/// Cook-Torrance with `K` Beckmann lobes.
pub type CookTorrance = MultiLobe<CtLobe>;
