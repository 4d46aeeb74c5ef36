//! What a fit reports to a program: the JSON of `brdf fit --json` (also what
//! the Python module's `fit` returns), and data-set names for outputs, so
//! every front end names fits and data the same way.

use brdf_core::SampleSet;

use crate::{FitError, FitReport};

/// The JSON report of the fits of one data set (one per channel set): the
/// fit summaries, and what the first fit's filters dropped; `data` is the
/// data set as loaded (its negative values are counted, they are kept).
pub fn fit_json(reports: &[FitReport], data: &SampleSet) -> Result<serde_json::Value, FitError> {
    let first = reports
        .first()
        .ok_or_else(|| FitError::Usage(format!("`{}`: no fit to report", data.name)))?;
    Ok(serde_json::json!({
        "fits": reports.iter().map(|r| &r.summary).collect::<Vec<_>>(),
        "samples_present": first.samples_present,
        "dropped_invalid": first.dropped_invalid,
        "dropped_angle": first.dropped_angle,
        "negative_values_kept": data.count_negative(),
    }))
}

/// A data set's name for outputs: relative to `BRDF_DATA` when it lies
/// inside it, as given when relative, its file name otherwise — never an
/// absolute machine path.
pub fn data_name(spec: &str) -> String {
    let path = std::path::Path::new(spec);
    if let Some(root) = std::env::var_os("BRDF_DATA")
        && let Ok(rest) = path.strip_prefix(std::path::Path::new(&root))
    {
        return rest.display().to_string();
    }
    if path.is_relative() {
        return spec.to_string();
    }
    path.file_name()
        .map(|f| f.to_string_lossy().into_owned())
        .unwrap_or_else(|| spec.to_string())
}
