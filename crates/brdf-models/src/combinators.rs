//! Generic combinators that assemble models from named parts.
//!
//! [`DiffuseLobe`] is `f_c = kd_c / pi + ks_c S(L, V; q)`: a Lambertian term
//! and one specular lobe shape `S` with non-linear parameters `q` shared by
//! all channels. `kd` and `ks` (per channel) enter linearly. Phong,
//! Blinn-Phong, Ward and Ward-Duer are such models; each lobe lives in its
//! model's file and implements [`Lobe`].

use std::f64::consts::FRAC_1_PI;

use brdf_core::params::per_channel_specs;
use brdf_core::{Brdf, DirPairs, PairGeometry, ParamError, ParamSpec, Parametric, SharedBasis};
use nalgebra::Vector3;

/// A specular lobe shape `S(L, V; q)` with its derivatives.
pub trait Lobe: Clone + Send + Sync + 'static {
    /// Catalogue name of the model `kd/pi + ks S`.
    const NAME: &'static str;
    /// Descriptions of the lobe's non-linear parameters `q`.
    fn specs() -> Vec<ParamSpec>;
    /// `S` at `q`, writing `dS/dq_k` into `dq` when it is `Some`. Called only
    /// for directions above the horizon.
    fn shape(q: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, dq: Option<&mut [f64]>) -> f64;
    /// Whether `S(L, V) = S(V, L)` (and `D`).
    fn reciprocal() -> bool {
        true
    }
    /// Whether [`Lobe::shape_batch`] and [`Lobe::diffuse_batch`] give the
    /// bits [`Lobe::shape`] and [`Lobe::diffuse`] give pair by pair (tested
    /// where set): renders of the model then take the batch kernels, as
    /// fits do.
    const BATCH_IS_EXACT: bool = false;
    /// Name of the diffuse coefficient.
    const DIFFUSE: &'static str = "kd";
    /// Name of the specular coefficient.
    const SPECULAR: &'static str = "ks";
    /// The diffuse shape `D(L, V; q)`, writing `dD/dq_k` into `dq` (zeroed
    /// by the caller) when it is `Some`. Lambert's `1/pi` by default.
    fn diffuse(_q: &[f64], _l: &Vector3<f64>, _v: &Vector3<f64>, _dq: Option<&mut [f64]>) -> f64 {
        FRAC_1_PI
    }

    /// `s[j] = S(L_j, V_j; q)` for every pair (0 where `geom.valid[j]` is
    /// false) and, when given, `ds[u * n + j] = dS/dq_u`. The default calls
    /// [`Lobe::shape`] per pair; lobes override it with a kernel over the
    /// precomputed geometry.
    fn shape_batch(
        q: &[f64],
        pairs: &DirPairs,
        geom: &PairGeometry,
        s: &mut [f64],
        ds: Option<&mut [f64]>,
    ) {
        per_pair(q, pairs, geom, s, ds, Self::shape)
    }

    /// The diffuse shape for every pair, as [`Lobe::shape_batch`] does for
    /// the lobe; the default calls [`Lobe::diffuse`] per pair.
    fn diffuse_batch(
        q: &[f64],
        pairs: &DirPairs,
        geom: &PairGeometry,
        d: &mut [f64],
        dd: Option<&mut [f64]>,
    ) {
        per_pair(q, pairs, geom, d, dd, Self::diffuse)
    }
}

/// Evaluate a per-pair shape function over every pair into batch layout
/// (`out[j]`, `d[u * n + j]`), 0 where the pair is invalid.
pub(crate) fn per_pair(
    q: &[f64],
    pairs: &DirPairs,
    geom: &PairGeometry,
    out: &mut [f64],
    d: Option<&mut [f64]>,
    f: impl Fn(&[f64], &Vector3<f64>, &Vector3<f64>, Option<&mut [f64]>) -> f64,
) {
    let n = pairs.len();
    let nq = q.len();
    let mut dq = [0.0; 8];
    match d {
        None => {
            for j in 0..n {
                out[j] = if geom.valid[j] {
                    f(q, &pairs.l(j), &pairs.v(j), None)
                } else {
                    0.0
                };
            }
        }
        Some(d) => {
            for j in 0..n {
                dq[..nq].fill(0.0);
                out[j] = if geom.valid[j] {
                    f(q, &pairs.l(j), &pairs.v(j), Some(&mut dq[..nq]))
                } else {
                    0.0
                };
                for u in 0..nq {
                    d[u * n + j] = dq[u];
                }
            }
        }
    }
}

