//! Loading a data set by name, with the format detected: [`load`] gives a
//! [`SampleSet`] from `PATH` or `PATH#SAMPLE`
//! (a material inside a multi-material file, e.g. `curet/abrdf.dat#25`),
//! with the format chosen by the file name:
//!
//! | file | format | channels |
//! | --- | --- | --- |
//! | `abrdf.dat#N` (with `table.txt` beside it) | CUReT | grey |
//! | `*.brdf` | Cornell (`#y` for luminance) | linear sRGB |
//! | `*.bsdf` | RGL (resampled onto Sopp's goniometric grid, cell weights) | RGB |
//! | `*.binary` | MERL (valid bins, solid-angle weights; every valid bin; `#STRIDE` keeps every STRIDE-th) | RGB |
//! | `*.csv` with a `light_theta_deg` header | Sopp's goniometric grid (cell weights) | RGB |
//! | other `*.csv` | generic samples | as in the header |

use std::path::{Path, PathBuf};

use brdf_core::{Brdf, SampleSet};

use crate::IoError;

/// Split `PATH#SAMPLE`. A `#` inside a folder or file name stays part of
/// the path: only a suffix without a path separator splits, and not when
/// the whole text names an existing file.
pub fn split_sample(spec: &str) -> (PathBuf, Option<String>) {
    if Path::new(spec).is_file() {
        return (PathBuf::from(spec), None);
    }
    match spec.rsplit_once('#') {
        Some((p, s)) if !s.is_empty() && !s.contains(['/', '\\']) => {
            (PathBuf::from(p), Some(s.to_string()))
        }
        _ => (PathBuf::from(spec), None),
    }
}

/// The file `path` names: as given when it exists; otherwise, when it is
/// relative and `BRDF_DATA` is set, under `BRDF_DATA`. The error names
/// every place tried.
pub fn resolve_path(path: &Path) -> Result<PathBuf, IoError> {
    if path.exists() {
        return Ok(path.to_path_buf());
    }
    let data = std::env::var_os("BRDF_DATA").filter(|d| !d.is_empty());
    let under = match data {
        Some(d) if path.is_relative() => Some(PathBuf::from(d).join(path)),
        _ => None,
    };
    if let Some(p) = under.as_ref().filter(|p| p.exists()) {
        return Ok(p.clone());
    }
    let mut reason = match &under {
        Some(p) => format!(
            "does not exist (looked in the working directory and at {} under BRDF_DATA)",
            p.display()
        ),
        None if path.is_relative() => {
            "does not exist in the working directory (set BRDF_DATA to look there too)".into()
        }
        None => "does not exist".into(),
    };
    let near = near_names(path, under.as_deref());
    if !near.is_empty() {
        reason += &format!("; did you mean {}?", near.join(" or "));
    }
    Err(IoError::Unsupported {
        path: path.to_path_buf(),
        reason,
    })
}

/// At most this many names are suggested for a missing file.
const SUGGESTIONS: usize = 3;

/// Existing files beside a missing `path` (in its folder as given, and in
/// the same folder under `BRDF_DATA` when `under` is that place) whose
/// names are near its name: within a few edits, or one's stem a prefix of
/// the other's (`paper_white.bsdf` for `paper_white_rgb.bsdf`). Each is
/// written as `path` was, with its folder, so it can be pasted back; the
/// nearest first.
fn near_names(path: &Path, under: Option<&Path>) -> Vec<String> {
    let Some(want) = path.file_name().and_then(|f| f.to_str()) else {
        return Vec::new();
    };
    let folder = path.parent().unwrap_or(Path::new(""));
    let mut found: Vec<(usize, String)> = Vec::new();
    let dirs = [
        Some(folder.to_path_buf()),
        under.and_then(|u| u.parent()).map(Path::to_path_buf),
    ];
    for dir in dirs.into_iter().flatten() {
        let listing = if dir.as_os_str().is_empty() {
            Path::new(".").read_dir()
        } else {
            dir.read_dir()
        };
        let Ok(listing) = listing else { continue };
        for entry in listing.flatten() {
            let name = entry.file_name();
            let Some(name) = name.to_str() else { continue };
            if let Some(d) = nearness(want, name) {
                let shown = folder.join(name).display().to_string();
                if !found.iter().any(|(_, s)| *s == shown) {
                    found.push((d, shown));
                }
            }
        }
    }
    found.sort();
    found
        .into_iter()
        .take(SUGGESTIONS)
        .map(|(_, s)| s)
        .collect()
}

/// How far the name `have` is from the wanted `want` (edits, ignoring
/// case), when near enough to suggest: within a third of the name's length
/// (at least 2), or either stem a prefix of the other.
fn nearness(want: &str, have: &str) -> Option<usize> {
    let (w, h) = (want.to_lowercase(), have.to_lowercase());
    if w == h {
        return None;
    }
    let d = edit_distance(&w, &h);
    let stem = |s: &str| {
        Path::new(s)
            .file_stem()
            .and_then(|f| f.to_str())
            .unwrap_or("")
            .to_string()
    };
    let (sw, sh) = (stem(&w), stem(&h));
    let prefix = sw.len() >= 3 && sh.len() >= 3 && (sh.starts_with(&sw) || sw.starts_with(&sh));
    (prefix || d <= (w.chars().count() / 3).max(2)).then_some(d)
}

