//! The shared context of the study's parts: the selection
//! ([`spec::StudySpec`]) and the [`Study`] every part runs on: the data (loaded only when a selected part
//! asks for it), the fits on CUReT (fitted in parallel, once, and shared by
//! the tables that use them), and the list of files written, from which
//! `results/README.md` is generated.
//!
//! This module imports no part: the part list ([`crate::parts`]) knows
//! the parts, and the parts know only this context.

pub mod models;
pub mod progress;
pub mod spec;

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use brdf_core::SampleSet;
use brdf_fit::{FitSummary, Objective};
use brdf_models::ModelConfig;
use rayon::prelude::*;

use crate::StudyError;
use models::{FitHow, fit_model};
use spec::StudySpec;

/// An RGL material and the samples the study fits: Sopp's grid within 80
/// degrees, cell weights, every 5th node (about 4,000 samples). Shared by
/// the dense tables and the figures.
pub fn rgl_material(dir: &Path, name: &str) -> Result<(brdf_io::rgl::Rgl, SampleSet), StudyError> {
    let (rgl, every, _) = rgl_material_and_grid(dir, name)?;
    Ok((rgl, every))
}

/// [`rgl_material`] and every node of the grid within 80 deg (the four
/// fifths the study does not fit included), on which a fit's error is
/// measured beside its error on the nodes it was fitted to.
pub fn rgl_material_and_grid(
    dir: &Path,
    name: &str,
) -> Result<(brdf_io::rgl::Rgl, SampleSet, SampleSet), StudyError> {
    let rgl = brdf_io::rgl::Rgl::read(&dir.join(format!("{name}.bsdf")))?;
    let full = brdf_io::sopp_grid::SoppGrid::resample(&rgl).to_samples(name, 80.0, true);
    let keep: Vec<bool> = (0..full.len()).map(|j| j % 5 == 0).collect();
    Ok((rgl, full.select(&keep), full))
}

/// One file the study wrote, for `results/README.md`.
#[derive(Clone, Debug)]
pub struct Written {
    /// File name(s) inside the output folder (`kurt_9_1.{csv,md}`).
    pub file: String,
    /// What it holds.
    pub what: String,
    /// Data it comes from (relative to `BRDF_DATA`).
    pub data: String,
    /// Metric of its numbers.
    pub metric: String,
    /// Angle limit of its data.
    pub limit: String,
}

/// The metric and angle limit of the CUReT fits of one pass.
#[derive(Clone, Debug, PartialEq)]
pub struct Variant {
    /// Objective name (`ngan`, ...).
    pub metric: String,
    /// Angle limit (degrees).
    pub limit: f64,
}

impl Variant {
    /// File-name suffix: empty for the thesis setting (Ngan, 80 deg).
    pub fn suffix(&self) -> String {
        if self.metric == "ngan" && self.limit == 80.0 {
            String::new()
        } else {
            format!("_{}_{}", self.metric, self.limit)
        }
    }

    /// The objective.
    pub fn objective(&self) -> Result<Objective, StudyError> {
        Ok(Objective::parse(&self.metric)?)
    }
}

/// The shared state of a study run.
pub struct Study {
    /// Data root (`BRDF_DATA` or `--data`); `None` runs the synthetic demonstration.
    pub data: Option<PathBuf>,
    /// Output folder.
    pub out: PathBuf,
    /// The selection.
    pub spec: StudySpec,
    /// The current metric and limit of the CUReT fits.
    pub variant: Variant,
    /// Files written so far.
    pub written: Vec<Written>,
    /// Parts skipped, with the reason (said in the README).
    pub skipped: Vec<(String, String)>,
    curet_raw: Option<Vec<SampleSet>>,
    fits: HashMap<String, FitSummary>,
}

impl Study {
    /// A study writing into `out`.
    pub fn new(data: Option<PathBuf>, out: PathBuf, spec: StudySpec) -> Self {
        let variant = Variant {
            metric: spec.metrics[0].clone(),
            limit: spec.limits[0],
        };
        Study {
            data,
            out,
            spec,
            variant,
            written: Vec::new(),
            skipped: Vec::new(),
            curet_raw: None,
            fits: HashMap::new(),
        }
    }

    /// Whether this run is on the built-in synthetic data.
    pub fn synthetic(&self) -> bool {
        self.data.is_none()
    }

    /// A figure title, marked when the data are synthetic.
    pub fn title(&self, t: impl Into<String>) -> String {
        let t = t.into();
        if self.synthetic() {
            format!("{t} [BUILT-IN SYNTHETIC DATA]")
        } else {
            t
        }
    }

    /// The data root's sub-folder `rel`, when it exists.
    pub fn data_dir(&self, rel: &str) -> Option<PathBuf> {
        self.data
            .as_ref()
            .map(|d| d.join(rel))
            .filter(|d| d.exists())
    }

    /// Where the CUReT material sets come from (for notes).
    pub fn curet_source(&self) -> String {
        if self.synthetic() {
            "BUILT-IN SYNTHETIC DATA (no measured data found: set BRDF_DATA or --data)".into()
        } else {
            format!(
                "measured CUReT data (grey, `$BRDF_DATA/curet/abrdf.dat`), angle limit {} deg",
                self.variant.limit
            )
        }
    }

    /// Record a written file.
    pub fn wrote(
        &mut self,
        file: impl Into<String>,
        what: impl Into<String>,
        data: impl Into<String>,
    ) {
        let limit = format!("{} deg", self.variant.limit);
        let data = if self.synthetic() {
            "BUILT-IN SYNTHETIC DATA".to_string()
        } else {
            data.into()
        };
        self.written.push(Written {
            file: file.into(),
            what: what.into(),
            data,
            metric: self.variant.metric.clone(),
            limit,
        });
    }

