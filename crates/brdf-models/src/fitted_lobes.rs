//! [`FittedLobe`]: `f_c = kd_c / pi + s_c S(L, V; q_c)`, the form of the
//! models published with per-material fits to measured data (Löw et al.
//! 2012, Bagher et al. 2012). It differs from
//! [`DiffuseLobe`](crate::combinators::DiffuseLobe) in two ways the
//! published parameters need:
//!
//! - the linear scale `s_c` has the lobe's own box (Löw's `A` reaches
//!   `2e3` on MERL materials, far outside `[0, 1]`);
//! - the non-linear parameters are either shared by all channels (Löw) or
//!   one set per channel (Bagher's fits give every RGB channel its own
//!   distribution, shadowing and Fresnel parameters).
//!
//! Layout of the parameter vector: `kd` per channel, the scale per channel,
//! then the lobe's parameters: shared, `q_0, q_1, ...`; per channel, each
//! parameter for every channel in turn (`alpha_r, alpha_g, alpha_b, p_r, ...`).
//!
//! With shared lobe parameters the model offers the channel-shared basis
//! `[1/pi, S]` to the solvers (variable projection over `kd`, `s`); with
//! per-channel ones it offers none, each channel being its own problem.

use std::f64::consts::FRAC_1_PI;

use brdf_core::params::{channel_param_name, per_channel_specs};
use brdf_core::{Brdf, DirPairs, PairGeometry, ParamError, ParamSpec, Parametric, SharedBasis};
use nalgebra::Vector3;

use crate::combinators::per_pair;

/// Most non-linear parameters a [`FittedShape`] may have.
pub const MAX_SHAPE_PARAMS: usize = 8;

/// A lobe shape `S(L, V; q)` with its linear scale's description.
pub trait FittedShape: Clone + Send + Sync + 'static {
    /// Catalogue name of the model.
    const NAME: &'static str;
    /// Name of the per-channel linear scale (`A`, `ks`).
    const SCALE: &'static str;
    /// Meaning of the scale.
    const SCALE_MEANING: &'static str;
    /// Box `[lower, upper]` of the scale and its default.
    const SCALE_BOX: (f64, f64, f64);
    /// Whether each channel has its own non-linear parameters.
    const PER_CHANNEL: bool;
    /// Descriptions of the non-linear parameters (at most
    /// [`MAX_SHAPE_PARAMS`]).
    fn specs() -> Vec<ParamSpec>;
    /// `S` at `q` for `L`, `V` above the horizon, writing `dS/dq_k` into
    /// `dq` when it is `Some`.
    fn shape(q: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, dq: Option<&mut [f64]>) -> f64;
    /// What [`FittedShape::shape_channels`] keeps from one pair to the
    /// next of a batch (whose parameters do not change).
    type Memo: Default;
    /// `S` of every channel at one pair (`L`, `V` above the horizon): at
    /// lobe parameters `qs[c][..nq]` into `s[c]` and, when given, `dS/dq`
    /// into `dq[c]`, the bits [`FittedShape::shape`] gives channel by
    /// channel. A shape may take its factors of the pair alone once for
    /// every channel, and read from `memo` what the pair before of the
    /// same batch computed. The default calls `shape` per channel.
    fn shape_channels(
        qs: &[[f64; MAX_SHAPE_PARAMS]],
        nq: usize,
        l: &Vector3<f64>,
        v: &Vector3<f64>,
        _memo: &mut Self::Memo,
        s: &mut [f64],
        mut dq: Option<&mut [[f64; MAX_SHAPE_PARAMS]]>,
    ) {
        for (c, q) in qs.iter().enumerate() {
            s[c] = Self::shape(&q[..nq], l, v, dq.as_deref_mut().map(|d| &mut d[c][..nq]));
        }
    }
}

/// `f_c = kd_c / pi + s_c S(L, V; q_c)` (see the module doc).
#[derive(Clone, Debug, PartialEq)]
pub struct FittedLobe<S: FittedShape> {
    channels: usize,
    specs: Vec<ParamSpec>,
    params: Vec<f64>,
    _shape: std::marker::PhantomData<S>,
}

