//! The one typed way to ask for a fit, shared by every front end (the
//! `brdf` command, Python, batches, the study, reports): a [`FitRequest`]
//! names the [`Material`], the model, the [`Metric`], the [`ChannelMode`],
//! the solver, the starts and the structure, and [`FitRequest::run`]
//! returns one [`FitOutcome`]. Front ends parse their options into these
//! types and print what comes back; none assembles a fit itself.
//!
//! ```no_run
//! use brdf_fit::{FitRequest, Material, Metric};
//! let material = Material::load("rgl/paper_white_rgb.bsdf")?;
//! let mut request = FitRequest::new(&material, brdf_fit::resolve("principled")?);
//! request.metric = Metric::Auto; // appearance for a renderer model on RGL data
//! let outcome = request.run()?;
//! let report = outcome.report()?;
//! println!("{:?}", report.image_error.as_ref().map(|e| e.mean_flip()));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::borrow::Cow;
use std::time::Instant;

use brdf_core::SampleSet;
use brdf_core::progress::{Progress, Silent};
use brdf_models::{ModelConfig, ModelEntry};
use brdf_solve::LmOptions;

use crate::appearance::REFINE_L2_GROWTH;
use crate::hints::hints;
use crate::judged::{self, SCATTERED_NOTE};
use crate::{Channels, Fit, FitError, FitOptions, FitReport, Material, Objective, Solver};

/// What a fit minimises, as a front end's `--metric` names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Metric {
    /// Appearance for a renderer model on data that can be rendered, else
    /// Ngan's L2.
    #[default]
    Auto,
    /// Candidates chosen by image error, refined in the image objective.
    Appearance,
    /// One objective of the pipeline.
    Objective(Objective),
}

impl Metric {
    /// The metric a front end's name means: `auto`, `appearance` or an
    /// objective's name ([`Objective::parse`]).
    pub fn parse(name: &str) -> Result<Self, FitError> {
        Ok(match name {
            "auto" => Metric::Auto,
            "appearance" => Metric::Appearance,
            other => Metric::Objective(Objective::parse(other)?),
        })
    }

    /// The name a front end gives it.
    pub fn name(self) -> &'static str {
        match self {
            Metric::Auto => "auto",
            Metric::Appearance => "appearance",
            Metric::Objective(o) => o.name(),
        }
    }

    /// Whether it means a fit for appearance of `model` (on data that can
    /// be rendered when `renderable`), and the objective of the fit (of
    /// the candidates' first, for appearance).
    pub fn resolve(self, model: &ModelEntry, renderable: bool) -> (bool, Objective) {
        match self {
            Metric::Auto => (model.renderer && renderable, Objective::Ngan),
            Metric::Appearance => (true, Objective::Ngan),
            Metric::Objective(o) => (false, o),
        }
    }
}

/// How a fit treats the data's channels.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ChannelMode {
    /// Every channel: shared non-linear, per-channel linear parameters.
    #[default]
    Rgb,
    /// The mean of the channels.
    Grey,
    /// One independent grey fit per channel (not rendered: a grey model
    /// of one channel has no colour to judge).
    PerChannel,
}

impl ChannelMode {
    /// `rgb`, `grey` or `per-channel`.
    pub fn parse(name: &str) -> Result<Self, FitError> {
        match name {
            "rgb" => Ok(ChannelMode::Rgb),
            "grey" => Ok(ChannelMode::Grey),
            "per-channel" => Ok(ChannelMode::PerChannel),
            other => Err(FitError::InvalidOption {
                option: "channels",
                value: other.to_string(),
                expected: "grey, rgb or per-channel",
            }),
        }
    }

    /// The name a front end gives it.
    pub fn name(self) -> &'static str {
        match self {
            ChannelMode::Rgb => "rgb",
            ChannelMode::Grey => "grey",
            ChannelMode::PerChannel => "per-channel",
        }
    }

    /// How many models a fit of `data` gives.
    pub fn models(self, data: &SampleSet) -> usize {
        match self {
            ChannelMode::PerChannel => data.channels(),
            _ => 1,
        }
    }
}