/// Levenshtein distance in characters.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diag = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let next = (row[j + 1] + 1)
                .min(row[j] + 1)
                .min(diag + usize::from(ca != *cb));
            diag = row[j + 1];
            row[j + 1] = next;
        }
    }
    row[b.len()]
}

/// [`split_sample`] with the path found by [`resolve_path`]; a `#` that is
/// part of an existing name under `BRDF_DATA` stays in the path.
pub fn resolve_spec(spec: &str) -> Result<(PathBuf, Option<String>), IoError> {
    if let Ok(p) = resolve_path(Path::new(spec))
        && p.is_file()
    {
        return Ok((p, None));
    }
    let (path, sample) = split_sample(spec);
    Ok((resolve_path(&path)?, sample))
}

/// The format of a path, by name (and, for CSV, its header).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub enum Format {
    /// CUReT `abrdf.dat`.
    Curet,
    /// Cornell `.brdf`.
    Cornell,
    /// MERL `.binary`.
    Merl,
    /// RGL `.bsdf`.
    Rgl,
    /// Sopp's grid CSV.
    SoppGrid,
    /// Generic sample CSV.
    Csv,
}

/// Detect the format of `path`.
pub fn format_of(path: &Path) -> Result<Format, IoError> {
    if path.is_dir() {
        return Err(IoError::Unsupported {
            path: path.to_path_buf(),
            reason: "is a folder; name one data file in it".into(),
        });
    }
    let name = path.file_name().and_then(|f| f.to_str()).unwrap_or("");
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    Ok(match (name, ext) {
        ("abrdf.dat", _) => Format::Curet,
        (_, "brdf") => Format::Cornell,
        (_, "binary") => Format::Merl,
        (_, "bsdf") => Format::Rgl,
        (_, "csv") => {
            let path = &resolve_path(path)?;
            let text = std::fs::read_to_string(path).map_err(|e| IoError::Io {
                path: path.to_path_buf(),
                source: e,
            })?;
            if text.starts_with("light_theta_deg") {
                Format::SoppGrid
            } else {
                Format::Csv
            }
        }
        _ => {
            return Err(IoError::Unsupported {
                path: path.to_path_buf(),
                reason: "unknown data format (CUReT abrdf.dat#N, Cornell .brdf, RGL .bsdf, MERL .binary, grid or sample .csv)".into(),
            });
        }
    })
}

/// A dense data set that can be evaluated at any direction pair (for
/// resampling and rendering): MERL tables and RGL materials are, scattered
/// sets are not.
pub fn load_dense(spec: &str) -> Result<Option<Box<dyn Brdf>>, IoError> {
    let (path, _) = resolve_spec(spec)?;
    Ok(match format_of(&path)? {
        Format::Merl => Some(Box::new(crate::merl::read(&path)?)),
        Format::Rgl => Some(Box::new(crate::rgl::Rgl::read(&path)?)),
        _ => None,
    })
}

/// Load the sample set named by `spec`.
pub fn load(spec: &str) -> Result<SampleSet, IoError> {
    let (path, sample) = resolve_spec(spec)?;
    match format_of(&path)? {
        Format::Curet => {
            let table = path.parent().unwrap_or(Path::new(".")).join("table.txt");
            let sets = crate::curet::read_grey(&path, &table)?;
            let Some(s) = sample else {
                return Err(IoError::Unsupported {
                    path: path.clone(),
                    reason: format!(
                        "name a sample, e.g. {}#25 (CUReT samples 1-61)",
                        path.display()
                    ),
                });
            };
            let prefix = format!("curet#{s} ");
            sets.into_iter()
                .find(|set| set.name.starts_with(&prefix))
                .ok_or_else(|| IoError::NoSample {
                    path: path.clone(),
                    sample: s.clone(),
                    reason: "CUReT samples are 1-61".into(),
                })
        }
        Format::Cornell => {
            let colour = match sample.as_deref() {
                Some("y") | Some("Y") => crate::cornell::CornellColour::Luminance,
                None | Some("rgb") => crate::cornell::CornellColour::Rgb,
                Some(other) => {
                    return Err(IoError::Unsupported {
                        path: path.clone(),
                        reason: format!("`#{other}`: use #rgb or #y"),
                    });
                }
            };
            Ok(crate::cornell::read(&path, colour)?)
        }
        Format::Merl => {
            let stride = match sample.as_deref() {
                None => 1,
                Some(s) => s.parse().ok().filter(|k: &usize| *k >= 1).ok_or_else(|| {
                    IoError::Unsupported {
                        path: path.clone(),
                        reason: format!("`#{s}` is not a stride (a whole number >= 1)"),
                    }
                })?,
            };
            let m = crate::merl::read(&path)?;
            let name = path
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default();
            Ok(m.to_samples(&format!("merl#{name}"), stride).0)
        }
        Format::Rgl => {
            let m = crate::rgl::Rgl::read(&path)?;
            let g = crate::sopp_grid::SoppGrid::resample(&m);
            let name = path
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default();
            Ok(g.to_samples(&format!("rgl#{name}"), 90.0, true))
        }
        Format::SoppGrid => {
            let g = crate::sopp_grid::read(&path)?;
            let name = path
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default();
            Ok(g.to_samples(&format!("grid#{name}"), 90.0, true))
        }
        Format::Csv => Ok(crate::csv_samples::read(&path)?),
    }
}
