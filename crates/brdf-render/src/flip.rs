//! FLIP image differences (Andersson et al. 2020, "FLIP: A Difference
//! Evaluator for Alternating Images"; HDR-FLIP: Andersson et al. 2021,
//! "Visualizing and Communicating Errors in Rendered Images") through the
//! `nv-flip` crate, the Rust bindings to NVIDIA's own C++ FLIP.
//!
//! The metric itself is never computed here: [`ldr_flip`] tone maps both
//! images with the judge's exposure and gamma 2.2, quantises to 8-bit sRGB
//! (what `nv-flip` takes) and calls `nv_flip::flip` at 67 pixels per degree
//! (FLIP's default: a 0.7 m wide 4K monitor seen from 0.7 m).
//!
//! [`hdr_flip`] follows `flip_evaluator`'s HDR mode (FLIP's `image.h`
//! `computeExposures` and the HDR loop in `FLIP.h`):
//! - luminance `Y = 0.2126 R + 0.7152 G + 0.0722 B` of every reference pixel
//!   (background included); `Y_max` and the median `Y_med` (mean of the two
//!   middle values, as FLIP);
//! - `x_max`: the larger root of `(a - t d) x^2 + (b - t e) x + (c - t f) = 0`,
//!   `t = 0.85`, with FLIP's ACES coefficients `(a..f)`;
//! - exposures from `start = log2(x_max / Y_max)` to
//!   `stop = log2(x_max / Y_med)`, `n = max(2, ceil(stop - start))` of them,
//!   evenly spaced;
//! - at each exposure `e`: both images scaled by `2^e`, ACES tone mapped
//!   (FLIP's fit), clipped to `[0, 1]`, sRGB encoded, compared by LDR-FLIP;
//! - the per-pixel maximum over exposures; its mean is HDR-FLIP.
//!
//! Both images are read as a display shows them, negative channels
//! clipped at 0 ([`shown_rgb_at`]), before the exposures and the tone curve
//! (whose rational fit turns large negative values bright).
//!
//! Differences from `flip_evaluator`: (1) each exposure's tone-mapped images
//! are quantised to 8 bits before LDR-FLIP (the Rust crate takes 8-bit sRGB;
//! `flip_evaluator` passes floats), which adds an error of up to half a
//! code value; (2) when the reference's median luminance is 0 (mostly black
//! background) FLIP's stop exposure would be infinite; we then use the
//! smallest non-zero luminance instead; (3) the tone curve is evaluated in
//! `f64`.

use nv_flip::{DEFAULT_PIXELS_PER_DEGREE, FlipImageFloat, FlipImageRgb8, FlipPool};

use crate::tonemap::{check_same_size, shown_rgb_at, to_rgb8};
use crate::{Image, RenderError};

/// FLIP's ACES fit `(a, b, c, d, e, f)`: `(a x^2 + b x + c) / (d x^2 + e x + f)`
/// (FLIP's `ToneMappingCoefficients`, 0.6 is its pre-exposure cancellation).
const ACES: [f64; 6] = [
    0.6 * 0.6 * 2.51,
    0.6 * 0.03,
    0.0,
    0.6 * 0.6 * 2.43,
    0.6 * 0.59,
    0.14,
];

/// A per-pixel FLIP error map (values in `[0, 1]`, row-major).
#[derive(Clone, Debug, PartialEq)]
pub struct FlipMap {
    /// width in pixels
    pub width: usize,
    /// height in pixels
    pub height: usize,
    /// error per pixel
    pub values: Vec<f32>,
}

impl FlipMap {
    /// Mean error (FLIP's recommended single number), by FLIP's own pool.
    pub fn mean(&self) -> f64 {
        let img = FlipImageFloat::with_data(self.width as u32, self.height as u32, &self.values);
        FlipPool::from_image(&img).mean() as f64
    }