/// A fit to run: everything a front end can ask for, typed.
pub struct FitRequest<'a> {
    /// The data, loaded once.
    pub material: &'a Material,
    /// The model, resolved ([`crate::resolve`]).
    pub model: ModelEntry,
    /// What the fit minimises.
    pub metric: Metric,
    /// How the channels are treated.
    pub channels: ChannelMode,
    /// The solver.
    pub solver: Solver,
    /// Multi-start count (at least 1).
    pub starts: usize,
    /// Reweighting cap of a robust (IRLS) fit.
    pub irls_max_iterations: usize,
    /// Samples with theta_i or theta_o above this angle (degrees) dropped.
    pub limit_deg: f64,
    /// The model's structure: lobes, Koenderink order, polynomial degree.
    pub config: ModelConfig,
    /// End a fit for appearance with a search on the judge's mean FLIP.
    pub polish: bool,
    /// How far the image refinement of a fit for appearance may let Ngan's
    /// L2 grow over the winning candidate's (default
    /// [`REFINE_L2_GROWTH`]); `f64::INFINITY` judges by the render alone,
    /// as a conversion between renderer models does, whose source has no
    /// unrendered directions to keep.
    pub refine_l2_growth: f64,
    /// The solver's tolerances (default [`LmOptions::default`]), for
    /// studies of convergence and profiling.
    pub lm: LmOptions,
    /// Tolerance of the multi-start search (default
    /// [`FitOptions::search_tolerance`]); the best start is polished to
    /// `lm`'s own tolerances.
    pub search_tolerance: f64,
    /// Who watches the fit's progress.
    pub progress: &'a dyn Progress,
}

/// What [`FitRequest::run`] gives.
pub struct FitOutcome {
    /// One report, or one per channel for [`ChannelMode::PerChannel`].
    pub reports: Vec<FitReport>,
    /// Whether the fits were chosen by image error.
    pub for_appearance: bool,
    /// Wall seconds of the whole request (candidates and image errors
    /// included; each report's summary holds its kept solve's own time).
    pub seconds: f64,
}

impl FitOutcome {
    /// The one report of a fit that gives one model.
    pub fn report(&self) -> Result<&FitReport, FitError> {
        match self.reports.as_slice() {
            [one] => Ok(one),
            _ => Err(FitError::NeedsOneModel {
                models: self.reports.len(),
            }),
        }
    }

    /// The one report, owned.
    pub fn into_report(mut self) -> Result<FitReport, FitError> {
        self.report()?;
        self.reports
            .pop()
            .ok_or(FitError::NeedsOneModel { models: 0 })
    }
}

impl<'a> FitRequest<'a> {
    /// A request with the defaults of `brdf fit`: metric auto, RGB, the
    /// automatic solver, 12 starts, an 80 degree limit, one lobe.
    pub fn new(material: &'a Material, model: ModelEntry) -> Self {
        let defaults = FitOptions::default();
        FitRequest {
            material,
            model,
            metric: Metric::Auto,
            channels: ChannelMode::Rgb,
            solver: Solver::Auto,
            starts: defaults.starts,
            irls_max_iterations: defaults.irls_max_iterations,
            limit_deg: 80.0,
            config: ModelConfig::default(),
            polish: false,
            refine_l2_growth: REFINE_L2_GROWTH,
            lm: defaults.lm,
            search_tolerance: defaults.search_tolerance,
            progress: &Silent,
        }
    }

    /// Whether the data will be rendered: dense data fitted as one model.
    pub fn is_judged(&self) -> bool {
        self.material.is_renderable() && self.channels != ChannelMode::PerChannel
    }

    /// Whether the fit is chosen by image error, and its objective.
    pub fn resolved_metric(&self) -> (bool, Objective) {
        self.metric.resolve(&self.model, self.is_judged())
    }

