//! Tone mapping with the exposure stated: the judge's display transform (`docs/appearance.md`)
//! `v -> clip(exposure v, 0, 1)^(1 / 2.2)` and the exposure
//! `1 / p99(reference sphere pixels)`.
//!
//! Why: PSNR, LDR-FLIP and PNG figures need display values, and comparing
//! two renders is only fair when both use the same exposure, derived from
//! the reference alone. The 99th percentile (nearest rank, over every
//! channel value of the pixels that see the sphere) ignores the few
//! brightest highlight pixels, so the body colour is not crushed to black.

use crate::{Image, RenderError};

/// RGB of pixel `p` (a grey image gives the same value in R, G, B).
pub fn rgb_at(image: &Image, p: usize) -> [f64; 3] {
    let base = p * image.channels;
    if image.channels >= 3 {
        [image.data[base], image.data[base + 1], image.data[base + 2]]
    } else {
        [image.data[base]; 3]
    }
}

/// RGB of pixel `p` as a display shows it: negative channels clipped at 0.
/// Every image metric reads pixels through this: renders of measured data
/// hold out-of-gamut colours with negative channels (a saturated glaze's
/// body under the sky), and an error measured against a negative
/// reference would count a difference no display can show.
pub fn shown_rgb_at(image: &Image, p: usize) -> [f64; 3] {
    rgb_at(image, p).map(|v| v.max(0.0))
}

/// `1 / p99` of the channel values of `reference` at the pixels where `mask`
/// is true (all pixels when `mask` is `None`).
pub fn p99_exposure(reference: &Image, mask: Option<&[bool]>) -> Result<f64, RenderError> {
    let n = reference.width * reference.height;
    let mut values: Vec<f64> = (0..n)
        .filter(|&p| mask.is_none_or(|m| m.get(p).copied().unwrap_or(false)))
        .flat_map(|p| shown_rgb_at(reference, p))
        .collect();
    values.sort_by(f64::total_cmp);
    let rank = ((0.99 * values.len() as f64).ceil() as usize).max(1);
    match values.get(rank - 1) {
        Some(&p99) if p99 > 0.0 && p99.is_finite() => Ok(1.0 / p99),
        _ => Err(RenderError::Invalid(
            "p99_exposure: the reference has no positive finite value on the sphere: render a lit reference".into(),
        )),
    }
}

/// The display value of linear `v` at `exposure`: clipped to `[0, 1]`,
/// gamma 2.2 encoded.
pub fn display(v: f64, exposure: f64) -> f64 {
    (v * exposure).clamp(0.0, 1.0).powf(1.0 / 2.2)
}

/// Display values of `image` (RGB) at `exposure`.
pub fn tone_map(image: &Image, exposure: f64) -> Image {
    let n = image.width * image.height;
    let data = (0..n)
        .flat_map(|p| shown_rgb_at(image, p).map(|v| display(v, exposure)))
        .collect();
    Image {
        width: image.width,
        height: image.height,
        channels: 3,
        data,
    }
}

/// 8-bit RGB bytes of `image` at `exposure` (as [`Image::write_png`]).
pub fn to_rgb8(image: &Image, exposure: f64) -> Vec<u8> {
    tone_map(image, exposure)
        .data
        .iter()
        .map(|v| (v * 255.0).round() as u8)
        .collect()
}

/// Error unless `a` and `b` have the same, non-zero width and height.
pub fn check_same_size(what: &'static str, a: &Image, b: &Image) -> Result<(), RenderError> {
    if a.width == 0 || a.height == 0 {
        return Err(RenderError::Invalid(format!(
            "{what}: the reference image is empty: render at least 1 x 1 pixels"
        )));
    }
    if a.width == b.width && a.height == b.height {
        return Ok(());
    }
    let shape = |i: &Image| format!("{}x{}x{}", i.width, i.height, i.channels);
    Err(RenderError::ShapeMismatch {
        what,
        a: shape(a),
        b: shape(b),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn p99_of_a_ramp_and_display_values() -> Result<(), RenderError> {
        let data: Vec<f64> = (1..=100).map(f64::from).collect();
        let img = Image {
            width: 100,
            height: 1,
            channels: 1,
            data,
        };
        // 300 values (grey counted in R, G, B): rank ceil(297) = 297 -> 99.
        assert_eq!(p99_exposure(&img, None)?, 1.0 / 99.0);
        let mask: Vec<bool> = (0..100).map(|i| i < 10).collect();
        assert_eq!(p99_exposure(&img, Some(&mask))?, 0.1);
        assert!((display(0.5, 1.0) - 0.5_f64.powf(1.0 / 2.2)).abs() < 1e-15);
        assert_eq!(display(7.0, 1.0), 1.0);
        let black = Image {
            width: 2,
            height: 1,
            channels: 3,
            data: vec![0.0; 6],
        };
        assert!(p99_exposure(&black, None).is_err());
        Ok(())
    }
}
