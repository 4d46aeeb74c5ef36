//! The judge: the data and a fit rendered on the judge sphere under the
//! standard light sets (`sky`: clear sky and sun; `studio`: a dim surround
//! and a square key light) and compared ([`crate::image_error`]).
//!
//! A lookdev user judges a fit by its render; for data that can be
//! evaluated at any direction pair (RGL `.bsdf`, MERL `.binary`) the judge
//! gives that verdict in numbers. The shading terms are computed once per
//! judge and shared ([`Judge::rendering`]); the data are rendered once
//! ([`Judge::with_data`], [`crate::reference`]) for every fit compared.

use std::sync::Arc;

use brdf_core::Brdf;

use crate::by_size::BySize;
use crate::flip::FlipMap;
use crate::image_error::{DataColourPlane, ImageError};
use crate::reference::Reference;
use crate::{Image, LightSet, RenderError, ShadingPoints};

/// Image size of the image errors in reports (the judge's film).
pub const REPORT_SIZE: usize = 128;
/// Image size of the image objective and of the candidate ranking.
pub const FIT_SIZE: usize = 32;

/// The standard light sets of reports and of the image objective.
pub fn standard_lights() -> Vec<LightSet> {
    vec![LightSet::sky(), LightSet::studio()]
}

/// Renders data and fits under the standard light sets and compares them
/// (the data rendered once, [`crate::reference`]).
pub struct Judge {
    size: usize,
    points: Arc<Vec<(LightSet, ShadingPoints)>>,
    /// The data's renders, one per light set, when made once
    /// ([`Judge::with_data`]).
    reference: Vec<Reference>,
}

impl Judge {
    /// The judge at `size x size` pixels (backgrounds shown, as the
    /// reference renderer's images; the terms are computed once and
    /// shared with every judge of the same size alive at the time,
    /// [`BySize`]).
    pub fn new(size: usize) -> Self {
        // The terms depend on the size alone: judges alive at once share
        // them (a `select` makes one per candidate).
        static TERMS: BySize<Vec<(LightSet, ShadingPoints)>> = BySize::new();
        let made: Result<_, std::convert::Infallible> = TERMS.get_or_make(size, || {
            Ok(standard_lights()
                .into_iter()
                .map(|l| {
                    let sp = ShadingPoints::judge_with_background(&l, size);
                    (l, sp)
                })
                .collect())
        });
        let Ok(points) = made;
        Judge {
            size,
            points,
            reference: Vec::new(),
        }
    }

    /// Pixels per side of the judge's images.
    pub fn size(&self) -> usize {
        self.size
    }

    /// Light sets the judge renders under.
    pub fn lights(&self) -> usize {
        self.points.len()
    }

    /// The judge with `data` rendered once, for [`Judge::fit_errors`] of
    /// many fits of the same data.
    pub fn with_data(size: usize, data: &dyn Brdf) -> Result<Self, RenderError> {
        Judge::new(size).rendering(data)
    }

    /// This judge's terms (shared, not copied) with `data` rendered on
    /// them: one set of terms serves every material of a batch.
    pub fn rendering(&self, data: &dyn Brdf) -> Result<Self, RenderError> {
        let reference = self
            .points
            .iter()
            .map(|(light, sp)| Reference::new(light, sp, data))
            .collect::<Result<_, _>>()?;
        Ok(Judge {
            size: self.size,
            points: Arc::clone(&self.points),
            reference,
        })
    }

    /// This judge's terms with the data's renders made before by a judge
    /// of the same size (kept in a cache: [`Judge::data_renders`]), one per
    /// light set in order; refused when one does not fit the film.
    pub fn rendering_from(&self, renders: Vec<Image>) -> Result<Self, RenderError> {
        if renders.len() != self.points.len() {
            return Err(RenderError::Invalid(format!(
                "{} renders of the data given for {} light sets",
                renders.len(),
                self.points.len()
            )));
        }
        let reference = self
            .points
            .iter()
            .zip(renders)
            .map(|((light, sp), image)| Reference::from_image(light, sp, image))
            .collect::<Result<_, _>>()?;
        Ok(Judge {
            size: self.size,
            points: Arc::clone(&self.points),
            reference,
        })
    }

