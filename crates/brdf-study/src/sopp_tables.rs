//! Sopp (2017) reproduced on the dense materials available here (the RGL
//! vinyl wrap films, wall paint and paper resampled onto his goniometric
//! grid): his two-stage Levenberg-Marquardt fit of the Ashikhmin-Shirley
//! paint shader without Fresnel, with and without solid-angle weighting, at
//! the angle limits 75 and 45 degrees and from his start exponents 25, 50
//! and 250; the variant with Fresnel started from that result; the
//! clear-coat split (data divided by `1 - Fr`, eta 1.5); and the project's
//! automatic fit for comparison. Written in the layout of his Appendix
//! A.8/A.9, with his preview strips (measured | model | difference) for
//! each material.

use std::path::Path;

use brdf_core::{Parametric, SampleSet};
use brdf_io::sopp_grid::{CAM_PHIS, CAM_THETAS, LIGHTS, SoppGrid};
use brdf_models::{ModelConfig, build};

use crate::StudyError;
use brdf_fit::pipeline::{fit, fit_sopp};
use brdf_fit::{FitOptions, FitSummary, Objective};
use rayon::prelude::*;

use crate::context::{Study, Written, progress};
use crate::report::{Cell, Table};
use brdf_render::Image;
use brdf_render::grid::{Grid, Tile, Tone, difference_scale, exposure_for};

/// The metric of Sopp's fits, for the README.
const SOPP_METRIC: &str = "Sopp's error (fitted weighted and unweighted; reported unweighted)";

/// The RGL materials of the stand-in.
pub const MATERIALS: [&str; 5] = [
    "cc_ibiza_sunset_rgb",
    "cc_iris_purple_gem_rgb",
    "vch_golden_yellow_rgb",
    "colodur_napoli_4f_rgb",
    "paper_white_rgb",
];

fn value(r: &FitSummary, name: &str) -> f64 {
    r.parameters
        .iter()
        .find(|p| p.name == name)
        .map_or(f64::NAN, |p| p.value)
}

fn rgb(r: &FitSummary, prefix: &str) -> [f64; 3] {
    [0, 1, 2].map(|c| value(r, &format!("{prefix}_{}", ["r", "g", "b"][c])))
}

/// Sopp's stage-1 start: the model's defaults with the exponent set.
fn grey_start(name: &str, n: f64) -> Result<Box<dyn Parametric>, StudyError> {
    let mut g = build(name, &ModelConfig::default())?;
    let mut p = g.params().to_vec();
    let specs = g.param_specs().to_vec();
    for (k, s) in specs.iter().enumerate() {
        if s.name == "ns" || s.name == "n" {
            p[k] = n;
        }
    }
    g.set_params(&p)?;
    Ok(g)
}

fn sopp_error(data: &SampleSet, m: &dyn Parametric) -> Result<f64, StudyError> {
    let mut fitted = vec![0.0; data.len() * 3];
    m.eval_batch_at(m.params(), data.pairs(), &mut fitted);
    // Sopp's reported error is computed without the weights.
    Ok(Objective::Sopp { weighted: false }
        .error(data, &fitted)?
        .total)
}

/// The preview: one strip per light angle (rows: camera polar angle,
/// columns: camera azimuth mirrored to the full hemisphere), measured |
/// model | difference side by side.
pub fn preview(measured: &SoppGrid, model: &SoppGrid) -> Image {
    let w = 2 * CAM_PHIS - 1;
    let h = LIGHTS * CAM_THETAS;
    let strip = |g: &SoppGrid| {
        let mut data = vec![0.0; w * h * 3];
        for il in 0..LIGHTS {
            for it in 0..CAM_THETAS {
                for col in 0..w {
                    // Column CAM_PHIS - 1 is phi = 0; mirrored either side.
                    let ip = (col as isize - (CAM_PHIS as isize - 1)).unsigned_abs();
                    let v = g.rgb(il, it, ip);
                    let px = ((il * CAM_THETAS + it) * w + col) * 3;
                    data[px..px + 3].copy_from_slice(&v);
                }
            }
        }
        Image {
            width: w,
            height: h,
            channels: 3,
            data,
        }
    };
    let a = strip(measured);
    let b = strip(model);
    let d = a.abs_difference(&b);
    Image::hstack(&[&a, &b, &d])
}

