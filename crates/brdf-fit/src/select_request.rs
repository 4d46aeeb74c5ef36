//! The one typed way to ask for a model selection, shared by `brdf
//! select` and Python: a [`SelectRequest`] names the [`Material`], the
//! candidates, the tolerance and how the choice is made ([`SelectBy`]), and
//! [`SelectRequest::run`] returns one [`SelectOutcome`], which also gives
//! the JSON both front ends print.

use brdf_core::SampleSet;
use brdf_core::progress::{Progress, Silent};

use brdf_render::ImageError;

use crate::select::{Among, Search, SelectRow};
use crate::select_by_image::{ByImage, ImageChoice, ModelSpec, select_by_image};
use crate::{FitError, FitOptions, FitReport, Material};

/// How the choice among candidates is made.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SelectBy {
    /// By image on data that can be rendered, else by L2: what a user
    /// looks at decides where it can be measured.
    #[default]
    Auto,
    /// The fewest stored numbers within the tolerance of the best Ngan L2.
    L2,
    /// The least image error among renderer models fitted for appearance
    /// (data that can be rendered only).
    Image,
}

/// A selection to run.
pub struct SelectRequest<'a> {
    /// The data, loaded once.
    pub material: &'a Material,
    /// How the choice is made.
    pub by: SelectBy,
    /// Accept errors up to `(1 + tolerance)` times the best (by L2).
    pub tolerance: f64,
    /// Samples with theta_i or theta_o above this angle (degrees) dropped.
    pub limit_deg: f64,
    /// Fit the mean of the channels.
    pub grey: bool,
    /// The candidates admitted (by name and size); by image, the models
    /// (empty: [`brdf_models::by_image_models`]).
    pub among: Among,
    /// Coarse to fine, or every candidate on all samples (by L2).
    pub search: Search,
    /// End each fit for appearance with the search on its mean FLIP (by
    /// image).
    pub polish: bool,
    /// Who watches the selection's progress.
    pub progress: &'a dyn Progress,
}

/// What [`SelectRequest::run`] gives.
pub enum SelectOutcome {
    /// A choice by Ngan L2.
    L2 {
        /// The samples the candidates were fitted to (filtered, grey).
        data: Box<SampleSet>,
        /// The tolerance used.
        tolerance: f64,
        /// How the candidates were fitted.
        search: Search,
        /// Every candidate's row, in candidate order.
        rows: Vec<SelectRow>,
        /// Index of the choice in `rows`.
        choice: usize,
        /// The choice's image errors, for data that can be rendered.
        image: Option<ImageError>,
    },
    /// A choice by image error.
    Image {
        /// The data's name in outputs.
        data: String,
        /// Every model's fit for appearance and image errors.
        rows: Vec<ImageChoice>,
        /// Index of the choice in `rows`.
        choice: usize,
        /// The chosen model's fit.
        chosen: Box<FitReport>,
    },
}

impl SelectOutcome {
    /// The JSON of `brdf select --json`.
    pub fn json(&self) -> Result<serde_json::Value, FitError> {
        match self {
            SelectOutcome::L2 {
                data,
                tolerance,
                search,
                rows,
                choice,
                image,
            } => crate::select_json(data, *tolerance, *search, rows, *choice, image.as_ref()),
            SelectOutcome::Image {
                data, rows, choice, ..
            } => crate::select_by_image_json(data, rows, *choice),
        }
    }
}

impl<'a> SelectRequest<'a> {
    /// A request with the defaults of `brdf select`: by image where the
    /// data can be rendered, else by L2 with tolerance 0.1,
    /// an 80 degree limit, every candidate, coarse to fine.
    pub fn new(material: &'a Material) -> Self {
        SelectRequest {
            material,
            by: SelectBy::Auto,
            tolerance: 0.1,
            limit_deg: 80.0,
            grey: false,
            among: Among::default(),
            search: Search::CoarseToFine,
            polish: false,
            progress: &Silent,
        }
    }

