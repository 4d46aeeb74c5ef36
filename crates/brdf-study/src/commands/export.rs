//! `brdf export --from MODEL.json --to mitsuba|pbrt|gltf|materialx OUT`:
//! write a saved model as a renderer's material, a thin layer over
//! [`brdf_export`]. Exact where the target has the model's equivalent;
//! otherwise converted by fitting a model the target has (`--via` names
//! it), with the conversion error printed and written into the file;
//! `--exact` refuses conversions.

use std::path::{Path, PathBuf};

use brdf_export::{ConvertOptions, Exported, Target, export, export_or_convert};
use brdf_models::saved_model::{Provenance, SavedModel};

use crate::StudyError;

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
pub fn run(args: &ExportArgs) -> Result<(), StudyError> {
    let target: Target = args.to.parse()?;
    let saved = SavedModel::load(&args.from)?;
    let model = saved
        .build()
        .map_err(|e| StudyError::Usage(format!("{}: {e}", args.from.display())))?;
    let exported = if args.exact {
        Exported {
            text: export(model.as_ref(), target)?,
            conversion: None,
        }
    } else {
        let opts = ConvertOptions {
            via: args.via.clone(),
            pairs: args.pairs,
            limit_deg: args.limit,
            starts: args.starts,
        };
        export_or_convert(model.as_ref(), target, &opts)?
    };
    match (&exported.conversion, &args.save_converted) {
        (Some(c), Some(path)) => save_converted(c, &saved, path)?,
        (None, Some(_)) => {
            return Err(StudyError::Usage(format!(
                "--save-converted: `{}` is written to {target} exactly, nothing was converted",
                saved.model
            )));
        }
        _ => {}
    }
    std::fs::write(&args.out, &exported.text).map_err(|source| StudyError::Io {
        path: args.out.display().to_string(),
        source,
    })?;
    report(args, &saved.model, target, &exported)
}

fn report(
    args: &ExportArgs,
    model: &str,
    target: Target,
    exported: &Exported,
) -> Result<(), StudyError> {
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

fn save_converted(
    c: &brdf_export::Conversion,
    source: &SavedModel,
    path: &Path,
) -> Result<(), StudyError> {
    let channel_names: Vec<String> = match c.model.channels() {
        1 => vec!["grey".into()],
        _ => vec!["r".into(), "g".into(), "b".into()],
    };
    let provenance = Provenance {
        data: source.provenance.data.clone(),
        samples_used: c.error.samples,
        samples_present: c.error.samples,
        objective: "ngan".into(),
        limit_deg: c.error.limit_deg,
        error: c.error.ngan_l2,
        solver: format!("conversion by fitting from `{}`", c.source),
        software: format!("brdf-export {}", env!("CARGO_PKG_VERSION")),
    };
    SavedModel::capture(
        c.model.as_ref(),
        &c.config,
        &c.pairs,
        None,
        &channel_names,
        provenance,
    )?
    .save(path)?;
    Ok(())
}
