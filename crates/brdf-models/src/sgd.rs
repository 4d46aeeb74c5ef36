//! Bagher, Soler & Holzschuch 2012, "Accurate fitting of measured
//! reflectances using a Shifted Gamma micro-facet distribution", Computer
//! Graphics Forum 31(4): Cook-Torrance with the shifted gamma distribution
//! (SGD), the paper's fitted approximation of the Smith shadowing term and
//! its two-parameter Fresnel term, every parameter per colour channel:
//!
//! `f_c = kd_c/pi + ks_c D(H) G1(theta_i) G1(theta_o) F(V.H) / (pi (N.L)(N.V))`,
//!
//! `D = P22(tan^2 delta) / (pi cos^4 delta)`,
//! `P22(t) = exp(-(alpha + t/alpha)) / (alpha + t/alpha)^p`,
//!
//! `G1(theta) = max(0, 1 + Lambda (1 - exp(c (theta - theta0)^k)))` for
//! `theta > theta0`, 1 otherwise,
//!
//! `F(x) = max(0, F0 + (1 - F0)(1 - x)^5 - F1 x)`.
//!
//! The paper's `D` carries a normalisation `K_ap = 1 / (alpha Gamma(1 - p,
//! alpha))` that depends only on `alpha`, `p`; it multiplies `ks`, with which
//! it is redundant in a fit, so this model's `ks` is the product
//! (`ks = rho_s K_ap`). The published fits (BBM `fits/bagher_sgd.fit`, whose
//! `Bagher(albedo, alpha, p, eta = [F0, F1], K, Lambda, c, k, theta0)`
//! evaluates the same formula) map as `ks = albedo * K`, every other
//! parameter unchanged (`eta[0] = F0`, `eta[1] = F1`); the published `K`
//! equal `1 / (alpha Gamma(1 - p, alpha))` to their printed digits
//! (`docs/derivations/fitted_microfacet_models.md`). The clamps at 0 of
//! `G1` and `F` are this crate's: the published formulas go negative for
//! some parameters (`G1` near grazing, `F` for `F1 > F0` near `V.H = 1`);
//! the fixture's four published materials stay positive at the reference
//! pairs (other materials and directions were not checked).
//!
//! | parameter (per channel) | meaning | default box | linear |
//! | --- | --- | --- | --- |
//! | `kd` | diffuse albedo | `[0, 1]` | yes |
//! | `ks` | specular scale (`rho_s K_ap`) | `[0, 1e5]` | yes |
//! | `alpha` | SGD width | `(0, 1]` | no |
//! | `p` | SGD shift exponent | `[0, 2]` | no |
//! | `f0` | Fresnel `F0` | `[0, 10]` | no |
//! | `f1` | Fresnel `F1` | `[-1, 10]` | no |
//! | `lambda` | shadowing depth `Lambda` | `[0, 100]` | no |
//! | `c` | shadowing rate | `[0, 1e3]` | no |
//! | `k` | shadowing exponent | `[1, 1e3]` | no |
//! | `theta0` | shadowing onset angle (rad) | `[-pi/2, pi/2]` | no |
//!
//! Ten parameters per channel (30 for RGB). The boxes hold most published
//! fits; a few (chrome, black-obsidian, chrome-steel) have `c` up to `1e109`
//! and need a wider box.
//!
//! Properties: reciprocal (`D(H)`, `F(V.H)`, `G1(theta_i) G1(theta_o)`);
//! non-negative by the clamps; finite above the horizon (`D` is evaluated as
//! `exp(-w - p ln w - 4 ln cos delta)`, which underflows to 0 towards
//! grazing half vectors). Energy: `G1 <= 1`, and `D` integrates to
//! `integral D (N.H) dH = 1 / K_ap` ([`sgd_normalisation`]), so for sharp
//! lobes the lobe's albedo tends to `4 ks F G1^2 / (pi K_ap)`, as
//! Cook-Torrance's tends to `4 ks F0`; the domain is
//! `kd + 4 ks max F / (pi K_ap) <= 1` for `alpha <= 0.1` and incidence up
//! to 70 deg even without shadowing (tested in `tests/models/new_models.rs`, and
//! shown exceeded just outside: at 1.3 times the bound; for a rough lobe,
//! `alpha = 0.5`, by 10% at the bound; towards grazing incidence when
//! `Lambda = 0`, since `G1 = 1` leaves the `1 / (N.L)`).
//!
//! ```
//! use brdf_core::Brdf;
//! use brdf_models::Sgd;
//! use nalgebra::Vector3;
//! // kd, ks, alpha, p, f0, f1, lambda, c, k, theta0 (one channel)
//! let m = Sgd::new(1, &[0.0, 1.0, 0.1, 0.5, 0.5, 0.0, 2.0, 0.1, 10.0, 0.5]).unwrap();
//! let mut f = [0.0];
//! m.eval(&Vector3::z(), &Vector3::z(), &mut f);
//! // At the pole: tan = 0, w = alpha, G1 = 1 (theta = 0 < theta0), F = F0.
//! let d = (-0.1f64).exp() / 0.1f64.powf(0.5) / std::f64::consts::PI;
//! let expect = d * 0.5 / std::f64::consts::PI;
//! assert!((f[0] - expect).abs() < 1e-13 * expect);
//! ```