/// `f_c = kd_c / pi + ks_c S(L, V; q)`.
#[derive(Clone, Debug, PartialEq)]
pub struct DiffuseLobe<S: Lobe> {
    pub(crate) channels: usize,
    specs: Vec<ParamSpec>,
    params: Vec<f64>,
    _lobe: std::marker::PhantomData<S>,
}

impl<S: Lobe> DiffuseLobe<S> {
    /// The model with `channels` channels at its default parameters.
    pub fn with_channels(channels: usize) -> Result<Self, ParamError> {
        if channels == 0 {
            return Err(ParamError::Config {
                model: S::NAME.into(),
                reason: "a model needs at least one channel".into(),
            });
        }
        let mut specs = per_channel_specs(S::DIFFUSE, "diffuse albedo", channels, 0.0, 1.0, 0.3);
        specs.extend(per_channel_specs(
            S::SPECULAR,
            "specular strength",
            channels,
            0.0,
            1.0,
            0.2,
        ));
        specs.extend(S::specs());
        let params = specs.iter().map(|s| s.default).collect();
        Ok(DiffuseLobe {
            channels,
            specs,
            params,
            _lobe: std::marker::PhantomData,
        })
    }

    /// The model with the given per-channel `kd`, `ks` (same length) and lobe
    /// parameters, validated against their boxes.
    pub fn new(kd: &[f64], ks: &[f64], q: &[f64]) -> Result<Self, ParamError> {
        if kd.len() != ks.len() {
            return Err(ParamError::Config {
                model: S::NAME.into(),
                reason: format!("kd has {} channels but ks has {}", kd.len(), ks.len()),
            });
        }
        let mut m = Self::with_channels(kd.len())?;
        let p: Vec<f64> = kd.iter().chain(ks).chain(q).copied().collect();
        m.set_params(&p)?;
        Ok(m)
    }
}

impl<S: Lobe> Brdf for DiffuseLobe<S> {
    fn channels(&self) -> usize {
        self.channels
    }
    fn eval(&self, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        self.eval_at(&self.params, l, v, out)
    }
    fn eval_pairs(&self, pairs: &DirPairs, out: &mut [f64]) {
        self.eval_batch_at(&self.params, pairs, out)
    }
}

impl<S: Lobe> Parametric for DiffuseLobe<S> {
    brdf_core::param_accessors!();
    fn name(&self) -> &str {
        S::NAME
    }
    fn eval_at(&self, p: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        let nc = self.channels;
        if !(l.z > 0.0 && v.z > 0.0) {
            out[..nc].iter_mut().for_each(|x| *x = 0.0);
            return;
        }
        let q = &p[2 * nc..];
        let s = S::shape(q, l, v, None);
        let d = S::diffuse(q, l, v, None);
        for c in 0..nc {
            out[c] = p[c] * d + p[nc + c] * s;
        }
    }
    /// Through the batch kernels when they are exact
    /// ([`Lobe::BATCH_IS_EXACT`]): the same values as pair by pair.
    fn eval_batch_at(&self, p: &[f64], pairs: &DirPairs, out: &mut [f64]) {
        if !S::BATCH_IS_EXACT {
            return brdf_core::brdf::eval_batch_per_pair(self, p, pairs, out);
        }
        let (n, nc) = (pairs.len(), self.channels);
        let geom = PairGeometry::new(pairs);
        let (mut d, mut s) = (vec![0.0; n], vec![0.0; n]);
        let q = &p[2 * nc..];
        S::diffuse_batch(q, pairs, &geom, &mut d, None);
        S::shape_batch(q, pairs, &geom, &mut s, None);
        for c in 0..nc {
            for j in 0..n {
                // As `eval_at`: 0 below the horizon, else kd D + ks S.
                out[c * n + j] = if geom.valid[j] {
                    p[c] * d[j] + p[nc + c] * s[j]
                } else {
                    0.0
                };
            }
        }
    }
    fn eval_grad_at(
        &self,
        p: &[f64],
        l: &Vector3<f64>,
        v: &Vector3<f64>,
        out: &mut [f64],
        grad: &mut [f64],
    ) {
        let nc = self.channels;
        let np = self.specs.len();
        let nq = np - 2 * nc;
        grad[..nc * np].iter_mut().for_each(|g| *g = 0.0);
        if !(l.z > 0.0 && v.z > 0.0) {
            out[..nc].iter_mut().for_each(|x| *x = 0.0);
            return;
        }
        let mut dq = [0.0; 8];
        let mut dd = [0.0; 8];
        let q = &p[2 * nc..];
        let s = S::shape(q, l, v, Some(&mut dq[..nq]));
        let d = S::diffuse(q, l, v, Some(&mut dd[..nq]));
        for c in 0..nc {
            let (kd, ks) = (p[c], p[nc + c]);
            out[c] = kd * d + ks * s;
            let row = &mut grad[c * np..(c + 1) * np];
            row[c] = d;
            row[nc + c] = s;
            for k in 0..nq {
                row[2 * nc + k] = kd * dd[k] + ks * dq[k];
            }
        }
    }
    fn is_reciprocal(&self) -> bool {
        S::reciprocal()
    }
    fn shared_basis(&self) -> Option<&dyn SharedBasis> {
        Some(self)
    }
}

