//! `brdf eval`: a model's value per channel at one direction pair.

use brdf_core::{Direction, params::assign_by_name};
use serde::Serialize;

use crate::StudyError;
use crate::cli::ModelOpts;

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

/// Parse `name=value,name=value`.
pub fn parse_assignments(s: &str) -> Result<Vec<(String, f64)>, StudyError> {
    s.split(',')
        .map(str::trim)
        .filter(|t| !t.is_empty())
        .map(|t| {
            let (k, v) = t.split_once('=').ok_or_else(|| {
                StudyError::Usage(format!("parameter `{t}` is not of the form name=value"))
            })?;
            let x: f64 = v.trim().parse().map_err(|_| {
                StudyError::Usage(format!(
                    "parameter `{}`: `{}` is not a number",
                    k.trim(),
                    v.trim()
                ))
            })?;
            Ok((k.trim().to_string(), x))
        })
        .collect()
}

/// Parse `THETA,PHI` into a direction.
pub fn parse_direction(s: &str, degrees: bool, what: &str) -> Result<Direction, StudyError> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    if parts.len() != 2 {
        return Err(StudyError::Usage(format!("{what} `{s}` must be THETA,PHI")));
    }
    let mut a = [0.0f64; 2];
    for (i, p) in parts.iter().enumerate() {
        a[i] = p
            .parse()
            .map_err(|_| StudyError::Usage(format!("{what}: `{p}` is not a number")))?;
    }
    if degrees {
        a = [a[0].to_radians(), a[1].to_radians()];
    }
    Ok(Direction::from_spherical(a[0], a[1])?)
}

#[derive(Serialize)]
struct EvalOut {
    model: String,
    parameters: Vec<(String, f64)>,
    wi: [f64; 3],
    wo: [f64; 3],
    channels: Vec<f64>,
}

/// Run `brdf eval`.
pub fn run(args: &EvalArgs) -> Result<(), StudyError> {
    let (model, values) = match &args.load {
        Some(path) => {
            let m = crate::saved_model::SavedModel::load(path)?.build()?;
            let v = m.params().to_vec();
            (m, v)
        }
        None => {
            if args.model.is_empty() {
                return Err(StudyError::Usage("give --model NAME or --load FILE".into()));
            }
            let mut m = brdf_models::build(&args.model, &args.model_opts.config())?;
            let v = assign_by_name(
                &args.model,
                m.param_specs(),
                &parse_assignments(&args.params)?,
            )?;
            m.set_params(&v)?;
            (m, v)
        }
    };
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
