//! PSNR of two renders as the appearance spec defines it: both displayed at
//! the same exposure (`1 / p99(reference)`), clipped to `[0, 1]`, gamma 2.2
//! encoded, then `10 log10(1 / MSE)` over every channel of every pixel.
//!
//! Why: a familiar, simple number beside FLIP. Identical images give
//! `f64::INFINITY` (an MSE of 0), which callers print as "inf".

use crate::tonemap::{check_same_size, tone_map};
use crate::{Image, RenderError};

/// PSNR (dB) of `test` against `reference`, both at `exposure`.
pub fn psnr(reference: &Image, test: &Image, exposure: f64) -> Result<f64, RenderError> {
    check_same_size("psnr", reference, test)?;
    let (r, t) = (tone_map(reference, exposure), tone_map(test, exposure));
    let n = r.data.len().max(1) as f64;
    let mse = r
        .data
        .iter()
        .zip(&t.data)
        .map(|(a, b)| (a - b) * (a - b))
        .sum::<f64>()
        / n;
    Ok(if mse == 0.0 {
        f64::INFINITY
    } else {
        -10.0 * mse.log10()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identical_images_are_infinite_and_a_uniform_offset_is_exact() -> Result<(), RenderError> {
        let a = Image {
            width: 2,
            height: 2,
            channels: 3,
            data: vec![0.25; 12],
        };
        assert_eq!(psnr(&a, &a, 1.0)?, f64::INFINITY);
        // Display values 0.5 and 0.6 everywhere: MSE 0.01, PSNR 20 dB.
        let r = Image {
            data: vec![0.5_f64.powf(2.2); 12],
            ..a.clone()
        };
        let t = Image {
            data: vec![0.6_f64.powf(2.2); 12],
            ..a.clone()
        };
        assert!((psnr(&r, &t, 1.0)? - 20.0).abs() < 1e-9);
        let small = Image {
            width: 1,
            height: 1,
            channels: 3,
            data: vec![0.0; 3],
        };
        assert!(matches!(
            psnr(&a, &small, 1.0),
            Err(RenderError::ShapeMismatch { .. })
        ));
        Ok(())
    }
}
