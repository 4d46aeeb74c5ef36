//! `brdf models`: the catalogue with parameters, boxes and linear flags.

use serde::Serialize;

use crate::error::CliError;
use crate::opts::ModelOpts;

/// Arguments of `brdf models`.
#[derive(Debug, clap::Args)]
pub struct ModelsArgs {
    /// Machine-readable output.
    #[arg(long)]
    pub json: bool,
    /// Structural options the listing is built with.
    #[command(flatten)]
    pub model: ModelOpts,
}

#[derive(Serialize)]
struct ParamOut {
    name: String,
    meaning: String,
    lower: f64,
    upper: f64,
    lower_open: bool,
    linear: bool,
    default: f64,
}

#[derive(Serialize)]
struct ModelOut {
    name: &'static str,
    family: &'static str,
    summary: &'static str,
    paper: &'static str,
    reciprocal: bool,
    parameters: Vec<ParamOut>,
}

/// Run `brdf models`.
pub fn run(args: &ModelsArgs) -> Result<(), CliError> {
    let config = args.model.config();
    let mut out = Vec::new();
    for e in brdf_models::catalogue() {
        let m = (e.build)(&config)?;
        out.push(ModelOut {
            name: e.name,
            family: e.family,
            summary: e.summary,
            paper: e.paper,
            reciprocal: m.is_reciprocal(),
            parameters: m
                .param_specs()
                .iter()
                .map(|s| ParamOut {
                    name: s.name.clone(),
                    meaning: s.meaning.clone(),
                    lower: s.lower,
                    upper: s.upper,
                    lower_open: s.lower_open,
                    linear: s.linear,
                    default: s.default,
                })
                .collect(),
        });
    }
    if args.json {
        say!("{}", serde_json::to_string_pretty(&out)?)?;
        return Ok(());
    }
    for m in &out {
        say!("{} ({}): {}", m.name, m.family, m.summary)?;
        say!("  paper: {}", m.paper)?;
        for p in &m.parameters {
            say!(
                "  {:<10} {}{}, {}] {:<10} default {:<8} {}",
                p.name,
                if p.lower_open { '(' } else { '[' },
                p.lower,
                p.upper,
                if p.linear { "linear" } else { "non-linear" },
                p.default,
                p.meaning
            )?;
        }
    }
    Ok(())
}
