//! [`ChannelSlice`]: one colour channel of a model whose channels share no
//! parameter (Bagher et al.'s SGD fits give every channel its own
//! distribution, shadowing and Fresnel), as a one-channel model in that
//! channel's parameters, the others held fixed.
//!
//! A fit of such a model is `channels` independent problems: the residuals
//! of channel `c` depend only on channel `c`'s parameters, so the joint
//! Jacobian is block-diagonal. Solving them one by one searches an
//! 8-dimensional box per channel instead of a 24-dimensional one (a Halton
//! multi-start in 24 dimensions puts the later coordinates of its first
//! points near their lower ends) and gives each solve its own damping.
//! [`channel_blocks`] finds the blocks by the parameter names
//! ([`channel_param_name`]) and checks the block structure on the
//! Jacobian at probe directions; a model that fails the check gets `None`.
//!
//! Sliced out of the whole model, every evaluation of one channel forms all
//! of them (and, for derivatives, the whole gradient). A model whose
//! catalogue entry has a one-channel model of a channel
//! ([`channel_model`](crate::catalogue::channel_model): Bagher's SGD) is
//! evaluated through it instead, in batch and with its shared basis, once
//! the slice has checked that it gives the channel's values and
//! derivatives at probe directions.
//!
//! ```
//! use brdf_core::Brdf;
//! use brdf_models::channel_slice::{ChannelSlice, channel_blocks};
//! use brdf_models::Sgd;
//! use nalgebra::Vector3;
//! let m = Sgd::with_channels(3).unwrap();
//! let blocks = channel_blocks(&m).expect("SGD's channels share nothing");
//! assert_eq!(blocks[1].len(), 10);
//! let g = ChannelSlice::new(&m, 1, blocks[1].clone()).unwrap();
//! let (mut a, mut b) = ([0.0; 3], [0.0]);
//! let (l, v) = (Vector3::new(0.3, 0.0, 0.95).normalize(), Vector3::new(-0.2, 0.1, 0.97).normalize());
//! m.eval(&l, &v, &mut a);
//! g.eval(&l, &v, &mut b);
//! assert_eq!(a[1], b[0]);
//! ```

use brdf_core::params::channel_param_name;
use brdf_core::{Brdf, DirPairs, ParamError, ParamSpec, Parametric, SharedBasis};
use nalgebra::Vector3;

/// Channel `channel` of `model` in that channel's parameters `indices`.
#[derive(Clone)]
pub struct ChannelSlice {
    model: Box<dyn Parametric>,
    channel: usize,
    indices: Vec<usize>,
    specs: Vec<ParamSpec>,
    params: Vec<f64>,
    /// The one-channel model that evaluates the channel (parameters in
    /// `indices` order), where the catalogue has one and it agrees.
    fast: Option<Box<dyn Parametric>>,
}

impl std::fmt::Debug for ChannelSlice {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ChannelSlice")
            .field("model", &self.model.name())
            .field("channel", &self.channel)
            .field("indices", &self.indices)
            .field("fast", &self.fast.is_some())
            .finish()
    }
}

impl ChannelSlice {
    /// The slice at the model's current parameters; an error for an index
    /// or channel out of range.
    pub fn new(
        model: &dyn Parametric,
        channel: usize,
        indices: Vec<usize>,
    ) -> Result<Self, ParamError> {
        let np = model.n_params();
        if channel >= model.channels() || indices.iter().any(|&k| k >= np) {
            return Err(ParamError::Config {
                model: model.name().to_string(),
                reason: format!(
                    "channel {channel} / parameters {indices:?} out of range ({} channels, {np} parameters)",
                    model.channels()
                ),
            });
        }
        let all = model.param_specs();
        let specs = indices.iter().map(|&k| all[k].clone()).collect();
        let params: Vec<f64> = indices.iter().map(|&k| model.params()[k]).collect();
        let fast = crate::catalogue::channel_model(model)
            .filter(|f| agrees(model, channel, &indices, &params, f.as_ref()));
        Ok(Self {
            model: model.clone_box(),
            channel,
            indices,
            specs,
            params,
            fast,
        })
    }

    /// Whether the channel is evaluated by a one-channel model of its own
    /// (else by the whole model).
    pub fn is_fast(&self) -> bool {
        self.fast.is_some()
    }

    /// The full parameter vector with this slice's entries from `p`.
    pub fn full(&self, p: &[f64]) -> Vec<f64> {
        let mut q = self.model.params().to_vec();
        for (&k, x) in self.indices.iter().zip(p) {
            q[k] = *x;
        }
        q
    }
}

impl Brdf for ChannelSlice {
    fn channels(&self) -> usize {
        1
    }
    fn eval(&self, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        self.eval_at(&self.params, l, v, out)
    }
}