    /// The data's renders this judge holds, one per light set (none
    /// before [`Judge::rendering`]): what a cache keeps.
    pub fn data_renders(&self) -> Vec<&Image> {
        self.reference.iter().map(Reference::image).collect()
    }

    /// The image errors of `fit` against `data`.
    pub fn errors(&self, data: &dyn Brdf, fit: &dyn Brdf) -> Result<ImageError, RenderError> {
        let refs = self
            .points
            .iter()
            .map(|(light, sp)| Reference::new(light, sp, data))
            .collect::<Result<Vec<_>, _>>()?;
        self.errors_against(&refs, fit)
    }

    /// The image errors of `fit` against the data of [`Judge::with_data`].
    pub fn fit_errors(&self, fit: &dyn Brdf) -> Result<ImageError, RenderError> {
        self.errors_against(&self.reference, fit)
    }

    /// The image errors of `fit` against the data of [`Judge::with_data`]
    /// and the renders they compare, one per light set: what a report
    /// shows beside its numbers (the fit rendered once for both).
    pub fn fit_renders(
        &self,
        fit: &dyn Brdf,
    ) -> Result<(ImageError, Vec<LightRenders>), RenderError> {
        let (errors, compared) = self.compare(&self.reference, fit)?;
        let renders = self
            .points
            .iter()
            .zip(&self.reference)
            .zip(compared)
            .map(|(((light, _), r), (fit, flip))| LightRenders {
                light: light.name().to_string(),
                data: r.image().clone(),
                fit,
                flip,
                exposure: r.exposure(),
            })
            .collect();
        Ok((errors, renders))
    }

    /// How far the data of [`Judge::with_data`] lie from every plane of
    /// white and one colour, under the first white light set; `None`
    /// without data renders, without a white set or for black data.
    pub fn data_colour_plane(&self) -> Option<DataColourPlane> {
        self.colour_plane_of(&self.reference)
    }

    fn colour_plane_of(&self, refs: &[Reference]) -> Option<DataColourPlane> {
        self.points
            .iter()
            .zip(refs)
            .find(|((light, _), _)| light.is_white())
            .and_then(|((light, _), r)| {
                r.colour_plane().map(|c| DataColourPlane {
                    light: light.name().to_string(),
                    colour: c.colour,
                    outside: c.outside,
                })
            })
    }

    fn errors_against(
        &self,
        refs: &[Reference],
        fit: &dyn Brdf,
    ) -> Result<ImageError, RenderError> {
        Ok(self.compare(refs, fit)?.0)
    }

    /// The image errors of `fit` against the data's `refs`, and per light
    /// set the fit's render and its FLIP map.
    fn compare(
        &self,
        refs: &[Reference],
        fit: &dyn Brdf,
    ) -> Result<(ImageError, Vec<(Image, FlipMap)>), RenderError> {
        if refs.len() != self.points.len() {
            return Err(RenderError::Invalid(
                "the judge has no renders of the data: build it with Judge::with_data".into(),
            ));
        }
        let mut lights = Vec::with_capacity(self.points.len());
        let mut compared = Vec::with_capacity(self.points.len());
        for ((_, sp), r) in self.points.iter().zip(refs) {
            let t = sp.render(fit);
            let (e, map) = r.compare(&t)?;
            compared.push((t, map));
            lights.push(e);
        }
        let colour_plane = self.colour_plane_of(refs);
        let errors = ImageError {
            size: self.size,
            lights,
            colour_plane,
        };
        Ok((errors, compared))
    }
}

/// A light set's renders of the data and of a fit on the judge's film
/// (background included), as [`Judge`] compares them.
#[derive(Clone, Debug)]
pub struct LightRenders {
    /// Light set name.
    pub light: String,
    /// The data's render.
    pub data: Image,
    /// The fit's render.
    pub fit: Image,
    /// The HDR-FLIP map between them (its mean is the light's FLIP).
    pub flip: FlipMap,
    /// The exposure `1 / p99` of the data's sphere pixels.
    pub exposure: f64,
}
