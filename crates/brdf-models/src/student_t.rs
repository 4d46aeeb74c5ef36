//! STD: the Student's t-distribution of slopes (Ribardière, Bringier,
//! Meneveaux & Simonot 2017, "STD: Student's t-Distribution of Slopes for
//! Microfacet Based BSDFs", Computer Graphics Forum 36(2)), an isotropic
//! microfacet lobe between GGX (`gamma = 2`) and Beckmann (`gamma -> inf`),
//! with height-correlated Smith masking-shadowing and Schlick's Fresnel
//! term, as the crate's `Ggx` (`ggx` family):
//!
//! `f = kd/pi + ks D(H) G(L, V) F(V.H) / (4 (N.L)(N.V))`,
//!
//! `D = 1 / (pi alpha^2 cos^4 delta (1 + tan^2 delta / (alpha^2 (gamma - 1)))^gamma)`
//! (normalised in closed form: `integral D (N.H) dH = 1`),
//!
//! `Lambda(a) = (gamma - 1)^(3/2) Gamma(gamma - 1/2) / (sqrt(pi) Gamma(gamma) (2 gamma - 3) a) x^(gamma - 3/2) - I_x(gamma - 1, 1/2) / 2`,
//! `a = cot(theta) / alpha`, `x = (gamma - 1) / (gamma - 1 + a^2)`,
//!
//! `G = 1 / (1 + Lambda(L) + Lambda(V))`, `F = F0 + (1 - F0)(1 - V.H)^5`
//! (derivation of `Lambda` in `docs/derivations/fitted_microfacet_models.md`).
//!
//! `Lambda` is the exact Smith integral `(1/a) integral_a^inf (q - a) P2(q) dq`
//! of the distribution's one-dimensional marginal, a Student's t of `2 gamma
//! - 2` degrees of freedom: its first moment gives the power term (the
//! paper's `S1`, eq. 14) and its tail the regularised incomplete beta
//! function `I_x` (the paper's `S2`, eq. 15, which the paper approximates by
//! the rational fit of eq. 23; here `I_x` is evaluated by its continued
//! fraction to rounding, so that `gamma = 2` gives GGX's
//! `Lambda = (sqrt(1 + 1/a^2) - 1)/2` to rounding).
//!
//! | parameter | meaning | default box | linear |
//! | --- | --- | --- | --- |
//! | `kd` (per channel) | diffuse albedo | `[0, 1]` | yes |
//! | `ks` (per channel) | specular strength | `[0, 1]` | yes |
//! | `alpha` | width | `(0, 1]` | no |
//! | `gamma` | tail exponent (`2` GGX, `inf` Beckmann) | `(1.5, 40]` (the paper's range) | no |
//! | `f0` | Fresnel reflectance at normal incidence | `[0, 1]` | no |
//!
//! Derivatives: in `alpha`, `f0` and through `D` in `gamma` analytic; the
//! derivative of `Lambda` in `gamma` (the incomplete beta function in its
//! parameter) is a central difference inside the model, step `1e-5 gamma`,
//! accurate to about `1e-9` relative.
//!
//! Properties: reciprocal; non-negative; finite above the horizon. Energy:
//! `D` is normalised and `Lambda` is its exact Smith function, so the
//! visible normals are normalised and `G <= G1`: each lobe's albedo is at
//! most `max F <= 1`; the model conserves energy for `kd + ks <= 1` (tested
//! in `tests/new_models.rs`).
//!
//! ```
//! use brdf_core::Brdf;
//! use brdf_models::Std;
//! use nalgebra::Vector3;
//! // kd, ks, alpha, gamma, f0
//! let m = Std::new(&[0.0], &[1.0], &[0.3, 5.0, 0.5]).unwrap();
//! let mut f = [0.0];
//! m.eval(&Vector3::z(), &Vector3::z(), &mut f);
//! // At the pole D = 1/(pi alpha^2), G = 1, F = F0 for every gamma.
//! let expect = 0.5 / (4.0 * std::f64::consts::PI * 0.09);
//! assert!((f[0] - expect).abs() < 1e-13 * expect);
//! ```