    /// The map colour-mapped with FLIP's magma map, as an RGB image whose
    /// values are linear (write it with exposure 1: the PNG shows the magma
    /// colours).
    pub fn to_magma(&self) -> Image {
        let img = FlipImageFloat::with_data(self.width as u32, self.height as u32, &self.values);
        let rgb = img.apply_color_lut(&nv_flip::magma_lut()).to_vec();
        let data = rgb.iter().map(|&b| (b as f64 / 255.0).powf(2.2)).collect();
        Image {
            width: self.width,
            height: self.height,
            channels: 3,
            data,
        }
    }
}

fn flip_bytes(width: usize, height: usize, reference: &[u8], test: &[u8]) -> FlipMap {
    let r = FlipImageRgb8::with_data(width as u32, height as u32, reference);
    let t = FlipImageRgb8::with_data(width as u32, height as u32, test);
    let map = nv_flip::flip(r, t, DEFAULT_PIXELS_PER_DEGREE);
    FlipMap {
        width,
        height,
        values: map.to_vec(),
    }
}

/// LDR-FLIP error map of `test` against `reference`, both displayed at
/// `exposure` (clip, gamma 2.2, 8 bits).
pub fn ldr_flip_map(
    reference: &Image,
    test: &Image,
    exposure: f64,
) -> Result<FlipMap, RenderError> {
    check_same_size("ldr_flip", reference, test)?;
    let (r, t) = (to_rgb8(reference, exposure), to_rgb8(test, exposure));
    Ok(flip_bytes(reference.width, reference.height, &r, &t))
}

/// Mean LDR-FLIP of `test` against `reference` at `exposure`.
pub fn ldr_flip(reference: &Image, test: &Image, exposure: f64) -> Result<f64, RenderError> {
    Ok(ldr_flip_map(reference, test, exposure)?.mean())
}

fn luminance(c: [f64; 3]) -> f64 {
    0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
}

/// The exposures (log2 scale factors) HDR-FLIP evaluates, from the
/// reference's luminance (see the module doc).
pub fn hdr_exposures(reference: &Image) -> Result<Vec<f64>, RenderError> {
    let n = reference.width * reference.height;
    let mut y: Vec<f64> = (0..n)
        .map(|p| luminance(shown_rgb_at(reference, p)))
        .collect();
    y.sort_by(f64::total_cmp);
    let err =
        || RenderError::Invalid("hdr_flip: the reference is black: render a lit reference".into());
    let y_max = *y
        .last()
        .filter(|&&m| m > 0.0 && m.is_finite())
        .ok_or_else(err)?;
    let mid = (n / 2).max(1);
    let mut y_med = 0.5 * (y[mid - 1] + y[mid.min(n - 1)]);
    if y_med <= 0.0 {
        y_med = y.iter().copied().find(|&v| v > 0.0).ok_or_else(err)?;
    }
    let t = 0.85;
    let [a, b, c, d, e, f] = ACES;
    let (qa, qb, qc) = (a - t * d, b - t * e, c - t * f);
    let d1 = -0.5 * qb / qa;
    let x_max = d1 + (d1 * d1 - qc / qa).sqrt();
    let start = (x_max / y_max).log2();
    let stop = (x_max / y_med).log2();
    let count = ((stop - start).ceil() as usize).max(2);
    let step = (stop - start) / (count - 1) as f64;
    Ok((0..count).map(|i| start + i as f64 * step).collect())
}

fn srgb_encode(v: f64) -> f64 {
    if v <= 0.0031308 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    }
}

/// 8-bit sRGB bytes of `image` scaled by `2^exposure`, ACES tone mapped and
/// clipped (FLIP's HDR display transform).
fn aces_rgb8(image: &Image, exposure: f64) -> Vec<u8> {
    let m = exposure.exp2();
    let [a, b, c, d, e, f] = ACES;
    (0..image.width * image.height)
        .flat_map(|p| shown_rgb_at(image, p))
        .map(|v| {
            let x = v * m;
            let tm = ((a * x + b) * x + c) / ((d * x + e) * x + f);
            (srgb_encode(tm.clamp(0.0, 1.0)) * 255.0 + 0.5) as u8
        })
        .collect()
}

