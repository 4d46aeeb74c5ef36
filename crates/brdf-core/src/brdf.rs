//! The two model traits.
//!
//! [`Brdf`] is all a renderer needs: `f(L, V)` per channel. [`Parametric`] adds
//! what a solver needs: the named parameter vector with boxes and linear flags,
//! evaluation at an arbitrary parameter vector (so solvers never mutate the
//! model), and parameter derivatives, with a central finite-difference default
//! that a model overrides with its analytic Jacobian.
//!
//! Batch methods work on structure-of-arrays direction storage
//! ([`DirPairs`]) and write channel-major output: value `c` of sample `j` at
//! `out[c * n + j]`; Jacobian row `c * n + j`, column `k` at
//! `jac[(c * n + j) * n_params + k]`. That row order is the residual order of
//! every least-squares problem built on a sample set.

use nalgebra::Vector3;

use crate::params::{ParamError, ParamSpec};
use crate::samples::DirPairs;
use crate::shared_basis::SharedBasis;

/// A BRDF that can be evaluated: `f(L, V)` in 1/sr, one value per channel.
///
/// `l` and `v` are unit vectors in the local frame (normal `+z`) pointing away
/// from the surface. Below the horizon (`l.z <= 0` or `v.z <= 0`) every model
/// returns 0.
pub trait Brdf: Send + Sync {
    /// Number of colour channels (1 for grey, 3 for RGB).
    fn channels(&self) -> usize;

    /// Write `f(L, V)` for every channel into `out[..channels]`.
    fn eval(&self, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]);

    /// Evaluate every pair; `out[c * n + j]`, `n = pairs.len()`.
    fn eval_pairs(&self, pairs: &DirPairs, out: &mut [f64]) {
        let n = pairs.len();
        let nc = self.channels();
        let mut tmp = [0.0; 16];
        let mut heap = Vec::new();
        let buf: &mut [f64] = if nc <= 16 {
            &mut tmp[..nc]
        } else {
            heap.resize(nc, 0.0);
            &mut heap
        };
        for j in 0..n {
            self.eval(&pairs.l(j), &pairs.v(j), buf);
            for c in 0..nc {
                out[c * n + j] = buf[c];
            }
        }
    }
}

/// A BRDF model with a named parameter vector and parameter derivatives.
///
/// Implementors store their current parameters (validated on construction and
/// by [`Parametric::set_params`]) and evaluate at any parameter vector through
/// [`Parametric::eval_at`], which does not validate (the solvers keep iterates
/// in the box). Linear parameters must enter the model linearly: for fixed
/// non-linear parameters, `f` is affine in the linear ones.
pub trait Parametric: Brdf {
    /// The model's catalogue name (`ward`, `cook-torrance`, ...).
    fn name(&self) -> &str;

    /// Parameter descriptions, in parameter-vector order.
    fn param_specs(&self) -> &[ParamSpec];

    /// Current parameter vector.
    fn params(&self) -> &[f64];

    /// Replace the parameter vector; validates length, finiteness and boxes,
    /// and leaves the model unchanged on error.
    fn set_params(&mut self, p: &[f64]) -> Result<(), ParamError>;

    /// `f(L, V)` per channel at parameters `p` (not validated).
    fn eval_at(&self, p: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]);

    /// Value and derivatives at `p`: `out[c]` and `grad[c * n_params + k] =
    /// d f_c / d p_k`. The default uses central finite differences
    /// ([`central_difference_grad`]); models override it analytically.
    fn eval_grad_at(
        &self,
        p: &[f64],
        l: &Vector3<f64>,
        v: &Vector3<f64>,
        out: &mut [f64],
        grad: &mut [f64],
    ) {
        self.eval_at(p, l, v, out);
        central_difference_grad(self, p, l, v, grad);
    }

    /// Batch values at `p`: `out[c * n + j]`.
    fn eval_batch_at(&self, p: &[f64], pairs: &DirPairs, out: &mut [f64]) {
        eval_batch_per_pair(self, p, pairs, out)
    }

    /// Batch values and Jacobian at `p`: `out[c * n + j]` and
    /// `jac[(c * n + j) * n_params + k]`.
    fn eval_grad_batch_at(&self, p: &[f64], pairs: &DirPairs, out: &mut [f64], jac: &mut [f64]) {
        eval_grad_batch_per_pair(self, p, pairs, out, jac)
    }

    /// The channel-shared basis, for models of the form
    /// `f_c = sum_t x_{c,t} phi_t(L, V; q)` ([`SharedBasis`]); `None` (the
    /// default) for other models. Solvers use it to fit all channels as
    /// right-hand sides of one basis.
    fn shared_basis(&self) -> Option<&dyn SharedBasis> {
        None
    }

    /// The table a model read off its data that its parameters do not
    /// hold (Dupuy et al.'s normal distribution: node angles in radians and
    /// `D` in 1/sr), so that a saved model can store it; `None` (the
    /// default) for models given by their parameters alone.
    fn data_table(&self) -> Option<(&[f64], &[f64])> {
        None
    }

    /// A boxed copy (models are cloned per thread and per fit).
    fn clone_box(&self) -> Box<dyn Parametric>;

    /// Number of parameters.
    fn n_params(&self) -> usize {
        self.param_specs().len()
    }

    /// Whether `f(L, V) = f(V, L)` for every parameter vector. Models that are
    /// not reciprocal by their published formula return false and document it.
    fn is_reciprocal(&self) -> bool {
        true
    }
}

impl Clone for Box<dyn Parametric> {
    fn clone(&self) -> Self {
        self.clone_box()
    }
}

