//! Sample weights: cosine weighting and the solid angles of grid cells and
//! MERL bins.
//!
//! A gridded data set samples a smooth function at nodes; each node stands for
//! the cell around it. In one angle, node `k`'s cell runs from the midpoint to
//! its left neighbour to the midpoint to its right neighbour, so the first and
//! last nodes get half cells and a corner node of a 2-D grid a quarter cell.
//! Weights are the exact solid angles of these cells, so they sum to the
//! measure of the region the grid covers. Derivation of the MERL bin measure in
//! `docs/derivations/merl_solid_angle.md`.

use std::f64::consts::PI;

use crate::CoreError;
use crate::samples::DirPairs;

/// `cos theta_i` of every pair (Ngan's metric multiplies residuals by it).
pub fn cosine_weights(pairs: &DirPairs) -> Vec<f64> {
    pairs.lz.iter().map(|c| c.max(0.0)).collect()
}

/// Cell edges of sorted 1-D nodes: midpoints between neighbours, the outer
/// nodes themselves at the ends (half cells there).
pub fn cell_edges(nodes: &[f64]) -> Result<Vec<f64>, CoreError> {
    if nodes.is_empty() {
        return Err(CoreError::Empty { what: "grid nodes" });
    }
    if nodes.windows(2).any(|w| !(w[1] > w[0])) || nodes.iter().any(|x| !x.is_finite()) {
        return Err(CoreError::InvalidOption {
            name: "grid nodes",
            value: f64::NAN,
            reason: "nodes must be finite and strictly increasing",
        });
    }
    let mut e = Vec::with_capacity(nodes.len() + 1);
    e.push(nodes[0]);
    for w in nodes.windows(2) {
        e.push(0.5 * (w[0] + w[1]));
    }
    e.push(nodes[nodes.len() - 1]);
    Ok(e)
}

/// Solid angle of the cell `[t0, t1] x [p0, p1]` in `(theta, phi)`:
/// `(cos t0 - cos t1) (p1 - p0)`.
#[inline]
pub fn cell_solid_angle(t0: f64, t1: f64, p0: f64, p1: f64) -> f64 {
    (t0.cos() - t1.cos()) * (p1 - p0)
}

/// Solid-angle weights of a `(theta, phi)` grid of directions, row-major
/// (`w[i * phis.len() + j]` for `thetas[i]`, `phis[j]`). The weights sum to
/// `(cos theta_0 - cos theta_last) (phi_last - phi_0)`, the solid angle the grid
/// covers. A single azimuth node stands for the full circle (`2 pi`).
pub fn grid_solid_angles(thetas: &[f64], phis: &[f64]) -> Result<Vec<f64>, CoreError> {
    let te = cell_edges(thetas)?;
    let pe = if phis.len() == 1 {
        vec![0.0, 2.0 * PI]
    } else {
        cell_edges(phis)?
    };
    let mut w = Vec::with_capacity(thetas.len() * phis.len());
    for i in 0..thetas.len() {
        for j in 0..phis.len() {
            w.push(cell_solid_angle(te[i], te[i + 1], pe[j], pe[j + 1]));
        }
    }
    Ok(w)
}

/// MERL bin counts in `theta_h`, `theta_d`, `phi_d`.
pub const MERL_DIMS: (usize, usize, usize) = (90, 90, 180);

/// Measure `dw_i dw_o` of the half/difference region
/// `[th0, th1] x [td0, td1] x [pd0, pd1]`, integrated over all `phi_h`:
/// `dw_i dw_o = 4 cos(theta_d) sin(theta_h) sin(theta_d) dtheta_h dphi_h dtheta_d dphi_d`,
/// so the region has measure
/// `8 pi (cos th0 - cos th1) (sin^2 td1 - sin^2 td0) / 2 (pd1 - pd0)`.
pub fn half_diff_measure(th0: f64, th1: f64, td0: f64, td1: f64, pd0: f64, pd1: f64) -> f64 {
    let sh = th0.cos() - th1.cos();
    let sd = 0.5 * (td1.sin().powi(2) - td0.sin().powi(2));
    4.0 * 2.0 * PI * sh * sd * (pd1 - pd0)
}

/// Measure of MERL bin `(i_h, i_d, i_phi)`, the same for every `i_phi`. `theta_h` bins are uniform in
/// `sqrt(theta_h / (pi/2))`; `theta_d` bins uniform in `[0, pi/2)`; `phi_d`
/// bins uniform in `[0, pi)` and, by reciprocity, each also stands for the bin
/// shifted by `pi`, so its `phi_d` extent is doubled. Over all bins the weights
/// sum to `8 pi^2`, the measure of the whole half/difference domain
/// (`theta_h, theta_d in [0, pi/2]`, `phi_h, phi_d in [0, 2 pi)`).
pub fn merl_bin_solid_angle(i_h: usize, i_d: usize) -> f64 {
    let (nh, nd, np) = MERL_DIMS;
    let th = |i: usize| {
        let x = i as f64 / nh as f64;
        x * x * PI / 2.0
    };
    let td = |i: usize| i as f64 / nd as f64 * PI / 2.0;
    let dphi = PI / np as f64;
    half_diff_measure(th(i_h), th(i_h + 1), td(i_d), td(i_d + 1), 0.0, 2.0 * dphi)
}
