//! Sphere renderings (Kurt's Figures 9.1-9.3, 9.6): a unit sphere seen
//! orthographically along `-z`, lit by a directional light, shaded with any
//! [`Brdf`]; PNG output and the PSNR between two renderings.
//!
//! Pixel radiance: `L_o = f(L, V) cos theta_i E` with `E = 1`, `L` and `V`
//! expressed in the local frame of the sphere point (normal = the point;
//! tangent = world `+x` made orthogonal to it, so anisotropic models have a
//! continuous tangent field). Pixels off the sphere are 0.

use std::path::Path;

use brdf_core::{Brdf, Frame};
use nalgebra::Vector3;

use crate::StudyError;

/// A linear RGB (or grey) image, row-major, `channels` values per pixel.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// width in pixels
    pub width: usize,
    /// height in pixels
    pub height: usize,
    /// channels per pixel
    pub channels: usize,
    /// values
    pub data: Vec<f64>,
}

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

impl Image {
    /// Largest value (the PSNR peak of a reference rendering).
    pub fn peak(&self) -> f64 {
        self.data.iter().cloned().fold(0.0, f64::max)
    }

    /// `|a - b|` per value.
    pub fn abs_difference(&self, other: &Image) -> Image {
        Image {
            data: self
                .data
                .iter()
                .zip(&other.data)
                .map(|(a, b)| (a - b).abs())
                .collect(),
            ..self.clone()
        }
    }

    /// Place images side by side (same height and channels).
    pub fn hstack(images: &[&Image]) -> Image {
        let h = images.first().map(|i| i.height).unwrap_or(0);
        let nc = images.first().map(|i| i.channels).unwrap_or(1);
        let w: usize = images.iter().map(|i| i.width).sum();
        let mut data = vec![0.0; w * h * nc];
        let mut x0 = 0;
        for img in images {
            for y in 0..h.min(img.height) {
                for x in 0..img.width {
                    for c in 0..nc.min(img.channels) {
                        data[(y * w + x0 + x) * nc + c] =
                            img.data[(y * img.width + x) * img.channels + c];
                    }
                }
            }
            x0 += img.width;
        }
        Image {
            width: w,
            height: h,
            channels: nc,
            data,
        }
    }

    /// Write as 8-bit PNG: values scaled by `exposure`, clamped to `[0, 1]`,
    /// gamma 2.2 encoded. Grey images are written as grey, others as RGB
    /// (the first three channels).
    pub fn write_png(&self, path: &Path, exposure: f64) -> Result<(), StudyError> {
        let io = |e: std::io::Error| StudyError::Io {
            path: path.display().to_string(),
            source: e,
        };
        let file = std::fs::File::create(path).map_err(io)?;
        let w = std::io::BufWriter::new(file);
        let mut enc = png::Encoder::new(w, self.width as u32, self.height as u32);
        let out_c = if self.channels >= 3 { 3 } else { 1 };
        enc.set_color(if out_c == 3 {
            png::ColorType::Rgb
        } else {
            png::ColorType::Grayscale
        });
        enc.set_depth(png::BitDepth::Eight);
        let mut writer = enc
            .write_header()
            .map_err(|e| io(std::io::Error::other(e.to_string())))?;
        let mut bytes = Vec::with_capacity(self.width * self.height * out_c);
        for p in 0..self.width * self.height {
            for c in 0..out_c {
                let v = (self.data[p * self.channels + c] * exposure).clamp(0.0, 1.0);
                bytes.push((v.powf(1.0 / 2.2) * 255.0).round() as u8);
            }
        }
        writer
            .write_image_data(&bytes)
            .map_err(|e| io(std::io::Error::other(e.to_string())))?;
        Ok(())
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
