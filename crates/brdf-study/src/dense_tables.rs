//! Kurt's Table 9.3 stand-in and his renderings (Figures 9.3, 9.6) on the
//! dense measured materials available here: the selected models of Table
//! 9.2 fitted (RGB, automatic starts) to each RGL material (resampled onto
//! Sopp's grid, 80-degree limit, cell weights, every 5th node) and to each
//! Cornell paint (its scattered samples); L2 error for all, and for the RGL
//! materials the PSNR of a sphere rendered with the fit against the sphere
//! rendered with the measured data (Cornell data are scattered and cannot
//! be rendered without an interpolation the project does not invent). The
//! renderings are a labelled grid: measured and every model, and their
//! difference images with a colour bar. The reciprocity check of Fig. 9.6:
//! the polynomial fit rendered with `L` and `V` swapped must give the same
//! image. The renderer models (GGX, principled, glTF) get the same metrics
//! in columns after the nine, with how each fit ended, and their own grid
//! of measured against fitted spheres ([`crate::renderer_spheres`]).

use std::path::Path;

use brdf_core::SampleSet;
use brdf_core::metrics::psnr;
use brdf_fit::FitSummary;
use brdf_models::ModelConfig;
use nalgebra::Vector3;
use rayon::prelude::*;

use crate::StudyError;
use crate::context::models::{FitHow, fit_model};
use crate::context::{Study, progress, rgl_material};
use crate::figures::{QUANTILE, SIZE, light, sphere, tone_note};
use crate::renderer_fits::{Model, fit_sets, status};
use crate::renderer_spheres::RendererSpheres;
use crate::report::{Cell, Table};
use brdf_render::grid::{Grid, Tile, Tone, difference_scale, exposure_for};
use brdf_render::{Image, render_sphere};

type Fitted = (Box<dyn brdf_core::Parametric>, FitSummary);

/// One row of a grid's tiles (`None`: an empty cell).
type Tiles = Vec<Option<Tile>>;

fn fit_all(
    models: &[(&'static str, &'static str, ModelConfig)],
    set: &SampleSet,
    how: FitHow,
    what: &str,
) -> Result<Vec<Fitted>, StudyError> {
    let bar = progress::bar(models.len(), what);
    let r: Vec<Result<Fitted, StudyError>> = models
        .par_iter()
        .map(|(_, name, config)| {
            let r = fit_model(
                name,
                ModelConfig {
                    channels: 3,
                    ..*config
                },
                set,
                how,
            );
            bar.inc(1);
            r
        })
        .collect();
    bar.finish_and_clear();
    r.into_iter().collect()
}

/// Run the part.
pub fn write(study: &mut Study) -> Result<(), StudyError> {
    let models = study.models();
    let renderers = study.renderer_models();
    let how = FitHow {
        lbox: study.spec.lafortune_box,
        ..FitHow::default()
    };
    let mut dense = Dense::new(&models, &renderers, how);
    if let Some(rgl_dir) = study.data_dir("rgl") {
        for name in crate::sopp_tables::MATERIALS {
            if !study.spec.has_material(name) || !rgl_dir.join(format!("{name}.bsdf")).exists() {
                continue;
            }
            dense.rgl(&rgl_dir, name)?;
        }
    }
    if let Some(cornell) = study.data_dir("cornell") {
        for name in ["cayman", "mystique", "krylon_blue", "acryl_blue"] {
            let path = cornell.join(format!("{name}.brdf"));
            if !study.spec.has_material(&format!("cornell {name}")) || !path.exists() {
                continue;
            }
            dense.cornell(study, &path, name)?;
        }
    }
    if dense.table.rows.is_empty() {
        study.skipped.push((
            "kurt_9_3".into(),
            "needs the dense materials ($BRDF_DATA/rgl, $BRDF_DATA/cornell)".into(),
        ));
        return Ok(());
    }
    dense.note();
    dense.write_files(study)
}

/// The part's state, built up one material at a time: the table, the grid
/// of Kurt's models' spheres, the renderer models' spheres, and the largest
/// reciprocity difference seen (said in the note once every material ran).
struct Dense<'a> {
    /// Kurt's models (those selected).
    models: &'a [Model],
    /// The renderer models (those selected), in the columns after Kurt's.
    renderers: &'a [Model],
    /// How every model is fitted (Ngan's L2, the spec's Lafortune box).
    how: FitHow,
    /// Table 9.3: a row per material.
    table: Table,
    /// Fig. 9.3: two rows per RGL material (spheres, differences).
    grid: Grid,
    /// The renderer models' spheres beside the measured ones.
    spheres: RendererSpheres,
    /// The largest difference between a polynomial sphere and the one
    /// rendered with `L` and `V` swapped (Fig. 9.6).
    reciprocity_max: f64,
}

