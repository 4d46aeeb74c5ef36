//! `brdf export --from MODEL.json --to mitsuba|pbrt|gltf|materialx OUT`:
//! write a saved model as a renderer's material, a thin layer over
//! [`brdf_export`]. Exact where the target has the model's equivalent;
//! otherwise converted by fitting a model the target has (`--via` names
//! it), with the conversion error printed and written into the file;
//! `--exact` refuses conversions.

use std::path::PathBuf;

use brdf_export::file::ExportJob;
use brdf_export::{ConvertOptions, Exported, Target};

use crate::error::CliError;

/// Arguments of `brdf export`.
#[derive(Debug, clap::Args)]
pub struct ExportArgs {
    /// A model saved by `brdf fit --save` (`.json`).
    #[arg(long)]
    pub from: PathBuf,
    /// Target: mitsuba, pbrt, gltf or materialx.
    #[arg(long)]
    pub to: String,
    /// Output file.
    pub out: PathBuf,
    /// Refuse to convert: fail where the target has no exact equivalent.
    #[arg(long)]
    pub exact: bool,
    /// The target's model to fit when converting (default: principled for
    /// Mitsuba, ggx-dielectric for pbrt, gltf for glTF and MaterialX).
    #[arg(long)]
    pub via: Option<String>,
    /// Direction pairs sampled from the model when converting.
    #[arg(long, default_value_t = 2048)]
    pub pairs: usize,
    /// Largest theta_i, theta_o (degrees) sampled when converting.
    #[arg(long, default_value_t = 80.0)]
    pub limit: f64,
    /// Multi-start count of the conversion fit.
    #[arg(long, default_value_t = 12)]
    pub starts: usize,
    /// Also save the converted model (the material written) here.
    #[arg(long)]
    pub save_converted: Option<PathBuf>,
    /// Machine-readable output.
    #[arg(long)]
    pub json: bool,
}

/// Run `brdf export`.
pub fn run(args: &ExportArgs) -> Result<(), CliError> {
    let job = ExportJob {
        from: args.from.clone(),
        target: args.to.parse()?,
        out: args.out.clone(),
        exact: args.exact,
        convert: ConvertOptions {
            via: args.via.clone(),
            pairs: args.pairs,
            limit_deg: args.limit,
            starts: args.starts,
        },
        save_converted: args.save_converted.clone(),
    };
    let done = brdf_export::file::run(&job)?;
    report(args, &done.model, job.target, &done.exported)
}

fn report(
    args: &ExportArgs,
    model: &str,
    target: Target,
    exported: &Exported,
) -> Result<(), CliError> {
    let out = args.out.display();
    if args.json {
        let conversion = exported.conversion.as_ref().map(|c| {
            serde_json::json!({
                "via": c.model.name(),
                "samples": c.error.samples,
                "limit_deg": c.error.limit_deg,
                "ngan_l2": c.error.ngan_l2,
                "relative_l2": c.error.relative_l2,
            })
        });
        let v = serde_json::json!({
            "model": model, "target": target.to_string(), "out": out.to_string(),
            "exact": exported.conversion.is_none(), "conversion": conversion,
        });
        return say!("{}", serde_json::to_string_pretty(&v)?);
    }
    match &exported.conversion {
        None => say!("wrote {out}: `{model}` exactly as {target}"),
        Some(c) => say!("wrote {out}: {}", c.note()),
    }
}
