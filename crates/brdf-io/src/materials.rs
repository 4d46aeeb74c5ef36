//! The data sets a path names, for commands that fit many at once (`brdf
//! batch --data`, `brdf.materials` in Python): a folder stands for every
//! file of a known format in it, a CUReT `abrdf.dat` without `#N` for
//! every sample in it (`abrdf.dat#N`), anything else for itself.

use std::path::Path;

use crate::{Format, IoError, format_of, split_sample};

/// The data specs `spec` stands for, sorted and without repeats. Files of
/// a folder whose format is unknown are skipped; a folder's sub-folders
/// are not entered. An error if the folder or a CUReT file cannot be read.
pub fn materials(spec: &str) -> Result<Vec<String>, IoError> {
    let mut out = expand(spec)?;
    out.sort();
    out.dedup();
    Ok(out)
}

/// `spec` expanded, in the order the folder and the file list them.
fn expand(spec: &str) -> Result<Vec<String>, IoError> {
    let path = Path::new(spec);
    if path.is_dir() {
        return expand_folder(path);
    }
    let (file, sample) = split_sample(spec);
    if sample.is_none() && format_of(&file)? == Format::Curet {
        let table = file.parent().unwrap_or(Path::new(".")).join("table.txt");
        let sets = crate::curet::read_grey(&file, &table)?;
        return Ok(sets
            .iter()
            .filter_map(|s| {
                let n = s.name.strip_prefix("curet#")?.split(' ').next()?;
                Some(format!("{spec}#{n}"))
            })
            .collect());
    }
    Ok(vec![spec.to_string()])
}

/// Every file of a known format in the folder `path`, each expanded.
fn expand_folder(path: &Path) -> Result<Vec<String>, IoError> {
    let io = |source| IoError::Io {
        path: path.to_path_buf(),
        source,
    };
    let mut out = Vec::new();
    for e in std::fs::read_dir(path).map_err(io)? {
        let p = e.map_err(io)?.path();
        if p.is_file() && format_of(&p).is_ok() {
            out.extend(expand(&p.display().to_string())?);
        }
    }
    Ok(out)
}
