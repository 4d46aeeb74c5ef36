//! Löw, Kronander, Ynnerman & Unger 2012, "BRDF models for accurate and
//! efficient rendering of glossy surfaces", ACM TOG 31(1): the smooth-surface
//! model and the microfacet model with the ABC distribution, both with the
//! exact dielectric Fresnel term of an index of refraction `eta`
//! (Cook & Torrance's form, equal to [`brdf_core::fresnel::fresnel_dielectric`]
//! for `eta >= 1`).
//!
//! **Smooth surface** (`abc-smooth`, the paper's eqs. 10-14): with `Lp`, `Vp`
//! the projections of `L`, `V` on the surface plane,
//!
//! `f_c = kd_c/pi + A_c S(|Lp + Vp|) F(cos theta_d; eta)`,
//! `S(f) = 1 / (1 + B f^2)^C`, `cos theta_d = sqrt(1 - |Lp - Vp|^2 / 4)`,
//! and the geometry factor `G = 1` (the paper's choice for this model).
//! `f = |Lp + Vp| = |beta - beta0|` is the paper's argument, the distance in
//! the projected plane between the viewing direction and the mirror
//! direction of `L` (`2 cos(theta_d) sin(theta_h)`, zero in the mirror
//! direction). The Fresnel cosine is the paper's projected form (eq. 14),
//! equal to `V.H` only when `N.L = N.V` (`|L - V|^2 = 4 sin^2 theta_d`, of
//! which the projection drops `(N.L - N.V)^2`); BBM's `lowsmooth` and the
//! published fits use it so.
//!
//! **Microfacet with the ABC distribution** (`abc`, eq. 15):
//!
//! `f_c = kd_c/pi + A_c D(H) G F(V.H; eta) / (pi (N.L)(N.V))`,
//! `D = 1 / (1 + B (1 - N.H))^C`,
//! `G = min(1, 2 (N.H)(N.V)/(V.H), 2 (N.H)(N.L)/(V.H))` (Cook-Torrance's
//! V-groove term, which the paper uses).
//!
//! The paper's eq. 15 has no `pi` under `A`; the MERL fits in its
//! supplemental material (BBM `fits/low_lowmicrofacet_E2.fit`) were made
//! with it, so it is kept here and those numbers are used as they are
//! (`A_paper = A / pi`). `D` is not normalised (`A` is free); its projected
//! integral is [`abc_normalisation`].
//!
//! | parameter | meaning | default box | linear |
//! | --- | --- | --- | --- |
//! | `kd` (per channel) | diffuse albedo | `[0, 1]` | yes |
//! | `A` (per channel) | lobe scale | `[0, 1e4]` | yes |
//! | `B` | lobe sharpness | `[0, 1e7]` | no |
//! | `C` | fall-off exponent | `[0, 10]` | no |
//! | `eta` | index of refraction | `[1, 20]` | no |
//!
//! The boxes hold every E2 fit of the paper's supplement (largest `A` 2192,
//! `B` 3.4e6, `eta` 10.4).
//!
//! Properties: reciprocal (`|Lp + Vp|`, `|Lp - Vp|`, `H` and `G` are
//! symmetric); non-negative; finite above the horizon. Energy: `A` is free,
//! so only a domain can be stated. Smooth model: `S F <= 1`, so the lobe's
//! albedo is at most `pi A`; the domain is `kd + pi A <= 1`. ABC model: with
//! `N(B, C) = integral D(H) (N.H) dH` ([`abc_normalisation`]), the lobe is a
//! Cook-Torrance lobe of strength `A N / pi` with a distribution normalised
//! as Beckmann's, so the Cook-Torrance domain applies: `kd + 4 A N / pi <= 1`
//! (both tested in `tests/models/new_models.rs`).
//!
//! ```
//! use brdf_core::Brdf;
//! use brdf_models::LowSmooth;
//! use nalgebra::Vector3;
//! // kd, A, B, C, eta
//! let m = LowSmooth::new(1, &[0.0, 2.0, 10.0, 1.0, 1.5]).unwrap();
//! let mut f = [0.0];
//! m.eval(&Vector3::z(), &Vector3::z(), &mut f);
//! // Mirror direction at the pole: S = 1, F = ((1.5 - 1)/(1.5 + 1))^2 = 0.04.
//! assert!((f[0] - 2.0 * 0.04).abs() < 1e-15);
//! ```

use std::f64::consts::PI;

use brdf_core::ParamSpec;
use brdf_core::fresnel::fresnel_dielectric_d_eta;
use nalgebra::Vector3;

use crate::fitted_lobes::{FittedLobe, FittedShape};
use crate::microfacet::HalfGeometry;

fn abc_specs() -> Vec<ParamSpec> {
    vec![
        ParamSpec::new("B", "lobe sharpness", 0.0, 1e7, 100.0, false),
        ParamSpec::new("C", "fall-off exponent", 0.0, 10.0, 1.0, false),
        ParamSpec::new("eta", "index of refraction", 1.0, 20.0, 1.5, false),
    ]
}

