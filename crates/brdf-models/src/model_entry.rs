//! What the catalogue holds of each model: its [`ModelEntry`] (name,
//! constructors, facts) and the structural [`ModelConfig`] it is built
//! at. Kept apart from the catalogue's table so a model family can
//! describe its own entries without importing the table that lists them.

use brdf_core::{DirPairs, ParamError, Parametric, SampleSet};

use crate::entry_facts::{
    ColourStructure, LinearSolver, NonlinearSearch, OptionalLobe, RendererForm,
};

/// Structural options of a model (not parameters: they fix the parameter
/// vector's length).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ModelConfig {
    /// Colour channels (1 grey, 3 RGB).
    pub channels: usize,
    /// Specular lobes (Lafortune, Cook-Torrance).
    pub lobes: usize,
    /// Expansion order (Koenderink).
    pub order: usize,
    /// Polynomial degree (Kurt).
    pub degree: usize,
}

impl Default for ModelConfig {
    fn default() -> Self {
        ModelConfig {
            channels: 1,
            lobes: 1,
            order: 8,
            degree: 7,
        }
    }
}

/// Constructor of a model whose structure depends on the data.
pub type BuildForData = fn(&ModelConfig, &DirPairs) -> Result<Box<dyn Parametric>, ParamError>;

/// Constructor of a model built from the samples it will be fitted to: its
/// structure is read off the measured values (Dupuy et al.'s normal
/// distribution, extracted from the back-scattering samples), its free
/// parameters are then fitted.
pub type BuildFromSamples = fn(&ModelConfig, &SampleSet) -> Result<Box<dyn Parametric>, ParamError>;

/// Start points a model proposes for its fit to the samples, beside the
/// pipeline's own (full parameter vectors inside the box, for the model as
/// built: the pipeline takes their non-linear entries). Most models read
/// only their own structure; a thin film scans its thickness on the data.
pub type SuggestStarts = fn(&dyn Parametric, &SampleSet) -> Vec<Vec<f64>>;

/// Constructor of a one-channel model equivalent to one channel of a
/// model whose channels share nothing ([`ModelEntry::channel_model`]).
pub type ChannelModel = fn() -> Result<Box<dyn Parametric>, ParamError>;

/// A catalogue entry.
#[derive(Clone, Copy)]
pub struct ModelEntry {
    /// Name used on the command line and in saved models.
    pub name: &'static str,
    /// Model family (as the Cargo feature that provides it).
    pub family: &'static str,
    /// One-line summary.
    pub summary: &'static str,
    /// The paper the formula comes from.
    pub paper: &'static str,
    /// Whether the `lobes` option applies.
    pub has_lobes: bool,
    /// Build the model at its default parameters.
    pub build: fn(&ModelConfig) -> Result<Box<dyn Parametric>, ParamError>,
    /// Build the model for a given set of direction pairs, for models whose
    /// structure depends on the data (Kurt's polynomial: its PCA transform).
    /// `None`: the data do not matter, use `build`.
    pub build_for_data: Option<BuildForData>,
    /// Build the model from the samples it will be fitted to, for models
    /// whose structure is read off the measured values (Dupuy's tabulated
    /// normal distribution). `None`: [`ModelEntry::build_for`] serves.
    pub from_samples: Option<BuildFromSamples>,
    /// Start points the model suggests for its fit (Bagher's SGD, whose
    /// shadowing term switches the lobe off from most points of its box).
    pub starts: Option<SuggestStarts>,
    /// Multiple of the solver's iteration cap the final polish of a fit
    /// may take (1 for most models). Bagher's SGD crawls along a narrow
    /// valley (`ks` against `F0`, whose grazing term `(1 - V.H)^5` few
    /// pairs see): on synthetic data its best start needed about 2000
    /// iterations to converge, past the pipeline's cap of 300.
    pub polish_factor: usize,
    /// One channel of the model as a one-channel model of its own, for
    /// models whose channels share no parameter (Bagher's SGD): its
    /// parameters are a channel's block in the model's order, and it
    /// evaluates that channel alone, in batch, where slicing the model
    /// ([`ChannelSlice`](crate::channel_slice::ChannelSlice)) evaluates
    /// every channel per direction pair. `None`: the slice evaluates.
    pub channel_model: Option<ChannelModel>,
    /// Whether renderers offer the model (principled, glTF, the GGX
    /// family): front ends fit it for appearance by default.
    pub renderer: bool,
    /// The model's place among those selection by image error (`brdf
    /// select --by-image`) chooses among, one per kind of renderer model
    /// (the order of its rows; [`crate::catalogue::by_image_models`]); `None`: not among
    /// them.
    pub by_image_rank: Option<u8>,
    /// How the model colours its lobes.
    pub colour: ColourStructure,
    /// Lobes the model may switch off, in the order a fit tries them.
    pub optional_lobes: &'static [OptionalLobe],
    /// How the model is solved by default when all its parameters are
    /// linear.
    pub linear_solver: LinearSolver,
    /// How its non-linear parameters are searched by default.
    pub nonlinear_search: NonlinearSearch,
    /// The renderer material its formula is, which its exporters write.
    pub form: RendererForm,
}

impl ModelEntry {
    /// Build the model for the direction pairs it will be fitted at: through
    /// `build_for_data` where the structure depends on the data (Kurt's
    /// polynomial), `build` otherwise.
    pub fn build_for(
        &self,
        config: &ModelConfig,
        pairs: &DirPairs,
    ) -> Result<Box<dyn Parametric>, ParamError> {
        match self.build_for_data {
            Some(f) => f(config, pairs),
            None => (self.build)(config),
        }
    }
}

impl ModelEntry {
    /// Build the model for the samples it will be fitted to: through
    /// `from_samples` where the model is read off the data (Dupuy), else
    /// [`ModelEntry::build_for`] on their direction pairs. `config.channels`
    /// must be the samples' channel count for a model read off them.
    pub fn build_from(
        &self,
        config: &ModelConfig,
        samples: &SampleSet,
    ) -> Result<Box<dyn Parametric>, ParamError> {
        match self.from_samples {
            Some(f) => f(config, samples),
            None => self.build_for(config, samples.pairs()),
        }
    }

    /// Whether the model depends on the data it is fitted to (its
    /// direction pairs or its values).
    pub fn is_data_dependent(&self) -> bool {
        self.build_for_data.is_some() || self.from_samples.is_some()
    }
}

impl std::fmt::Debug for ModelEntry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ModelEntry")
            .field("name", &self.name)
            .finish()
    }
}