/// HDR-FLIP error map: the per-pixel maximum of LDR-FLIP over
/// [`hdr_exposures`].
pub fn hdr_flip_map(reference: &Image, test: &Image) -> Result<FlipMap, RenderError> {
    check_same_size("hdr_flip", reference, test)?;
    let (w, h) = (reference.width, reference.height);
    let mut max = FlipMap {
        width: w,
        height: h,
        values: vec![0.0; w * h],
    };
    for e in hdr_exposures(reference)? {
        let map = flip_bytes(w, h, &aces_rgb8(reference, e), &aces_rgb8(test, e));
        for (m, v) in max.values.iter_mut().zip(map.values) {
            *m = m.max(v);
        }
    }
    Ok(max)
}

/// Mean HDR-FLIP of `test` against `reference` (linear radiance).
pub fn hdr_flip(reference: &Image, test: &Image) -> Result<f64, RenderError> {
    Ok(hdr_flip_map(reference, test)?.mean())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hdr_exposures_span_max_to_median_where_aces_reaches_085() -> Result<(), RenderError> {
        // Luminances 1 (x2) and 8 (x2): median 4.5 (mean of the middle two),
        // max 8.
        let data = [1.0, 1.0, 8.0, 8.0].iter().flat_map(|&v| [v; 3]).collect();
        let img = Image {
            width: 2,
            height: 2,
            channels: 3,
            data,
        };
        let e = hdr_exposures(&img)?;
        let x = 8.0 * e[0].exp2();
        let [a, b, c, d, ee, f] = ACES;
        assert!(((a * x * x + b * x + c) / (d * x * x + ee * x + f) - 0.85).abs() < 1e-12);
        let span = (8.0_f64 / 4.5).log2();
        assert!((e[e.len() - 1] - e[0] - span).abs() < 1e-12);
        assert_eq!(e.len(), 2);
        Ok(())
    }

    #[test]
    fn magma_map_of_no_error_is_magma_zero() {
        let map = FlipMap {
            width: 2,
            height: 1,
            values: vec![0.0, 1.0],
        };
        let img = map.to_magma();
        assert_eq!((img.width, img.height, img.channels), (2, 1, 3));
        // Magma runs from near black to a light yellow.
        assert!(img.data[..3].iter().all(|&v| v < 0.01));
        assert!(img.data[3] > 0.9 && img.data[4] > 0.9);
        assert_eq!(map.mean(), 0.5);
    }

    /// A reference with out-of-gamut pixels (negative red, as the
    /// measured plugin renders a saturated glaze) against the same image
    /// clipped at 0: what a display shows of both is the same, so the
    /// error is 0; unclipped, the tone curve would have turned -2 bright.
    #[test]
    fn negative_channels_are_clipped_before_the_comparison() -> Result<(), RenderError> {
        let reference: Vec<f64> = (0..64)
            .flat_map(|p| {
                let v = 0.1 + 0.02 * p as f64;
                [if p % 5 == 0 { -2.0 } else { v }, v, 0.5 * v]
            })
            .collect();
        let image = |data: Vec<f64>| Image {
            width: 8,
            height: 8,
            channels: 3,
            data,
        };
        let shown = image(reference.iter().map(|v| v.max(0.0)).collect());
        let reference = image(reference);
        assert_eq!(hdr_flip(&reference, &shown)?, 0.0);
        let zero_red = image(
            shown
                .data
                .iter()
                .enumerate()
                .map(|(k, v)| if k % 3 == 0 { 0.0 } else { *v })
                .collect(),
        );
        assert!(hdr_flip(&reference, &zero_red)? > 0.0);
        Ok(())
    }
}