impl<'a> Dense<'a> {
    /// The empty table (a column pair per model of Kurt's, a triple per
    /// renderer model) and grids.
    fn new(models: &'a [Model], renderers: &'a [Model], how: FitHow) -> Self {
        let mut hdr = vec!["material".to_string()];
        for (label, _, _) in models {
            hdr.push(format!("{label} L2"));
            hdr.push(format!("{label} PSNR (dB)"));
        }
        for (label, _, _) in renderers {
            hdr.push(format!("{label} L2"));
            hdr.push(format!("{label} PSNR (dB)"));
            hdr.push(format!("{label} fit"));
        }
        let hdr_ref: Vec<&str> = hdr.iter().map(String::as_str).collect();
        let table = Table::new(
            "Kurt Table 9.3 stand-in: dense materials, L2 error and rendering PSNR",
            &hdr_ref,
        );
        let grid = Grid {
            title: "Kurt Fig. 9.3 stand-in: measured RGL materials and the fitted models".into(),
            columns: std::iter::once("measured".to_string())
                .chain(models.iter().map(|m| m.0.to_string()))
                .collect(),
            ..Grid::default()
        };
        let labels: Vec<&str> = renderers.iter().map(|m| m.0).collect();
        Dense {
            models,
            renderers,
            how,
            table,
            grid,
            spheres: RendererSpheres::new(&labels),
            reciprocity_max: 0.0,
        }
    }

    /// One RGL material: every model fitted and rendered against the
    /// sphere of the measured data; its row of the table and its two rows
    /// of the grid (spheres, differences).
    fn rgl(&mut self, rgl_dir: &Path, name: &str) -> Result<(), StudyError> {
        let (rgl, set) = rgl_material(rgl_dir, name)?;
        let reference = sphere(&rgl);
        let exposure = exposure_for(&reference, QUANTILE);
        let fits = fit_all(self.models, &set, self.how, name)?;
        let mut row = vec![Cell::Text(name.to_string())];
        let (tiles, diffs) = self.kurt_rgl(&fits, &reference, exposure, &mut row)?;
        row.extend(renderer_rgl(
            self.renderers,
            &set,
            self.how,
            name,
            &reference,
            exposure,
            &mut self.spheres,
        )?);
        self.table.rows.push(row);
        self.grid.rows.push(format!(
            "{name}\nexposure x{}",
            brdf_core::format::number(exposure, 3)
        ));
        self.grid.rows.push(format!("{name}\n|difference|"));
        self.grid.tiles.push(tiles);
        self.grid.tiles.push(diffs);
        Ok(())
    }

    /// Kurt's models fitted to one RGL material: their cells (L2, PSNR)
    /// pushed onto `row`; their tiles after the measured one and their
    /// difference tiles (on one colour scale for the row). The polynomial
    /// is rendered once more with `L` and `V` swapped for Fig. 9.6's
    /// reciprocity check.
    fn kurt_rgl(
        &mut self,
        fits: &[Fitted],
        reference: &Image,
        exposure: f64,
        row: &mut Vec<Cell>,
    ) -> Result<(Tiles, Tiles), StudyError> {
        let peak = reference.peak().max(1e-12);
        let mut tiles = vec![Some(Tile {
            image: reference.clone(),
            tone: Tone::Exposure(exposure),
        })];
        let mut diffs = vec![None];
        let images: Vec<Image> = fits.iter().map(|(m, _)| sphere(m.as_ref())).collect();
        let max = difference_scale(
            &images
                .iter()
                .map(|i| i.abs_difference(reference))
                .collect::<Vec<_>>(),
        );
        for ((label, _, _), ((m, r), img)) in self.models.iter().zip(fits.iter().zip(images)) {
            row.push(Cell::Num(r.ngan_l2, 4));
            row.push(Cell::Num(psnr(&reference.data, &img.data, peak)?, 4));
            if *label == "Polynomial (p = 7)" {
                let swapped = render_sphere(m.as_ref(), SIZE, &light(), &Vector3::z(), true);
                self.reciprocity_max = self
                    .reciprocity_max
                    .max(img.abs_difference(&swapped).peak());
            }
            diffs.push(Some(Tile {
                image: img.abs_difference(reference),
                tone: Tone::Difference(max),
            }));
            tiles.push(Some(Tile {
                image: img,
                tone: Tone::Exposure(exposure),
            }));
        }
        Ok((tiles, diffs))
    }

