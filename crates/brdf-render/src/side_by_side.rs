//! The composition behind `brdf render`: a labelled sphere of measured
//! data, of a model, or both side by side with their absolute difference.
//! Lit by a standard light set on the judge's camera (the same sphere the
//! reports, the image errors and Python's `Model.render` show), or by one
//! directional light seen from `+z`; tone mapped with the exposure of the
//! first sphere stated in the image. The caller loads the data and the
//! model (this crate reads no files); this module only renders and lays
//! out.

use std::path::Path;

use brdf_core::Brdf;
use brdf_core::format::number;
use nalgebra::Vector3;

use crate::grid::{Grid, Tile, Tone, difference_scale, exposure_for};
use crate::{Image, RenderError, render_sphere};

/// One side: what to render and how to label it.
pub struct Side<'a> {
    /// The reflectance rendered.
    pub brdf: &'a dyn Brdf,
    /// Column label (`measured: NAME`, `model: NAME`).
    pub column: String,
    /// Its part of the title.
    pub title: String,
}

/// How the spheres are lit.
#[derive(Clone, Debug)]
pub enum SphereLight {
    /// A standard light set on the judge's camera
    /// ([`crate::shading::render_judge`]).
    Set(crate::LightSet),
    /// One directional light (unit, above the horizon), sphere seen from
    /// `+z`.
    Directional(Vector3<f64>),
}

impl SphereLight {
    /// Render `brdf` at `size x size` pixels.
    pub fn render(&self, brdf: &dyn Brdf, size: usize) -> Image {
        match self {
            SphereLight::Set(lights) => crate::shading::render_judge(brdf, lights, size),
            SphereLight::Directional(l) => render_sphere(brdf, size, l, &Vector3::z(), false),
        }
    }

    /// The footer's words for the light and camera.
    fn describe(&self, label: &str, size: usize) -> String {
        match self {
            SphereLight::Set(_) => format!(
                "Sphere {size} px on the judge's camera under the `{label}` light set (as the reports, the image errors and Python's Model.render), pixel = radiance."
            ),
            SphereLight::Directional(_) => format!(
                "Sphere {size} px seen from +z, directional light at (theta, phi) = ({label}) deg, pixel = f(L, V) cos(theta_i)."
            ),
        }
    }
}

/// The picture: measured data and/or a model under one light.
pub struct SideBySide<'a> {
    /// Measured data (first column when given).
    pub measured: Option<Side<'a>>,
    /// A model (beside the data when both are given).
    pub model: Option<Side<'a>>,
    /// How the spheres are lit.
    pub light: SphereLight,
    /// The light as the user gave it (a set's name or `THETA,PHI` in
    /// degrees), for labels.
    pub light_label: String,
    /// Sphere size in pixels.
    pub size: usize,
}

impl SideBySide<'_> {
    /// The labelled grid: one row, a sphere per side and, with both, the
    /// difference tile.
    pub fn grid(&self) -> Result<Grid, RenderError> {
        let sides: Vec<&Side> = self.measured.iter().chain(self.model.iter()).collect();
        if sides.is_empty() {
            return Err(RenderError::Invalid(
                "give --model FILE, --data PATH or both".into(),
            ));
        }
        let tiles: Vec<Image> = sides
            .iter()
            .map(|s| self.light.render(s.brdf, self.size))
            .collect();
        let exposure = exposure_for(&tiles[0], 0.95);
        let mut columns: Vec<String> = sides.iter().map(|s| s.column.clone()).collect();
        let title: Vec<&str> = sides.iter().map(|s| s.title.as_str()).collect();
        let mut row: Vec<Option<Tile>> = tiles
            .iter()
            .map(|i| {
                Some(Tile {
                    image: i.clone(),
                    tone: Tone::Exposure(exposure),
                })
            })
            .collect();
        if tiles.len() == 2 {
            let d = tiles[0].abs_difference(&tiles[1]);
            let max = difference_scale(std::slice::from_ref(&d));
            row.push(Some(Tile {
                image: d,
                tone: Tone::Difference(max),
            }));
            columns.push("|model - measured|".into());
        }
        Ok(Grid {
            title: title.join(" vs "),
            columns,
            rows: vec![format!("light {}\nexposure x{}", self.light_label, number(exposure, 3))],
            tiles: vec![row],
            footer: vec![
                self.light.describe(&self.light_label, self.size),
                "Tone mapping: linear x exposure (95th percentile of the first sphere's non-zero values -> 0.8), clamped, gamma 2.2; difference in Viridis from 0 to the bar's maximum (99th percentile of the differences; larger ones saturate).".into(),
            ],
        })
    }

    /// Render and write the PNG.
    pub fn write_png(&self, path: &Path) -> Result<(), RenderError> {
        self.grid()?.write_png(path)
    }
}
