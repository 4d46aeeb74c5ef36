//! OpenEXR output of linear radiance (RGB, 32-bit float) through the `exr`
//! crate.
//!
//! Why: renders are high dynamic range; an EXR keeps the linear values so
//! that other tools (Mitsuba's own comparisons, `flip_evaluator` in HDR mode,
//! an image viewer with an exposure slider) can read them. `f32` is used only
//! at this boundary.

use std::path::Path;

use crate::tonemap::rgb_at;
use crate::{Image, RenderError};

impl Image {
    /// Write the image as an RGB `f32` OpenEXR file (grey images are written
    /// with R = G = B).
    pub fn write_exr(&self, path: &Path) -> Result<(), RenderError> {
        exr::prelude::write_rgb_file(path, self.width, self.height, |x, y| {
            let [r, g, b] = rgb_at(self, y * self.width + x);
            (r as f32, g as f32, b as f32)
        })
        .map_err(|e| RenderError::Exr {
            path: path.display().to_string(),
            message: e.to_string(),
        })
    }

    /// Read the first RGB(A) layer of an OpenEXR file as a linear RGB image.
    pub fn read_exr(path: &Path) -> Result<Image, RenderError> {
        let img = exr::prelude::read_first_rgba_layer_from_file(
            path,
            |size, _| Image {
                width: size.0,
                height: size.1,
                channels: 3,
                data: vec![0.0; size.0 * size.1 * 3],
            },
            |img: &mut Image, pos, (r, g, b, _a): (f32, f32, f32, f32)| {
                let base = (pos.1 * img.width + pos.0) * 3;
                img.data[base..base + 3].copy_from_slice(&[r as f64, g as f64, b as f64]);
            },
        )
        .map_err(|e| RenderError::Exr {
            path: path.display().to_string(),
            message: e.to_string(),
        })?;
        Ok(img.layer_data.channel_data.pixels)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exr_round_trip_keeps_the_f32_values() -> Result<(), RenderError> {
        let data: Vec<f64> = (0..5 * 3 * 3)
            .map(|i| 0.1 * i as f64 + 1e3 * (i % 4) as f64)
            .collect();
        let img = Image {
            width: 5,
            height: 3,
            channels: 3,
            data,
        };
        let dir = std::env::temp_dir().join(format!("brdf-render-exr-{}", std::process::id()));
        std::fs::create_dir_all(&dir).map_err(|e| RenderError::Io {
            path: dir.display().to_string(),
            source: e,
        })?;
        let path = dir.join("round_trip.exr");
        img.write_exr(&path)?;
        let back = Image::read_exr(&path)?;
        std::fs::remove_dir_all(&dir).ok();
        assert_eq!((back.width, back.height, back.channels), (5, 3, 3));
        for (a, b) in img.data.iter().zip(&back.data) {
            assert_eq!(*a as f32 as f64, *b);
        }
        Ok(())
    }
}
