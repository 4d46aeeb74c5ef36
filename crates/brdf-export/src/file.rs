//! Export orchestration behind `brdf export`: read a saved model, write it
//! as a renderer's material (exactly, or converted by fitting a model the
//! target has), and optionally save the converted model beside it.

use std::path::{Path, PathBuf};

use brdf_models::saved_model::{Provenance, SavedModel, SavedModelError};
use thiserror::Error;

use crate::{
    Conversion, ConvertOptions, ExportError, Exported, Target, WriteOptions,
    export_or_convert_with, export_with, identifier,
};

/// What to export where.
#[derive(Clone, Debug)]
pub struct ExportJob {
    /// A model saved by `brdf fit --save` (`.json`).
    pub from: PathBuf,
    /// The target format.
    pub target: Target,
    /// The material file to write.
    pub out: PathBuf,
    /// Refuse to convert: fail where the target has no exact equivalent.
    pub exact: bool,
    /// How to convert when the target has no equivalent.
    pub convert: ConvertOptions,
    /// Also save the converted model (the material written) here.
    pub save_converted: Option<PathBuf>,
    /// The target's options; an empty `name` is the data's file stem
    /// (see [`material_name`]).
    pub write: WriteOptions,
}

/// The material's name for `saved`: its data's file stem (`paper_white_rgb`)
/// as an [`identifier`], or `fitted`.
pub fn material_name(saved: &SavedModel) -> String {
    let data = saved.provenance.data.replace('\\', "/");
    let stem = Path::new(&data)
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    identifier(&stem)
}

/// What an export did.
pub struct ExportDone {
    /// The source model's catalogue name.
    pub model: String,
    /// The file's text and the conversion, if there was one.
    pub exported: Exported,
}

/// Why an export job failed.
#[derive(Debug, Error)]
pub enum ExportFileError {
    /// The model could not be exported.
    #[error(transparent)]
    Export(#[from] ExportError),
    /// The saved model could not be read, or the converted one written.
    #[error(transparent)]
    SavedModel(#[from] SavedModelError),
    /// The converted model's parameters could not be captured.
    #[error(transparent)]
    Param(#[from] brdf_core::ParamError),
    /// The saved model does not build a model.
    #[error("{path}: {reason}")]
    Model {
        /// the saved model
        path: String,
        /// why it does not build
        reason: String,
    },
    /// A converted model was to be saved, but the export was exact.
    #[error("--save-converted: `{model}` is written to {target} exactly, nothing was converted")]
    NothingConverted {
        /// catalogue name
        model: String,
        /// the target
        target: Target,
    },
    /// The measurement to tabulate on could not be read, or the model
    /// cannot be stored on its grid.
    #[error(transparent)]
    Grid(#[from] brdf_io::IoError),
    /// Writing the material failed.
    #[error("{path}: {source}")]
    Io {
        /// the file
        path: String,
        /// the underlying error
        source: std::io::Error,
    },
}

/// Run an export job: the material file is written, and the converted
/// model when asked for.
pub fn run(job: &ExportJob) -> Result<ExportDone, ExportFileError> {
    let saved = SavedModel::load(&job.from)?;
    let model = saved.build().map_err(|e| ExportFileError::Model {
        path: job.from.display().to_string(),
        reason: e.to_string(),
    })?;
    let mut write = job.write.clone();
    if write.name.is_empty() {
        write.name = material_name(&saved);
    }
    let exported = if job.exact {
        Exported {
            text: export_with(model.as_ref(), job.target, None, &write)?,
            conversion: None,
            warnings: crate::warnings(model.as_ref(), job.target, crate::FrontEnd::Cli),
        }
    } else {
        export_or_convert_with(model.as_ref(), job.target, &job.convert, &write)?
    };
    match (&exported.conversion, &job.save_converted) {
        (Some(c), Some(path)) => save_converted(c, &saved, path)?,
        (None, Some(_)) => {
            return Err(ExportFileError::NothingConverted {
                model: saved.model.clone(),
                target: job.target,
            });
        }
        _ => {}
    }
    std::fs::write(&job.out, &exported.text).map_err(|source| ExportFileError::Io {
        path: job.out.display().to_string(),
        source,
    })?;
    Ok(ExportDone {
        model: saved.model,
        exported,
    })
}

/// Save the model a conversion fitted, with the source's provenance.
fn save_converted(c: &Conversion, source: &SavedModel, path: &Path) -> Result<(), ExportFileError> {
    let channel_names: Vec<String> = match c.model.channels() {
        1 => vec!["grey".into()],
        _ => vec!["r".into(), "g".into(), "b".into()],
    };
    let provenance = Provenance {
        data: source.provenance.data.clone(),
        samples_used: c.error.samples,
        samples_present: c.error.samples,
        // The error below is Ngan's L2 on the sampled pairs.
        objective: "ngan".into(),
        limit_deg: c.error.limit_deg,
        error: c.error.ngan_l2,
        solver: if c.appearance {
            format!(
                "conversion by fitting from `{}` for appearance (image objective)",
                c.source
            )
        } else {
            format!("conversion by fitting from `{}`", c.source)
        },
        software: format!("brdf-export {}", env!("CARGO_PKG_VERSION")),
        ..Provenance::default()
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