/// Basis `[D, S]`: `x_{c,0} = kd_c`, `x_{c,1} = ks_c`.
impl<S: Lobe> SharedBasis for DiffuseLobe<S> {
    fn basis_len(&self) -> usize {
        2
    }
    fn coefficient_index(&self, channel: usize, t: usize) -> usize {
        t * self.channels + channel
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
        let q = &p[2 * self.channels..];
        let nq = q.len();
        let (d, s) = phi[..2 * n].split_at_mut(n);
        match dphi {
            None => {
                S::diffuse_batch(q, pairs, geom, d, None);
                S::shape_batch(q, pairs, geom, s, None);
            }
            Some(dphi) => {
                let (dd, ds) = dphi[..2 * nq * n].split_at_mut(nq * n);
                S::diffuse_batch(q, pairs, geom, d, Some(dd));
                S::shape_batch(q, pairs, geom, s, Some(ds));
            }
        }
    }
}

/// `c^n` and `d(c^n)/dn = c^n ln c` for a cosine `c` clamped at 0, computed
/// as `exp(n ln c)` so exponents up to `1e6` neither overflow nor give NaN
/// (`0^n = 0` for every `n`, with derivative 0).
#[inline]
pub fn pow_clamped(c: f64, n: f64) -> (f64, f64) {
    if c <= 0.0 {
        return (0.0, 0.0);
    }
    let lc = c.min(1.0).ln();
    let v = (n * lc).exp();
    (v, v * lc)
}

/// Names the lobe type of a [`DiffuseLobe`] model (used by the catalogue).
pub trait HasLobe {
    /// The lobe.
    type L: Lobe;
}

impl<S: Lobe> HasLobe for DiffuseLobe<S> {
    type L = S;
}

/// `f_c = kd_c / pi + sum_k ks_kc S(L, V; q_k)`: `K` lobes of one shape.
/// Parameters: `kd` per channel, then for each lobe `k = 1..K` its `ks{k}`
/// per channel and its shape parameters with the suffix `k` (`m1`, `f0_1`).
#[derive(Clone, Debug, PartialEq)]
pub struct MultiLobe<S: Lobe> {
    pub(crate) channels: usize,
    lobes: usize,
    specs: Vec<ParamSpec>,
    params: Vec<f64>,
    _lobe: std::marker::PhantomData<S>,
}

