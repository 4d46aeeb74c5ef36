//! Sphere renderings (Kurt's Figures 9.1-9.3, 9.6): a unit sphere seen
//! orthographically along `-z`, lit by a directional light, shaded with any
//! [`Brdf`].
//!
//! Pixel radiance: `L_o = f(L, V) cos theta_i E` with `E = 1`, `L` and `V`
//! expressed in the local frame of the sphere point (normal = the point;
//! tangent = world `+x` made orthogonal to it, so anisotropic models have a
//! continuous tangent field). Pixels off the sphere are 0.

use brdf_core::{Brdf, Frame};
use nalgebra::Vector3;

use crate::Image;

/// Render a sphere of `size x size` pixels lit from world direction `light`,
/// seen from `view` (unit vectors; `view = +z` is the usual camera). With
/// `swap`, `L` and `V` are exchanged in every BRDF evaluation (the
/// reciprocity check of Kurt's Fig. 9.6): a reciprocal model gives the same
/// image.
pub fn render_sphere(
    brdf: &(impl Brdf + ?Sized),
    size: usize,
    light: &Vector3<f64>,
    view: &Vector3<f64>,
    swap: bool,
) -> Image {
    let nc = brdf.channels();
    let mut data = vec![0.0; size * size * nc];
    let mut f = vec![0.0; nc];
    for py in 0..size {
        for px in 0..size {
            let x = (px as f64 + 0.5) / size as f64 * 2.0 - 1.0;
            let y = 1.0 - (py as f64 + 0.5) / size as f64 * 2.0;
            let r2 = x * x + y * y;
            if r2 >= 1.0 {
                continue;
            }
            let n = Vector3::new(x, y, (1.0 - r2).sqrt());
            let frame = if n.x.abs() > 1.0 - 1e-9 {
                Frame::from_z(n)
            } else {
                Frame::from_xz(Vector3::x(), n)
            };
            let l = frame.to_local(light);
            let v = frame.to_local(view);
            if l.z <= 0.0 || v.z <= 0.0 {
                continue;
            }
            if swap {
                brdf.eval(&v, &l, &mut f);
            } else {
                brdf.eval(&l, &v, &mut f);
            }
            let base = (py * size + px) * nc;
            for c in 0..nc {
                data[base + c] = f[c] * l.z;
            }
        }
    }
    Image {
        width: size,
        height: size,
        channels: nc,
        data,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Lam(f64);
    impl Brdf for Lam {
        fn channels(&self) -> usize {
            1
        }
        fn eval(&self, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
            out[0] = if l.z > 0.0 && v.z > 0.0 {
                self.0 / std::f64::consts::PI
            } else {
                0.0
            };
        }
    }

    #[test]
    fn lambert_sphere_is_kd_cos_over_pi() {
        let img = render_sphere(&Lam(0.5), 33, &Vector3::z(), &Vector3::z(), false);
        // The centre pixel's normal is (0, 0, 1) up to half a pixel: radiance
        // kd/pi * cos_i with cos_i = n.z.
        let c = 16 * 33 + 16;
        let x: f64 = (16.5 / 33.0) * 2.0 - 1.0;
        let expect = 0.5 / std::f64::consts::PI * (1.0 - 2.0 * x * x).sqrt();
        assert!((img.data[c] - expect).abs() < 1e-12);
        assert_eq!(img.data[0], 0.0);
        let swapped = render_sphere(&Lam(0.5), 33, &Vector3::z(), &Vector3::z(), true);
        assert_eq!(img, swapped);
    }
}
