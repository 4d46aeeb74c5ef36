//! The public entry point: a [`Fit`] builder that names the model, the
//! objective, the angle limit, the channels, the starts and the solver, and
//! [`Fit::run`] on a sample set giving a [`FitReport`] that holds the
//! fitted model, the summary and what was filtered out.
//!
//! ```no_run
//! use brdf_fit::{Channels, Fit};
//! let samples = brdf_io::load("curet/abrdf.dat#25")?;
//! let report = Fit::model("blinn-phong")?.channels(Channels::Grey).run(&samples)?;
//! println!("Ngan L2 {:.4} from {} of {} samples", report.summary.ngan_l2,
//!          report.summary.samples, report.samples_present);
//! report.saved_model("curet/abrdf.dat#25")?.save("fit.json".as_ref())?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use brdf_core::{Parametric, SampleSet};
use brdf_models::saved_model::{Provenance, RenderedError, SavedModel, SavedTermination};
use brdf_models::{ModelConfig, ModelEntry};

use crate::FitError;
use crate::boxed::BoxedModel;
use crate::names::resolve;
use crate::objective::Objective;
use crate::options::{FitOptions, Solver};
use crate::pipeline::{fit, fit_sopp};
use crate::scaling::fit_scaled;
use crate::summary::FitSummary;

/// Which channels a fit uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Channels {
    /// Every channel of the data, shared non-linear and per-channel linear
    /// parameters (default).
    #[default]
    All,
    /// The mean of the channels (one grey channel).
    Grey,
}

/// A fit to be run: model, objective, limit, channels, starts, solver.
#[derive(Clone, Debug)]
pub struct Fit {
    entry: ModelEntry,
    config: ModelConfig,
    options: FitOptions,
    limit_deg: f64,
    channels: Channels,
    /// Narrower boxes `(prefix, lower, upper)` ([`BoxedModel::narrowed`]).
    boxes: Vec<(String, f64, f64)>,
    /// Whether an appearance fit ends with a search on FLIP itself
    /// ([`Fit::polish_on_flip`]).
    flip_polish: bool,
}

/// The outcome of [`Fit::run`].
pub struct FitReport {
    /// The model at the fitted parameters.
    pub model: Box<dyn Parametric>,
    /// Its structural configuration.
    pub config: ModelConfig,
    /// Parameters, errors, solver, iterations, termination, time.
    pub summary: FitSummary,
    /// Samples in the data set before any filter.
    pub samples_present: usize,
    /// Samples dropped as invalid (NaN, infinite).
    pub dropped_invalid: usize,
    /// Samples dropped beyond the angle limit.
    pub dropped_angle: usize,
    /// Angle limit used, in degrees.
    pub limit_deg: f64,
    /// Channel names of the fitted data.
    pub channel_names: Vec<String>,
    /// What the fit did beyond the request, in words (internal scaling of
    /// extreme data, a solver chosen for the objective, parameters on a
    /// bound of their box), for the report.
    pub notes: Vec<String>,
    /// Image errors against the data under the standard light sets, for
    /// data that can be rendered ([`crate::FitRequest`]).
    pub image_error: Option<brdf_render::ImageError>,
    /// Why there is no image error (scattered data), when there is none.
    pub image_note: Option<String>,
    /// The candidates of a fit chosen by image error.
    pub candidates: Vec<crate::appearance::Candidate>,
    /// The direction pairs fitted (Kurt's polynomial stores its PCA of them).
    pairs: brdf_core::DirPairs,
}

impl Fit {
    /// A fit of the catalogue model `name`; names are forgiving (case,
    /// `_` for `-`, display names such as "Blinn-Phong"); an unknown name
    /// is an error suggesting the nearest ones.
    pub fn model(name: &str) -> Result<Self, FitError> {
        Ok(Self::entry(resolve(name)?))
    }

    /// A fit of a catalogue entry.
    pub fn entry(entry: ModelEntry) -> Self {
        Fit {
            entry,
            config: ModelConfig::default(),
            options: FitOptions::default(),
            limit_deg: 80.0,
            channels: Channels::All,
            boxes: Vec::new(),
            flip_polish: false,
        }
    }

    /// End a fit for appearance ([`crate::appearance::fit_for_appearance`])
    /// with a derivative-free search on the judge's own metric, the mean
    /// HDR-FLIP of the renders ([`crate::flip_polish`]): a lower image
    /// error for a few seconds more. Off by default; other fits ignore it.
    pub fn polish_on_flip(mut self, on: bool) -> Self {
        self.flip_polish = on;
        self
    }