impl<S: Lobe> MultiLobe<S> {
    /// The model with `lobes >= 1` lobes and `channels` channels at its
    /// default parameters.
    pub fn new(lobes: usize, channels: usize) -> Result<Self, ParamError> {
        if channels == 0 || lobes == 0 {
            return Err(ParamError::Config {
                model: S::NAME.into(),
                reason: "a model needs at least one channel and one lobe".into(),
            });
        }
        let mut specs = per_channel_specs(S::DIFFUSE, "diffuse albedo", channels, 0.0, 1.0, 0.3);
        for k in 1..=lobes {
            specs.extend(per_channel_specs(
                &format!("{}{k}", S::SPECULAR),
                &format!("strength of lobe {k}"),
                channels,
                0.0,
                1.0,
                0.2 / lobes as f64,
            ));
            for mut q in S::specs() {
                let sep = if q.name.ends_with(|c: char| c.is_ascii_digit()) {
                    "_"
                } else {
                    ""
                };
                q.name = format!("{}{sep}{k}", q.name);
                q.meaning = format!("{} of lobe {k}", q.meaning);
                specs.push(q);
            }
        }
        let params = specs.iter().map(|s| s.default).collect();
        Ok(Self {
            channels,
            lobes,
            specs,
            params,
            _lobe: std::marker::PhantomData,
        })
    }

    /// Number of lobes.
    pub fn lobes(&self) -> usize {
        self.lobes
    }

    /// Parameters per lobe (strengths per channel, then the shape's),
    /// from the stored specs: `S::specs()` builds named specs, too slow
    /// for a per-evaluation call.
    fn block(&self) -> usize {
        (self.specs.len() - self.channels) / self.lobes
    }
}

impl<S: Lobe> Brdf for MultiLobe<S> {
    fn channels(&self) -> usize {
        self.channels
    }
    fn eval(&self, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        self.eval_at(&self.params, l, v, out)
    }
    fn eval_pairs(&self, pairs: &DirPairs, out: &mut [f64]) {
        self.eval_batch_at(&self.params, pairs, out)
    }
}

impl<S: Lobe> Parametric for MultiLobe<S> {
    brdf_core::param_accessors!();
    fn name(&self) -> &str {
        S::NAME
    }
    /// Through the lobe's batch kernel when it is exact
    /// ([`Lobe::BATCH_IS_EXACT`]): each lobe added in order, as
    /// [`Parametric::eval_at`] adds them pair by pair.
    fn eval_batch_at(&self, p: &[f64], pairs: &DirPairs, out: &mut [f64]) {
        if !S::BATCH_IS_EXACT {
            return brdf_core::brdf::eval_batch_per_pair(self, p, pairs, out);
        }
        let (n, nc, b) = (pairs.len(), self.channels, self.block());
        let geom = PairGeometry::new(pairs);
        for c in 0..nc {
            out[c * n..(c + 1) * n].fill(p[c] * FRAC_1_PI);
        }
        let mut s = vec![0.0; n];
        for k in 0..self.lobes {
            let base = nc + k * b;
            S::shape_batch(&p[base + nc..base + b], pairs, &geom, &mut s, None);
            for c in 0..nc {
                for (o, sj) in out[c * n..(c + 1) * n].iter_mut().zip(&s) {
                    *o += p[base + c] * sj;
                }
            }
        }
        // As `eval_at`: 0 below the horizon.
        for (j, ok) in geom.valid.iter().enumerate() {
            if !ok {
                (0..nc).for_each(|c| out[c * n + j] = 0.0);
            }
        }
    }
    fn eval_at(&self, p: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        let nc = self.channels;
        out[..nc]
            .iter_mut()
            .enumerate()
            .for_each(|(c, x)| *x = p[c] * FRAC_1_PI);
        if !(l.z > 0.0 && v.z > 0.0) {
            out[..nc].iter_mut().for_each(|x| *x = 0.0);
            return;
        }
        let b = self.block();
        for k in 0..self.lobes {
            let base = nc + k * b;
            let s = S::shape(&p[base + nc..base + b], l, v, None);
            for c in 0..nc {
                out[c] += p[base + c] * s;
            }
        }
    }
    fn eval_grad_at(
        &self,
        p: &[f64],
        l: &Vector3<f64>,
        v: &Vector3<f64>,
        out: &mut [f64],
        grad: &mut [f64],
    ) {
        let nc = self.channels;
        let np = self.specs.len();
        grad[..nc * np].iter_mut().for_each(|g| *g = 0.0);
        if !(l.z > 0.0 && v.z > 0.0) {
            out[..nc].iter_mut().for_each(|x| *x = 0.0);
            return;
        }
        let b = self.block();
        let nq = b - nc;
        for c in 0..nc {
            out[c] = p[c] * FRAC_1_PI;
            grad[c * np + c] = FRAC_1_PI;
        }
        let mut dq = [0.0; 8];
        for k in 0..self.lobes {
            let base = nc + k * b;
            let s = S::shape(&p[base + nc..base + b], l, v, Some(&mut dq[..nq]));
            for c in 0..nc {
                let ks = p[base + c];
                out[c] += ks * s;
                let row = &mut grad[c * np..(c + 1) * np];
                row[base + c] = s;
                for t in 0..nq {
                    row[base + nc + t] = ks * dq[t];
                }
            }
        }
    }
    fn is_reciprocal(&self) -> bool {
        S::reciprocal()
    }
    fn shared_basis(&self) -> Option<&dyn SharedBasis> {
        Some(self)
    }
}

