//! Kurt's rendered figures as labelled PNG grids: Figure 9.1 (the
//! polynomial at degrees 1..6 beside the measured material, with
//! difference images) on the dense RGL materials, and Figure 9.2 (spheres
//! of the models fitted to the Table 9.2 materials; CUReT data are
//! scattered, so there is no measured sphere to show beside them).

use std::path::Path;

use brdf_core::{Parametric, SampleSet};
use brdf_fit::FitSummary;
use brdf_models::ModelConfig;
use nalgebra::Vector3;
use rayon::prelude::*;

use crate::StudyError;
use crate::context::models::{FitHow, build_model, fit_model};
use crate::context::{Study, progress};
use brdf_render::grid::{Grid, Tile, Tone, difference_scale, exposure_for};
use brdf_render::{Image, render_sphere};

/// Sphere size in pixels.
pub const SIZE: usize = 96;
/// Quantile of the measured sphere's values mapped to 0.8.
pub const QUANTILE: f64 = 0.95;

/// The light of every rendering (world frame; the camera looks down `-z`).
pub fn light() -> Vector3<f64> {
    Vector3::new(0.5, 0.5, 0.707).normalize()
}

/// Render a sphere of `m` with the study's light and camera.
pub fn sphere(m: &(impl brdf_core::Brdf + ?Sized)) -> Image {
    render_sphere(m, SIZE, &light(), &Vector3::z(), false)
}

/// The tone mapping stated under every grid.
pub fn tone_note(q: f64) -> String {
    format!(
        "Sphere {SIZE} px, orthographic camera along -z, directional light from (0.5, 0.5, 0.707), pixel = f(L, V) cos(theta_i). Tone mapping: linear x exposure (per row: the {:.0}th percentile of the first sphere's non-zero values -> 0.8), clamped to [0, 1], gamma 2.2. Difference tiles: |model - measured| averaged over channels, Viridis from 0 to the bar's maximum (the 99th percentile of the row's differences; larger ones saturate).",
        q * 100.0
    )
}

/// A fitted model rebuilt from its summary (the study keeps summaries).
pub fn rebuild(
    name: &str,
    config: ModelConfig,
    set: &brdf_core::SampleSet,
    how: FitHow,
    r: &FitSummary,
) -> Result<Box<dyn Parametric>, StudyError> {
    let mut m = build_model(name, config, set, how.lbox)?;
    let p: Vec<f64> = r.parameters.iter().map(|q| q.value).collect();
    m.set_params(&p)?;
    Ok(m)
}

/// Figure 9.1.
pub fn figure_9_1(study: &mut Study) -> Result<(), StudyError> {
    let Some(rgl) = study.data_dir("rgl") else {
        study.skipped.push((
            "fig_9_1".into(),
            "needs the dense RGL materials ($BRDF_DATA/rgl)".into(),
        ));
        return Ok(());
    };
    let degrees: Vec<usize> = study
        .spec
        .degrees
        .iter()
        .copied()
        .filter(|d| *d <= 6)
        .collect();
    let mut grid = Grid {
        title:
            "Kurt Fig. 9.1: the polynomial model at degree p (IRLS) beside the measured material"
                .into(),
        columns: std::iter::once("measured".to_string())
            .chain(degrees.iter().map(|d| format!("p = {d}")))
            .collect(),
        ..Grid::default()
    };
    let names: Vec<&str> = crate::sopp_tables::MATERIALS
        .iter()
        .copied()
        .filter(|n| study.spec.has_material(n) && rgl.join(format!("{n}.bsdf")).exists())
        .collect();
    let bar = progress::bar(names.len() * degrees.len(), "Fig. 9.1");
    for name in &names {
        polynomial_rows(&mut grid, &rgl, name, &degrees, &bar)?;
    }
    bar.finish_and_clear();
    grid.footer = vec![
        tone_note(QUANTILE),
        "Fits: RGB, Sopp's grid within 80 deg, every 5th node; measured = the RGL data rendered directly.".into(),
    ];
    grid.write_png(&study.path("kurt_fig_9_1.png"))?;
    study.wrote("kurt_fig_9_1.png", "Figure 9.1: polynomial p = 1..6 spheres beside the measured RGL materials, difference images with colour bars", "`rgl/*.bsdf`");
    Ok(())
}

