//! Models whose colour channels share one basis of functions.
//!
//! Most analytic models are `f_c(L, V) = sum_t x_{c,t} phi_t(L, V; q)`: the
//! non-linear parameters `q` (exponents, roughness, Fresnel) are shared by
//! all channels and each channel has its own linear coefficients (`kd_c`,
//! `ks_c`). For such a model the least-squares problem of `C` channels is
//! block-diagonal: one basis matrix `Phi(q)` (samples x basis functions)
//! serves every channel as a right-hand side, so a solver factors `Phi`
//! once and never materialises the zero blocks. [`SharedBasis`] exposes
//! that structure and evaluates the basis in batch, over precomputed
//! [`PairGeometry`], with or without derivatives.

use crate::pair_geometry::PairGeometry;
use crate::samples::DirPairs;

/// The channel-shared basis of a model (see the module doc).
pub trait SharedBasis: Send + Sync {
    /// Number of basis functions `phi_t` (per channel).
    fn basis_len(&self) -> usize;

    /// Index in the parameter vector of the coefficient `x_{c,t}`.
    fn coefficient_index(&self, channel: usize, t: usize) -> usize;

    /// `phi[t * n + j] = phi_t(L_j, V_j; q)` at the non-linear parameters of
    /// `p` (its linear entries are ignored), `n = pairs.len()`. When `dphi`
    /// is given, `dphi[(t * Q + u) * n + j] = d phi_t / d q_u` for the `u`-th
    /// of the `Q` non-linear parameters in parameter-vector order.
    /// Every entry of both outputs is written.
    fn basis_batch(
        &self,
        p: &[f64],
        pairs: &DirPairs,
        geom: &PairGeometry,
        phi: &mut [f64],
        dphi: Option<&mut [f64]>,
    );
}