impl<S: FittedShape> FittedLobe<S> {
    /// The model with `channels` channels at its default parameters.
    pub fn with_channels(channels: usize) -> Result<Self, ParamError> {
        if channels == 0 {
            return Err(ParamError::Config {
                model: S::NAME.into(),
                reason: "a model needs at least one channel".into(),
            });
        }
        let mut specs = per_channel_specs("kd", "diffuse albedo", channels, 0.0, 1.0, 0.1);
        let (lo, hi, def) = S::SCALE_BOX;
        specs.extend(per_channel_specs(
            S::SCALE,
            S::SCALE_MEANING,
            channels,
            lo,
            hi,
            def,
        ));
        for q in S::specs() {
            if S::PER_CHANNEL {
                specs.extend((0..channels).map(|c| ParamSpec {
                    name: channel_param_name(&q.name, c, channels),
                    meaning: format!("{} (channel {c})", q.meaning),
                    ..q.clone()
                }));
            } else {
                specs.push(q);
            }
        }
        let params = specs.iter().map(|s| s.default).collect();
        Ok(Self {
            channels,
            specs,
            params,
            _shape: std::marker::PhantomData,
        })
    }

    /// The model with the given parameter vector (layout in the module
    /// doc), validated against the boxes.
    pub fn new(channels: usize, p: &[f64]) -> Result<Self, ParamError> {
        let mut m = Self::with_channels(channels)?;
        m.set_params(p)?;
        Ok(m)
    }

    /// Gather channel `c`'s lobe parameters from `p` into `q`; returns their
    /// number.
    fn lobe_params(&self, p: &[f64], c: usize, q: &mut [f64; MAX_SHAPE_PARAMS]) -> usize {
        let nc = self.channels;
        let nq = (self.specs.len() - 2 * nc) / if S::PER_CHANNEL { nc } else { 1 };
        for (k, x) in q.iter_mut().enumerate().take(nq) {
            *x = p[self.q_index(k, c)];
        }
        nq
    }

    /// Every channel's lobe parameters from `p`, and their number.
    fn all_lobe_params(&self, p: &[f64]) -> (Vec<[f64; MAX_SHAPE_PARAMS]>, usize) {
        let mut qs = vec![[0.0; MAX_SHAPE_PARAMS]; self.channels];
        let mut nq = 0;
        for (c, q) in qs.iter_mut().enumerate() {
            nq = self.lobe_params(p, c, q);
        }
        (qs, nq)
    }

    /// Index in the parameter vector of lobe parameter `k` of channel `c`.
    fn q_index(&self, k: usize, c: usize) -> usize {
        let nc = self.channels;
        if S::PER_CHANNEL {
            2 * nc + k * nc + c
        } else {
            2 * nc + k
        }
    }
}

