//! Loading a data set named on the command line: `PATH` or `PATH#SAMPLE`
//! (a material inside a multi-material file, e.g. `curet/abrdf.dat#25`).

use std::path::{Path, PathBuf};

use brdf_core::SampleSet;

use crate::StudyError;

/// Split `PATH#SAMPLE`.
pub fn split_sample(spec: &str) -> (PathBuf, Option<String>) {
    match spec.rsplit_once('#') {
        Some((p, s)) if !s.is_empty() => (PathBuf::from(p), Some(s.to_string())),
        _ => (PathBuf::from(spec), None),
    }
}

/// Load the sample set named by `spec`. Supported so far: CUReT
/// `abrdf.dat#N` (with `table.txt` beside it).
pub fn load(spec: &str) -> Result<SampleSet, StudyError> {
    let (path, sample) = split_sample(spec);
    let file = path.file_name().and_then(|f| f.to_str()).unwrap_or("");
    if file == "abrdf.dat" {
        let table = path.parent().unwrap_or(Path::new(".")).join("table.txt");
        let sets = brdf_io::curet::read_grey(&path, &table)?;
        let Some(s) = sample else {
            return Err(StudyError::Usage(format!(
                "{}: name a sample, e.g. {}#25 (CUReT samples 1-61)",
                path.display(),
                path.display()
            )));
        };
        let prefix = format!("curet#{s} ");
        return sets
            .into_iter()
            .find(|set| set.name.starts_with(&prefix))
            .ok_or_else(|| {
                StudyError::Usage(format!("{}: no CUReT sample `{s}`", path.display()))
            });
    }
    Err(StudyError::Usage(format!(
        "{}: unsupported data format (supported so far: CUReT abrdf.dat#N)",
        path.display()
    )))
}
