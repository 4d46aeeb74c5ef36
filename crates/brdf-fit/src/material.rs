//! A measured material as every front end uses it, loaded once: its
//! samples (what fits minimise over), the data itself when it can be
//! evaluated at any direction pair (RGL `.bsdf`, MERL `.binary`: what the
//! judge renders), and the judge holding the data's renders, made the
//! first time an image error is asked for. A fit, a selection, a report
//! page and a batch row of the same file share one [`Material`] instead of
//! each reading and rendering the file again; across processes the
//! renders of a file are kept in [`crate::render_cache`].

use std::path::PathBuf;
use std::sync::OnceLock;

use brdf_core::{Brdf, SampleSet};

use crate::FitError;
use brdf_render::judge::{Judge, REPORT_SIZE};

/// A data set loaded once for fits, selection, reports and batches.
pub struct Material {
    spec: String,
    name: String,
    samples: SampleSet,
    dense: Option<Box<dyn Brdf>>,
    /// The file the dense data were read from: the render cache's key.
    file: Option<PathBuf>,
    judge: OnceLock<Judge>,
}

impl Material {
    /// Load `spec` (`PATH` or `PATH#SAMPLE`, relative paths also under
    /// `BRDF_DATA`): its samples and, when the format allows, the dense
    /// data. A folder is refused with the command that fits one.
    pub fn load(spec: &str) -> Result<Self, FitError> {
        let (path, _) = brdf_io::load::resolve_spec(spec)?;
        if path.is_dir() {
            return Err(FitError::FolderGiven {
                spec: spec.to_string(),
            });
        }
        let dense = brdf_io::load_dense(spec)?;
        Ok(Material {
            spec: spec.to_string(),
            name: crate::data_name(spec),
            samples: brdf_io::load(spec)?,
            file: dense.is_some().then_some(path),
            dense,
            judge: OnceLock::new(),
        })
    }

    /// [`Material::load`], dense data rendered at once on the judge terms
    /// `terms` gives (asked for only then; shared, not copied): one set of
    /// terms serves every material of a batch or a report.
    pub fn load_on<'j>(spec: &str, terms: impl FnOnce() -> &'j Judge) -> Result<Self, FitError> {
        let material = Material::load(spec)?;
        if let Some(data) = material.dense.as_deref() {
            let judge = material.render(terms(), data)?;
            let _ = material.judge.set(judge);
        }
        Ok(material)
    }

    /// Samples prepared by the caller (a Python dict of arrays, a study's
    /// subsample of a file) with, when it can be rendered, the data they
    /// were taken from; `name` names them in outputs.
    pub fn new(name: &str, samples: SampleSet, dense: Option<Box<dyn Brdf>>) -> Self {
        Material {
            spec: name.to_string(),
            name: name.to_string(),
            samples,
            dense,
            file: None,
            judge: OnceLock::new(),
        }
    }

    /// The spec it was loaded from, as given.
    pub fn spec(&self) -> &str {
        &self.spec
    }

    /// Its name in outputs: relative to `BRDF_DATA` when under it
    /// ([`crate::data_name`]).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Every sample present (filters are the fit's business).
    pub fn samples(&self) -> &SampleSet {
        &self.samples
    }

    /// The data evaluable at any direction pair, when the format allows.
    pub fn dense(&self) -> Option<&dyn Brdf> {
        self.dense.as_deref()
    }

    /// Whether the judge can render it (and fits for appearance apply).
    pub fn is_renderable(&self) -> bool {
        self.dense.is_some()
    }

    /// The judge at [`REPORT_SIZE`] pixels holding the data's renders,
    /// made on first use and kept; `None` for scattered data.
    pub fn judge(&self) -> Result<Option<&Judge>, FitError> {
        let Some(data) = self.dense.as_deref() else {
            return Ok(None);
        };
        if let Some(judge) = self.judge.get() {
            return Ok(Some(judge));
        }
        let judge = self.render(&Judge::new(REPORT_SIZE), data)?;
        Ok(Some(self.judge.get_or_init(|| judge)))
    }

    /// `terms` with the data's renders: from the render cache for data
    /// read from a file, else rendered.
    fn render(&self, terms: &Judge, data: &dyn Brdf) -> Result<Judge, FitError> {
        match &self.file {
            Some(file) => crate::render_cache::rendering(terms, file, data),
            None => Ok(terms.rendering(data)?),
        }
    }
}
