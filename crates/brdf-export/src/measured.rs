//! Any saved model as a Mitsuba 3 `measured` BSDF: the model tabulated on
//! the grid of an RGL measurement (`brdf export --to mitsuba --tabulate-on
//! DATA.bsdf OUT.bsdf`).
//!
//! Mitsuba has no plugin for most of the catalogue's models; the exact
//! Mitsuba export ([`crate::mitsuba`]) covers principled, Lambert and the
//! separable GGX, and [`mod@crate::convert`] refits the others as
//! principled, which can change their look. A tabulation keeps the model
//! itself: [`brdf_io::rgl_tabulated`] writes the model's values at the
//! nodes of the measurement's own adaptive grid, which Mitsuba's
//! `measured` plugin interpolates exactly as it interpolates the
//! measurement. Between the nodes it is the model's bilinear interpolation
//! on that grid (0.75% median difference for a smooth lobe in the tests),
//! so a fit and its measurement rendered this way differ by the fit alone.

use std::path::{Path, PathBuf};

use brdf_io::rgl_tabulated::Tabulated;
use brdf_models::saved_model::SavedModel;

use crate::file::ExportFileError;

/// What a tabulated export wrote.
#[derive(Clone, Debug)]
pub struct TabulatedExport {
    /// The source model's catalogue name.
    pub model: String,
    /// Incident directions and sample-space nodes per direction.
    pub incident: usize,
    /// Sample-space nodes per incident direction.
    pub per_incident: usize,
    /// The Mitsuba snippet that loads the file written.
    pub snippet: String,
}

/// The Mitsuba 3 snippet of a `measured` BSDF reading `file`.
pub fn snippet(file: &Path) -> String {
    crate::xml::Node::new("bsdf")
        .attr("type", "measured")
        .child(
            crate::xml::Node::new("string")
                .attr("name", "filename")
                .attr("value", file.display()),
        )
        .to_document(false, None)
}

/// The saved model tabulated on the grid of the RGL file `grid` (a
/// relative path not found here is looked up under `BRDF_DATA`, as data
/// paths are): the bytes of an RGL `.bsdf` file (what [`run`] writes).
pub fn tabulate(saved: &SavedModel, grid: &Path) -> Result<Tabulated, ExportFileError> {
    let grid = &brdf_io::load::resolve_path(grid)?;
    let model = saved.build().map_err(|e| ExportFileError::Model {
        path: saved.model.clone(),
        reason: e.to_string(),
    })?;
    let grid_name = grid.file_name().map(PathBuf::from).unwrap_or_default();
    let description = format!(
        "{} fitted to {} (brdf fit), tabulated on the grid of {} by brdf-export {}",
        saved.model,
        saved.provenance.data,
        grid_name.display(),
        env!("CARGO_PKG_VERSION")
    );
    Ok(brdf_io::rgl_tabulated::tabulate(
        grid,
        model.as_ref(),
        &description,
    )?)
}

/// Tabulate the model saved at `from` on the grid of the RGL file `grid`
/// and write it to `out` (an RGL `.bsdf` file).
pub fn run(from: &Path, grid: &Path, out: &Path) -> Result<TabulatedExport, ExportFileError> {
    let saved = SavedModel::load(from)?;
    let t = tabulate(&saved, grid)?;
    std::fs::write(out, &t.bytes).map_err(|source| ExportFileError::Io {
        path: out.display().to_string(),
        source,
    })?;
    Ok(TabulatedExport {
        model: saved.model,
        incident: t.incident,
        per_incident: t.per_incident,
        snippet: snippet(out),
    })
}
