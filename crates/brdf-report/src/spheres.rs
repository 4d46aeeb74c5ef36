//! Spheres under the judge's light sets: measured | fitted | FLIP map per
//! light (dense data), or the fitted sphere alone (scattered data, where no
//! image error can be formed), each as a PNG `data:` URI with its exposure.

use brdf_core::Brdf;
use brdf_render::LightSet;
use brdf_render::ShadingPoints;
use brdf_render::tonemap::p99_exposure;
use serde::Serialize;

use crate::ReportError;
use crate::embed::png_uri;

/// Pixels per side of the report's spheres.
pub const SIZE: usize = 128;

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

/// The light sets shown.
pub fn lights() -> Vec<LightSet> {
    vec![LightSet::sky(), LightSet::studio()]
}

/// The spheres of `fitted` (and `dense`, when given) under [`lights`] at
/// `size` pixels.
pub fn rows(
    dense: Option<&dyn Brdf>,
    fitted: &dyn Brdf,
    size: usize,
) -> Result<Vec<SphereRow>, ReportError> {
    lights()
        .iter()
        .map(|light| row(dense, fitted, light, size))
        .collect()
}

fn row(
    dense: Option<&dyn Brdf>,
    fitted: &dyn Brdf,
    light: &LightSet,
    size: usize,
) -> Result<SphereRow, ReportError> {
    let sp = ShadingPoints::judge(light, size);
    let mask = sp.mask();
    let fit_img = sp.render(fitted);
    let Some(dense) = dense else {
        let exposure = p99_exposure(&fit_img, Some(&mask))?;
        return Ok(SphereRow {
            light: light.name().into(),
            exposure,
            measured: None,
            fitted: png_uri(&fit_img, exposure)?,
            flip: None,
        });
    };
    let data_img = sp.render(dense);
    let exposure = p99_exposure(&data_img, Some(&mask))?;
    let flip = brdf_render::flip::hdr_flip_map(&data_img, &fit_img)?.to_magma();
    Ok(SphereRow {
        light: light.name().into(),
        exposure,
        measured: Some(png_uri(&data_img, exposure)?),
        fitted: png_uri(&fit_img, exposure)?,
        flip: Some(png_uri(&flip, 1.0)?),
    })
}