    /// Whether [`Fit::polish_on_flip`] is set.
    pub fn polishes_on_flip(&self) -> bool {
        self.flip_polish
    }

    /// Objective and metric (default Ngan).
    pub fn objective(mut self, objective: Objective) -> Self {
        self.options.objective = objective;
        self
    }

    /// The image objective's target (data rendered under the light sets;
    /// see [`crate::appearance`]); used with [`Objective::Image`].
    pub fn image_target(
        mut self,
        target: std::sync::Arc<crate::image_objective::ImageTarget>,
    ) -> Self {
        self.options.image = Some(target);
        self
    }

    /// Whether the fit is in the image objective without a target yet (a
    /// front end's `--metric image`: [`crate::FitRequest`]
    /// makes the target and its start).
    pub(crate) fn needs_image_target(&self) -> bool {
        self.options.objective == Objective::Image && self.options.image.is_none()
    }

    /// Fit in a narrower box: parameters named `prefix` (or `prefix` and a
    /// lobe number) kept within `[lower, upper]`; `[0, 0]` switches a lobe
    /// off (a nested model).
    pub fn narrow(mut self, prefix: &str, lower: f64, upper: f64) -> Self {
        self.boxes.push((prefix.to_string(), lower, upper));
        self
    }

    /// Solver (default Auto).
    pub fn solver(mut self, solver: Solver) -> Self {
        self.options.solver = solver;
        self
    }

    /// Multi-start count (default 12); 0 is refused by [`Fit::run`].
    pub fn starts(mut self, starts: usize) -> Self {
        self.options.starts = starts;
        self
    }

    /// Reweighting cap of a robust (IRLS) fit (default
    /// [`IRLS_MAX_ITERATIONS`](crate::options::IRLS_MAX_ITERATIONS); 50 is
    /// MATLAB's `robustfit`'s, which with
    /// [`Fit::irls_stop_on_cycle`]`(false)` is MATLAB's loop); 0 is
    /// refused by [`Fit::run`].
    pub fn irls_max_iterations(mut self, cap: usize) -> Self {
        self.options.irls_max_iterations = cap;
        self
    }

    /// Whether a robust (IRLS) fit whose reweighting cycles stops when a
    /// weighted solution recurs (default true) or runs to its cap, as
    /// MATLAB's `robustfit` does.
    pub fn irls_stop_on_cycle(mut self, on: bool) -> Self {
        self.options.irls_stop_on_cycle = on;
        self
    }

    /// Angle limit in degrees, in `(0, 90]` (default 80).
    pub fn limit_deg(mut self, limit: f64) -> Self {
        self.limit_deg = limit;
        self
    }

    /// Channels (default All).
    pub fn channels(mut self, channels: Channels) -> Self {
        self.channels = channels;
        self
    }

    /// Specular lobes (Lafortune, Cook-Torrance) (default 1).
    pub fn lobes(mut self, lobes: usize) -> Self {
        self.config.lobes = lobes;
        self
    }

    /// Koenderink order (default 8).
    pub fn order(mut self, order: usize) -> Self {
        self.config.order = order;
        self
    }

    /// Kurt's polynomial degree (default 7).
    pub fn degree(mut self, degree: usize) -> Self {
        self.config.degree = degree;
        self
    }

    /// Solver options of the non-linear stages.
    pub fn lm_options(mut self, lm: brdf_solve::LmOptions) -> Self {
        self.options.lm = lm;
        self
    }

    /// Tolerance of the multi-start search (default 1e-7); the best start
    /// is polished to the solver options' own tolerances
    /// ([`FitOptions::search_tolerance`](crate::FitOptions)).
    pub fn search_tolerance(mut self, tolerance: f64) -> Self {
        self.options.search_tolerance = tolerance;
        self
    }

    /// The fit as the start of another: its best start solved to the
    /// search's tolerance ([`Fit::search_tolerance`]) and not polished
    /// further. The appearance pipeline's candidates of a fitted-data
    /// model are such starts: each is refined in the image objective,
    /// whose few iterations begin where the candidate's basin is, not at
    /// its last digits.
    pub fn as_start(mut self) -> Self {
        self.options.lm = self.options.search_lm();
        self
    }