pub mod channel;

use std::f64::consts::{FRAC_PI_2, PI};

use brdf_core::ParamSpec;
use nalgebra::Vector3;

use crate::fitted_lobes::{FittedLobe, FittedShape, MAX_SHAPE_PARAMS};
use crate::microfacet::HalfGeometry;

/// `D(H)` of the SGD without `K_ap` and `(d ln D/d alpha, d ln D/d p)`, or
/// `None` where it underflows.
#[inline]
pub fn sgd_d(nh: f64, alpha: f64, p: f64) -> Option<(f64, f64, f64)> {
    if !(nh > 0.0) {
        return None;
    }
    let c2 = nh * nh;
    let t = (1.0 - c2).max(0.0) / c2;
    let w = alpha + t / alpha;
    let lw = w.ln();
    let d = (-w - p * lw - 2.0 * c2.ln()).exp() / PI;
    if !(d > 0.0) {
        return None;
    }
    let dw = 1.0 - t / (alpha * alpha);
    Some((d, -(1.0 + p / w) * dw, -lw))
}

/// Bagher's `G1(theta)` with `[Lambda, c, k, theta0]` and its derivatives.
#[inline]
pub fn sgd_g1(theta: f64, s: &[f64]) -> (f64, [f64; 4]) {
    let (lambda, c, k, theta0) = (s[0], s[1], s[2], s[3]);
    let x = theta - theta0;
    if !(x > 0.0) {
        return (1.0, [0.0; 4]);
    }
    let lx = x.ln();
    // x^k may overflow for x > 1; c x^k is formed in logs so c = 0 gives 0.
    let xk = (k * lx).exp().min(f64::MAX);
    let e = if c > 0.0 {
        (c.ln() + k * lx).exp()
    } else {
        0.0
    };
    let ee = e.exp();
    let g = 1.0 + lambda * (1.0 - ee);
    if lambda == 0.0 {
        // G1 = 1 whatever exp gives; only its slope in Lambda remains.
        return (1.0, [(1.0 - ee).max(f64::MIN), 0.0, 0.0, 0.0]);
    }
    // Past the clamp (also where exp overflows) G1 is 0 with no slope.
    if !(g > 0.0) {
        return (0.0, [0.0; 4]);
    }
    let de = -lambda * ee;
    (g, [1.0 - ee, de * xk, de * e * lx, -de * e * k / x])
}

