//! Command-line definition (clap derive): the subcommands, one per file
//! in `commands/`. This module knows the commands; no command imports it.

use clap::{Parser, Subcommand};

/// Fit analytic BRDF models to measured reflectance data, and reproduce the
/// Kurt (2007) and Sopp (2017) studies.
#[derive(Debug, Parser)]
#[command(name = "brdf", version, about)]
pub struct Cli {
    /// Render measured data for the image errors every time instead of
    /// reading the renders kept in the cache folder (`BRDF_CACHE_DIR`, else
    /// the platform's cache folder under `brdf-fit/judge`).
    #[arg(long, global = true)]
    pub no_cache: bool,
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
    /// Write a saved model as a renderer's material (`--to` lists the targets).
    Export(crate::commands::export::ExportArgs),
    /// Render a labelled sphere of a saved model, dense data, or both side by side.
    Render(crate::commands::render::RenderArgs),
    /// Write a self-contained HTML report of a fit, or of a batch of fits.
    Report(crate::commands::report::ReportArgs),
    /// Run the study and write its tables and figures into `results/`.
    Reproduce(crate::commands::reproduce::ReproduceArgs),
}