    /// One Cornell paint (the file at `path`): every model fitted, L2 only
    /// (scattered samples cannot be rendered as measured).
    fn cornell(&mut self, study: &Study, path: &Path, name: &str) -> Result<(), StudyError> {
        let set = brdf_io::cornell::read(path, brdf_io::cornell::CornellColour::Rgb)?;
        let (set, _) = set.filter_angle_limit(80f64.to_radians());
        let mut row = vec![Cell::Text(format!("cornell {name}"))];
        for (_, r) in fit_all(self.models, &set, self.how, name)? {
            row.push(Cell::Num(r.ngan_l2, 4));
            row.push(Cell::Text("n/a (scattered)".into()));
        }
        for f in fit_sets(
            self.renderers,
            std::slice::from_ref(&set),
            3,
            self.how,
            name,
        )
        .into_iter()
        .flatten()
        {
            row.push(
                f.as_ref()
                    .map_or(Cell::Empty, |(_, r)| Cell::Num(r.ngan_l2, 4)),
            );
            row.push(Cell::Text("n/a (scattered)".into()));
            row.push(Cell::Text(study.relative(&status(&f))));
        }
        self.table.rows.push(row);
        Ok(())
    }

    /// The table's note, written once every material ran: the reciprocity
    /// result needs them all, and the comparisons of the renderer and new
    /// models are read off the finished rows.
    fn note(&mut self) {
        let reciprocity_max = self.reciprocity_max;
        let t = &mut self.table;
        t.note = format!(
            "Kurt used five MERL materials (not available); the RGL materials and Cornell paints stand in. RGB fits, automatic starts; RGL materials sampled on Sopp's grid (every 5th node within 80 deg). {} PSNR against the sphere rendered from the measured RGL data (peak = its largest value). Renderings: `kurt_fig_9_3.png`. Fig. 9.6 reciprocity check: the polynomial fits rendered with L and V swapped differ from the unswapped renderings by at most {reciprocity_max:.3e}. {} Generated by `brdf reproduce`.",
            tone_note(QUANTILE),
            crate::kurt::common::lafortune_note(self.how.lbox)
        );
        if self.renderers.is_empty() {
            return;
        }
        t.note.push_str(RENDERER_NOTE);
        let new: Vec<&str> = self
            .renderers
            .iter()
            .filter(|m| crate::new_models::NEW_MODELS.contains(&m.1))
            .map(|m| m.0)
            .collect();
        let renderer: Vec<&str> = self
            .renderers
            .iter()
            .map(|m| m.0)
            .filter(|l| !new.contains(l))
            .collect();
        if !self.models.is_empty() {
            t.note.push_str(&lowest_l2(
                t,
                &renderer,
                &new,
                "a renderer model against the lowest of Kurt's models: the renderer model's",
            ));
        }
        if !new.is_empty() {
            t.note.push_str(&lowest_l2(
                t,
                &new,
                &[],
                "a new model against the lowest of Kurt's and the renderer models: the new model's",
            ));
        }
    }

    /// Write the table and, when there is anything in them, the two grids
    /// of spheres; each listed in the README.
    fn write_files(self, study: &mut Study) -> Result<(), StudyError> {
        let Dense {
            models,
            table: t,
            mut grid,
            spheres,
            ..
        } = self;
        t.write(&study.out, "kurt_9_3")?;
        study.wrote("kurt_9_3.{csv,md}", "Table 9.3 stand-in: L2 and rendering PSNR of Kurt's models and the renderer models (GGX, principled, glTF; how each fit ended) on the RGL materials and Cornell paints; Fig. 9.6 reciprocity check", "`rgl/*.bsdf`, `cornell/*.brdf` (RGB)");
        if !spheres.is_empty() {
            spheres.write(&study.path("kurt_fig_9_3_renderer.png"))?;
            study.wrote("kurt_fig_9_3_renderer.png", "Renderer models: measured RGL spheres beside the fitted GGX, principled and glTF spheres and their differences with colour bars", "`rgl/*.bsdf`");
        }
        if !grid.tiles.is_empty() && !models.is_empty() {
            grid.footer = vec![tone_note(QUANTILE)];
            grid.write_png(&study.path("kurt_fig_9_3.png"))?;
            study.wrote("kurt_fig_9_3.png", "Figure 9.3 stand-in: measured RGL spheres, every model's sphere, difference images with colour bars", "`rgl/*.bsdf`");
        }
        Ok(())
    }
}