/// The paper's normalisation `K_ap = 1 / integral D (N.H) dH` of the `D`
/// above: `integral = 2 integral_0^inf P22(t^2) t dt = alpha Gamma(1 - p,
/// alpha) = alpha integral_alpha^inf exp(-u) u^-p du`, computed by Simpson's
/// rule in `y = ln u` (the integrand `exp(-u) u^(1-p)` is smooth in `y`;
/// 4000 intervals over `[ln alpha, ln(alpha + 60)]` put the error below
/// `1e-12` relative, and `exp(-60)` bounds the cut tail).
pub fn sgd_normalisation(alpha: f64, p: f64) -> f64 {
    let (a, b) = (alpha.ln(), (alpha + 60.0).ln());
    let n = 4000;
    let h = (b - a) / n as f64;
    let f = |y: f64| {
        let u = y.exp();
        (-u + (1.0 - p) * y).exp()
    };
    let mut sum = f(a) + f(b);
    for i in 1..n {
        sum += f(a + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    1.0 / (alpha * sum * h / 3.0)
}

/// Bagher's Fresnel term `max(0, F0 + (1 - F0)(1 - x)^5 - F1 x)` and its
/// derivatives in `F0`, `F1`.
#[inline]
pub fn sgd_fresnel(f0: f64, f1: f64, x: f64) -> (f64, f64, f64) {
    let m5 = (1.0 - x).max(0.0).powi(5);
    let f = f0 + (1.0 - f0) * m5 - f1 * x;
    if f > 0.0 {
        (f, 1.0 - m5, -x)
    } else {
        (0.0, 0.0, 0.0)
    }
}

/// The SGD lobe `D G1 G1 F / (pi N.L N.V)`, parameters
/// `[alpha, p, f0, f1, lambda, c, k, theta0]`.
#[derive(Clone, Debug, PartialEq)]
pub struct SgdShape;

impl FittedShape for SgdShape {
    const NAME: &'static str = "sgd";
    const SCALE: &'static str = "ks";
    const SCALE_MEANING: &'static str = "specular scale (rho_s K_ap)";
    const SCALE_BOX: (f64, f64, f64) = (0.0, 1e5, 1.0);
    const PER_CHANNEL: bool = true;
    fn specs() -> Vec<ParamSpec> {
        vec![
            ParamSpec::new("alpha", "SGD width", 0.0, 1.0, 0.1, false).open_below(),
            ParamSpec::new("p", "SGD shift exponent", 0.0, 2.0, 0.5, false),
            ParamSpec::new("f0", "Fresnel F0", 0.0, 10.0, 0.1, false),
            ParamSpec::new("f1", "Fresnel F1", -1.0, 10.0, 0.0, false),
            ParamSpec::new("lambda", "shadowing depth", 0.0, 100.0, 3.0, false),
            ParamSpec::new("c", "shadowing rate", 0.0, 1e3, 1e-7, false),
            ParamSpec::new("k", "shadowing exponent", 1.0, 1e3, 20.0, false),
            ParamSpec::new(
                "theta0",
                "shadowing onset angle (rad)",
                -FRAC_PI_2,
                FRAC_PI_2,
                0.0,
                false,
            ),
        ]
    }
    fn shape(q: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, dq: Option<&mut [f64]>) -> f64 {
        let Some(g) = HalfGeometry::new(l, v) else {
            if let Some(dq) = dq {
                dq.fill(0.0);
            }
            return 0.0;
        };
        let g1 = |theta: f64| sgd_g1(theta, &q[4..8]);
        shape_at(q, &g, [polar_angle(l), polar_angle(v)], g1, dq)
    }
    type Memo = G1Memo;
    /// The half-vector geometry and both polar angles once for every
    /// channel; each channel's `G1` read from `memo` when the pair before
    /// had the same angle (the view of every term of a rendered pixel,
    /// the incident direction along a measurement's grid).
    fn shape_channels(
        qs: &[[f64; MAX_SHAPE_PARAMS]],
        nq: usize,
        l: &Vector3<f64>,
        v: &Vector3<f64>,
        memo: &mut G1Memo,
        s: &mut [f64],
        mut dq: Option<&mut [[f64; MAX_SHAPE_PARAMS]]>,
    ) {
        let Some(g) = HalfGeometry::new(l, v) else {
            s[..qs.len()].fill(0.0);
            if let Some(dq) = dq {
                dq.iter_mut().for_each(|d| d[..nq].fill(0.0));
            }
            return;
        };
        let thetas = [memo.polar_angle(0, l), memo.polar_angle(1, v)];
        memo.last.resize(qs.len(), [None; 2]);
        for (c, q) in qs.iter().enumerate() {
            let last = &mut memo.last[c];
            // `shape_at` asks for `G1` at `theta_i`, then at `theta_o`: the
            // role is which of the pair's angles is asked for (either slot
            // holds the right value when both angles are equal).
            let g1 = |theta: f64| {
                let role = usize::from(theta.to_bits() != thetas[0].to_bits());
                match last[role] {
                    Some((bits, value)) if bits == theta.to_bits() => value,
                    _ => {
                        let value = sgd_g1(theta, &q[4..8]);
                        last[role] = Some((theta.to_bits(), value));
                        value
                    }
                }
            };
            s[c] = shape_at(
                &q[..nq],
                &g,
                thetas,
                g1,
                dq.as_deref_mut().map(|d| &mut d[c][..nq]),
            );
        }
    }
}

/// The polar angle of unit `w`, `atan2(|w_xy|, w_z)`.
fn polar_angle(w: &Vector3<f64>) -> f64 {
    w.x.hypot(w.y).atan2(w.z)
}

/// `G1` and its derivatives in `[Lambda, c, k, theta0]`.
type G1Value = (f64, [f64; 4]);

/// `G1` of each channel at the polar angles of its last pair, per role
/// (`L`, `V`): `(theta's bits, G1 and its derivatives)`.
/// And the polar angle of the last `L` and `V` by their bits.
#[derive(Default)]
pub struct G1Memo {
    last: Vec<[Option<(u64, G1Value)>; 2]>,
    angles: [Option<([u64; 3], f64)>; 2],
}

impl G1Memo {
    /// [`polar_angle`] of `w` in role `role` (0: `L`, 1: `V`), read again
    /// when the last pair's direction in that role was `w`.
    fn polar_angle(&mut self, role: usize, w: &Vector3<f64>) -> f64 {
        let bits = [w.x.to_bits(), w.y.to_bits(), w.z.to_bits()];
        match self.angles[role] {
            Some((b, theta)) if b == bits => theta,
            _ => {
                let theta = polar_angle(w);
                self.angles[role] = Some((bits, theta));
                theta
            }
        }
    }
}

/// The lobe at `q` from the pair's geometry `g`, the polar angles of `L`
/// and `V` and `G1` by angle (`g1`).
fn shape_at(
    q: &[f64],
    g: &HalfGeometry,
    [theta_i, theta_o]: [f64; 2],
    mut g1: impl FnMut(f64) -> (f64, [f64; 4]),
    dq: Option<&mut [f64]>,
) -> f64 {
    let Some((d, d_alpha, d_p)) = sgd_d(g.nh, q[0], q[1]) else {
        if let Some(dq) = dq {
            dq.fill(0.0);
        }
        return 0.0;
    };
    let (gi, dgi) = g1(theta_i);
    let (go, dgo) = g1(theta_o);
    let (fr, fr0, fr1) = sgd_fresnel(q[2], q[3], g.vh);
    let common = d / (PI * g.nl * g.nv);
    let s = common * gi * go * fr;
    if let Some(dq) = dq {
        dq[0] = s * d_alpha;
        dq[1] = s * d_p;
        dq[2] = common * gi * go * fr0;
        dq[3] = common * gi * go * fr1;
        for k in 0..4 {
            dq[4 + k] = common * fr * (dgi[k] * go + gi * dgo[k]);
        }
    }
    s
}

/// Bagher et al.'s SGD model with a Lambertian term, parameters per channel.
pub type Sgd = FittedLobe<SgdShape>;

/// The lobe shapes [`suggested_starts`] proposes, `[alpha, p, f0, f1,
/// lambda, c, k, theta0]`: the defaults (shadowing practically off:
/// `c x^k <= 1e-4` above the horizon), then widths `0.02, 0.1, 0.4` and
/// shifts `0.3, 1.2` with a mild shadowing term (`G1` 1 up to 0.5 rad,
/// 0.86 at 1 rad, 0.38 at 1.4 rad), whose derivatives in
/// `Lambda, c, k, theta0` are all non-zero above the onset.
pub const SGD_START_SHAPES: [[f64; 8]; 7] = [
    [0.1, 0.5, 0.1, 0.0, 3.0, 1e-7, 20.0, 0.0],
    [0.02, 0.3, 0.5, 0.0, 0.5, 1.0, 2.0, 0.5],
    [0.1, 0.3, 0.5, 0.0, 0.5, 1.0, 2.0, 0.5],
    [0.4, 0.3, 0.5, 0.0, 0.5, 1.0, 2.0, 0.5],
    [0.02, 1.2, 0.5, 0.0, 0.5, 1.0, 2.0, 0.5],
    [0.1, 1.2, 0.5, 0.0, 0.5, 1.0, 2.0, 0.5],
    [0.4, 1.2, 0.5, 0.0, 0.5, 1.0, 2.0, 0.5],
];

/// Starts of an SGD fit (the catalogue's [`SuggestStarts`](crate::catalogue::SuggestStarts)):
/// every channel with the same shape from [`SGD_START_SHAPES`], `kd` and
/// `ks` at their defaults (the solver projects them). Most points of the
/// box switch the lobe off: with `k` and `c` drawn over `[1, 1e3]` and
/// `theta0 < 0`, `c (theta - theta0)^k` overflows and the clamp sets `G1`
/// to 0 everywhere, where every derivative of the shape vanishes; the
/// pipeline's Halton starts on the RGL materials all ended with `ks = 0`.
/// These starts keep the lobe on; the fit then moves the shadowing.
/// Models other than an [`Sgd`] layout (a parameter count that is not
/// `10 * channels`) get none.
pub fn suggested_starts(model: &dyn brdf_core::Parametric) -> Vec<Vec<f64>> {
    let nc = model.channels();
    let specs = model.param_specs();
    if specs.len() != 10 * nc {
        return Vec::new();
    }
    SGD_START_SHAPES
        .iter()
        .map(|shape| {
            let mut p: Vec<f64> = specs.iter().take(2 * nc).map(|s| s.default).collect();
            for q in shape {
                p.extend(std::iter::repeat_n(*q, nc));
            }
            p
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use brdf_core::{DirPairs, Parametric};

    use super::*;

    /// The batch paths of the RGB model (every channel's shape at a pair at
    /// once, `G1` read again for a repeated angle) give the bits of the
    /// pair-by-pair ones, directions below the horizon and repeated views
    /// included.
    #[test]
    fn the_batch_gives_the_per_pair_values_and_jacobian_bit_for_bit() {
        let dir = |t: f64, f: f64| Vector3::new(t.sin() * f.cos(), t.sin() * f.sin(), t.cos());
        let mut pairs = DirPairs::with_capacity(0);
        for i in 0..9 {
            for j in 0..7 {
                pairs.push(
                    &dir(0.18 * i as f64, 0.5),
                    &dir(0.23 * j as f64, 2.0 + 0.3 * j as f64),
                );
            }
            // One view for many lights, as a rendered pixel's terms.
            pairs.push(&dir(0.1 * i as f64, 1.0), &dir(0.9, 0.2));
            pairs.push(&dir(0.1 * i as f64 + 0.05, 4.0), &dir(0.9, 0.2));
        }
        pairs.push(&dir(2.0, 0.0), &dir(0.5, 1.0));
        pairs.push(&Vector3::z(), &Vector3::z());
        let n = pairs.len();
        #[rustfmt::skip]
        let p = [
            0.2, 0.3, 0.1, 2.0, 3.0, 4.0, // kd, ks
            0.05, 0.1, 0.3, 0.4, 0.8, 1.2, 0.5, 0.6, 0.7, 0.0, 0.1, -0.2, // alpha, p, f0, f1
            0.5, 2.0, 0.0, 1.0, 0.3, 1e-7, 2.0, 5.0, 20.0, 0.5, -0.3, 0.0, // lambda, c, k, theta0
        ];
        let m = Sgd::new(3, &p).expect("sgd");
        let np = p.len();
        let (mut val, mut jac) = (vec![0.0; 3 * n], vec![0.0; 3 * n * np]);
        m.eval_grad_batch_at(&p, &pairs, &mut val, &mut jac);
        let mut only = vec![0.0; 3 * n];
        m.eval_batch_at(&p, &pairs, &mut only);
        let (mut one, mut grad) = ([0.0; 3], vec![0.0; 3 * np]);
        for j in 0..n {
            m.eval_grad_at(&p, &pairs.l(j), &pairs.v(j), &mut one, &mut grad);
            for c in 0..3 {
                assert_eq!(val[c * n + j].to_bits(), one[c].to_bits(), "pair {j}");
                assert_eq!(only[c * n + j].to_bits(), one[c].to_bits(), "pair {j}");
                let row = &jac[(c * n + j) * np..(c * n + j + 1) * np];
                let bits = |r: &[f64]| r.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(row), bits(&grad[c * np..(c + 1) * np]), "pair {j}");
            }
        }
        assert!(val.iter().filter(|x| **x > 0.0).count() > n);
    }
}