    /// Run the selection.
    pub fn run(&self) -> Result<SelectOutcome, FitError> {
        // Refused whichever way the choice is made: a selection by image
        // has no use for it, but a bad value is a mistake to point out.
        if !(self.tolerance >= 0.0 && self.tolerance.is_finite()) {
            return Err(FitError::OutOfRange {
                option: "--tolerance",
                value: self.tolerance,
                range: ">= 0",
            });
        }
        match self.by {
            SelectBy::Auto if self.material.is_renderable() => self.by_image(),
            SelectBy::Auto | SelectBy::L2 => self.by_l2(),
            SelectBy::Image => self.by_image(),
        }
    }

    fn by_l2(&self) -> Result<SelectOutcome, FitError> {
        if self.polish && self.by == SelectBy::L2 {
            return Err(FitError::InvalidOption {
                option: "polish",
                value: "on".into(),
                expected: "a selection by image: it refines fits for appearance (renderer models on RGL `.bsdf` or MERL `.binary` data)",
            });
        }
        let data = crate::select::prepare(self.material.samples(), self.limit_deg, self.grey)?;
        let n = crate::select::candidates(data.channels()).len();
        let task = self.progress.task("select", 1);
        task.item(&format!("fitting up to {n} candidates to {}", data.name));
        // The judge's renders do not depend on the choice: made beside it.
        let (selected, judge) = rayon::join(
            || {
                crate::select::select_fitted(
                    &data,
                    self.tolerance,
                    &FitOptions::default(),
                    &self.among,
                    self.search,
                )
            },
            || self.material.judge(),
        );
        let selection = selected?;
        let image = match judge? {
            Some(j) => Some(j.fit_errors(selection.model.as_ref())?),
            None => None,
        };
        task.finish();
        Ok(SelectOutcome::L2 {
            data: Box::new(data),
            tolerance: self.tolerance,
            search: self.search,
            rows: selection.rows,
            choice: selection.choice,
            image,
        })
    }

    /// The options only a selection by L2 reads, refused in a selection
    /// by image rather than ignored.
    fn refuse_l2_options(&self) -> Result<(), FitError> {
        const EXPECTED: &str = "a selection by L2 (`--by-l2`): a selection by image fits every renderer model for appearance on all channels";
        let given = [
            ("grey", self.grey.then(|| "on".to_string())),
            (
                "max_parameters",
                self.among.max_parameters.map(|n| n.to_string()),
            ),
            (
                "exhaustive",
                (self.search == Search::Exhaustive).then(|| "on".to_string()),
            ),
        ];
        match given.into_iter().find_map(|(o, v)| v.map(|v| (o, v))) {
            Some((option, value)) => Err(FitError::InvalidOption {
                option,
                value,
                expected: EXPECTED,
            }),
            None => Ok(()),
        }
    }

    fn by_image(&self) -> Result<SelectOutcome, FitError> {
        let names: Vec<&str> = if self.among.models.is_empty() {
            brdf_models::by_image_models()
        } else {
            self.among.models.iter().map(String::as_str).collect()
        };
        let specs: Vec<ModelSpec> = names.into_iter().map(ModelSpec::named).collect();
        self.by_image_among(&specs)
    }

    /// A selection by image among `specs` (models with their number of
    /// specular lobes), whatever `among` names: the request's material,
    /// limit, polish and progress.
    pub fn by_image_among(&self, specs: &[ModelSpec]) -> Result<SelectOutcome, FitError> {
        if !self.material.is_renderable() {
            return Err(FitError::NotRenderable {
                data: self.material.spec().to_string(),
            });
        }
        self.refuse_l2_options()?;
        let task = self.progress.task("select", specs.len());
        task.item(&format!(
            "{} renderer models on {}",
            specs.len(),
            self.material.name()
        ));
        let how = ByImage {
            polish: self.polish,
            limit_deg: self.limit_deg,
        };
        let (rows, choice, chosen) = select_by_image(specs, self.material, how, task.as_ref())?;
        task.finish();
        Ok(SelectOutcome::Image {
            data: self.material.samples().name.clone(),
            rows,
            choice,
            chosen: Box::new(chosen),
        })
    }
}