/// `g^-C` for `g = 1 + B x >= 1` and its derivatives in `B` and `C`.
#[inline]
fn abc_power(b: f64, c: f64, x: f64) -> (f64, f64, f64) {
    let g = 1.0 + b * x;
    let lg = g.ln();
    let s = (-c * lg).exp();
    (s, -c * x * s / g, -lg * s)
}

/// The smooth-surface lobe `S(|Lp + Vp|) F(cos theta_d; eta)`.
#[derive(Clone, Debug, PartialEq)]
pub struct LowSmoothShape;

impl FittedShape for LowSmoothShape {
    const NAME: &'static str = "abc-smooth";
    const SCALE: &'static str = "A";
    const SCALE_MEANING: &'static str = "lobe scale";
    const SCALE_BOX: (f64, f64, f64) = (0.0, 1e4, 1.0);
    const PER_CHANNEL: bool = false;
    type Memo = ();
    fn specs() -> Vec<ParamSpec> {
        abc_specs()
    }
    fn shape(q: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, dq: Option<&mut [f64]>) -> f64 {
        let (sx, sy) = (l.x + v.x, l.y + v.y);
        let (dx, dy) = (l.x - v.x, l.y - v.y);
        let f2 = sx * sx + sy * sy;
        // |Lp - Vp| <= 2, so the root is real; the clamp only absorbs rounding.
        let cos_d = (1.0 - 0.25 * (dx * dx + dy * dy)).max(0.0).sqrt();
        let (s, s_b, s_c) = abc_power(q[0], q[1], f2);
        let (fr, fr_eta) = fresnel_dielectric_d_eta(cos_d, q[2]);
        if let Some(dq) = dq {
            dq[0] = s_b * fr;
            dq[1] = s_c * fr;
            dq[2] = s * fr_eta;
        }
        s * fr
    }
}

/// The ABC microfacet lobe `D G F / (pi N.L N.V)`.
#[derive(Clone, Debug, PartialEq)]
pub struct LowAbcShape;

impl FittedShape for LowAbcShape {
    const NAME: &'static str = "abc";
    const SCALE: &'static str = "A";
    const SCALE_MEANING: &'static str = "lobe scale";
    const SCALE_BOX: (f64, f64, f64) = (0.0, 1e4, 1.0);
    const PER_CHANNEL: bool = false;
    type Memo = ();
    fn specs() -> Vec<ParamSpec> {
        abc_specs()
    }
    fn shape(q: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, dq: Option<&mut [f64]>) -> f64 {
        let Some(g) = HalfGeometry::new(l, v) else {
            if let Some(dq) = dq {
                dq.fill(0.0);
            }
            return 0.0;
        };
        // 1 - N.H >= 0; the max only absorbs rounding above 1.
        let (d, d_b, d_c) = abc_power(q[0], q[1], (1.0 - g.nh).max(0.0));
        let (fr, fr_eta) = fresnel_dielectric_d_eta(g.vh, q[2]);
        let common = g.shadowing() / (PI * g.nl * g.nv);
        if let Some(dq) = dq {
            dq[0] = common * d_b * fr;
            dq[1] = common * d_c * fr;
            dq[2] = common * d * fr_eta;
        }
        common * d * fr
    }
}

/// `(U^s - 1) / s` for `U >= 1`, continuous through `s = 0` (`ln U`).
fn pow_minus_one_over(lu: f64, s: f64) -> f64 {
    if s.abs() * lu < 1e-300 {
        lu
    } else {
        (s * lu).exp_m1() / s
    }
}

/// `N(B, C) = integral over the hemisphere of D(H) (N.H) dH` for the ABC
/// distribution `D = (1 + B (1 - N.H))^-C`: with `u = 1 + B (1 - mu)`,
/// `N = 2 pi / B^2 integral_1^{1+B} (1 + B - u) u^-C du`
/// `= 2 pi / B^2 [(1 + B) g(1 - C) - g(2 - C)]`, `g(s) = ((1+B)^s - 1)/s`;
/// `N(0, C) = pi` (a constant `D = 1`).
pub fn abc_normalisation(b: f64, c: f64) -> f64 {
    if b < 1e-6 {
        // Series in B: D = 1 - C B (1 - mu) + ..., so N = pi - 2 pi C B / 6.
        return PI * (1.0 - c * b / 3.0);
    }
    let lu = b.ln_1p();
    2.0 * PI / (b * b)
        * ((1.0 + b) * pow_minus_one_over(lu, 1.0 - c) - pow_minus_one_over(lu, 2.0 - c))
}

/// Löw's smooth-surface model with a Lambertian term.
pub type LowSmooth = FittedLobe<LowSmoothShape>;
/// Löw's microfacet model with the ABC distribution and a Lambertian term.
pub type LowAbc = FittedLobe<LowAbcShape>;
