//! A [`Parametric`] model from a formula written once over [`Dual`]
//! numbers: [`DualModel`] keeps the parameters, and evaluates the formula
//! with constant duals for values and with seeded duals for the exact
//! parameter derivatives. The Disney principled and glTF models are built
//! this way.

use brdf_core::{Brdf, DirPairs, ParamError, ParamSpec, Parametric};
use nalgebra::Vector3;

use crate::dual::{Dual, MAX_DERIV, seed};

/// Most colour channels a [`DualModel`] takes.
pub const MAX_CHANNELS: usize = 8;

/// A reflectance formula over duals.
pub trait DualFormula: Clone + Send + Sync + 'static {
    /// Catalogue name.
    const NAME: &'static str;
    /// Parameter descriptions for `channels` channels.
    fn specs(channels: usize) -> Vec<ParamSpec>;
    /// `f_c(L, V)` into `out[..channels]`, for `L`, `V` above the horizon.
    fn eval<const N: usize>(
        p: &[Dual<N>],
        channels: usize,
        l: &Vector3<f64>,
        v: &Vector3<f64>,
        out: &mut [Dual<N>],
    );
    /// Whether `f(L, V) = f(V, L)`.
    fn reciprocal() -> bool {
        true
    }
    /// A batch kernel with hand-written derivatives, for the fits: values
    /// `out[c * n + j]` and, with `jac`, `jac[(c * n + j) * n_params + k]`
    /// on every pair (0 below the horizon), as [`Parametric::eval_batch_at`]
    /// and [`Parametric::eval_grad_batch_at`]. Returns `false` (the
    /// default) when the formula has none; the duals are then evaluated
    /// pair by pair.
    fn batch(
        _p: &[f64],
        _channels: usize,
        _pairs: &DirPairs,
        _out: &mut [f64],
        _jac: Option<&mut [f64]>,
    ) -> bool {
        false
    }
}

/// The model of a [`DualFormula`].
#[derive(Clone, Debug, PartialEq)]
pub struct DualModel<F: DualFormula> {
    pub(crate) channels: usize,
    specs: Vec<ParamSpec>,
    params: Vec<f64>,
    _f: std::marker::PhantomData<F>,
}

impl<F: DualFormula> DualModel<F> {
    /// The model with `channels` (1 to [`MAX_CHANNELS`]) channels at its
    /// default parameters.
    pub fn with_channels(channels: usize) -> Result<Self, ParamError> {
        if channels == 0 || channels > MAX_CHANNELS {
            return Err(ParamError::Config {
                model: F::NAME.into(),
                reason: format!("takes 1 to {MAX_CHANNELS} channels, not {channels}"),
            });
        }
        let specs = F::specs(channels);
        debug_assert!(specs.len() <= MAX_DERIV);
        let params = specs.iter().map(|s| s.default).collect();
        Ok(DualModel {
            channels,
            specs,
            params,
            _f: std::marker::PhantomData,
        })
    }

    /// The model with the given parameters, validated against their boxes.
    pub fn new(channels: usize, p: &[f64]) -> Result<Self, ParamError> {
        let mut m = Self::with_channels(channels)?;
        m.set_params(p)?;
        Ok(m)
    }

    /// The formula at `p` over duals with room for `N` derivatives
    /// (seeded when `grad`).
    fn run<const N: usize>(
        &self,
        p: &[f64],
        l: &Vector3<f64>,
        v: &Vector3<f64>,
        grad: bool,
    ) -> [Dual<N>; MAX_CHANNELS] {
        let mut q = [Dual::<N>::c(0.0); MAX_DERIV];
        let np = p.len().min(MAX_DERIV);
        seed(&p[..np], grad, &mut q[..np]);
        let mut out = [Dual::<N>::c(0.0); MAX_CHANNELS];
        F::eval(&q[..np], self.channels, l, v, &mut out);
        out
    }

    /// The values and, in `grad` (`c * np + k`), the derivatives at `p`,
    /// with the smallest dual that holds the parameters.
    fn value_and_gradient(
        &self,
        p: &[f64],
        l: &Vector3<f64>,
        v: &Vector3<f64>,
        out: &mut [f64],
        grad: &mut [f64],
    ) {
        fn copy<const N: usize>(r: &[Dual<N>], np: usize, out: &mut [f64], grad: &mut [f64]) {
            for (c, rc) in r.iter().enumerate().take(out.len()) {
                out[c] = rc.v;
                let k = rc.n.min(np).min(N);
                grad[c * np..c * np + k].copy_from_slice(&rc.d[..k]);
            }
        }
        let np = self.specs.len();
        let nc = self.channels;
        let (out, grad) = (&mut out[..nc], &mut grad[..nc * np]);
        match np {
            0..=8 => copy(&self.run::<8>(p, l, v, true), np, out, grad),
            9..=16 => copy(&self.run::<16>(p, l, v, true), np, out, grad),
            _ => copy(&self.run::<MAX_DERIV>(p, l, v, true), np, out, grad),
        }
    }
}

impl<F: DualFormula> Brdf for DualModel<F> {
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

impl<F: DualFormula> Parametric for DualModel<F> {
    brdf_core::param_accessors!();
    fn name(&self) -> &str {
        F::NAME
    }
    fn eval_at(&self, p: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        let nc = self.channels;
        if !(l.z > 0.0 && v.z > 0.0) {
            out[..nc].fill(0.0);
            return;
        }
        // No derivatives: duals without derivative storage.
        let r = self.run::<0>(p, l, v, false);
        for c in 0..nc {
            out[c] = r[c].v;
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
        self.value_and_gradient(p, l, v, out, grad);
    }
    fn eval_batch_at(&self, p: &[f64], pairs: &DirPairs, out: &mut [f64]) {
        if F::batch(p, self.channels, pairs, out, None) {
            return;
        }
        brdf_core::brdf::eval_batch_per_pair(self, p, pairs, out);
    }
    fn eval_grad_batch_at(&self, p: &[f64], pairs: &DirPairs, out: &mut [f64], jac: &mut [f64]) {
        if F::batch(p, self.channels, pairs, out, Some(jac)) {
            return;
        }
        brdf_core::brdf::eval_grad_batch_per_pair(self, p, pairs, out, jac);
    }
    fn is_reciprocal(&self) -> bool {
        F::reciprocal()
    }
}
