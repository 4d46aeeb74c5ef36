//! A linear-radiance image (grey or RGB, `f64` per value): what every
//! renderer of this crate returns and every metric, grid and writer takes.

use std::path::Path;

use crate::RenderError;

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
    pub fn write_png(&self, path: &Path, exposure: f64) -> Result<(), RenderError> {
        let io = |e: std::io::Error| RenderError::Io {
            path: path.display().to_string(),
            source: e,
        };
        let file = std::fs::File::create(path).map_err(io)?;
        self.encode_png(std::io::BufWriter::new(file), exposure)
            .map_err(io)
    }

    /// The PNG of [`Image::write_png`] in memory (for data: URIs).
    pub fn png_bytes(&self, exposure: f64) -> Result<Vec<u8>, RenderError> {
        let mut out = Vec::new();
        self.encode_png(&mut out, exposure)
            .map_err(|source| RenderError::Io {
                path: "in-memory PNG".into(),
                source,
            })?;
        Ok(out)
    }

    fn encode_png(&self, w: impl std::io::Write, exposure: f64) -> Result<(), std::io::Error> {
        let io = |e: png::EncodingError| std::io::Error::other(e.to_string());
        let mut enc = png::Encoder::new(w, self.width as u32, self.height as u32);
        let out_c = if self.channels >= 3 { 3 } else { 1 };
        enc.set_color(if out_c == 3 {
            png::ColorType::Rgb
        } else {
            png::ColorType::Grayscale
        });
        enc.set_depth(png::BitDepth::Eight);
        let mut writer = enc.write_header().map_err(io)?;
        let mut bytes = Vec::with_capacity(self.width * self.height * out_c);
        for p in 0..self.width * self.height {
            for c in 0..out_c {
                let v = (self.data[p * self.channels + c] * exposure).clamp(0.0, 1.0);
                bytes.push((v.powf(1.0 / 2.2) * 255.0).round() as u8);
            }
        }
        writer.write_image_data(&bytes).map_err(io)?;
        writer.finish().map_err(io)
    }
}
