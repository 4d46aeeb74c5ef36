//! [`SgdChannel`]: one colour channel of Bagher et al.'s SGD model
//! ([`Sgd`]) as a one-channel model with a batch kernel, what
//! the per-channel fit of an RGB SGD model solves three times.
//!
//! Every parameter of an SGD channel is its own, so a fit of the RGB model
//! is three one-channel problems ([`ChannelSlice`](crate::channel_slice::ChannelSlice)).
//! Sliced out of the RGB model, each evaluation formed all three channels
//! and their 30-column gradient per direction pair, which made most of the
//! time of `brdf select` on an RGL file. This model evaluates one channel:
//!
//! - with the channel-shared basis `[1/pi, S]` ([`SharedBasis`]), so the
//!   solvers project `kd`, `ks` out analytically and evaluate the basis
//!   over the pair geometry they cache (half-vector cosines, `ln N.H`,
//!   `(1 - V.H)^5`), not through per-pair gradients of the linear
//!   parameters;
//! - with a values-only path (the trial points of a solve) that forms no
//!   derivative factor (`x^k` of the shadowing term is one `exp` per
//!   direction that only the derivatives need);
//! - with the parameter-only factors (`ln c`) formed once per batch, and
//!   `ln cos^2 delta` read from the cached `ln N.H`.
//!
//! Parameters `[kd, ks, alpha, p, f0, f1, lambda, c, k, theta0]`: a channel's
//! block of the RGB model in its order, with the same boxes. Values and
//! derivatives agree with [`SgdShape`]'s per-pair formula to rounding
//! (tested).
//!
//! ```
//! use brdf_core::{Brdf, Parametric};
//! use brdf_models::Sgd;
//! use brdf_models::sgd::channel::SgdChannel;
//! use nalgebra::Vector3;
//! let p = [0.2, 1.0, 0.1, 0.5, 0.5, 0.0, 2.0, 0.1, 10.0, 0.5];
//! let fast = SgdChannel::new(&p).unwrap();
//! let reference = Sgd::new(1, &p).unwrap();
//! let (l, v) = (Vector3::new(0.3, 0.1, 0.9).normalize(), Vector3::new(-0.2, 0.0, 0.97).normalize());
//! let (mut a, mut b) = ([0.0], [0.0]);
//! fast.eval(&l, &v, &mut a);
//! reference.eval(&l, &v, &mut b);
//! assert!((a[0] - b[0]).abs() <= 1e-13 * b[0]);
//! ```

use std::f64::consts::{FRAC_1_PI, PI};

use brdf_core::{Brdf, DirPairs, PairGeometry, ParamError, ParamSpec, Parametric, SharedBasis};
use nalgebra::Vector3;

use crate::Sgd;
use crate::sgd::SgdShape;

/// Non-linear parameters of the lobe.
const NQ: usize = 8;
/// All parameters: `kd`, `ks` and the lobe's.
const NP: usize = NQ + 2;

/// One SGD channel (see the module doc).
#[derive(Clone, Debug, PartialEq)]
pub struct SgdChannel {
    /// The per-pair reference: specs, stored parameters, single points.
    inner: Sgd,
}

impl SgdChannel {
    /// The channel at `p = [kd, ks, alpha, p, f0, f1, lambda, c, k,
    /// theta0]`, validated against the boxes.
    pub fn new(p: &[f64]) -> Result<Self, ParamError> {
        Ok(Self {
            inner: Sgd::new(1, p)?,
        })
    }

    /// The channel at the model's default parameters.
    pub fn with_defaults() -> Result<Self, ParamError> {
        Ok(Self {
            inner: Sgd::with_channels(1)?,
        })
    }
}

/// The parameter-only factors of a batch.
struct Hoisted {
    alpha: f64,
    p: f64,
    f0: f64,
    f1: f64,
    lambda: f64,
    c: f64,
    /// `ln c` (unused where `c <= 0`: the shadowing exponent is then 0).
    ln_c: f64,
    k: f64,
    theta0: f64,
}

