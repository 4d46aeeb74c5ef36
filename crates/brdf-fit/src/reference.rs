//! The data's render made once, and the image errors of fits against it.
//!
//! The data's render under a light set does not depend on the fit:
//! [`Reference`] keeps it (with its sphere mask, exposure and mean colour),
//! so ranking candidates renders the data once, not once per candidate.
//! Renders are `brdf_render::ShadingPoints::render`, a row of terms per
//! batch evaluation (`brdf_render::batch`).

use brdf_core::Brdf;
use brdf_render::colour::{delta_e_mean_colours, mean_colour};
use brdf_render::colour_plane::{ColourPlane, colour_plane};
use brdf_render::compare::ImageErrors;
use brdf_render::flip::{FlipMap, hdr_flip_map};
use brdf_render::psnr::psnr;
use brdf_render::tonemap::p99_exposure;
use brdf_render::{Image, RenderError, ShadingPoints};

/// The data's render under one light set, with what every comparison
/// against it needs (sphere mask, exposure, mean colour).
pub struct Reference {
    image: Image,
    mask: Vec<bool>,
    exposure: f64,
    mean_colour: [f64; 3],
    colour_plane: Option<ColourPlane>,
}

impl Reference {
    /// Render `data` on `sp`.
    pub fn new(sp: &ShadingPoints, data: &dyn Brdf) -> Result<Self, RenderError> {
        let image: Image = sp.render(data);
        let mask = sp.mask();
        let exposure = p99_exposure(&image, Some(&mask))?;
        let mean_colour = mean_colour(&image, &mask);
        let colour_plane = colour_plane(&image, &mask);
        Ok(Reference {
            image,
            mask,
            exposure,
            mean_colour,
            colour_plane,
        })
    }

    /// The plane of white and one colour closest to the data's sphere
    /// colours, and how much of them lies off it
    /// ([`brdf_render::colour_plane`]; a bound on models with one base
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

    /// The image errors of `t`, a fit rendered on the terms this reference
    /// was rendered on (as `brdf_render::compare::compare_with`), and the
    /// HDR-FLIP map whose mean is their FLIP (a report shows it beside the
    /// number).
    pub fn compare(&self, t: &Image) -> Result<(ImageErrors, FlipMap), RenderError> {
        let map = hdr_flip_map(&self.image, t)?;
        let mean_colour_test = mean_colour(t, &self.mask);
        let errors = ImageErrors {
            flip: map.mean(),
            psnr: psnr(&self.image, t, self.exposure)?,
            delta_e_mean_colour: delta_e_mean_colours(self.mean_colour, mean_colour_test),
            mean_colour_ref: self.mean_colour,
            mean_colour_test,
            exposure: self.exposure,
        };
        Ok((errors, map))
    }
}

#[cfg(test)]
mod tests {
    use brdf_render::LightSet;

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
