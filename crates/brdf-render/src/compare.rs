//! One call that judges a test BRDF against a reference BRDF by their
//! renders: the appearance spec's metrics under one light set.
//!
//! Why: a fit report needs FLIP, PSNR and the colour difference together,
//! all from the same two renders at the same exposure; the shading terms
//! are computed once and both BRDFs are rendered from them, the reference
//! as the judge renders the data ([`Reference`]).

use brdf_core::Brdf;

use crate::RenderError;
use crate::image_error::LightError;
use crate::light::LightSet;
use crate::reference::Reference;
use crate::shading::ShadingPoints;

/// Render `reference` and `test` under `lights` with the judge camera at
/// `size x size`, the environment visible behind the sphere (as the judge's
/// renders; HDR-FLIP is the mean over the whole image), and compute their
/// image errors ([`LightError`]).
pub fn compare(
    reference: &(impl Brdf + ?Sized),
    test: &(impl Brdf + ?Sized),
    lights: &LightSet,
    size: usize,
) -> Result<LightError, RenderError> {
    if size < 2 {
        return Err(RenderError::Invalid(format!(
            "compare: size = {size}: use at least 2 pixels (reports use 128)"
        )));
    }
    let sp = ShadingPoints::judge_with_background(lights, size);
    let reference = Reference::new(lights, &sp, reference)?;
    Ok(reference.compare(&sp.render(test))?.0)
}