/// The note on the renderer models' columns.
const RENDERER_NOTE: &str = " Renderer models after the nine, fitted by the same pipeline in the renderers' own boxes: GGX (`ggx`: height-correlated Smith, Schlick Fresnel), GGX separable (`ggx-separable`: separable Smith, as Mitsuba 3), Principled (Disney, as Mitsuba 3's `principled`), glTF (2.0 metallic-roughness) and glTF + KHR (`gltf-ext`: with KHR_materials_ior, _specular, _clearcoat). Their `fit` column says whether the fit converged, which parameters it left on a bound, or that it failed (its other cells then empty). Then the fitted-data models, fitted the same way (Ngan's L2): ABC and ABC smooth (Löw et al. 2012), STD (Ribardière et al. 2017), SGD (Bagher et al. 2012, every parameter per channel) and Dupuy (Dupuy et al. 2015: the normal distribution extracted from the back-scattering samples, which the Cornell paints' scattered samples lack: its cells there say so). Their spheres: `kurt_fig_9_3_renderer.png`.";

/// The renderer models on one RGL material: fitted, rendered, added to the
/// grid; their cells (L2, PSNR, how the fit ended).
fn renderer_rgl(
    renderers: &[crate::renderer_fits::Model],
    set: &SampleSet,
    how: FitHow,
    name: &str,
    reference: &Image,
    exposure: f64,
    spheres: &mut RendererSpheres,
) -> Result<Vec<Cell>, StudyError> {
    if renderers.is_empty() {
        return Ok(Vec::new());
    }
    let peak = reference.peak().max(1e-12);
    let fits: Vec<_> = fit_sets(renderers, std::slice::from_ref(set), 3, how, name)
        .into_iter()
        .flatten()
        .collect();
    let images: Vec<Option<Image>> = fits
        .iter()
        .map(|f| f.as_ref().ok().map(|(m, _)| sphere(m.as_ref())))
        .collect();
    let mut cells = Vec::new();
    for (f, img) in fits.iter().zip(&images) {
        cells.push(
            f.as_ref()
                .map_or(Cell::Empty, |(_, r)| Cell::Num(r.ngan_l2, 4)),
        );
        cells.push(match img {
            Some(i) => Cell::Num(psnr(&reference.data, &i.data, peak)?, 4),
            None => Cell::Empty,
        });
        cells.push(Cell::Text(status(f)));
    }
    spheres.add(name, reference, exposure, &images);
    Ok(cells)
}

/// A comparison the added columns are for, read off the table: per
/// material, the lowest L2 of the models labelled `group` against the
/// lowest of the others, the `skip` labels left out; `what` names the
/// comparison in the sentence.
fn lowest_l2(t: &Table, group: &[&str], skip: &[&str], what: &str) -> String {
    let mut wins = 0;
    let mut each = Vec::new();
    for row in &t.rows {
        let (mut ours, mut theirs) = (None::<(&str, f64)>, None::<(&str, f64)>);
        for (col, cell) in t.columns.iter().zip(row) {
            let (Some(label), Cell::Num(v, _)) = (col.strip_suffix(" L2"), cell) else {
                continue;
            };
            if skip.contains(&label) {
                continue;
            }
            let best = if group.contains(&label) {
                &mut ours
            } else {
                &mut theirs
            };
            if best.is_none_or(|(_, b)| *v < b) {
                *best = Some((label, *v));
            }
        }
        let (Some(Cell::Text(name)), Some((rl, rv)), Some((tl, tv))) = (row.first(), ours, theirs)
        else {
            continue;
        };
        wins += usize::from(rv < tv);
        each.push(format!(
            "{name} {rl} {} against {tl} {}",
            brdf_core::format::number(rv, 4),
            brdf_core::format::number(tv, 4)
        ));
    }
    format!(
        " Lowest L2 of {what} is lower on {wins} of {} materials ({}).",
        each.len(),
        each.join("; ")
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lowest_l2_compares_the_best_of_each_group_per_material() {
        let mut t = Table::new(
            "t",
            &[
                "material",
                "Ward L2",
                "Ward PSNR (dB)",
                "GGX L2",
                "GGX fit",
                "glTF L2",
            ],
        );
        let num = |v| Cell::Num(v, 4);
        let fit = || Cell::Text("converged".into());
        t.rows = vec![
            // Best renderer model glTF (0.02) beats Ward (0.03).
            vec![
                Cell::Text("a".into()),
                num(0.03),
                num(30.0),
                num(0.05),
                fit(),
                num(0.02),
            ],
            // Ward (0.01) beats GGX (0.04); glTF failed (empty).
            vec![
                Cell::Text("b".into()),
                num(0.01),
                num(31.0),
                num(0.04),
                fit(),
                Cell::Empty,
            ],
        ];
        assert_eq!(
            lowest_l2(
                &t,
                &["GGX", "glTF"],
                &[],
                "a renderer model against the lowest of Kurt's models: the renderer model's"
            ),
            " Lowest L2 of a renderer model against the lowest of Kurt's models: the renderer model's is lower on 1 of 2 materials (a glTF 0.02000 against Ward 0.03000; b GGX 0.04000 against Ward 0.01000)."
        );
    }
}