impl Parametric for ChannelSlice {
    brdf_core::param_accessors!();
    fn name(&self) -> &str {
        self.model.name()
    }
    fn eval_at(&self, p: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        if let Some(f) = &self.fast {
            return f.eval_at(p, l, v, out);
        }
        let mut all = vec![0.0; self.model.channels()];
        self.model.eval_at(&self.full(p), l, v, &mut all);
        out[0] = all[self.channel];
    }
    fn eval_grad_at(
        &self,
        p: &[f64],
        l: &Vector3<f64>,
        v: &Vector3<f64>,
        out: &mut [f64],
        grad: &mut [f64],
    ) {
        if let Some(f) = &self.fast {
            return f.eval_grad_at(p, l, v, out, grad);
        }
        let (nc, np) = (self.model.channels(), self.model.n_params());
        let mut all = vec![0.0; nc];
        let mut g = vec![0.0; nc * np];
        self.model
            .eval_grad_at(&self.full(p), l, v, &mut all, &mut g);
        out[0] = all[self.channel];
        let row = &g[self.channel * np..(self.channel + 1) * np];
        for (d, &k) in grad.iter_mut().zip(&self.indices) {
            *d = row[k];
        }
    }
    fn eval_batch_at(&self, p: &[f64], pairs: &DirPairs, out: &mut [f64]) {
        match &self.fast {
            Some(f) => f.eval_batch_at(p, pairs, out),
            None => brdf_core::brdf::eval_batch_per_pair(self, p, pairs, out),
        }
    }
    fn eval_grad_batch_at(&self, p: &[f64], pairs: &DirPairs, out: &mut [f64], jac: &mut [f64]) {
        match &self.fast {
            Some(f) => f.eval_grad_batch_at(p, pairs, out, jac),
            None => brdf_core::brdf::eval_grad_batch_per_pair(self, p, pairs, out, jac),
        }
    }
    fn shared_basis(&self) -> Option<&dyn SharedBasis> {
        self.fast.as_ref().and_then(|f| f.shared_basis())
    }
    fn is_reciprocal(&self) -> bool {
        self.model.is_reciprocal()
    }
}

/// Probe direction pairs of the block checks (one near the pole, one
/// oblique, one grazing).
fn probes() -> [(Vector3<f64>, Vector3<f64>); 3] {
    [
        (Vector3::new(0.3, 0.1, 0.9), Vector3::new(-0.2, 0.05, 0.95)),
        (Vector3::new(0.7, -0.2, 0.5), Vector3::new(0.6, 0.3, 0.6)),
        (Vector3::new(0.0, 0.0, 1.0), Vector3::new(-0.9, 0.1, 0.3)),
    ]
    .map(|(l, v)| (l.normalize(), v.normalize()))
}

/// Whether the one-channel model `fast` at `params` gives channel
/// `channel` of `model` and its derivatives in `indices` at the probe
/// directions, one by one and in batch (to `1e-12` relative: the two may
/// round differently).
fn agrees(
    model: &dyn Parametric,
    channel: usize,
    indices: &[usize],
    params: &[f64],
    fast: &dyn Parametric,
) -> bool {
    let nf = indices.len();
    if fast.channels() != 1 || fast.n_params() != nf {
        return false;
    }
    let (nc, np) = (model.channels(), model.n_params());
    let (mut all, mut g) = (vec![0.0; nc], vec![0.0; nc * np]);
    let (mut one, mut dg) = ([0.0], vec![0.0; nf]);
    let mut pairs = DirPairs::with_capacity(3);
    let (mut batch, mut jac) = (vec![0.0; 3], vec![0.0; 3 * nf]);
    for (l, v) in probes() {
        pairs.push(&l, &v);
    }
    fast.eval_grad_batch_at(params, &pairs, &mut batch, &mut jac);
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * a.abs().max(b.abs()) + 1e-300;
    probes().iter().enumerate().all(|(j, (l, v))| {
        model.eval_grad_at(model.params(), l, v, &mut all, &mut g);
        fast.eval_grad_at(params, l, v, &mut one, &mut dg);
        let row = &g[channel * np..(channel + 1) * np];
        let batch_row = &jac[j * nf..(j + 1) * nf];
        close(all[channel], one[0])
            && close(all[channel], batch[j])
            && (0..nf)
                .all(|u| close(row[indices[u]], dg[u]) && close(row[indices[u]], batch_row[u]))
    })
}

/// Every parameter's channel by its name (`kd_r`, `alpha_g`, ... as
/// [`channel_param_name`] forms them), then the block structure checked:
/// the derivative of channel `c` in a parameter of another channel is 0 at
/// a few direction pairs (at the current parameters). `None` for a
/// one-channel model, a model with a shared parameter, or one whose
/// Jacobian is not block-diagonal.
pub fn channel_blocks(model: &dyn Parametric) -> Option<Vec<Vec<usize>>> {
    let nc = model.channels();
    if nc < 2 {
        return None;
    }
    let mut blocks = vec![Vec::new(); nc];
    for (k, s) in model.param_specs().iter().enumerate() {
        let c = (0..nc).find(|&c| {
            let suffix = channel_param_name("", c, nc);
            s.name.len() > suffix.len() && s.name.ends_with(&suffix)
        })?;
        blocks[c].push(k);
    }
    if blocks.iter().any(Vec::is_empty) {
        return None;
    }
    let np = model.n_params();
    let mut out = vec![0.0; nc];
    let mut grad = vec![0.0; nc * np];
    for (l, v) in probes() {
        model.eval_grad_at(model.params(), &l, &v, &mut out, &mut grad);
        for (c, block) in blocks.iter().enumerate() {
            for k in 0..np {
                if !block.contains(&k) && grad[c * np + k] != 0.0 {
                    return None;
                }
            }
        }
    }
    Some(blocks)
}