impl Hoisted {
    /// From the lobe parameters `q = [alpha, p, f0, f1, lambda, c, k, theta0]`.
    fn new(q: &[f64]) -> Self {
        Self {
            alpha: q[0],
            p: q[1],
            f0: q[2],
            f1: q[3],
            lambda: q[4],
            c: q[5],
            ln_c: if q[5] > 0.0 { q[5].ln() } else { 0.0 },
            k: q[6],
            theta0: q[7],
        }
    }

    /// Bagher's `G1(theta)`, with its derivatives in `[Lambda, c, k,
    /// theta0]` when `d` is given: the arithmetic of
    /// [`sgd_g1`](crate::sgd::sgd_g1) with `ln c` hoisted, and `x^k`
    /// formed only for the derivatives.
    #[inline(always)]
    fn g1(&self, theta: f64, d: Option<&mut [f64; 4]>) -> f64 {
        let x = theta - self.theta0;
        if !(x > 0.0) {
            if let Some(d) = d {
                *d = [0.0; 4];
            }
            return 1.0;
        }
        let lx = x.ln();
        let e = if self.c > 0.0 {
            (self.ln_c + self.k * lx).exp()
        } else {
            0.0
        };
        let ee = e.exp();
        if self.lambda == 0.0 {
            if let Some(d) = d {
                *d = [(1.0 - ee).max(f64::MIN), 0.0, 0.0, 0.0];
            }
            return 1.0;
        }
        let g = 1.0 + self.lambda * (1.0 - ee);
        if !(g > 0.0) {
            if let Some(d) = d {
                *d = [0.0; 4];
            }
            return 0.0;
        }
        if let Some(d) = d {
            let xk = (self.k * lx).exp().min(f64::MAX);
            let de = -self.lambda * ee;
            *d = [1.0 - ee, de * xk, de * e * lx, -de * e * self.k / x];
        }
        g
    }
}

/// The last `G1` evaluated at one angle: read again, not evaluated again,
/// when the next pair has the same angle (the same bits).
#[derive(Default)]
struct LastG1 {
    /// `theta`'s bits, whether the derivatives were taken, `G1` and them.
    at: Option<(u64, bool, f64, [f64; 4])>,
}

impl LastG1 {
    /// [`Hoisted::g1`] at `theta`.
    #[inline(always)]
    fn g1(&mut self, h: &Hoisted, theta: f64, d: Option<&mut [f64; 4]>) -> f64 {
        let (bits, grad) = (theta.to_bits(), d.is_some());
        if let Some((b, g, value, dv)) = self.at
            && b == bits
            && g == grad
        {
            if let Some(d) = d {
                *d = dv;
            }
            return value;
        }
        let mut dv = [0.0; 4];
        let value = h.g1(theta, grad.then_some(&mut dv));
        if let Some(d) = d {
            *d = dv;
        }
        self.at = Some((bits, grad, value, dv));
        value
    }
}