impl<S: FittedShape> Brdf for FittedLobe<S> {
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

impl<S: FittedShape> Parametric for FittedLobe<S> {
    brdf_core::param_accessors!();
    fn name(&self) -> &str {
        S::NAME
    }
    fn eval_at(&self, p: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        let nc = self.channels;
        if !(l.z > 0.0 && v.z > 0.0) {
            out[..nc].fill(0.0);
            return;
        }
        let mut q = [0.0; MAX_SHAPE_PARAMS];
        let mut shared = None;
        for c in 0..nc {
            // Shared parameters: one shape evaluation serves every channel.
            let s = match shared {
                Some(s) => s,
                None => {
                    let nq = self.lobe_params(p, c, &mut q);
                    let s = S::shape(&q[..nq], l, v, None);
                    if !S::PER_CHANNEL {
                        shared = Some(s);
                    }
                    s
                }
            };
            out[c] = p[c] * FRAC_1_PI + p[nc + c] * s;
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
        grad[..nc * np].fill(0.0);
        if !(l.z > 0.0 && v.z > 0.0) {
            out[..nc].fill(0.0);
            return;
        }
        let mut q = [0.0; MAX_SHAPE_PARAMS];
        let mut dq = [0.0; MAX_SHAPE_PARAMS];
        for c in 0..nc {
            let nq = self.lobe_params(p, c, &mut q);
            dq[..nq].fill(0.0);
            let s = S::shape(&q[..nq], l, v, Some(&mut dq[..nq]));
            let scale = p[nc + c];
            out[c] = p[c] * FRAC_1_PI + scale * s;
            let row = &mut grad[c * np..(c + 1) * np];
            row[c] = FRAC_1_PI;
            row[nc + c] = s;
            for k in 0..nq {
                row[self.q_index(k, c)] = scale * dq[k];
            }
        }
    }
    /// With per-channel lobe parameters, every channel's shape at a pair at
    /// once ([`FittedShape::shape_channels`]), its memo kept along the
    /// batch; the values [`Parametric::eval_at`] gives pair by pair.
    fn eval_batch_at(&self, p: &[f64], pairs: &DirPairs, out: &mut [f64]) {
        if !S::PER_CHANNEL {
            return brdf_core::brdf::eval_batch_per_pair(self, p, pairs, out);
        }
        let (n, nc) = (pairs.len(), self.channels);
        let (qs, nq) = self.all_lobe_params(p);
        let mut memo = S::Memo::default();
        let mut s = vec![0.0; nc];
        for j in 0..n {
            let (l, v) = (pairs.l(j), pairs.v(j));
            if !(l.z > 0.0 && v.z > 0.0) {
                (0..nc).for_each(|c| out[c * n + j] = 0.0);
                continue;
            }
            S::shape_channels(&qs, nq, &l, &v, &mut memo, &mut s, None);
            for c in 0..nc {
                out[c * n + j] = p[c] * FRAC_1_PI + p[nc + c] * s[c];
            }
        }
    }
    /// As [`FittedLobe::eval_batch_at`], with the Jacobian rows that
    /// [`Parametric::eval_grad_at`] gives pair by pair.
    fn eval_grad_batch_at(&self, p: &[f64], pairs: &DirPairs, out: &mut [f64], jac: &mut [f64]) {
        if !S::PER_CHANNEL {
            return brdf_core::brdf::eval_grad_batch_per_pair(self, p, pairs, out, jac);
        }
        let (n, nc, np) = (pairs.len(), self.channels, self.specs.len());
        let (qs, nq) = self.all_lobe_params(p);
        let mut memo = S::Memo::default();
        let mut s = vec![0.0; nc];
        let mut dq = vec![[0.0; MAX_SHAPE_PARAMS]; nc];
        for j in 0..n {
            let (l, v) = (pairs.l(j), pairs.v(j));
            for c in 0..nc {
                jac[(c * n + j) * np..(c * n + j + 1) * np].fill(0.0);
            }
            if !(l.z > 0.0 && v.z > 0.0) {
                (0..nc).for_each(|c| out[c * n + j] = 0.0);
                continue;
            }
            dq.iter_mut().for_each(|d| d.fill(0.0));
            S::shape_channels(&qs, nq, &l, &v, &mut memo, &mut s, Some(&mut dq));
            for c in 0..nc {
                let scale = p[nc + c];
                out[c * n + j] = p[c] * FRAC_1_PI + scale * s[c];
                let row = &mut jac[(c * n + j) * np..(c * n + j + 1) * np];
                row[c] = FRAC_1_PI;
                row[nc + c] = s[c];
                for k in 0..nq {
                    row[self.q_index(k, c)] = scale * dq[c][k];
                }
            }
        }
    }
    fn shared_basis(&self) -> Option<&dyn SharedBasis> {
        // Per-channel lobe parameters give each channel its own basis.
        if S::PER_CHANNEL { None } else { Some(self) }
    }
}

/// Basis `[1/pi, S]` when the lobe parameters are shared:
/// `x_{c,0} = kd_c`, `x_{c,1} = s_c`.
impl<S: FittedShape> SharedBasis for FittedLobe<S> {
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
        let (d, s) = phi[..2 * n].split_at_mut(n);
        for j in 0..n {
            d[j] = if geom.valid[j] { FRAC_1_PI } else { 0.0 };
        }
        match dphi {
            None => per_pair(q, pairs, geom, s, None, S::shape),
            Some(dphi) => {
                let nq = q.len();
                let (dd, ds) = dphi[..2 * nq * n].split_at_mut(nq * n);
                dd.fill(0.0);
                per_pair(q, pairs, geom, s, Some(ds), S::shape);
            }
        }
    }
}
