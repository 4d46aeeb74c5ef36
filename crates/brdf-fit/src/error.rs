//! The error type of `brdf-fit`: every lower crate's error, plus invalid
//! requests (an unknown model, an option out of range, a model that does
//! not fit the data), one variant per kind, each with a one-line message
//! that names the option or parameter and what to do.

use thiserror::Error;

/// Errors of fitting, selecting, saving and loading models.
#[derive(Debug, Error)]
pub enum FitError {
    /// A name that is not one of an option's choices.
    #[error("unknown {option} `{value}`: {choices}")]
    UnknownChoice {
        /// the option (`metric`, `solver`)
        option: &'static str,
        /// the value given
        value: String,
        /// the choices, in words
        choices: &'static str,
    },
    /// An option's value is not of the form it takes.
    #[error("{option} {value}: expected {expected}")]
    InvalidOption {
        /// the option
        option: &'static str,
        /// the value given
        value: String,
        /// what it takes
        expected: &'static str,
    },
    /// A number outside its option's range.
    #[error("{option} {value} must be {range}")]
    OutOfRange {
        /// the option
        option: &'static str,
        /// the value given
        value: f64,
        /// the range, in words
        range: &'static str,
    },
    /// A count that must be at least 1 is 0.
    #[error("{option} = 0: {needs}")]
    ZeroCount {
        /// the option
        option: &'static str,
        /// why it needs one
        needs: &'static str,
    },
    /// No catalogue model has the name.
    #[error("{}", unknown_model(name, suggestions))]
    UnknownModel {
        /// the name given
        name: String,
        /// close catalogue names
        suggestions: Vec<String>,
    },
    /// The model's channels are not the data's.
    #[error("model `{model}` has {model_channels} channels, data `{data}` has {data_channels}")]
    ChannelMismatch {
        /// the model
        model: String,
        /// its channels
        model_channels: usize,
        /// the data set
        data: String,
        /// its channels
        data_channels: usize,
    },
    /// Fewer numbers than the model has parameters.
    #[error(
        "{samples} samples x {channels} channels are not more than the {parameters} parameters of `{model}`"
    )]
    TooFewSamples {
        /// samples
        samples: usize,
        /// channels
        channels: usize,
        /// the model's parameters
        parameters: usize,
        /// the model
        model: String,
    },
    /// Filtering left no sample.
    #[error(
        "`{data}`: no sample is left of {present} after dropping {invalid} invalid and {beyond} beyond {limit_deg} deg"
    )]
    NoSampleLeft {
        /// the data set
        data: String,
        /// samples present
        present: usize,
        /// invalid samples dropped
        invalid: usize,
        /// samples beyond the angle limit
        beyond: usize,
        /// the angle limit in degrees
        limit_deg: f64,
    },
    /// A linear solver asked for a model with a non-linear parameter.
    #[error(
        "--solver ols/irls need an all-linear model; `{model}` has the non-linear parameter `{parameter}`"
    )]
    NeedsAllLinear {
        /// the model
        model: String,
        /// its first non-linear parameter
        parameter: String,
    },
    /// A linear solver asked for an objective that transforms the residual.
    #[error(
        "--solver ols/irls solve linear least squares; the log metric is not linear in `{model}`'s parameters: use --solver auto, sqp or lm"
    )]
    LinearSolverOnTransformed {
        /// the model
        model: String,
    },
    /// Sopp's procedure asked of [`crate::pipeline::fit`].
    #[error("Sopp's two-stage procedure needs a one-channel model for stage 1: use fit_sopp")]
    SoppNeedsGreyModel,
    /// The image objective without data that can be rendered.
    #[error(
        "the image objective needs data that can be evaluated at any direction pair (RGL `.bsdf`, MERL `.binary`): use --metric cube-root or log for scattered data"
    )]
    NeedsDenseData,
    /// An image-objective start of the wrong length.
    #[error("image objective: a start of {given} parameters for `{model}` with {parameters}")]
    StartLength {
        /// the start's length
        given: usize,
        /// the model
        model: String,
        /// its parameters
        parameters: usize,
    },
    /// Image-objective terms or targets that do not fit together.
    #[error("{0}")]
    ImageTerms(String),
    /// A model without channels.
    #[error("a model without channels")]
    NoChannels,
    /// An appearance fit without a candidate.
    #[error("no candidate fit")]
    NoCandidate,
    /// No candidate of a selection could be fitted.
    #[error("`{data}`: no candidate could be fitted ({why})")]
    NoCandidateFitted {
        /// the data set
        data: String,
        /// the first candidate's failure, or why there was none
        why: String,
    },
    /// The chosen candidate of a selection kept no model.
    #[error("`{data}`: the chosen candidate {label} kept no model")]
    ChoiceWithoutModel {
        /// the data set
        data: String,
        /// the candidate
        label: String,
    },
    /// Selection by image error without a model.
    #[error("select by image: no model to fit")]
    NoModelToFit,
    /// A fit of renderable data without image errors.
    #[error("`{data}`: the fit has no image error")]
    NoImageError {
        /// the data set
        data: String,
    },
    /// Saving or reporting a fit that gave one model per channel.
    #[error(
        "{models} models were fitted (one per channel): saving or reporting needs one model; fit with channels rgb or grey"
    )]
    NeedsOneModel {
        /// how many models the fit gave
        models: usize,
    },
    /// Data named by a folder where one file is fitted.
    #[error("`{spec}` is a folder: fit one file, or `brdf batch --data {spec}`")]
    FolderGiven {
        /// the spec given
        spec: String,
    },
    /// A request for image errors of data that cannot be rendered.
    #[error(
        "`{data}` holds scattered samples that cannot be rendered; use RGL `.bsdf` or MERL `.binary` data"
    )]
    NotRenderable {
        /// the data set
        data: String,
    },
    /// A polish on a fit that is not for appearance.
    #[error(
        "polish refines a fit for appearance, which `{model}` with metric {metric} on {data} is not: use a renderer model (principled, gltf, gltf-ext, ggx) or metric appearance on RGL `.bsdf` or MERL `.binary` data"
    )]
    PolishNeedsAppearance {
        /// the model
        model: String,
        /// the metric asked for
        metric: &'static str,
        /// the data set
        data: String,
    },
    /// A report without a fit.
    #[error("`{data}`: no fit to report")]
    NoFit {
        /// the data set
        data: String,
    },
    /// A selection report without a chosen candidate.
    #[error("`{data}`: no candidate chosen")]
    NoChoice {
        /// the data set
        data: String,
    },
    /// Scattered data asked onto a grid.
    #[error(
        "{from}: scattered data cannot be resampled onto a grid without an interpolation; use --to csv, or fit a model and resample the saved model"
    )]
    ScatteredToGrid {
        /// the data
        from: String,
    },
    /// A parameter was impossible.
    #[error(transparent)]
    Param(#[from] brdf_core::ParamError),
    /// A core value could not be built.
    #[error(transparent)]
    Core(#[from] brdf_core::CoreError),
    /// Reading data failed.
    #[error(transparent)]
    Data(#[from] brdf_io::IoError),
    /// A saved model could not be read.
    #[error(transparent)]
    SavedModel(#[from] brdf_models::saved_model::SavedModelError),
    /// Rendering or judging a fit failed.
    #[error(transparent)]
    Render(#[from] brdf_render::RenderError),
    /// A solver was misused or given impossible input.
    #[error(transparent)]
    Solve(#[from] brdf_solve::SolveError),
    /// A saved model could not be read or written as JSON.
    #[error("{path}: {reason}")]
    Json {
        /// the file
        path: String,
        /// what serde_json reported
        reason: String,
    },
    /// A fit ended without a finite result.
    #[error(
        "{data}: the fit of `{model}` ended with a non-finite {what} ({value}); the data may be out of any representable range"
    )]
    NonFinite {
        /// the data set
        data: String,
        /// the model
        model: String,
        /// what is not finite
        what: String,
        /// its value
        value: f64,
    },
    /// Reading or writing a file failed.
    #[error("{path}: {source}")]
    Io {
        /// file or folder
        path: String,
        /// the underlying error
        source: std::io::Error,
    },
}

/// The message of [`FitError::UnknownModel`].
fn unknown_model(name: &str, suggestions: &[String]) -> String {
    if suggestions.is_empty() {
        format!("no model `{name}`; `brdf models` lists them")
    } else {
        let quoted: Vec<String> = suggestions.iter().map(|s| format!("`{s}`")).collect();
        format!("no model `{name}`; did you mean {}?", quoted.join(", "))
    }
}