/// Step for a central difference in parameter `x`: `eps^(1/3) max(|x|, 1)`,
/// which balances truncation `O(h^2)` against rounding `O(eps / h)`.
pub fn fd_step(x: f64) -> f64 {
    f64::EPSILON.cbrt() * x.abs().max(1.0)
}

/// Central finite-difference derivatives `grad[c * n_params + k]` of any
/// parametric model at `p`. Where the central stencil would leave the box, a
/// one-sided second-order stencil inside the box is used instead, so models
/// are never evaluated at impossible parameters.
pub fn central_difference_grad<M: Parametric + ?Sized>(
    model: &M,
    p: &[f64],
    l: &Vector3<f64>,
    v: &Vector3<f64>,
    grad: &mut [f64],
) {
    let nc = model.channels();
    let np = p.len();
    let specs = model.param_specs();
    let mut q = p.to_vec();
    let mut f1 = vec![0.0; nc];
    let mut f2 = vec![0.0; nc];
    let mut f0 = vec![0.0; nc];
    for k in 0..np {
        let h = fd_step(p[k]);
        let (lo_ok, hi_ok) = match specs.get(k) {
            Some(s) => {
                let lo = if s.lower_open {
                    p[k] - h > s.lower
                } else {
                    p[k] - h >= s.lower
                };
                (lo, p[k] + h <= s.upper)
            }
            None => (true, true),
        };
        if lo_ok && hi_ok || (!lo_ok && !hi_ok) {
            q[k] = p[k] + h;
            model.eval_at(&q, l, v, &mut f1);
            q[k] = p[k] - h;
            model.eval_at(&q, l, v, &mut f2);
            for c in 0..nc {
                grad[c * np + k] = (f1[c] - f2[c]) / (2.0 * h);
            }
        } else {
            // One-sided: f'(x) ~ (-3 f(x) + 4 f(x + s) - f(x + 2 s)) / (2 s).
            let s = if lo_ok { -h } else { h };
            model.eval_at(p, l, v, &mut f0);
            q[k] = p[k] + s;
            model.eval_at(&q, l, v, &mut f1);
            q[k] = p[k] + 2.0 * s;
            model.eval_at(&q, l, v, &mut f2);
            for c in 0..nc {
                grad[c * np + k] = (-3.0 * f0[c] + 4.0 * f1[c] - f2[c]) / (2.0 * s);
            }
        }
        q[k] = p[k];
    }
}

/// Implements [`Brdf`] for a [`Parametric`] model by evaluating at its stored
/// parameters. `impl_brdf_via_params!(Ward);` — the model must have a
/// `channels: usize` field reachable as `self.channels`.
#[macro_export]
macro_rules! impl_brdf_via_params {
    ($t:ty) => {
        impl $crate::Brdf for $t {
            fn channels(&self) -> usize {
                self.channels
            }
            fn eval(
                &self,
                l: &$crate::nalgebra::Vector3<f64>,
                v: &$crate::nalgebra::Vector3<f64>,
                out: &mut [f64],
            ) {
                $crate::Parametric::eval_at(self, $crate::Parametric::params(self), l, v, out)
            }
            fn eval_pairs(&self, pairs: &$crate::DirPairs, out: &mut [f64]) {
                $crate::Parametric::eval_batch_at(
                    self,
                    $crate::Parametric::params(self),
                    pairs,
                    out,
                )
            }
        }
    };
}

/// The four bookkeeping methods of [`Parametric`] for a model that stores
/// `specs: Vec<ParamSpec>` and `params: Vec<f64>` and is `Clone`:
/// `param_specs`, `params`, `set_params` (validated against the boxes, under
/// the model's `name()`) and `clone_box`. Use inside `impl Parametric for T`.
#[macro_export]
macro_rules! param_accessors {
    () => {
        fn param_specs(&self) -> &[$crate::ParamSpec] {
            &self.specs
        }
        fn params(&self) -> &[f64] {
            &self.params
        }
        fn set_params(&mut self, p: &[f64]) -> Result<(), $crate::ParamError> {
            $crate::params::validate($crate::Parametric::name(self), &self.specs, p)?;
            self.params.copy_from_slice(p);
            Ok(())
        }
        fn clone_box(&self) -> Box<dyn $crate::Parametric> {
            Box::new(self.clone())
        }
    };
}

/// [`Parametric::eval_batch_at`] by [`Parametric::eval_at`] pair by pair
/// (the default; a model whose batch kernel holds only in some
/// configurations falls back to it).
pub fn eval_batch_per_pair<M: Parametric + ?Sized>(
    model: &M,
    p: &[f64],
    pairs: &DirPairs,
    out: &mut [f64],
) {
    let n = pairs.len();
    let nc = model.channels();
    let mut buf = vec![0.0; nc];
    for j in 0..n {
        model.eval_at(p, &pairs.l(j), &pairs.v(j), &mut buf);
        for c in 0..nc {
            out[c * n + j] = buf[c];
        }
    }
}

/// [`Parametric::eval_grad_batch_at`] by [`Parametric::eval_grad_at`] pair
/// by pair (the default).
pub fn eval_grad_batch_per_pair<M: Parametric + ?Sized>(
    model: &M,
    p: &[f64],
    pairs: &DirPairs,
    out: &mut [f64],
    jac: &mut [f64],
) {
    let n = pairs.len();
    let nc = model.channels();
    let np = p.len();
    let mut val = vec![0.0; nc];
    let mut grad = vec![0.0; nc * np];
    for j in 0..n {
        model.eval_grad_at(p, &pairs.l(j), &pairs.v(j), &mut val, &mut grad);
        for c in 0..nc {
            out[c * n + j] = val[c];
            jac[(c * n + j) * np..(c * n + j + 1) * np]
                .copy_from_slice(&grad[c * np..(c + 1) * np]);
        }
    }
}