use std::f64::consts::PI;

use brdf_core::ParamSpec;
use brdf_core::fresnel::{schlick, schlick_d_f0};
use nalgebra::Vector3;

use crate::combinators::{DiffuseLobe, Lobe};

/// `ln Gamma(x)` for `x >= 1/2` (Lanczos, `g = 7`, 9 terms: relative error
/// below `2e-15`).
pub fn ln_gamma(x: f64) -> f64 {
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    let x = x - 1.0;
    let mut a = C[0];
    for (i, c) in C.iter().enumerate().skip(1) {
        a += c / (x + i as f64);
    }
    let t = x + 7.5;
    0.5 * (2.0 * PI).ln() + (x + 0.5) * t.ln() - t + a.ln()
}

/// Continued fraction of the incomplete beta function (modified Lentz).
fn beta_cf(a: f64, b: f64, x: f64) -> f64 {
    const TINY: f64 = 1e-300;
    let guard = |d: f64| if d.abs() < TINY { TINY } else { d };
    let (qab, qap, qam) = (a + b, a + 1.0, a - 1.0);
    let mut c = 1.0;
    let mut d = 1.0 / guard(1.0 - qab * x / qap);
    let mut h = d;
    for m in 1..=500 {
        let m = m as f64;
        let m2 = 2.0 * m;
        let aa = m * (b - m) * x / ((qam + m2) * (a + m2));
        d = 1.0 / guard(1.0 + aa * d);
        c = guard(1.0 + aa / c);
        h *= d * c;
        let aa = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2));
        d = 1.0 / guard(1.0 + aa * d);
        c = guard(1.0 + aa / c);
        let del = d * c;
        h *= del;
        if (del - 1.0).abs() < 1e-16 {
            break;
        }
    }
    h
}

/// Regularised incomplete beta `I_x(a, b)`, given `x` and `1 - x` (both
/// passed so neither is formed by cancellation).
pub fn incomplete_beta(a: f64, b: f64, x: f64, one_minus_x: f64) -> f64 {
    if x <= 0.0 {
        return 0.0;
    }
    if one_minus_x <= 0.0 {
        return 1.0;
    }
    let ln_front = ln_gamma(a + b) - ln_gamma(a) - ln_gamma(b) + a * x.ln() + b * one_minus_x.ln();
    let front = ln_front.exp();
    // The fraction converges fast on this side; the other side by symmetry.
    if x < (a + 1.0) / (a + b + 2.0) {
        front * beta_cf(a, b, x) / a
    } else {
        1.0 - front * beta_cf(b, a, one_minus_x) / b
    }
}

/// `D(h)` of the STD for a unit half vector above the horizon and
/// `(d ln D/d alpha, d ln D/d gamma)`.
#[inline]
pub fn std_d(h: &Vector3<f64>, alpha: f64, gamma: f64) -> (f64, f64, f64) {
    let c2 = h.z * h.z;
    let t2 = (h.x * h.x + h.y * h.y) / c2;
    let u = t2 / (alpha * alpha * (gamma - 1.0));
    let l1u = u.ln_1p();
    // cos^4 (1 + u)^gamma in logs: for gamma < 2 it vanishes towards
    // grazing half vectors, for gamma > 2 it grows, neither overflows here.
    let d = (-(2.0 * c2.ln() + gamma * l1u)).exp() / (PI * alpha * alpha);
    let r = u / (1.0 + u);
    (
        d,
        (-2.0 + 2.0 * gamma * r) / alpha,
        -l1u + gamma * r / (gamma - 1.0),
    )
}

