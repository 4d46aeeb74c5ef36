//! Command-line definition (clap derive). One subcommand per file in
//! `commands/`.

use clap::{Parser, Subcommand};

/// Fit analytic BRDF models to measured reflectance data, and reproduce the
/// Kurt (2007) and Sopp (2017) studies.
#[derive(Debug, Parser)]
#[command(name = "brdf", version, about)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// List the available models with their parameters, boxes and which are linear.
    Models(crate::commands::models::ModelsArgs),
    /// Evaluate a model at one direction pair.
    Eval(crate::commands::eval::EvalArgs),
    /// Fit any model to a data set (automatic starts, any objective).
    Fit(crate::commands::fit::FitArgs),
    /// Certify the solver on the NIST StRD non-linear regression problems.
    Nist(crate::commands::nist::NistArgs),
    /// Fit every material x model of a database (resumable, shardable).
    Batch(crate::commands::batch::BatchArgs),
    /// Fit the candidate models and choose the smallest adequate one.
    Select(crate::commands::select::SelectArgs),
    /// Describe a data file: format, samples, channels, invalid values, ranges.
    Info(crate::commands::info::InfoArgs),
    /// Convert data or a saved model to MERL, Sopp's grid or CSV samples.
    Resample(crate::commands::resample::ResampleArgs),
    /// Write a saved model as a Mitsuba 3, pbrt-v4, glTF or MaterialX material.
    Export(crate::commands::export::ExportArgs),
    /// Run the study and write its tables and figures into `results/`.
    Reproduce(crate::commands::reproduce::ReproduceArgs),
}

/// Structural options shared by every command that builds a model.
#[derive(Debug, Clone, clap::Args)]
pub struct ModelOpts {
    /// Colour channels of the model (1 grey, 3 RGB).
    #[arg(long, default_value_t = 1)]
    pub channels: usize,
    /// Specular lobes (Lafortune, Cook-Torrance).
    #[arg(long, default_value_t = 1)]
    pub lobes: usize,
    /// Koenderink expansion order.
    #[arg(long, default_value_t = 8)]
    pub order: usize,
    /// Polynomial degree (Kurt's model).
    #[arg(long, default_value_t = 7)]
    pub degree: usize,
}

impl ModelOpts {
    /// As a model configuration.
    pub fn config(&self) -> brdf_models::ModelConfig {
        brdf_models::ModelConfig {
            channels: self.channels,
            lobes: self.lobes,
            order: self.order,
            degree: self.degree,
        }
    }
}