/// The measured and model strips of [`preview`], separately.
pub fn strips(measured: &SoppGrid, model: &SoppGrid) -> (Image, Image) {
    let full = preview(measured, model);
    let w = full.width / 3;
    let cut = |k: usize| Image {
        width: w,
        height: full.height,
        channels: 3,
        data: (0..full.height)
            .flat_map(|y| {
                let o = (y * full.width + k * w) * 3;
                full.data[o..o + 3 * w].to_vec()
            })
            .collect(),
    };
    (cut(0), cut(1))
}

/// One material's rows of the table and its preview strips (measured, model).
type MaterialRows = (Vec<Vec<Cell>>, Option<(Image, Image)>);

/// One material's rows of the table and its preview (measured, model).
fn material(rgl_dir: &Path, name: &str) -> Result<MaterialRows, StudyError> {
    let path = rgl_dir.join(format!("{name}.bsdf"));
    let rgl = brdf_io::rgl::Rgl::read(&path)?;
    let grid = SoppGrid::resample(&rgl);
    let mut fits = MaterialFits {
        name,
        rows: Vec::new(),
        best: None,
    };
    for weighted in [true, false] {
        for limit in [75.0, 45.0] {
            let data = grid.to_samples(name, limit, weighted);
            let opts = FitOptions {
                objective: Objective::Sopp { weighted },
                ..FitOptions::default()
            };
            fits.sopp_starts(weighted, limit, &data, &opts)?;
            if weighted && limit == 75.0 {
                fits.beside_sopp(weighted, limit, &data, &opts)?;
            }
        }
    }
    let preview = fits.best.map(|(_, m)| {
        let model_grid = SoppGrid::resample(m.as_ref());
        strips(&grid, &model_grid)
    });
    Ok((fits.rows, preview))
}

/// The configuration of the fitted RGB models (the stage-1 start is grey).
fn rgb_cfg() -> ModelConfig {
    ModelConfig {
        channels: 3,
        ..ModelConfig::default()
    }
}

/// One material's fits as they are made: its rows of the table so far and
/// the best Sopp two-stage fit (weighted, 75 deg), which starts the fit
/// with Fresnel and is drawn in the preview.
struct MaterialFits<'a> {
    /// The material.
    name: &'a str,
    /// Its rows so far.
    rows: Vec<Vec<Cell>>,
    /// Sopp's error and model of the best weighted 75-degree Sopp fit.
    best: Option<(f64, Box<dyn Parametric>)>,
}