/// The lobe `S` of every pair into `s[j]` and, when `ds` is given, its
/// derivatives `ds[u * n + j]` in the lobe parameters `q`; 0 where the
/// pair is invalid or `D` underflows.
fn lobe_batch(
    q: &[f64],
    pairs: &DirPairs,
    geom: &PairGeometry,
    s: &mut [f64],
    mut ds: Option<&mut [f64]>,
) {
    let h = Hoisted::new(q);
    let n = pairs.len();
    let mut dgi = [0.0; 4];
    let mut dgo = [0.0; 4];
    // `G1` depends on one direction's polar angle, which consecutive
    // pairs often share (the view of every term of a rendered pixel, the
    // incident direction along a measurement's grid).
    let (mut last_i, mut last_o) = (LastG1::default(), LastG1::default());
    for j in 0..n {
        let nh = geom.nh[j];
        if !(geom.valid[j] && nh > 0.0) {
            s[j] = 0.0;
            if let Some(ds) = ds.as_deref_mut() {
                for u in 0..NQ {
                    ds[u * n + j] = 0.0;
                }
            }
            continue;
        }
        // D (without K_ap) as `sgd_d`, with ln(cos^2 delta) = 2 ln N.H.
        let c2 = nh * nh;
        let t = (1.0 - c2).max(0.0) / c2;
        let w = h.alpha + t / h.alpha;
        let lw = w.ln();
        let d = (-w - h.p * lw - 4.0 * geom.ln_nh[j]).exp() / PI;
        if !(d > 0.0) {
            s[j] = 0.0;
            if let Some(ds) = ds.as_deref_mut() {
                for u in 0..NQ {
                    ds[u * n + j] = 0.0;
                }
            }
            continue;
        }
        let (nl, nv) = (pairs.lz[j], pairs.vz[j]);
        let (theta_i, theta_o) = (geom.theta_i[j], geom.theta_o[j]);
        // Fresnel as `sgd_fresnel`, (1 - V.H)^5 from the geometry.
        let (vh, m5) = (geom.vh[j], geom.schlick5[j]);
        let f = h.f0 + (1.0 - h.f0) * m5 - h.f1 * vh;
        let (fr, fr0, fr1) = if f > 0.0 {
            (f, 1.0 - m5, -vh)
        } else {
            (0.0, 0.0, 0.0)
        };
        let common = d / (PI * nl * nv);
        match ds.as_deref_mut() {
            None => {
                let (gi, go) = (last_i.g1(&h, theta_i, None), last_o.g1(&h, theta_o, None));
                s[j] = common * gi * go * fr;
            }
            Some(ds) => {
                let gi = last_i.g1(&h, theta_i, Some(&mut dgi));
                let go = last_o.g1(&h, theta_o, Some(&mut dgo));
                let v = common * gi * go * fr;
                s[j] = v;
                let dw = 1.0 - t / (h.alpha * h.alpha);
                ds[j] = v * (-(1.0 + h.p / w) * dw);
                ds[n + j] = v * -lw;
                ds[2 * n + j] = common * gi * go * fr0;
                ds[3 * n + j] = common * gi * go * fr1;
                for u in 0..4 {
                    ds[(4 + u) * n + j] = common * fr * (dgi[u] * go + gi * dgo[u]);
                }
            }
        }
    }
}

impl Brdf for SgdChannel {
    fn channels(&self) -> usize {
        1
    }
    fn eval(&self, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        self.inner.eval(l, v, out)
    }
    fn eval_pairs(&self, pairs: &DirPairs, out: &mut [f64]) {
        self.eval_batch_at(self.params(), pairs, out)
    }
}

impl Parametric for SgdChannel {
    fn name(&self) -> &str {
        <SgdShape as crate::fitted_lobes::FittedShape>::NAME
    }
    fn param_specs(&self) -> &[ParamSpec] {
        self.inner.param_specs()
    }
    fn params(&self) -> &[f64] {
        self.inner.params()
    }
    fn set_params(&mut self, p: &[f64]) -> Result<(), ParamError> {
        self.inner.set_params(p)
    }
    fn clone_box(&self) -> Box<dyn Parametric> {
        Box::new(self.clone())
    }
    fn eval_at(&self, p: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        self.inner.eval_at(p, l, v, out)
    }
    fn eval_grad_at(
        &self,
        p: &[f64],
        l: &Vector3<f64>,
        v: &Vector3<f64>,
        out: &mut [f64],
        grad: &mut [f64],
    ) {
        self.inner.eval_grad_at(p, l, v, out, grad)
    }
    fn eval_batch_at(&self, p: &[f64], pairs: &DirPairs, out: &mut [f64]) {
        let n = pairs.len();
        let geom = PairGeometry::new(pairs);
        lobe_batch(&p[2..], pairs, &geom, &mut out[..n], None);
        for j in 0..n {
            let diffuse = if geom.valid[j] { p[0] * FRAC_1_PI } else { 0.0 };
            out[j] = diffuse + p[1] * out[j];
        }
    }
    fn eval_grad_batch_at(&self, p: &[f64], pairs: &DirPairs, out: &mut [f64], jac: &mut [f64]) {
        let n = pairs.len();
        let geom = PairGeometry::new(pairs);
        let mut ds = vec![0.0; NQ * n];
        lobe_batch(&p[2..], pairs, &geom, &mut out[..n], Some(&mut ds));
        for j in 0..n {
            let row = &mut jac[j * NP..(j + 1) * NP];
            if !geom.valid[j] {
                out[j] = 0.0;
                row.fill(0.0);
                continue;
            }
            let s = out[j];
            out[j] = p[0] * FRAC_1_PI + p[1] * s;
            row[0] = FRAC_1_PI;
            row[1] = s;
            for u in 0..NQ {
                row[2 + u] = p[1] * ds[u * n + j];
            }
        }
    }
    fn shared_basis(&self) -> Option<&dyn SharedBasis> {
        Some(self)
    }
}