    /// Run the fit: one report per model, image errors attached for data
    /// that can be rendered (the data's renders made beside the fit).
    pub fn run(&self) -> Result<FitOutcome, FitError> {
        let t0 = Instant::now();
        let (for_appearance, objective) = self.resolved_metric();
        if self.polish && !for_appearance {
            return Err(self.polish_refused());
        }
        let fit = self.builder(objective);
        let sets = self.channel_sets();
        let task = self.progress.task("fit", sets.len());
        let mut reports = Vec::with_capacity(sets.len());
        for (set, channels) in &sets {
            task.item(&format!("{} on {}", self.model.name, set.name));
            let fit = fit.clone().channels(*channels);
            reports.push(self.fit_one(&fit, set, for_appearance)?);
            task.advance(1);
        }
        task.finish();
        Ok(FitOutcome {
            reports,
            for_appearance,
            seconds: t0.elapsed().as_secs_f64(),
        })
    }

    /// The pipeline's builder for this request.
    fn builder(&self, objective: Objective) -> Fit {
        Fit::entry(self.model)
            .objective(objective)
            .solver(self.solver)
            .starts(self.starts)
            .irls_max_iterations(self.irls_max_iterations)
            .limit_deg(self.limit_deg)
            .lobes(self.config.lobes)
            .order(self.config.order)
            .degree(self.config.degree)
            .polish_on_flip(self.polish)
            .lm_options(self.lm.clone())
            .search_tolerance(self.search_tolerance)
    }

    /// The sample sets fitted, each with the builder's channel setting.
    fn channel_sets(&self) -> Vec<(Cow<'a, SampleSet>, Channels)> {
        let data = self.material.samples();
        match self.channels {
            ChannelMode::Rgb => vec![(Cow::Borrowed(data), Channels::All)],
            ChannelMode::Grey => vec![(Cow::Borrowed(data), Channels::Grey)],
            ChannelMode::PerChannel => (0..data.channels())
                .map(|c| (Cow::Owned(data.single_channel(c)), Channels::All))
                .collect(),
        }
    }

    /// One model's fit and, for rendered data, its image errors (the
    /// judge's renders of the data made beside the fit, on another thread
    /// when there is one).
    fn fit_one(
        &self,
        fit: &Fit,
        set: &SampleSet,
        for_appearance: bool,
    ) -> Result<FitReport, FitError> {
        let data = match self.material.dense() {
            Some(d) if self.is_judged() => d,
            _ => {
                let mut report = fit.run(set)?;
                report.image_note = Some(SCATTERED_NOTE.to_string());
                return Ok(report);
            }
        };
        let (report, judge) = rayon::join(
            || judged::fit_rendered(fit, set, data, for_appearance, self.refine_l2_growth),
            || self.material.judge(),
        );
        let judge = judge?.ok_or_else(|| FitError::NotRenderable {
            data: self.material.name().to_string(),
        })?;
        let mut report = judged::with_image_errors(report?, judge)?;
        if let Some(image) = &report.image_error {
            let advice = hints(
                self.material.spec(),
                &self.model,
                self.is_default_fit(),
                image,
            );
            report.notes.extend(advice);
        }
        Ok(report)
    }

    /// Whether this is the fit `brdf select` makes of the model: for
    /// appearance, with the default structure and options.
    fn is_default_fit(&self) -> bool {
        let defaults = FitRequest::new(self.material, self.model);
        matches!(self.metric, Metric::Auto | Metric::Appearance)
            && self.channels == ChannelMode::Rgb
            && self.solver == defaults.solver
            && self.starts == defaults.starts
            && self.limit_deg == defaults.limit_deg
            && self.config == defaults.config
            && self.refine_l2_growth == defaults.refine_l2_growth
            && self.lm == defaults.lm
            && self.search_tolerance == defaults.search_tolerance
            && !self.polish
    }

    fn polish_refused(&self) -> FitError {
        FitError::PolishNeedsAppearance {
            model: self.model.name.to_string(),
            metric: self.metric.name(),
            data: self.material.spec().to_string(),
        }
    }
}