impl MaterialFits<'_> {
    /// Sopp's two-stage fit from each of his start exponents on `data`.
    fn sopp_starts(
        &mut self,
        weighted: bool,
        limit: f64,
        data: &SampleSet,
        opts: &FitOptions,
    ) -> Result<(), StudyError> {
        for start in [25.0, 50.0, 250.0] {
            let mut grey = grey_start("as-paint", start)?;
            let mut m = build("as-paint", &rgb_cfg())?;
            let r = fit_sopp(grey.as_mut(), m.as_mut(), data, opts)?;
            self.row(
                "Sopp two-stage",
                "no",
                weighted,
                limit,
                Some(start),
                &r,
                m.as_ref(),
                data,
            )?;
            if weighted && limit == 75.0 {
                let e = sopp_error(data, m.as_ref())?;
                if self.best.as_ref().is_none_or(|b| e < b.0) {
                    self.best = Some((e, m.clone_box()));
                }
            }
        }
        Ok(())
    }

    /// The fits set beside Sopp's on the weighted 75-degree data: the
    /// project's automatic fit, the model with Fresnel started from the
    /// best Sopp result, and the clear-coat split.
    fn beside_sopp(
        &mut self,
        weighted: bool,
        limit: f64,
        data: &SampleSet,
        opts: &FitOptions,
    ) -> Result<(), StudyError> {
        // The project's automatic fit of the same model.
        let mut m = build("as-paint", &rgb_cfg())?;
        let r = fit(m.as_mut(), data, opts)?;
        self.row(
            "automatic",
            "no",
            weighted,
            limit,
            None,
            &r,
            m.as_ref(),
            data,
        )?;
        // With Fresnel, started from the best Sopp result.
        let start_n = self.best.as_ref().map_or(50.0, |b| b.1.params()[6]);
        let mut grey = grey_start("ashikhmin-shirley", start_n)?;
        let mut mf = build("ashikhmin-shirley", &rgb_cfg())?;
        let r = fit_sopp(grey.as_mut(), mf.as_mut(), data, opts)?;
        self.row(
            "Sopp two-stage, from the result without Fresnel",
            "yes",
            weighted,
            limit,
            Some(start_n),
            &r,
            mf.as_ref(),
            data,
        )?;
        // The clear-coat split: base fitted to data / (1 - Fr).
        let base = brdf_models::clear_coat::divide_by_transmission(data, 1.5)?;
        let mut mb = build("as-paint", &rgb_cfg())?;
        let r = fit(mb.as_mut(), &base, opts)?;
        self.row(
            "automatic, clear-coat split (eta 1.5)",
            "no",
            weighted,
            limit,
            None,
            &r,
            mb.as_ref(),
            &base,
        )
    }

    /// One fit's row: how it was made (procedure, Fresnel, weighting,
    /// limit, start exponent), the fitted exponent, colours and `Rs`,
    /// Sopp's unweighted error of `m` on `data`, and how the fit ended.
    fn row(
        &mut self,
        proc_: &str,
        fresnel: &str,
        weighted: bool,
        limit: f64,
        start: Option<f64>,
        r: &FitSummary,
        m: &dyn Parametric,
        data: &SampleSet,
    ) -> Result<(), StudyError> {
        let (cd, cs) = if fresnel == "yes" {
            (rgb(r, "kd"), rgb(r, "ks"))
        } else {
            (rgb(r, "cd"), rgb(r, "cs"))
        };
        let rs = cs.iter().fold(0.0f64, |a, v| a.max(*v));
        let n = if fresnel == "yes" {
            value(r, "n")
        } else {
            value(r, "ns")
        };
        let mut cells = vec![
            Cell::Text(self.name.to_string()),
            Cell::Text(proc_.into()),
            Cell::Text(fresnel.into()),
            Cell::Text(if weighted { "yes" } else { "no" }.into()),
            Cell::Text(format!("{limit}")),
            start.map_or(Cell::Text("auto".into()), |s| Cell::Num(s, 3)),
            Cell::Num(n, 4),
        ];
        cells.extend(cd.iter().chain(&cs).map(|v| Cell::Num(*v, 4)));
        cells.push(Cell::Num(rs, 4));
        cells.push(Cell::Num(sopp_error(data, m)?, 4));
        cells.push(Cell::Text(r.termination.to_string()));
        self.rows.push(cells);
        Ok(())
    }
}