/// One RGL material's two rows of Figure 9.1: the measured sphere and the
/// polynomial's at every degree, then their differences from the measured
/// one (on one colour scale for the row).
fn polynomial_rows(
    grid: &mut Grid,
    rgl: &Path,
    name: &str,
    degrees: &[usize],
    bar: &progress::Bar,
) -> Result<(), StudyError> {
    let (measured, set) = crate::context::rgl_material(rgl, name)?;
    let reference = sphere(&measured);
    let exposure = exposure_for(&reference, QUANTILE);
    let images = polynomial_spheres(&set, degrees, bar)?;
    let max = difference_scale(
        &images
            .iter()
            .map(|i| i.abs_difference(&reference))
            .collect::<Vec<_>>(),
    );
    let mut row = vec![Some(Tile {
        image: reference.clone(),
        tone: Tone::Exposure(exposure),
    })];
    let mut diff = vec![None];
    for img in images {
        diff.push(Some(Tile {
            image: img.abs_difference(&reference),
            tone: Tone::Difference(max),
        }));
        row.push(Some(Tile {
            image: img,
            tone: Tone::Exposure(exposure),
        }));
    }
    grid.rows.push(format!(
        "{name}\nexposure x{}",
        brdf_core::format::number(exposure, 3)
    ));
    grid.rows.push(format!("{name}\n|difference|"));
    grid.tiles.push(row);
    grid.tiles.push(diff);
    Ok(())
}

/// The spheres of the polynomial (RGB, IRLS) fitted to `set` at each of
/// `degrees`, the fits run in parallel; in the order of `degrees`.
fn polynomial_spheres(
    set: &SampleSet,
    degrees: &[usize],
    bar: &progress::Bar,
) -> Result<Vec<Image>, StudyError> {
    let fits: Vec<Result<Image, StudyError>> = degrees
        .par_iter()
        .map(|d| {
            let config = ModelConfig {
                channels: 3,
                degree: *d,
                ..ModelConfig::default()
            };
            let r = fit_model("polynomial", config, set, FitHow::default())
                .map(|(m, _)| sphere(m.as_ref()));
            bar.inc(1);
            r
        })
        .collect();
    fits.into_iter().collect::<Result<Vec<_>, _>>()
}

/// Figure 9.2.
pub fn figure_9_2(study: &mut Study) -> Result<(), StudyError> {
    let all = study.curet()?;
    let cols = crate::kurt::table_9_2::columns(&all);
    let sets: Vec<_> = cols.iter().map(|c| c.1.clone()).collect();
    let models = study.models();
    let how = study.how()?;
    let results = study.fits(&models, &sets, how)?;
    let mut grid = Grid {
        title: study.title(format!(
            "Kurt Fig. 9.2: the models fitted to the Table 9.2 materials (grey CUReT, {})",
            how.objective.name()
        )),
        columns: models.iter().map(|m| m.0.to_string()).collect(),
        ..Grid::default()
    };
    for (s, (k, set)) in cols.iter().enumerate() {
        let mut images = Vec::new();
        for (m, (_, name, config)) in models.iter().enumerate() {
            images.push(sphere(
                rebuild(name, *config, set, how, &results[m][s])?.as_ref(),
            ));
        }
        // No measured sphere (scattered data): expose by all the row's spheres.
        let joined = Image::hstack(&images.iter().collect::<Vec<_>>());
        let exposure = exposure_for(&joined, QUANTILE);
        grid.rows.push(format!(
            "{}\nexposure x{}",
            crate::kurt::common::TABLE_9_2_MATERIALS[*k].1,
            brdf_core::format::number(exposure, 3)
        ));
        grid.tiles.push(
            images
                .into_iter()
                .map(|i| {
                    Some(Tile {
                        image: i,
                        tone: Tone::Exposure(exposure),
                    })
                })
                .collect(),
        );
    }
    grid.footer = vec![
        tone_note(QUANTILE).replace("the first sphere's", "all the row's spheres'"),
        crate::kurt::common::lafortune_note(how.lbox).into(),
    ];
    let file = format!("{}.png", study.stem("kurt_fig_9_2"));
    grid.write_png(&study.path(&file))?;
    study.wrote(
        file,
        "Figure 9.2: spheres of the selected models fitted to the Table 9.2 materials",
        "`curet/abrdf.dat` #1, 55, 25, 33, 34 (grey)",
    );
    Ok(())
}
