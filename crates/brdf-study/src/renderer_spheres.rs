//! The labelled "measured vs fitted" spheres of the renderer models: one
//! row per dense RGL material, the sphere rendered from
//! the measured data first, then for each renderer model its fitted sphere
//! and the difference from the measured one, every difference tile of a row
//! on the colour bar at the row's end. Same camera, light and tone mapping
//! as Kurt's Figure 9.3 stand-in, so the two grids can be read side by side.

use std::path::Path;

use crate::StudyError;
use crate::figures::{QUANTILE, tone_note};
use brdf_render::Image;
use brdf_render::grid::{Grid, Tile, Tone, difference_scale};

/// The grid being filled, one material at a time.
pub struct RendererSpheres {
    grid: Grid,
}

impl RendererSpheres {
    /// An empty grid with a fitted and a difference column per model label.
    pub fn new(labels: &[&str]) -> Self {
        let columns = std::iter::once("measured".to_string())
            .chain(
                labels
                    .iter()
                    .flat_map(|l| [format!("{l} fitted"), format!("{l} |diff|")]),
            )
            .collect();
        RendererSpheres {
            grid: Grid {
                title: "Renderer models: measured RGL spheres against the fitted GGX, principled and glTF spheres".into(),
                columns,
                ..Grid::default()
            },
        }
    }

    /// Add a material's row: the measured sphere at `exposure` and each
    /// model's sphere (`None`: the fit failed, the tiles stay blank).
    pub fn add(&mut self, name: &str, measured: &Image, exposure: f64, fitted: &[Option<Image>]) {
        let diffs: Vec<Option<Image>> = fitted
            .iter()
            .map(|f| f.as_ref().map(|i| i.abs_difference(measured)))
            .collect();
        let max = difference_scale(&diffs.iter().flatten().cloned().collect::<Vec<_>>());
        let mut row = vec![Some(Tile {
            image: measured.clone(),
            tone: Tone::Exposure(exposure),
        })];
        for (img, diff) in fitted.iter().zip(diffs) {
            row.push(img.clone().map(|image| Tile {
                image,
                tone: Tone::Exposure(exposure),
            }));
            row.push(diff.map(|image| Tile {
                image,
                tone: Tone::Difference(max),
            }));
        }
        self.grid.rows.push(format!(
            "{name}\nexposure x{}",
            brdf_core::format::number(exposure, 3)
        ));
        self.grid.tiles.push(row);
    }

    /// Whether no material was added.
    pub fn is_empty(&self) -> bool {
        self.grid.tiles.is_empty()
    }

    /// Write the PNG, with the tone mapping and the fits stated under it.
    pub fn write(mut self, path: &Path) -> Result<(), StudyError> {
        self.grid.footer = vec![
            tone_note(QUANTILE),
            "Fits: RGB, automatic starts, Sopp's grid within 80 deg, every 5th node (as kurt_9_3.md, whose `fit` columns say which parameters ended on a bound); measured = the RGL data rendered directly; a blank tile: the fit failed.".into(),
        ];
        Ok(self.grid.write_png(path)?)
    }
}
