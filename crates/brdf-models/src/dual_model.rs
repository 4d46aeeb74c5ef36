//! A [`Parametric`] model from a formula written once over [`Dual`]
//! numbers: [`DualModel`] keeps the parameters, and evaluates the formula
//! with constant duals for values and with seeded duals for the exact
//! parameter derivatives. The Disney principled and glTF models are built
//! this way.

use brdf_core::{Brdf, ParamError, ParamSpec, Parametric};
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
    fn eval(p: &[Dual], channels: usize, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [Dual]);
    /// Whether `f(L, V) = f(V, L)`.
    fn reciprocal() -> bool {
        true
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

    fn run(
        &self,
        p: &[f64],
        l: &Vector3<f64>,
        v: &Vector3<f64>,
        grad: bool,
    ) -> [Dual; MAX_CHANNELS] {
        let mut q = [Dual::c(0.0); MAX_DERIV];
        let np = p.len().min(MAX_DERIV);
        seed(&p[..np], grad, &mut q[..np]);
        let mut out = [Dual::c(0.0); MAX_CHANNELS];
        F::eval(&q[..np], self.channels, l, v, &mut out);
        out
    }
}

impl<F: DualFormula> Brdf for DualModel<F> {
    fn channels(&self) -> usize {
        self.channels
    }
    fn eval(&self, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        self.eval_at(&self.params, l, v, out)
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
        let r = self.run(p, l, v, false);
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
        let r = self.run(p, l, v, true);
        for c in 0..nc {
            out[c] = r[c].v;
            let row = &mut grad[c * np..(c + 1) * np];
            row[..r[c].n.min(np)].copy_from_slice(&r[c].d[..r[c].n.min(np)]);
        }
    }
    fn is_reciprocal(&self) -> bool {
        F::reciprocal()
    }
}