/// Index of `x_{c,t}` in the parameter vector of a Lambert term plus `K`
/// lobes laid out as `kd` per channel, then per lobe a block of `block`
/// entries starting with its strengths per channel (`MultiLobe`,
/// `Lafortune`).
pub(crate) fn lobes_coefficient_index(
    channels: usize,
    block: usize,
    channel: usize,
    t: usize,
) -> usize {
    if t == 0 {
        channel
    } else {
        channels + (t - 1) * block + channel
    }
}

/// The Lambert column `phi_0` (`1/pi` on valid pairs) of a basis
/// `[1/pi, S_1, .., S_K]`, and every derivative zeroed (`Q` non-linear
/// parameters in all; each lobe then writes its own block).
pub(crate) fn start_lobes_basis(
    geom: &PairGeometry,
    lobes: usize,
    q: usize,
    phi: &mut [f64],
    dphi: Option<&mut [f64]>,
) {
    let n = geom.len();
    for j in 0..n {
        phi[j] = if geom.valid[j] { FRAC_1_PI } else { 0.0 };
    }
    if let Some(d) = dphi {
        d[..(1 + lobes) * q * n].fill(0.0);
    }
}

/// Basis `[1/pi, S_1, ..., S_K]`: `x_{c,0} = kd_c`, `x_{c,k} = ks{k}_c`.
impl<S: Lobe> SharedBasis for MultiLobe<S> {
    fn basis_len(&self) -> usize {
        1 + self.lobes
    }
    fn coefficient_index(&self, channel: usize, t: usize) -> usize {
        lobes_coefficient_index(self.channels, self.block(), channel, t)
    }
    fn basis_batch(
        &self,
        p: &[f64],
        pairs: &DirPairs,
        geom: &PairGeometry,
        phi: &mut [f64],
        mut dphi: Option<&mut [f64]>,
    ) {
        let (n, nc, b) = (pairs.len(), self.channels, self.block());
        let nq = b - nc;
        let big_q = nq * self.lobes;
        start_lobes_basis(geom, self.lobes, big_q, phi, dphi.as_deref_mut());
        for k in 0..self.lobes {
            let q = &p[nc + k * b + nc..nc + (k + 1) * b];
            let s = &mut phi[(k + 1) * n..(k + 2) * n];
            match dphi.as_deref_mut() {
                None => S::shape_batch(q, pairs, geom, s, None),
                Some(d) => {
                    let at = ((k + 1) * big_q + k * nq) * n;
                    S::shape_batch(q, pairs, geom, s, Some(&mut d[at..at + nq * n]));
                }
            }
        }
    }
}

/// Test support: `model.eval_pairs` (what renders call) against
/// `model.eval` pair by pair, to the bit, on `pairs`.
#[cfg(test)]
pub(crate) fn assert_renders_as_pair_by_pair(model: &dyn Brdf, pairs: &DirPairs) {
    let (n, nc) = (pairs.len(), model.channels());
    let mut batch = vec![f64::NAN; nc * n];
    model.eval_pairs(pairs, &mut batch);
    let mut one = vec![0.0; nc];
    for j in 0..n {
        model.eval(&pairs.l(j), &pairs.v(j), &mut one);
        for c in 0..nc {
            assert_eq!(
                batch[c * n + j].to_bits(),
                one[c].to_bits(),
                "pair {j}, channel {c}"
            );
        }
    }
}
