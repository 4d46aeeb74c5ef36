//! One call that judges a test BRDF against a reference BRDF by their
//! renders: the appearance spec's metrics under one light set.
//!
//! Why: a fit report needs FLIP, PSNR and the colour difference together,
//! all from the same two renders at the same exposure; the shading terms
//! are computed once and both BRDFs are rendered from them.

use brdf_core::Brdf;

use crate::RenderError;
use crate::colour::{delta_e_mean_colours, mean_colour};
use crate::flip::hdr_flip;
use crate::light::LightSet;
use crate::psnr::psnr;
use crate::shading::ShadingPoints;
use crate::tonemap::p99_exposure;

/// Image size of reports (the spec's 128 x 128 film).
pub const REPORT_SIZE: usize = 128;

/// The image errors of a test render against a reference render.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImageErrors {
    /// mean HDR-FLIP over the whole image (background included)
    pub flip: f64,
    /// PSNR (dB) at `exposure`, clipped, gamma 2.2 (infinite when identical)
    pub psnr: f64,
    /// CIEDE2000 between the mean sphere colours, scaled so the reference's
    /// luminance is 0.5 (the judge's figure; [`crate::colour`])
    pub delta_e_mean_colour: f64,
    /// mean linear RGB of the reference's sphere pixels
    pub mean_colour_ref: [f64; 3],
    /// mean linear RGB of the test's sphere pixels
    pub mean_colour_test: [f64; 3],
    /// `1 / p99(reference sphere pixels)`
    pub exposure: f64,
}

/// Render `reference` and `test` under `lights` with the judge camera at
/// `size x size`, the environment visible behind the sphere (as the judge's
/// renders; HDR-FLIP is the mean over the whole image), and compute their
/// [`ImageErrors`].
pub fn compare(
    reference: &(impl Brdf + ?Sized),
    test: &(impl Brdf + ?Sized),
    lights: &LightSet,
    size: usize,
) -> Result<ImageErrors, RenderError> {
    if size < 2 {
        return Err(RenderError::Invalid(format!(
            "compare: size = {size}: use at least 2 pixels (reports use 128)"
        )));
    }
    let sp = ShadingPoints::judge_with_background(lights, size);
    compare_with(&sp, reference, test)
}

/// [`compare`] with precomputed shading terms.
pub fn compare_with(
    sp: &ShadingPoints,
    reference: &(impl Brdf + ?Sized),
    test: &(impl Brdf + ?Sized),
) -> Result<ImageErrors, RenderError> {
    let (r, t) = (sp.render(reference), sp.render(test));
    let mask = sp.mask();
    let exposure = p99_exposure(&r, Some(&mask))?;
    let mean_colour_ref = mean_colour(&r, &mask);
    let mean_colour_test = mean_colour(&t, &mask);
    Ok(ImageErrors {
        flip: hdr_flip(&r, &t)?,
        psnr: psnr(&r, &t, exposure)?,
        delta_e_mean_colour: delta_e_mean_colours(mean_colour_ref, mean_colour_test),
        mean_colour_ref,
        mean_colour_test,
        exposure,
    })
}
