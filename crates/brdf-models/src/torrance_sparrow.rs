//! Torrance-Sparrow (Torrance & Sparrow 1967, "Theory for off-specular
//! reflection from roughened surfaces", JOSA 57(9)) with the Gaussian facet
//! distribution normalised as Ramamoorthi & Hanrahan (2001):
//!
//! `f = kd/pi + ks D G F(V.H) / ((N.L)(N.V))`, `D = exp(-(delta/m)^2) / (pi m^2)`,
//! `G = min(1, 2 (N.H)(N.V)/(V.H), 2 (N.H)(N.L)/(V.H))`, Schlick `F`.
//!
//! | parameter | meaning | default box | linear |
//! | --- | --- | --- | --- |
//! | `kd` (per channel) | diffuse albedo | `[0, 1]` | yes |
//! | `ks` (per channel) | specular strength | `[0, 1]` | yes |
//! | `m` | facet slope (radians) | `(0, 0.999]` | no |
//! | `f0` | Fresnel reflectance at normal incidence | `[0, 0.999]` | no |
//!
//! Properties: reciprocal; non-negative; finite above the horizon (the
//! `1/(N.L N.V)` is bounded by `G <= 2 NH min(NL, NV)/VH`, leaving
//! `1/max(NL, NV)`). Not energy conserving towards grazing incidence for
//! every `ks`: the lobe's albedo approaches `4 F0` for sharp lobes, so the
//! domain is `kd + 4 ks <= 1` (at every incidence; tested in
//! `tests/models/energy.rs`, with `ks = 0.3` shown to exceed 1).
//!
//! ```
//! use brdf_core::Brdf;
//! use brdf_models::TorranceSparrow;
//! use nalgebra::Vector3;
//! // L = V = N: delta = 0, G = 1, F = F0: f = ks F0 / (pi m^2).
//! let m = TorranceSparrow::new(&[0.0], &[1.0], &[0.3, 0.5]).unwrap();
//! let mut f = [0.0];
//! m.eval(&Vector3::z(), &Vector3::z(), &mut f);
//! assert!((f[0] - 0.5 / (std::f64::consts::PI * 0.09)).abs() < 1e-12);
//! ```

use std::f64::consts::PI;

use brdf_core::ParamSpec;
use nalgebra::Vector3;

use crate::ashikhmin_shirley::f0_spec;
use crate::combinators::{DiffuseLobe, Lobe};
use crate::microfacet::facet_lobe;

/// The Torrance-Sparrow lobe `D G F / (N.L N.V)`, parameters `m`, `f0`.
#[derive(Clone, Debug, PartialEq)]
pub struct TsLobe;

impl Lobe for TsLobe {
    const NAME: &'static str = "torrance-sparrow";
    fn specs() -> Vec<ParamSpec> {
        vec![
            ParamSpec::new("m", "facet slope (radians)", 0.0, 0.999, 0.2, false).open_below(),
            f0_spec(),
        ]
    }
    fn shape(q: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, dq: Option<&mut [f64]>) -> f64 {
        facet_lobe(q, l, v, dq, |g, m| {
            let t = g.nh.clamp(-1.0, 1.0).acos() / m;
            let d = (-t * t).exp() / (PI * m * m);
            Some((d, (2.0 * t * t - 2.0) / m))
        })
    }
}

/// Torrance-Sparrow: `kd`, `ks` per channel, `m`, `f0`.
pub type TorranceSparrow = DiffuseLobe<TsLobe>;