    /// The catalogue name of the model.
    pub fn model_name(&self) -> &'static str {
        self.entry.name
    }

    /// The parameters (names, boxes, defaults) of this fit's model at its
    /// configuration, before any [`Fit::narrow`].
    pub fn param_specs(&self) -> Result<Vec<brdf_core::ParamSpec>, FitError> {
        Ok((self.entry.build)(&self.config)?.param_specs().to_vec())
    }

    /// Filter `samples` (invalid values, the angle limit), build the model
    /// for them and fit it.
    pub fn run(&self, samples: &SampleSet) -> Result<FitReport, FitError> {
        self.check_options()?;
        let present = samples.len();
        let (data, invalid) = samples.filter_invalid(false);
        let (data, angle) = data.filter_angle_limit(self.limit_deg.to_radians());
        let data = match self.channels {
            Channels::All => data,
            Channels::Grey => data.mean_channel(),
        };
        if data.is_empty() {
            return Err(FitError::NoSampleLeft {
                data: samples.name.clone(),
                present,
                invalid: invalid.dropped(),
                beyond: angle.dropped(),
                limit_deg: self.limit_deg,
            });
        }
        let config = ModelConfig {
            channels: data.channels(),
            ..self.config
        };
        let mut notes = Vec::new();
        if 2 * angle.dropped() > present {
            notes.push(format!(
                "{} of {present} samples are beyond the {} deg limit and were dropped",
                angle.dropped(),
                self.limit_deg
            ));
        }
        let options = self.options_for(&config, &mut notes)?;
        let model = self.build_model(&config, &data)?;
        // Parameters whose box is one value (a lobe switched off, its
        // companions): held, not pushed onto a bound by the fit.
        let held: Vec<String> = model
            .param_specs()
            .iter()
            .filter(|s| s.lower == s.upper)
            .map(|s| s.name.clone())
            .collect();
        let (model, summary, scale) = fit_scaled(model, &data, options.objective, |m, d, s| {
            self.fit_model(m, d, &config, &options, s)
        })?;
        let mut summary = summary;
        if !summary.ngan_l2.is_finite() {
            let m = crate::scaling::ngan_l2_rescaled(model.as_ref(), &data)?;
            summary.ngan_l2 = m.total;
            summary.ngan_l2_per_channel = m.per_channel;
        }
        if !scale.is_identity() {
            notes.push(scale.describe());
        }
        check_finite(&summary, &samples.name)?;
        notes.extend(bound_notes(&summary, &held));
        Ok(FitReport {
            model,
            config,
            summary,
            samples_present: present,
            dropped_invalid: invalid.dropped(),
            dropped_angle: angle.dropped(),
            limit_deg: self.limit_deg,
            channel_names: data.channel_names.clone(),
            notes,
            image_error: None,
            image_note: None,
            candidates: Vec::new(),
            pairs: data.pairs().clone(),
        })
    }

    /// Refuse options no fit can run with.
    fn check_options(&self) -> Result<(), FitError> {
        if !(self.limit_deg > 0.0 && self.limit_deg <= 90.0) {
            return Err(FitError::OutOfRange {
                option: "angle limit",
                value: self.limit_deg,
                range: "in (0, 90] degrees",
            });
        }
        if self.options.starts == 0 {
            return Err(FitError::ZeroCount {
                option: "starts",
                needs: "a fit needs at least one start",
            });
        }
        if self.options.irls_max_iterations == 0 {
            return Err(FitError::ZeroCount {
                option: "irls_max_iterations",
                needs: "a robust fit needs at least one reweighting",
            });
        }
        Ok(())
    }

    /// The model for `data` in this fit's boxes.
    fn build_model(
        &self,
        config: &ModelConfig,
        data: &SampleSet,
    ) -> Result<Box<dyn Parametric>, FitError> {
        let model = self.entry.build_from(config, data)?;
        if self.boxes.is_empty() {
            return Ok(model);
        }
        let boxes: Vec<(&str, f64, f64)> = self
            .boxes
            .iter()
            .map(|(p, l, u)| (p.as_str(), *l, *u))
            .collect();
        Ok(Box::new(BoxedModel::narrowed(model, &boxes)?))
    }

    /// The options of this fit for the model: the automatic solver of an
    /// all-linear model under the log objective (not a linear problem) is
    /// the bounded LM; the linear solvers asked for with it are an error.
    fn options_for(
        &self,
        config: &ModelConfig,
        notes: &mut Vec<String>,
    ) -> Result<FitOptions, FitError> {
        let mut options = self.options.clone();
        if !options.objective.is_transformed() {
            return Ok(options);
        }
        match options.solver {
            Solver::Ols | Solver::Irls(_) => Err(FitError::LinearSolverOnTransformed {
                model: self.entry.name.to_string(),
            }),
            Solver::Auto => {
                let probe = (self.entry.build)(config)?;
                if probe.param_specs().iter().all(|s| s.linear) {
                    options.solver = Solver::Lm;
                    notes.push(
                        "the log metric is not linear in the parameters: fitted by the bounded LM (not least squares)"
                            .into(),
                    );
                }
                Ok(options)
            }
            _ => Ok(options),
        }
    }

    /// Fit `model` (already built for the data, its linear boxes divided
    /// by `scale`, the data's value scale) to `data`.
    fn fit_model(
        &self,
        model: &mut dyn Parametric,
        data: &SampleSet,
        config: &ModelConfig,
        options: &FitOptions,
        scale: f64,
    ) -> Result<FitSummary, FitError> {
        if options.solver != Solver::Sopp {
            return fit(model, data, options);
        }
        let grey = self.entry.build_from(
            &ModelConfig {
                channels: 1,
                ..*config
            },
            &data.mean_channel(),
        )?;
        // The one-channel stage sees the same boxes as the full model.
        if scale != 1.0 {
            let mut grey = BoxedModel::scaled(grey, scale);
            fit_sopp(&mut grey, model, data, options)
        } else {
            let mut grey = grey;
            fit_sopp(grey.as_mut(), model, data, options)
        }
    }
}

