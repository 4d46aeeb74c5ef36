//! Benchmark crate: shared fixed-seed inputs for the criterion benches in
//! `benches/`, the IRLS designs ([`irls_designs`]) and the peer comparison
//! ([`peers`]). Nothing here is published.
//!
//! ## Layering
//!
//! The benchmarks sit on top of the workspace, beside the `brdf` command:
//! they call the libraries (`brdf-fit`, `brdf-solve`, `brdf-study` for the
//! `fits` bench) and nothing depends on them.

use brdf_core::{DirPairs, spherical_to_cartesian};

/// `n` deterministic direction pairs above the horizon (a low-discrepancy
/// sequence in `(cos theta_i, phi_i, cos theta_o, phi_o)`), the same in every run.
pub fn fixed_pairs(n: usize) -> DirPairs {
    let mut p = DirPairs::with_capacity(n);
    let g = [
        0.8191725133961645,
        0.6710436067037893,
        0.5497004779019703,
        0.4502995220980297,
    ];
    for i in 0..n {
        let u: Vec<f64> = g.iter().map(|a| (0.5 + a * i as f64).fract()).collect();
        let l = spherical_to_cartesian((0.02 + 0.97 * u[0]).acos(), u[1] * std::f64::consts::TAU);
        let v = spherical_to_cartesian((0.02 + 0.97 * u[2]).acos(), u[3] * std::f64::consts::TAU);
        p.push(&l, &v);
    }
    p
}

pub mod irls_designs;
pub mod peers;
