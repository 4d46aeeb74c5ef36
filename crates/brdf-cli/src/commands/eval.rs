//! `brdf eval`: a model's value per channel at one direction pair.

use brdf_core::params::assign_by_name;
use serde::Serialize;

use crate::error::CliError;
use crate::opts::{ModelOpts, parse_assignments, parse_direction};

/// Arguments of `brdf eval`.
#[derive(Debug, clap::Args)]
pub struct EvalArgs {
    /// Model name (see `brdf models`); not needed with --load.
    #[arg(long, default_value = "")]
    pub model: String,
    /// Evaluate a model saved by `brdf fit --save FILE`.
    #[arg(long)]
    pub load: Option<std::path::PathBuf>,
    /// Parameters as `name=value,...`; unnamed ones take their defaults.
    #[arg(long, default_value = "")]
    pub params: String,
    /// Incident direction `THETA,PHI` (radians unless --degrees).
    #[arg(long, allow_hyphen_values = true)]
    pub wi: String,
    /// Outgoing direction `THETA,PHI` (radians unless --degrees).
    #[arg(long, allow_hyphen_values = true)]
    pub wo: String,
    /// Angles are in degrees.
    #[arg(long)]
    pub degrees: bool,
    /// Machine-readable output.
    #[arg(long)]
    pub json: bool,
    /// Structural options.
    #[command(flatten)]
    pub model_opts: ModelOpts,
}

#[derive(Serialize)]
struct EvalOut {
    model: String,
    parameters: Vec<(String, f64)>,
    wi: [f64; 3],
    wo: [f64; 3],
    channels: Vec<f64>,
}

/// Without `--degrees`, a polar angle above pi/2 is almost surely degrees
/// typed without the flag: refuse it rather than wrap it around.
fn check_radians(s: &str, degrees: bool, what: &str) -> Result<(), CliError> {
    if degrees {
        return Ok(());
    }
    let theta = s.split(',').next().map(str::trim).unwrap_or_default();
    match theta.parse::<f64>() {
        Ok(t) if t.abs() > std::f64::consts::FRAC_PI_2 => Err(CliError::Usage(format!(
            "`{what} {s}`: {theta} is not an angle in radians (> pi/2); add --degrees"
        ))),
        _ => Ok(()),
    }
}

/// Run `brdf eval`.
pub fn run(args: &EvalArgs) -> Result<(), CliError> {
    let (model, values) = match &args.load {
        Some(path) => {
            let m = brdf_models::saved_model::SavedModel::load(path)?.build()?;
            let v = m.params().to_vec();
            (m, v)
        }
        None => {
            if args.model.is_empty() {
                return Err(CliError::Usage("give --model NAME or --load FILE".into()));
            }
            // Forgiving names ("Blinn-Phong", "blinn_phong"), with a
            // suggestion for a misspelt one: the same resolver as `fit`.
            let name = brdf_fit::resolve(&args.model)?.name;
            let mut m = brdf_models::build(name, &args.model_opts.config())?;
            let v = assign_by_name(name, m.param_specs(), &parse_assignments(&args.params)?)?;
            m.set_params(&v)?;
            (m, v)
        }
    };
    check_radians(&args.wi, args.degrees, "--wi")?;
    check_radians(&args.wo, args.degrees, "--wo")?;
    let wi = parse_direction(&args.wi, args.degrees, "--wi")?;
    let wo = parse_direction(&args.wo, args.degrees, "--wo")?;
    let mut f = vec![0.0; model.channels()];
    model.eval(wi.vector(), wo.vector(), &mut f);
    let out = EvalOut {
        model: model.name().to_string(),
        parameters: model
            .param_specs()
            .iter()
            .map(|s| s.name.clone())
            .zip(values.iter().copied())
            .collect(),
        wi: [wi.x, wi.y, wi.z],
        wo: [wo.x, wo.y, wo.z],
        channels: f.clone(),
    };
    if args.json {
        say!("{}", serde_json::to_string_pretty(&out)?)?;
    } else {
        for (i, v) in f.iter().enumerate() {
            say!("channel {i}: {v:.10e}")?;
        }
    }
    Ok(())
}
