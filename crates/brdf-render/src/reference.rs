//! The data's render made once, and the image errors of fits against it.
//!
//! The data's render under a light set does not depend on the fit:
//! [`Reference`] keeps it (with its sphere mask, exposure and mean colour),
//! so ranking candidates renders the data once, not once per candidate.
//! Renders are [`ShadingPoints::render`], a row of terms per batch
//! evaluation ([`crate::batch`]).

use brdf_core::Brdf;

use crate::colour::{delta_e_mean_colours, mean_colour};
use crate::colour_plane::{ColourPlane, colour_plane};
use crate::flip::{FlipMap, hdr_flip_map};
use crate::image_error::LightError;
use crate::psnr::psnr;
use crate::tonemap::p99_exposure;
use crate::{Image, LightSet, RenderError, ShadingPoints};

/// The data's render under one light set, with what every comparison
/// against it needs (sphere mask, exposure, mean colour).
pub struct Reference {
    /// The light set's name.
    light: &'static str,
    image: Image,
    mask: Vec<bool>,
    exposure: f64,
    mean_colour: [f64; 3],
    colour_plane: Option<ColourPlane>,
}

impl Reference {
    /// Render `data` on `sp`, the terms of `light`.
    pub fn new(
        light: &LightSet,
        sp: &ShadingPoints,
        data: &(impl Brdf + ?Sized),
    ) -> Result<Self, RenderError> {
        Reference::from_image(light, sp, sp.render(data))
    }

    /// The reference of a render of the data made before on `sp` (kept in
    /// a cache): refused unless it has `sp`'s film and holds only finite,
    /// non-negative radiance.
    pub fn from_image(
        light: &LightSet,
        sp: &ShadingPoints,
        image: Image,
    ) -> Result<Self, RenderError> {
        let mask = sp.mask();
        if image.channels != 3 || image.width * image.height != mask.len() {
            return Err(RenderError::Invalid(format!(
                "a {}x{}x{} render of the data given for a {}-pixel film of 3 channels",
                image.width,
                image.height,
                image.channels,
                mask.len()
            )));
        }
        if image.data.len() != mask.len() * 3
            || image.data.iter().any(|v| !(*v >= 0.0 && v.is_finite()))
        {
            return Err(RenderError::Invalid(
                "a render of the data with missing, negative or non-finite values".into(),
            ));
        }
        let exposure = p99_exposure(&image, Some(&mask))?;
        let mean_colour = mean_colour(&image, &mask);
        let colour_plane = colour_plane(&image, &mask);
        Ok(Reference {
            light: light.name(),
            image,
            mask,
            exposure,
            mean_colour,
            colour_plane,
        })
    }

    /// The plane of white and one colour closest to the data's sphere
    /// colours, and how much of them lies off it
    /// ([`crate::colour_plane`]; a bound on models with one base
    /// colour only under a white light set).
    pub fn colour_plane(&self) -> Option<ColourPlane> {
        self.colour_plane
    }

    /// The data's render.
    pub fn image(&self) -> &Image {
        &self.image
    }

    /// The exposure `1 / p99` of the data's sphere pixels.
    pub fn exposure(&self) -> f64 {
        self.exposure
    }

    /// The image errors of `t`, a test rendered on the terms this
    /// reference was rendered on, and the HDR-FLIP map whose mean is their
    /// FLIP (a report shows it beside the number).
    pub fn compare(&self, t: &Image) -> Result<(LightError, FlipMap), RenderError> {
        let map = hdr_flip_map(&self.image, t)?;
        let mean_colour_fit = mean_colour(t, &self.mask);
        let errors = LightError {
            light: self.light.to_string(),
            flip: map.mean(),
            psnr: psnr(&self.image, t, self.exposure)?,
            delta_e: delta_e_mean_colours(self.mean_colour, mean_colour_fit),
            mean_colour_data: self.mean_colour,
            mean_colour_fit,
            exposure: self.exposure,
        };
        Ok((errors, map))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The batched render of a model (its batch kernel) is the sum of its
    /// terms evaluated one by one with the scalar formula, to rounding (the
    /// two differ in operation order).
    #[test]
    fn batched_render_matches_the_scalar_sum_of_terms() {
        let config = brdf_models::catalogue::ModelConfig {
            channels: 3,
            ..Default::default()
        };
        let mut m = brdf_models::catalogue::build("principled", &config).expect("model");
        let mut p = m.params().to_vec();
        p[0] = 0.7;
        p[6] = 0.3;
        m.set_params(&p).expect("params");
        let brdf: &dyn Brdf = m.as_ref();
        for light in [LightSet::sky(), LightSet::studio()] {
            let sp = ShadingPoints::judge(&light, 24);
            let mut scalar = vec![0.0; 24 * 24 * 3];
            let mut f = [0.0; 3];
            for t in sp.terms() {
                brdf.eval(&t.v_local, &t.l_local, &mut f);
                for c in 0..3 {
                    scalar[t.pixel * 3 + c] += t.weight[c] * f[c];
                }
            }
            let batched = sp.render(brdf);
            let peak = scalar.iter().fold(0.0f64, |x, y| x.max(y.abs()));
            assert!(peak > 0.0);
            for (x, y) in scalar.iter().zip(&batched.data) {
                assert!((x - y).abs() <= 1e-12 * peak, "{x} vs {y}");
            }
        }
    }
}
