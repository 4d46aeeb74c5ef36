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
use brdf_models::saved_model::{Provenance, SavedModel};
use brdf_models::{ModelConfig, ModelEntry};

use crate::FitError;
use crate::names::resolve;
use crate::pipeline::{FitOptions, FitSummary, Objective, Solver, fit, fit_sopp};

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
        }
    }

    /// Objective and metric (default Ngan).
    pub fn objective(mut self, objective: Objective) -> Self {
        self.options.objective = objective;
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

    /// The catalogue name of the model.
    pub fn model_name(&self) -> &'static str {
        self.entry.name
    }

    /// Filter `samples` (invalid values, the angle limit), build the model
    /// for them and fit it.
    pub fn run(&self, samples: &SampleSet) -> Result<FitReport, FitError> {
        if !(self.limit_deg > 0.0 && self.limit_deg <= 90.0) {
            return Err(FitError::Usage(format!(
                "angle limit {} must be in (0, 90] degrees",
                self.limit_deg
            )));
        }
        if self.options.starts == 0 {
            return Err(FitError::Usage(
                "starts = 0: a fit needs at least one start".into(),
            ));
        }
        let present = samples.len();
        let (data, invalid) = samples.filter_invalid(false);
        let (data, angle) = data.filter_angle_limit(self.limit_deg.to_radians());
        let data = match self.channels {
            Channels::All => data,
            Channels::Grey => data.mean_channel(),
        };
        if data.is_empty() {
            return Err(FitError::Usage(format!(
                "`{}`: no sample is left of {present} after dropping {} invalid and {} beyond {} deg",
                samples.name,
                invalid.dropped(),
                angle.dropped(),
                self.limit_deg
            )));
        }
        let config = ModelConfig {
            channels: data.channels(),
            ..self.config
        };
        let mut model = self.entry.build_for(&config, data.pairs())?;
        let summary = if self.options.solver == Solver::Sopp {
            let mut grey = self.entry.build_for(
                &ModelConfig {
                    channels: 1,
                    ..config
                },
                data.pairs(),
            )?;
            fit_sopp(grey.as_mut(), model.as_mut(), &data, &self.options)?
        } else {
            fit(model.as_mut(), &data, &self.options)?
        };
        Ok(FitReport {
            model,
            config,
            summary,
            samples_present: present,
            dropped_invalid: invalid.dropped(),
            dropped_angle: angle.dropped(),
            limit_deg: self.limit_deg,
            channel_names: data.channel_names.clone(),
            pairs: data.pairs().clone(),
        })
    }
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