/// A fit whose error is not finite is not a result: an error naming the
/// data and the model (never a success with `"error": null`).
fn check_finite(summary: &FitSummary, data: &str) -> Result<(), FitError> {
    let bad = |what: &str, v: f64| {
        Err(FitError::NonFinite {
            data: data.to_string(),
            model: summary.model.clone(),
            what: what.to_string(),
            value: v,
        })
    };
    if !summary.error.is_finite() {
        return bad("error", summary.error);
    }
    if !summary.ngan_l2.is_finite() {
        return bad("Ngan L2", summary.ngan_l2);
    }
    if let Some(p) = summary.parameters.iter().find(|p| !p.value.is_finite()) {
        return bad(&format!("parameter `{}`", p.name), p.value);
    }
    Ok(())
}

/// The notes on parameters a fit left on a bound of their box, or held
/// (`held`: their box is one value).
fn bound_notes(summary: &FitSummary, held: &[String]) -> Vec<String> {
    let mut notes = Vec::new();
    for fp in &summary.parameters {
        let value = brdf_io::error::short(fp.value);
        if held.contains(&fp.name) {
            notes.push(format!(
                "`{}` = {value} is held there (its box is that value)",
                fp.name
            ));
        } else if let Some(b) = &fp.at_bound {
            notes.push(format!(
                "`{}` = {value} sits on the {b} bound of its box",
                fp.name
            ));
        }
    }
    notes
}

impl FitReport {
    /// The saved form of the fitted model, with structured provenance;
    /// `data` names the data set (relative to `BRDF_DATA` where possible).
    pub fn saved_model(&self, data: &str) -> Result<SavedModel, FitError> {
        let provenance = Provenance {
            data: data.to_string(),
            samples_used: self.summary.samples,
            samples_present: self.samples_present,
            objective: self.summary.objective.to_string(),
            limit_deg: self.limit_deg,
            error: self.summary.error,
            solver: self.summary.solver.clone(),
            software: format!("brdf-fit {}", env!("CARGO_PKG_VERSION")),
            image_error: self.image_error.as_ref().map_or_else(Vec::new, |e| {
                e.lights
                    .iter()
                    .map(|l| RenderedError {
                        light: l.light.clone(),
                        flip: l.flip,
                        psnr: l.psnr,
                        delta_e: l.delta_e,
                    })
                    .collect()
            }),
            termination: Some(SavedTermination {
                converged: self.summary.termination.is_converged(),
                reason: self.summary.termination.to_string(),
            }),
        };
        Ok(SavedModel::capture(
            self.model.as_ref(),
            &self.config,
            &self.pairs,
            Some(&self.summary.parameters),
            &self.channel_names,
            provenance,
        )?)
    }
}
