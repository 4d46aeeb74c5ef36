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
//! in `tests/models/new_models.rs`).
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

use brdf_core::fresnel::{schlick, schlick_d_f0};
use brdf_core::{DirPairs, PairGeometry, ParamSpec};
use nalgebra::Vector3;

use crate::combinators::{DiffuseLobe, Lobe};

mod batch;

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

/// Most terms of the incomplete beta function's continued fraction.
const CF_MAX_TERMS: usize = 500;

/// Lentz's guard: a denominator below `1e-300` in magnitude taken as
/// `1e-300`.
#[inline(always)]
fn cf_guard(d: f64) -> f64 {
    const TINY: f64 = 1e-300;
    if d.abs() < TINY { TINY } else { d }
}

/// Continued fraction of the incomplete beta function (modified Lentz).
fn beta_cf(a: f64, b: f64, x: f64) -> f64 {
    let guard = cf_guard;
    let (qab, qap, qam) = (a + b, a + 1.0, a - 1.0);
    let mut c = 1.0;
    let mut d = 1.0 / guard(1.0 - qab * x / qap);
    let mut h = d;
    for m in 1..=CF_MAX_TERMS {
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
    let ln_beta = ln_gamma(a + b) - ln_gamma(a) - ln_gamma(b);
    match BetaTail::start(ln_beta, a, b, x, one_minus_x, x.ln()) {
        BetaTail::Known(v) => v,
        BetaTail::Fraction(f) => f.finish(beta_cf(f.a, f.b, f.x)),
    }
}

/// `I_x(a, b)` up to its continued fraction: known outright at the ends
/// of `[0, 1]`, else the fraction's arguments and the factors around it.
#[derive(Clone, Copy, Debug)]
enum BetaTail {
    Known(f64),
    Fraction(Fraction),
}

/// `I_x(a, b) = front cf(a, b, x) / a` (`direct`), or by the symmetry
/// `1 - front cf(b, a, 1 - x) / b`; `(a, b, x)` here are the fraction's.
#[derive(Clone, Copy, Debug)]
struct Fraction {
    front: f64,
    a: f64,
    b: f64,
    x: f64,
    direct: bool,
}

impl BetaTail {
    /// `ln_beta = ln Gamma(a + b) - ln Gamma(a) - ln Gamma(b)` (it depends on
    /// the parameters alone, so a batch takes it once) and `ln_x = ln x`.
    fn start(ln_beta: f64, a: f64, b: f64, x: f64, one_minus_x: f64, ln_x: f64) -> BetaTail {
        if x <= 0.0 {
            return BetaTail::Known(0.0);
        }
        if one_minus_x <= 0.0 {
            return BetaTail::Known(1.0);
        }
        let front = (ln_beta + a * ln_x + b * one_minus_x.ln()).exp();
        // The fraction converges fast on this side; the other side by symmetry.
        BetaTail::Fraction(if x < (a + 1.0) / (a + b + 2.0) {
            Fraction {
                front,
                a,
                b,
                x,
                direct: true,
            }
        } else {
            Fraction {
                front,
                a: b,
                b: a,
                x: one_minus_x,
                direct: false,
            }
        })
    }
}

impl Fraction {
    /// `I_x` from the continued fraction's value `cf`.
    fn finish(&self, cf: f64) -> f64 {
        if self.direct {
            self.front * cf / self.a
        } else {
            1.0 - self.front * cf / self.a
        }
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

/// Smith's `Lambda` of the STD at one `gamma`: the factors that depend on
/// `gamma` alone (five log-gamma functions) taken once, for every `a`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct LambdaAt {
    gamma: f64,
    g1: f64,
    /// `ln Gamma(gamma - 1/2) - ln Gamma(gamma - 1) - ln Gamma(1/2)`: the
    /// front factor of `I_x(gamma - 1, 1/2)`
    ln_beta: f64,
    /// log of the power term's constant
    ln_k: f64,
}

/// What [`LambdaAt`] needs of one `a` around the continued fraction.
#[derive(Clone, Copy, Debug)]
struct LambdaStart {
    a: f64,
    ln_x: f64,
    tail: BetaTail,
}

impl LambdaAt {
    pub(crate) fn new(gamma: f64) -> LambdaAt {
        let g1 = gamma - 1.0;
        LambdaAt {
            gamma,
            g1,
            ln_beta: ln_gamma(g1 + 0.5) - ln_gamma(g1) - ln_gamma(0.5),
            ln_k: 1.5 * g1.ln() + ln_gamma(gamma - 0.5) - ln_gamma(gamma) - 0.5 * PI.ln(),
        }
    }

    /// `Lambda(a)` at `a = cot(theta)/alpha > 0` and the tail
    /// `I_x(gamma - 1, 1/2) / 2`.
    fn eval(&self, a: f64) -> (f64, f64) {
        let s = self.start(a);
        let i_x = match s.tail {
            BetaTail::Known(v) => v,
            BetaTail::Fraction(f) => f.finish(beta_cf(f.a, f.b, f.x)),
        };
        self.finish(&s, i_x)
    }

    /// The stage before the continued fraction.
    fn start(&self, a: f64) -> LambdaStart {
        let den = self.g1 + a * a;
        let (x, omx) = (self.g1 / den, a * a / den);
        let ln_x = x.ln();
        LambdaStart {
            a,
            ln_x,
            tail: BetaTail::start(self.ln_beta, self.g1, 0.5, x, omx, ln_x),
        }
    }

    /// `(Lambda, tail)` from `I_x(gamma - 1, 1/2)`.
    fn finish(&self, s: &LambdaStart, i_x: f64) -> (f64, f64) {
        let tail = 0.5 * i_x;
        let gamma = self.gamma;
        let first = (self.ln_k + (gamma - 1.5) * s.ln_x).exp() / ((2.0 * gamma - 3.0) * s.a);
        ((first - tail).max(0.0), tail)
    }
}

/// Step of the central difference of `Lambda` in `gamma` (0: none, at the
/// lower end of the box).
fn gamma_step(gamma: f64) -> f64 {
    (1e-5 * gamma).min(0.5 * (gamma - 1.5))
}

/// `a = cot(theta)/alpha` of `w`, or `None` at the pole (where `Lambda = 0`).
fn cot_over_alpha(w: &Vector3<f64>, alpha: f64) -> Option<f64> {
    let r = w.x.hypot(w.y);
    (r > 0.0).then(|| w.z / (alpha * r))
}

/// Smith's `Lambda(w)` of the STD and `(dLambda/d alpha, dLambda/d gamma)`
/// for `w` above the horizon.
pub fn std_lambda(w: &Vector3<f64>, alpha: f64, gamma: f64) -> (f64, f64, f64) {
    let at = [gamma, gamma + gamma_step(gamma), gamma - gamma_step(gamma)].map(LambdaAt::new);
    std_lambda_with(w, alpha, &at, true)
}

/// As [`std_lambda`] with `Lambda` at `gamma` and at `gamma` plus and minus
/// [`gamma_step`] (`at`); the derivative in `gamma` only when `d_gamma`
/// is set, 0 otherwise.
fn std_lambda_with(
    w: &Vector3<f64>,
    alpha: f64,
    at: &[LambdaAt; 3],
    d_gamma: bool,
) -> (f64, f64, f64) {
    let Some(a) = cot_over_alpha(w, alpha) else {
        return (0.0, 0.0, 0.0);
    };
    let (lam, tail) = at[0].eval(a);
    let ends =
        (d_gamma && gamma_step(at[0].gamma) > 0.0).then(|| (at[1].eval(a).0, at[2].eval(a).0));
    lambda_derivatives(lam, tail, alpha, at[0].gamma, ends)
}

/// `(Lambda, dLambda/d alpha, dLambda/d gamma)` from `Lambda` and its tail
/// at `gamma` and, for the derivative in `gamma`, `Lambda` at `gamma`
/// plus and minus [`gamma_step`].
fn lambda_derivatives(
    lam: f64,
    tail: f64,
    alpha: f64,
    gamma: f64,
    ends: Option<(f64, f64)>,
) -> (f64, f64, f64) {
    // dLambda/da = -(Lambda + tail)/a and da/dalpha = -a/alpha.
    let d_alpha = (lam + tail) / alpha;
    let d_g = ends.map_or(0.0, |(plus, minus)| {
        (plus - minus) / (2.0 * gamma_step(gamma))
    });
    (lam, d_alpha, d_g)
}

/// One STD lobe `D G F / (4 N.L N.V)`, parameters `alpha`, `gamma`, `f0`.
#[derive(Clone, Debug, PartialEq)]
pub struct StdLobe;

impl Lobe for StdLobe {
    const NAME: &'static str = "std";
    const BATCH_IS_EXACT: bool = true;
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
        let Some(h) = half_vector(l, v) else {
            if let Some(dq) = dq {
                dq.fill(0.0);
            }
            return 0.0;
        };
        let grad = dq.is_some();
        let at = lambdas_at(q[1], grad);
        let ll = std_lambda_with(l, q[0], &at, grad);
        let lv = std_lambda_with(v, q[0], &at, grad);
        lobe_value(q, l, v, &h, ll, lv, dq)
    }
    fn shape_batch(
        q: &[f64],
        pairs: &DirPairs,
        geom: &PairGeometry,
        s: &mut [f64],
        ds: Option<&mut [f64]>,
    ) {
        batch::shape_batch(q, pairs, &geom.valid, s, ds);
    }
}

/// The unit half vector of `l` and `v`, `None` where `l + v = 0`.
fn half_vector(l: &Vector3<f64>, v: &Vector3<f64>) -> Option<Vector3<f64>> {
    let s = l + v;
    let len = s.norm();
    (len > 0.0).then(|| s / len)
}

/// [`LambdaAt`] at `gamma` and, when the derivative in `gamma` is wanted,
/// at `gamma` plus and minus [`gamma_step`] (else copies of the first).
fn lambdas_at(gamma: f64, d_gamma: bool) -> [LambdaAt; 3] {
    let at = LambdaAt::new(gamma);
    if d_gamma {
        let h = gamma_step(gamma);
        [at, LambdaAt::new(gamma + h), LambdaAt::new(gamma - h)]
    } else {
        [at; 3]
    }
}

/// The lobe `S = D G F / (4 N.L N.V)` at parameters `q` from the pair's
/// unit half vector `h` and `(Lambda, dLambda/d alpha, dLambda/d gamma)`
/// of `l` (`ll`) and of `v` (`lv`); `dS/dq` into `dq` when given.
fn lobe_value(
    q: &[f64],
    l: &Vector3<f64>,
    v: &Vector3<f64>,
    h: &Vector3<f64>,
    (ll, ll_a, ll_g): (f64, f64, f64),
    (lv, lv_a, lv_g): (f64, f64, f64),
    dq: Option<&mut [f64]>,
) -> f64 {
    let (alpha, gamma, f0) = (q[0], q[1], q[2]);
    let (d, d_la, d_lg) = std_d(h, alpha, gamma);
    let g = 1.0 / (1.0 + ll + lv);
    let vh = v.dot(h).clamp(0.0, 1.0);
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

/// Lambert plus one STD lobe.
pub type Std = DiffuseLobe<StdLobe>;