/// Smith's `Lambda(a)` of the STD at `a = cot(theta)/alpha > 0` and the
/// tail `I_x(gamma - 1, 1/2) / 2`.
fn lambda_of_a(a: f64, gamma: f64) -> (f64, f64) {
    let g1 = gamma - 1.0;
    let den = g1 + a * a;
    let (x, omx) = (g1 / den, a * a / den);
    let tail = 0.5 * incomplete_beta(g1, 0.5, x, omx);
    let ln_k = 1.5 * g1.ln() + ln_gamma(gamma - 0.5) - ln_gamma(gamma) - 0.5 * PI.ln();
    let first = (ln_k + (gamma - 1.5) * x.ln()).exp() / ((2.0 * gamma - 3.0) * a);
    ((first - tail).max(0.0), tail)
}

/// Smith's `Lambda(w)` of the STD and `(dLambda/d alpha, dLambda/d gamma)`
/// for `w` above the horizon.
pub fn std_lambda(w: &Vector3<f64>, alpha: f64, gamma: f64) -> (f64, f64, f64) {
    std_lambda_with(w, alpha, gamma, true)
}

/// As [`std_lambda`]; the derivative in `gamma` (two more evaluations) only
/// when `d_gamma` is set, 0 otherwise.
fn std_lambda_with(w: &Vector3<f64>, alpha: f64, gamma: f64, d_gamma: bool) -> (f64, f64, f64) {
    let r = w.x.hypot(w.y);
    if !(r > 0.0) {
        return (0.0, 0.0, 0.0);
    }
    let a = w.z / (alpha * r);
    let (lam, tail) = lambda_of_a(a, gamma);
    // dLambda/da = -(Lambda + tail)/a and da/dalpha = -a/alpha.
    let d_alpha = (lam + tail) / alpha;
    let h = (1e-5 * gamma).min(0.5 * (gamma - 1.5));
    let d_g = if d_gamma && h > 0.0 {
        (lambda_of_a(a, gamma + h).0 - lambda_of_a(a, gamma - h).0) / (2.0 * h)
    } else {
        0.0
    };
    (lam, d_alpha, d_g)
}

/// One STD lobe `D G F / (4 N.L N.V)`, parameters `alpha`, `gamma`, `f0`.
#[derive(Clone, Debug, PartialEq)]
pub struct StdLobe;

impl Lobe for StdLobe {
    const NAME: &'static str = "std";
    fn specs() -> Vec<ParamSpec> {
        vec![
            ParamSpec::new("alpha", "STD width", 0.0, 1.0, 0.2, false).open_below(),
            ParamSpec::new("gamma", "STD tail exponent", 1.5, 40.0, 2.0, false).open_below(),
            ParamSpec::new(
                "f0",
                "Fresnel reflectance at normal incidence",
                0.0,
                1.0,
                0.04,
                false,
            ),
        ]
    }
    fn shape(q: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, dq: Option<&mut [f64]>) -> f64 {
        let (alpha, gamma, f0) = (q[0], q[1], q[2]);
        let s = l + v;
        let len = s.norm();
        if !(len > 0.0) {
            if let Some(dq) = dq {
                dq.fill(0.0);
            }
            return 0.0;
        }
        let h = s / len;
        let (d, d_la, d_lg) = std_d(&h, alpha, gamma);
        let grad = dq.is_some();
        let (ll, ll_a, ll_g) = std_lambda_with(l, alpha, gamma, grad);
        let (lv, lv_a, lv_g) = std_lambda_with(v, alpha, gamma, grad);
        let g = 1.0 / (1.0 + ll + lv);
        let vh = v.dot(&h).clamp(0.0, 1.0);
        let base = d * g / (4.0 * l.z * v.z);
        let f = schlick(f0, vh);
        if let Some(dq) = dq {
            // d ln G = -G dLambda.
            dq[0] = base * f * (d_la - g * (ll_a + lv_a));
            dq[1] = base * f * (d_lg - g * (ll_g + lv_g));
            dq[2] = base * schlick_d_f0(vh);
        }
        base * f
    }
}

/// Lambert plus one STD lobe.
pub type Std = DiffuseLobe<StdLobe>;
