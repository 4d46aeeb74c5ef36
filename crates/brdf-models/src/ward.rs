//! Ward (1992, "Measuring and modeling anisotropic reflection", SIGGRAPH),
//! isotropic and anisotropic, and the Ward-Duer variant (Duer 2004, "On the
//! Ward model for global illumination") which replaces `sqrt(cos_i cos_o)` by
//! `cos_i cos_o` in the denominator.
//!
//! isotropic: `f = kd/pi + ks exp(-tan^2(delta)/a^2) / (4 pi a^2 sqrt(cos_i cos_o))`
//!
//! anisotropic: `f = kd/pi + ks exp(-tan^2(delta) (cos^2(phi_h)/ax^2 + sin^2(phi_h)/ay^2)) / (4 pi ax ay sqrt(cos_i cos_o))`
//!
//! with `tan^2(delta) cos^2(phi_h) = (Hx/Hz)^2` and `tan^2(delta) sin^2(phi_h) = (Hy/Hz)^2`
//! for the (unnormalised) half vector `H = L + V`.
//!
//! | parameter | meaning | default box | linear |
//! | --- | --- | --- | --- |
//! | `kd` (per channel) | diffuse albedo | `[0, 1]` | yes |
//! | `ks` (per channel) | specular strength | `[0, 1]` | yes |
//! | `a` (iso) / `ax`, `ay` (aniso) | RMS slope (roughness) | `(0, 0.5]` | no |
//!
//! Properties: reciprocal; non-negative; finite above the horizon (the
//! denominator is at least `4 pi a^2 * 1e-6`-ish within `1e-6` of the horizon,
//! and `exp(-tan^2/a^2)` is 0 when `H` is on the horizon). Ward's `sqrt`
//! denominator makes the lobe's albedo grow without bound towards grazing
//! incidence for rough surfaces; Duer's variant is the better-normalised one.
//!
//! Energy (directional albedo at most 1, tested in `tests/models/energy.rs`):
//! Ward for `kd + ks <= 1` at incidence up to 85 deg (a rough lobe, `a =
//! 0.5`, exceeds 1 at grazing); Ward-Duer for `kd + ks <= 1` up to 70 deg
//! (an anisotropic lobe with `ax = 0.05`, `ay = 0.48` exceeds 1 at 80 deg).
//!
//! ```
//! use brdf_core::Brdf;
//! use brdf_models::Ward;
//! use nalgebra::Vector3;
//! let m = Ward::new(&[0.0], &[1.0], &[0.2]).unwrap();
//! let mut f = [0.0];
//! m.eval(&Vector3::z(), &Vector3::z(), &mut f);
//! // delta = 0: f = 1 / (4 pi a^2).
//! assert!((f[0] - 1.0 / (4.0 * std::f64::consts::PI * 0.04)).abs() < 1e-12);
//! ```

use std::f64::consts::PI;

use brdf_core::ParamSpec;
use nalgebra::Vector3;

use crate::combinators::{DiffuseLobe, Lobe};

fn roughness(name: &str) -> ParamSpec {
    ParamSpec::new(name, "RMS slope (roughness)", 0.0, 0.5, 0.2, false).open_below()
}

/// Shared lobe: `exp(-(hx^2/ax^2 + hy^2/ay^2)/hz^2) / (4 pi ax ay D)` with
/// `D = sqrt(cos_i cos_o)` (Ward) or `cos_i cos_o` (Duer). Returns the value
/// and `(dS/dax, dS/day)`.
#[inline]
fn ward_shape(ax: f64, ay: f64, l: &Vector3<f64>, v: &Vector3<f64>, duer: bool) -> (f64, f64, f64) {
    let h = l + v;
    if h.z <= 0.0 {
        return (0.0, 0.0, 0.0);
    }
    let tx = (h.x / h.z).powi(2);
    let ty = (h.y / h.z).powi(2);
    let e = (-(tx / (ax * ax) + ty / (ay * ay))).exp();
    let d = if duer { l.z * v.z } else { (l.z * v.z).sqrt() };
    let s = e / (4.0 * PI * ax * ay * d);
    if s == 0.0 {
        return (0.0, 0.0, 0.0);
    }
    let dax = s * (2.0 * tx / (ax * ax * ax) - 1.0 / ax);
    let day = s * (2.0 * ty / (ay * ay * ay) - 1.0 / ay);
    (s, dax, day)
}

macro_rules! iso_lobe {
    ($lobe:ident, $name:literal, $duer:expr, $doc:literal) => {
        #[doc = $doc]
        #[derive(Clone, Debug, PartialEq)]
        pub struct $lobe;
        impl Lobe for $lobe {
            const NAME: &'static str = $name;
            fn specs() -> Vec<ParamSpec> {
                vec![roughness("a")]
            }
            fn shape(q: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, dq: Option<&mut [f64]>) -> f64 {
                let (s, dx, dy) = ward_shape(q[0], q[0], l, v, $duer);
                if let Some(d) = dq {
                    d[0] = dx + dy;
                }
                s
            }
        }
    };
}

macro_rules! aniso_lobe {
    ($lobe:ident, $name:literal, $duer:expr, $doc:literal) => {
        #[doc = $doc]
        #[derive(Clone, Debug, PartialEq)]
        pub struct $lobe;
        impl Lobe for $lobe {
            const NAME: &'static str = $name;
            fn specs() -> Vec<ParamSpec> {
                vec![roughness("ax"), roughness("ay")]
            }
            fn shape(q: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, dq: Option<&mut [f64]>) -> f64 {
                let (s, dx, dy) = ward_shape(q[0], q[1], l, v, $duer);
                if let Some(d) = dq {
                    d[0] = dx;
                    d[1] = dy;
                }
                s
            }
        }
    };
}

iso_lobe!(WardLobe, "ward", false, "Ward's isotropic lobe.");
aniso_lobe!(
    WardAnisoLobe,
    "ward-aniso",
    false,
    "Ward's anisotropic lobe."
);
iso_lobe!(
    WardDuerLobe,
    "ward-duer",
    true,
    "Ward-Duer isotropic lobe (`cos_i cos_o` denominator)."
);
aniso_lobe!(
    WardDuerAnisoLobe,
    "ward-duer-aniso",
    true,
    "Ward-Duer anisotropic lobe."
);

/// Ward, isotropic.
pub type Ward = DiffuseLobe<WardLobe>;
/// Ward, anisotropic (`ax` along the tangent `+x`, `ay` along `+y`).
pub type WardAniso = DiffuseLobe<WardAnisoLobe>;
/// Ward-Duer, isotropic.
pub type WardDuer = DiffuseLobe<WardDuerLobe>;
/// Ward-Duer, anisotropic.
pub type WardDuerAniso = DiffuseLobe<WardDuerAnisoLobe>;