/// Basis `[1/pi, S]`: `x_0 = kd`, `x_1 = ks`.
impl SharedBasis for SgdChannel {
    fn basis_len(&self) -> usize {
        2
    }
    fn coefficient_index(&self, _channel: usize, t: usize) -> usize {
        t
    }
    fn basis_batch(
        &self,
        p: &[f64],
        pairs: &DirPairs,
        geom: &PairGeometry,
        phi: &mut [f64],
        dphi: Option<&mut [f64]>,
    ) {
        let n = pairs.len();
        let (d, s) = phi[..2 * n].split_at_mut(n);
        for j in 0..n {
            d[j] = if geom.valid[j] { FRAC_1_PI } else { 0.0 };
        }
        match dphi {
            None => lobe_batch(&p[2..], pairs, geom, s, None),
            Some(dphi) => {
                let (dd, ds) = dphi[..2 * NQ * n].split_at_mut(NQ * n);
                dd.fill(0.0);
                lobe_batch(&p[2..], pairs, geom, s, Some(ds));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use brdf_core::{DirPairs, PairGeometry, Parametric, SharedBasis};
    use nalgebra::Vector3;

    use super::{NQ, SgdChannel};
    use crate::Sgd;

    /// A deterministic uniform sequence on `[0, 1)` (64-bit LCG, high bits).
    fn uniform(state: &mut u64) -> f64 {
        *state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (*state >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Pairs over the hemisphere (pole, grazing, mirror, retro-reflection,
    /// random), and two below the horizon.
    fn pairs(state: &mut u64) -> DirPairs {
        let dir = |t: f64, p: f64| Vector3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos());
        let mut pairs = DirPairs::with_capacity(300);
        let thetas = [0.0, 0.3, 0.8, 1.2, 1.5, std::f64::consts::FRAC_PI_2 - 1e-6];
        for &ti in &thetas {
            for &to in &thetas {
                for k in 0..4 {
                    pairs.push(&dir(ti, 0.4), &dir(to, 0.4 + k as f64 * 1.05));
                }
            }
        }
        for _ in 0..100 {
            let (a, b, c, d) = (
                uniform(state),
                uniform(state),
                uniform(state),
                uniform(state),
            );
            pairs.push(&dir(1.55 * a, 6.3 * b), &dir(1.55 * c, 6.3 * d));
        }
        pairs.push(&dir(2.0, 0.0), &dir(0.5, 1.0));
        pairs.push(&dir(0.5, 0.0), &dir(1.7, 1.0));
        pairs
    }

    /// The batch paths (basis with and without derivatives, batch values
    /// and Jacobian) against the per-pair formula of the RGB model's
    /// one-channel instance at `p`: values to 1e-12 relative, derivatives
    /// to 1e-10 of the value's and the derivative's size, and both value
    /// paths identical.
    fn assert_matches_per_pair(p: &[f64], pairs: &DirPairs) {
        let fast = SgdChannel::new(p).unwrap();
        let reference = Sgd::new(1, p).unwrap();
        let n = pairs.len();
        let geom = PairGeometry::new(pairs);
        let (mut phi, mut phi_only) = (vec![0.0; 2 * n], vec![0.0; 2 * n]);
        let mut dphi = vec![f64::NAN; 2 * NQ * n];
        fast.basis_batch(p, pairs, &geom, &mut phi, Some(&mut dphi));
        fast.basis_batch(p, pairs, &geom, &mut phi_only, None);
        assert_eq!(phi, phi_only, "values without derivatives");
        let (mut out, mut jac) = (vec![0.0; n], vec![f64::NAN; n * 10]);
        fast.eval_grad_batch_at(p, pairs, &mut out, &mut jac);
        let mut only = vec![0.0; n];
        fast.eval_batch_at(p, pairs, &mut only);
        let (mut f, mut g) = ([0.0], [0.0; 10]);
        for j in 0..n {
            reference.eval_grad_at(p, &pairs.l(j), &pairs.v(j), &mut f, &mut g);
            let tol = 1e-12 * f[0].abs();
            assert!(
                (out[j] - f[0]).abs() <= tol,
                "{p:?} pair {j}: {} vs {}",
                out[j],
                f[0]
            );
            assert_eq!(out[j], only[j], "value without derivatives");
            let model = p[0] * phi[j] + p[1] * phi[n + j];
            assert!((model - f[0]).abs() <= tol, "basis {p:?} pair {j}");
            for k in 0..10 {
                let dtol = 1e-10 * (f[0].abs() + g[k].abs());
                assert!(
                    (jac[j * 10 + k] - g[k]).abs() <= dtol,
                    "d/dp{k} {p:?} pair {j}: {} vs {}",
                    jac[j * 10 + k],
                    g[k]
                );
                // The basis: d/dkd = phi_0, d/dks = phi_1, d/dq = ks dphi_1.
                let b = match k {
                    0 => phi[j],
                    1 => phi[n + j],
                    _ => {
                        assert_eq!(dphi[(k - 2) * n + j], 0.0, "diffuse derivative");
                        p[1] * dphi[(NQ + k - 2) * n + j]
                    }
                };
                assert!((b - g[k]).abs() <= dtol, "basis d/dp{k} {p:?} pair {j}");
            }
        }
    }

    /// At the starts the catalogue suggests, at random points of the box
    /// and at the corner cases of the clamps (shadowing off with
    /// `Lambda = 0`, rate `c = 0`, `G1` clamped to 0 by a steep onset at
    /// `theta0 < 0`, Fresnel clamped to 0 by `F1 > F0`), the kernel is the
    /// per-pair formula.
    #[test]
    fn kernel_equals_the_per_pair_formula() {
        let mut state = 0x5ed_u64;
        let pairs = pairs(&mut state);
        let mut points: Vec<Vec<f64>> = crate::sgd::SGD_START_SHAPES
            .iter()
            .map(|q| [&[0.3, 2.0][..], q].concat())
            .collect();
        points.push(vec![0.1, 3.0, 0.2, 0.7, 0.5, 0.1, 0.0, 1.0, 2.0, 0.3]);
        points.push(vec![0.1, 3.0, 0.2, 0.7, 0.5, 0.1, 2.0, 0.0, 2.0, 0.3]);
        points.push(vec![0.1, 3.0, 0.2, 0.7, 0.5, 0.1, 50.0, 500.0, 900.0, -1.2]);
        points.push(vec![0.1, 3.0, 0.2, 0.7, 0.05, 5.0, 2.0, 1.0, 2.0, 0.3]);
        points.push(vec![
            0.7, 51.0, 0.96, 1.39, 0.045, 0.028, 100.0, 0.0101, 1.0, 0.578,
        ]);
        for _ in 0..40 {
            let specs = SgdChannel::with_defaults().unwrap().param_specs().to_vec();
            points.push(
                specs
                    .iter()
                    .map(|s| {
                        let (lo, hi) = (s.lower.max(-10.0), s.upper.min(10.0));
                        let x = lo + (hi - lo) * uniform(&mut state);
                        if s.lower_open && x <= s.lower { hi } else { x }
                    })
                    .collect(),
            );
        }
        for p in &points {
            assert_matches_per_pair(p, &pairs);
        }
    }
}