    /// Record a written file with its own metric and limit.
    pub fn wrote_with(&mut self, w: Written) {
        self.written.push(w);
    }

    /// The stem of a CUReT table for the current variant (`kurt_9_4`,
    /// `kurt_9_4_log_70`).
    pub fn stem(&self, base: &str) -> String {
        format!("{base}{}", self.variant.suffix())
    }

    fn curet_all(&mut self) -> Result<&[SampleSet], StudyError> {
        if self.curet_raw.is_none() {
            let sets = match &self.data {
                Some(dir) => {
                    let abrdf = dir.join("curet/abrdf.dat");
                    let table = dir.join("curet/table.txt");
                    brdf_io::curet::read_grey(&abrdf, &table)?
                        .into_iter()
                        .filter(|s| sample_number(s).is_some_and(brdf_io::curet::is_isotropic))
                        .map(|s| s.filter_invalid(false).0)
                        .collect()
                }
                None => {
                    let pairs = crate::synthetic::scattered_pairs(205, 80f64.to_radians());
                    crate::synthetic::MATERIALS
                        .iter()
                        .filter(|m| {
                            !m.name.starts_with("cayman") && !m.name.starts_with("mystique")
                        })
                        .map(|m| crate::synthetic::sample(m, &pairs, 1))
                        .collect::<Result<Vec<_>, _>>()?
                }
            };
            self.curet_raw = Some(sets);
        }
        Ok(self.curet_raw.as_deref().unwrap_or(&[]))
    }

    /// The selected CUReT materials (isotropic), at the current angle limit.
    pub fn curet(&mut self) -> Result<Vec<SampleSet>, StudyError> {
        let limit = self.variant.limit.to_radians();
        let spec = self.spec.clone();
        Ok(self
            .curet_all()?
            .iter()
            .filter(|s| spec.has_material(&s.name))
            .map(|s| s.filter_angle_limit(limit).0)
            .collect())
    }

    /// Fit every model to every set (parallel over the pairs not fitted
    /// before in this run; results in order, identical for any thread
    /// count): `[model][set]`.
    pub fn fits(
        &mut self,
        models: &[(&'static str, &'static str, ModelConfig)],
        sets: &[SampleSet],
        how: FitHow,
    ) -> Result<Vec<Vec<FitSummary>>, StudyError> {
        let key = |label: &str, set: &SampleSet| {
            format!(
                "{label}|{}|{}|{:?}|{}|{}|{}",
                set.name,
                how.objective.name(),
                how.lbox,
                how.ols,
                set.len(),
                set.channels()
            )
        };
        let todo: Vec<(usize, usize)> = (0..models.len())
            .flat_map(|m| (0..sets.len()).map(move |s| (m, s)))
            .filter(|(m, s)| !self.fits.contains_key(&key(models[*m].0, &sets[*s])))
            .collect();
        if !todo.is_empty() {
            let bar = progress::bar(todo.len(), "fitting");
            let done: Vec<Result<FitSummary, StudyError>> = todo
                .par_iter()
                .map(|(m, s)| {
                    let (_, name, config) = models[*m];
                    let r = fit_model(name, config, &sets[*s], how).map(|r| r.1);
                    bar.inc(1);
                    r
                })
                .collect();
            bar.finish_and_clear();
            for ((m, s), r) in todo.iter().zip(done) {
                self.fits.insert(key(models[*m].0, &sets[*s]), r?);
            }
        }
        Ok(models
            .iter()
            .map(|(label, _, _)| {
                sets.iter()
                    .map(|s| self.fits[&key(label, s)].clone())
                    .collect()
            })
            .collect())
    }

    /// The selected models of Kurt's nine.
    pub fn models(&self) -> Vec<(&'static str, &'static str, ModelConfig)> {
        models::nine_models(self.spec.lobes)
            .into_iter()
            .filter(|(label, name, _)| self.spec.has_model(label, name))
            .collect()
    }

    /// The selected renderer models (GGX, principled, glTF), compared with
    /// the nine in the Table 9.3 stand-in and the error against time.
    pub fn renderer_models(&self) -> Vec<(&'static str, &'static str, ModelConfig)> {
        models::renderer_models(self.spec.lobes)
            .into_iter()
            .filter(|(label, name, _)| self.spec.has_model(label, name))
            .collect()
    }

    /// How the thesis tables are fitted in the current variant.
    pub fn how(&self) -> Result<FitHow, StudyError> {
        Ok(FitHow {
            objective: self.variant.objective()?,
            lbox: self.spec.lafortune_box,
            ols: false,
        })
    }

    /// `message` with the data folder written `$BRDF_DATA` (no machine
    /// path in results; error messages name the files they read).
    pub fn relative(&self, message: &str) -> String {
        match &self.data {
            Some(root) => message.replace(&root.display().to_string(), "$BRDF_DATA"),
            None => message.to_string(),
        }
    }

    /// Output path of a file.
    pub fn path(&self, file: &str) -> PathBuf {
        self.out.join(file)
    }
}

/// CUReT sample number of a set named `curet#N ...`.
pub fn sample_number(set: &SampleSet) -> Option<u32> {
    set.name
        .strip_prefix("curet#")?
        .split(' ')
        .next()?
        .parse()
        .ok()
}

/// Create the output folder.
pub fn create_dir(dir: &Path) -> Result<(), StudyError> {
    std::fs::create_dir_all(dir).map_err(|e| StudyError::Io {
        path: dir.display().to_string(),
        source: e,
    })
}
