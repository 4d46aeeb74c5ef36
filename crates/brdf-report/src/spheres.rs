//! Spheres under the judge's light sets: measured | fitted | FLIP map per
//! light (dense data: the judge's own renders, [`rows_of`], so the map is
//! the one whose mean the page reports), or the fitted sphere alone
//! (scattered data, where no image error can be formed, [`fitted_rows`]),
//! each as a PNG `data:` URI with its exposure.

use brdf_core::Brdf;
use brdf_render::ShadingPoints;
use brdf_render::judge::{LightRenders, standard_lights};
use brdf_render::tonemap::p99_exposure;
use serde::Serialize;

use crate::ReportError;
use crate::embed::png_uri;

/// The spheres of one light set.
#[derive(Clone, Debug, Serialize)]
pub struct SphereRow {
    /// light set name
    pub light: String,
    /// exposure applied to both spheres (`1 / p99` of the measured one,
    /// or of the fitted one when there is no measured sphere)
    pub exposure: f64,
    /// measured sphere (dense data only)
    pub measured: Option<String>,
    /// fitted sphere
    pub fitted: String,
    /// HDR-FLIP map, magma (dense data only)
    pub flip: Option<String>,
}

/// The spheres of the judge's renders (dense data): measured | fitted |
/// FLIP map per light set, the pictures whose FLIP the report gives
/// (the judge's film, background included), at the measured sphere's
/// exposure.
pub fn rows_of(renders: &[LightRenders]) -> Result<Vec<SphereRow>, ReportError> {
    renders
        .iter()
        .map(|r| {
            Ok(SphereRow {
                light: r.light.clone(),
                exposure: r.exposure,
                measured: Some(png_uri(&r.data, r.exposure)?),
                fitted: png_uri(&r.fit, r.exposure)?,
                flip: Some(png_uri(&r.flip.to_magma(), 1.0)?),
            })
        })
        .collect()
}

/// The spheres of `fitted` alone under [`standard_lights`] at `size` pixels
/// (scattered data: nothing measured to show beside it).
pub fn fitted_rows(fitted: &dyn Brdf, size: usize) -> Result<Vec<SphereRow>, ReportError> {
    standard_lights()
        .iter()
        .map(|light| {
            let sp = ShadingPoints::judge(light, size);
            let fit_img = sp.render(fitted);
            let exposure = p99_exposure(&fit_img, Some(&sp.mask()))?;
            Ok(SphereRow {
                light: light.name().into(),
                exposure,
                measured: None,
                fitted: png_uri(&fit_img, exposure)?,
                flip: None,
            })
        })
        .collect()
}
