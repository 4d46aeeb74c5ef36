//! A fixed, deterministic quadrature over the sphere of directions: the
//! spherical Fibonacci point set with equal solid-angle weights `4 pi / n`.
//!
//! Why: environment lights (the sky dome, the studio's constant surround)
//! become a finite list of directions, so a render is a deterministic sum
//! (no sampling noise, the same image on every run and thread count) and a
//! fitting objective can precompute it. The Fibonacci set covers the sphere
//! almost uniformly (each point owns an area of about `4 pi / n`): with
//! `n = 512` the cosine integral over any hemisphere is `pi` to about
//! `1e-3` (the error comes from the horizon cut of the clamped cosine).
//!
//! Point `i` (of `n`): `z = 1 - (2 i + 1) / n`, `phi = i pi (3 - sqrt 5)`
//! (the golden angle). Reference: Marques et al. 2013, "Spherical Fibonacci
//! point sets for illumination integrals", Computer Graphics Forum 32(8).

use nalgebra::Vector3;

/// `n` unit directions of the spherical Fibonacci set, each representing
/// the solid angle `4 pi / n`.
pub fn fibonacci_sphere(n: usize) -> Vec<Vector3<f64>> {
    let golden = std::f64::consts::PI * (3.0 - 5.0_f64.sqrt());
    (0..n)
        .map(|i| {
            let z = 1.0 - (2.0 * i as f64 + 1.0) / n as f64;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let phi = golden * i as f64;
            Vector3::new(r * phi.cos(), r * phi.sin(), z)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hemisphere_cosine_integral_is_pi() {
        let dirs = fibonacci_sphere(512);
        let w = 4.0 * std::f64::consts::PI / 512.0;
        for n in [
            Vector3::z(),
            Vector3::new(0.3, -0.5, 0.2).normalize(),
            Vector3::x(),
        ] {
            let s: f64 = dirs.iter().map(|d| n.dot(d).max(0.0) * w).sum();
            assert!((s / std::f64::consts::PI - 1.0).abs() < 2e-3, "{s}");
        }
        let mean = dirs.iter().sum::<Vector3<f64>>() / 512.0;
        assert!(mean.norm() < 1e-2);
    }
}
