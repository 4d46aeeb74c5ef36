//! `brdf fit`: fit a model to a data set and report parameters, error and time.

use brdf_models::{ModelConfig, entry};

use crate::StudyError;
use crate::cli::ModelOpts;
use crate::fit::fit_linear;

/// Arguments of `brdf fit`.
#[derive(Debug, clap::Args)]
pub struct FitArgs {
    /// Data set: `PATH` or `PATH#SAMPLE` (e.g. `$BRDF_DATA/curet/abrdf.dat#25`).
    #[arg(long)]
    pub data: String,
    /// Model name (see `brdf models`).
    #[arg(long)]
    pub model: String,
    /// Drop samples with theta_i or theta_o above this angle (degrees).
    #[arg(long, default_value_t = 80.0)]
    pub limit: f64,
    /// Machine-readable output.
    #[arg(long)]
    pub json: bool,
    /// Structural options (degree, order, lobes).
    #[command(flatten)]
    pub model_opts: ModelOpts,
}

/// Run `brdf fit`.
pub fn run(args: &FitArgs) -> Result<(), StudyError> {
    if !(args.limit > 0.0 && args.limit <= 90.0) {
        return Err(StudyError::Usage(format!(
            "--limit {} must be in (0, 90] degrees",
            args.limit
        )));
    }
    let data = crate::data::load(&args.data)?;
    let (data, invalid) = data.filter_invalid(false);
    let (data, angle) = data.filter_angle_limit(args.limit.to_radians());
    let e = entry(&args.model)
        .ok_or_else(|| StudyError::Usage(format!("no such model `{}`", args.model)))?;
    let config = ModelConfig {
        channels: data.channels(),
        ..args.model_opts.config()
    };
    let mut model = match e.build_for_data {
        Some(f) => f(&config, data.pairs())?,
        None => (e.build)(&config)?,
    };
    let report = fit_linear(model.as_mut(), &data)?;
    if args.json {
        let v = serde_json::json!({
            "fit": report,
            "dropped_invalid": invalid.dropped(),
            "dropped_angle": angle.dropped(),
            "negative_values_kept": data.count_negative(),
        });
        println!("{}", serde_json::to_string_pretty(&v)?);
    } else {
        println!(
            "model {} on {} ({} samples; dropped {} invalid, {} beyond {} deg)",
            report.model,
            report.data,
            report.samples,
            invalid.dropped(),
            angle.dropped(),
            args.limit
        );
        println!("solver: {}, rank {}", report.solver, report.rank);
        for (name, v) in &report.parameters {
            println!("  {name:<8} {v:.6e}");
        }
        println!(
            "Ngan L2: {:.6}  time: {:.3} ms",
            report.ngan_l2,
            report.seconds * 1e3
        );
    }
    Ok(())
}