/// Run the Sopp study on the selected RGL materials (in parallel).
pub fn write(study: &mut Study) -> Result<(), StudyError> {
    let Some(rgl_dir) = study.data_dir("rgl") else {
        study.skipped.push((
            "sopp".into(),
            "needs the dense RGL materials ($BRDF_DATA/rgl)".into(),
        ));
        return Ok(());
    };
    let mut t = table();
    let names: Vec<&str> = MATERIALS
        .iter()
        .copied()
        .filter(|n| study.spec.has_material(n) && rgl_dir.join(format!("{n}.bsdf")).exists())
        .collect();
    let bar = progress::bar(names.len(), "Sopp");
    let done: Vec<_> = names
        .par_iter()
        .map(|n| {
            let r = material(&rgl_dir, n);
            bar.inc(1);
            r
        })
        .collect();
    bar.finish_and_clear();
    for (name, r) in names.iter().zip(done) {
        let (rows, preview) = r?;
        t.rows.extend(rows);
        if let Some((a, b)) = preview {
            write_preview(study, name, a, b)?;
        }
    }
    if !t.rows.is_empty() {
        t.write(&study.out, "sopp_a8")?;
        study.wrote_with(Written {
            file: "sopp_a8.{csv,md}".into(),
            what: "Sopp's Appendix A.8/A.9 layout: two-stage LM fits (Fresnel, weighting, limit, start), the automatic fit, clear-coat split".into(),
            data: "`rgl/*.bsdf` on Sopp's grid (RGB)".into(),
            metric: SOPP_METRIC.into(),
            limit: "75 and 45 deg".into(),
        });
    }
    Ok(())
}

/// The empty table in the layout of Sopp's Appendix A.8/A.9, with its note.
fn table() -> Table {
    let mut t = Table::new(
        "Sopp Appendix A.8/A.9 layout: Ashikhmin-Shirley paint shader on the RGL materials (Sopp's grid)",
        &[
            "material",
            "procedure",
            "Fresnel",
            "weighting",
            "limit (deg)",
            "start n",
            "end n",
            "cd r",
            "cd g",
            "cd b",
            "cs r",
            "cs g",
            "cs b",
            "Rs",
            "error (Sopp, unweighted)",
            "termination",
        ],
    );
    t.note = "Sopp's car-paint files are not available; the RGL materials stand in, resampled onto his grid (19 x 37 x 36, RGB). `cd`, `cs` are the fitted forms (cd' = cd (1 - Rs), cs' = Rs cs), Rs = max cs'. Sopp two-stage: LM with his damping schedule on the channel mean, then the per-channel linear coefficients solved directly within their box (least squares with inequality constraints); automatic: variable projection + bounded solver from deterministic multi-starts, no start values. Generated by `brdf reproduce`.".into();
    t
}

/// Write one material's preview (measured strip `a`, model strip `b`,
/// their difference) as `sopp_preview_{name}.png` and list it.
fn write_preview(study: &mut Study, name: &str, a: Image, b: Image) -> Result<(), StudyError> {
    let exposure = exposure_for(&a, 0.99);
    let d = a.abs_difference(&b);
    let max = difference_scale(std::slice::from_ref(&d));
    let grid = Grid {
        title: format!("Sopp preview: {name}"),
        columns: vec!["measured".into(), "model".into(), "|difference|".into()],
        rows: vec![format!(
            "{name}\nexposure x{}",
            brdf_core::format::number(exposure, 3)
        )],
        tiles: vec![vec![
            Some(Tile {
                image: a,
                tone: Tone::Exposure(exposure),
            }),
            Some(Tile {
                image: b,
                tone: Tone::Exposure(exposure),
            }),
            Some(Tile {
                image: d,
                tone: Tone::Difference(max),
            }),
        ]],
        footer: vec![
            "Best Sopp two-stage fit (weighted, 75 deg) on Sopp's grid.".into(),
            "Rows: light angle x camera polar angle;".into(),
            "columns: camera azimuth mirrored.".into(),
            "Linear x exposure (99th percentile".into(),
            "of the measured -> 0.8), gamma 2.2.".into(),
            "Difference: Viridis to the 99th".into(),
            "percentile (larger ones saturate).".into(),
        ],
    };
    let file = format!("sopp_preview_{name}.png");
    grid.write_png(&study.path(&file))?;
    study.wrote_with(Written {
        file,
        what: "Sopp preview strip: measured, best two-stage fit, difference with colour bar".into(),
        data: format!("`rgl/{name}.bsdf` on Sopp's grid"),
        metric: SOPP_METRIC.into(),
        limit: "75 deg".into(),
    });
    Ok(())
}
