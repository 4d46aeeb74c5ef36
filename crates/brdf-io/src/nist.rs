//! NIST StRD non-linear regression `.dat` files (NIST ITL, Statistical
//! Reference Datasets): the header with the model, both certified starting
//! points, the certified parameters and their standard deviations, the
//! certified residual sum of squares and standard deviation, and the data.
//!
//! Layout: parameter lines `b1 = start1 start2 certified sd`; lines
//! `Residual Sum of Squares: v`, `Residual Standard Deviation: v`,
//! `Degrees of Freedom: n`, `Number of Observations: n`; then a line
//! `Data: y x` (or `y x1 x2`) naming the columns, followed by exactly
//! `Number of Observations` data lines.

use std::path::{Path, PathBuf};

use crate::IoError;
use crate::error::parse_fields;

/// One StRD problem as read from its file.
#[derive(Clone, Debug, PartialEq)]
pub struct NistDataset {
    /// Problem name (the file stem, e.g. `BoxBOD`).
    pub name: String,
    /// The file read.
    pub path: PathBuf,
    /// The model text of the header.
    pub model_text: String,
    /// The two certified starting points.
    pub starts: [Vec<f64>; 2],
    /// Certified parameter values.
    pub certified: Vec<f64>,
    /// Certified standard deviations of the parameters.
    pub certified_sd: Vec<f64>,
    /// Certified residual sum of squares.
    pub rss: f64,
    /// Certified residual standard deviation.
    pub residual_sd: f64,
    /// Degrees of freedom, always `observations - parameters` (the value
    /// the certified residual standard deviation is computed with).
    pub dof: usize,
    /// What the reader noticed and corrected (e.g. NIST's `Rat43.dat`
    /// header says 9 degrees of freedom for 15 observations and 4
    /// parameters; its certified residual standard deviation uses 11).
    pub warnings: Vec<String>,
    /// Number of predictors per observation.
    pub n_predictors: usize,
    /// Predictors, row after row.
    pub x: Vec<f64>,
    /// Responses.
    pub y: Vec<f64>,
}

fn value_after_colon(path: &Path, no: usize, line: &str) -> Result<f64, IoError> {
    let text = line.split(':').nth(1).unwrap_or("").trim();
    text.parse::<f64>().map_err(|_| IoError::NotANumber {
        path: path.to_path_buf(),
        line: no,
        field: 1,
        text: text.to_string(),
    })
}

/// Read a StRD `.dat` file.
pub fn read(path: &Path) -> Result<NistDataset, IoError> {
    let text = std::fs::read_to_string(path).map_err(|source| IoError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    parse(path, &text)
}

/// Parse the text of a StRD `.dat` file (`path` only names it in errors).
pub fn parse(path: &Path, text: &str) -> Result<NistDataset, IoError> {
    let lines: Vec<&str> = text.lines().collect();
    let header = Header::scan(path, &lines)?;
    let missing = |what: &str| format_error(path, 0, format!("missing {what}"));
    if header.params.is_empty() {
        return Err(missing("parameter lines `b1 = ...`"));
    }
    let rss = header
        .rss
        .ok_or_else(|| missing("Residual Sum of Squares"))?;
    let residual_sd = header
        .rsd
        .ok_or_else(|| missing("Residual Standard Deviation"))?;
    let dof = header.dof.ok_or_else(|| missing("Degrees of Freedom"))?;
    let nobs = header
        .nobs
        .ok_or_else(|| missing("Number of Observations"))?;
    let (hdr, ncols) = header
        .data_header
        .ok_or_else(|| missing("the `Data: y x` line"))?;
    let (x, y) = read_data(path, &lines, hdr, ncols)?;
    let params = &header.params;
    check_observations(path, y.len(), nobs, params.len())?;
    let warnings = dof_warnings(path, dof, nobs, params.len());
    let dof = nobs - params.len();
    let name = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    Ok(NistDataset {
        name,
        path: path.to_path_buf(),
        model_text: header.model_text,
        starts: [
            params.iter().map(|p| p.1[0]).collect(),
            params.iter().map(|p| p.1[1]).collect(),
        ],
        certified: params.iter().map(|p| p.1[2]).collect(),
        certified_sd: params.iter().map(|p| p.1[3]).collect(),
        rss,
        residual_sd,
        dof,
        warnings,
        n_predictors: ncols - 1,
        x,
        y,
    })
}

fn format_error(path: &Path, line: usize, reason: String) -> IoError {
    IoError::Format {
        path: path.to_path_buf(),
        line,
        reason,
    }
}

/// What the header of a StRD file says, gathered line by line up to the
/// `Data:` line.
#[derive(Default)]
struct Header {
    /// `(line, [start 1, start 2, certified, sd])` of `b1`, `b2`, ...
    params: Vec<(usize, [f64; 4])>,
    rss: Option<f64>,
    rsd: Option<f64>,
    dof: Option<usize>,
    nobs: Option<usize>,
    model_text: String,
    /// Whether the scan is inside the model block, which runs from
    /// `Model:` to the starting values.
    in_model: bool,
    /// The index of the `Data:` line naming the columns, and their count.
    data_header: Option<(usize, usize)>,
}

impl Header {
    fn scan(path: &Path, lines: &[&str]) -> Result<Self, IoError> {
        let mut header = Header::default();
        for (i, line) in lines.iter().enumerate() {
            let t = line.trim();
            if header.model_line(t) {
                continue;
            }
            if let Some(ncols) = header.value_line(path, i + 1, t)? {
                header.data_header = Some((i, ncols));
                break;
            }
        }
        Ok(header)
    }

    /// Collect the model text; true when the line belongs to the model
    /// block. Its formula lines may contain `=` and look like anything
    /// else, so they are set aside before any other rule reads them.
    fn model_line(&mut self, t: &str) -> bool {
        if t.starts_with("Model:") {
            self.in_model = true;
            return true;
        }
        if !self.in_model {
            return false;
        }
        if t.starts_with("Starting") || t.starts_with("b1") {
            self.in_model = false;
            return false;
        }
        if !t.is_empty() {
            self.model_text.push_str(t);
            self.model_text.push('\n');
        }
        true
    }

    /// Read a parameter line or a certified value; at the `Data:` line
    /// naming the columns (only `y...` and `x...`), their count. Another
    /// `Data:` line (a prose mention) is not the data header.
    fn value_line(&mut self, path: &Path, no: usize, t: &str) -> Result<Option<usize>, IoError> {
        if let Some((lhs, rhs)) = t.split_once('=')
            && let Some(k) = lhs.trim().strip_prefix('b')
            && let Ok(k) = k.parse::<usize>()
        {
            let v = parse_fields(path, no, rhs)?;
            if v.len() != 4 {
                return Err(IoError::Count {
                    path: path.to_path_buf(),
                    line: no,
                    expected: "4 numbers (start 1, start 2, certified, sd)".into(),
                    found: format!("{}", v.len()),
                });
            }
            if k != self.params.len() + 1 {
                return Err(format_error(
                    path,
                    no,
                    format!("parameter b{k} out of order"),
                ));
            }
            self.params.push((no, [v[0], v[1], v[2], v[3]]));
        } else if t.starts_with("Residual Sum of Squares:") {
            self.rss = Some(value_after_colon(path, no, t)?);
        } else if t.starts_with("Residual Standard Deviation:") {
            self.rsd = Some(value_after_colon(path, no, t)?);
        } else if t.starts_with("Degrees of Freedom:") {
            self.dof = Some(value_after_colon(path, no, t)? as usize);
        } else if t.starts_with("Number of Observations:") {
            self.nobs = Some(value_after_colon(path, no, t)? as usize);
        } else if let Some(rest) = t.strip_prefix("Data:") {
            let cols: Vec<&str> = rest.split_whitespace().collect();
            if !cols.is_empty()
                && cols
                    .iter()
                    .all(|c| c.starts_with('y') || c.starts_with('x'))
            {
                return Ok(Some(cols.len()));
            }
        }
        Ok(None)
    }
}

/// The data lines after the `Data:` line at index `hdr`: `(x, y)`, the
/// predictors row after row. Every line must have `ncols` finite numbers.
fn read_data(
    path: &Path,
    lines: &[&str],
    hdr: usize,
    ncols: usize,
) -> Result<(Vec<f64>, Vec<f64>), IoError> {
    let mut x = Vec::new();
    let mut y = Vec::new();
    for (i, line) in lines.iter().enumerate().skip(hdr + 1) {
        if line.trim().is_empty() {
            continue;
        }
        let v = parse_fields(path, i + 1, line)?;
        if v.len() != ncols {
            return Err(IoError::Count {
                path: path.to_path_buf(),
                line: i + 1,
                expected: format!("{ncols} columns"),
                found: format!("{}", v.len()),
            });
        }
        if let Some(k) = v.iter().position(|f| !f.is_finite()) {
            return Err(IoError::NotFinite {
                path: path.to_path_buf(),
                line: i + 1,
                field: k + 1,
                value: v[k],
            });
        }
        y.push(v[0]);
        x.extend_from_slice(&v[1..]);
    }
    Ok((x, y))
}

/// The data lines must be as many as the header announces (fewer is a
/// truncated file), and more than the parameters.
fn check_observations(path: &Path, lines: usize, nobs: usize, np: usize) -> Result<(), IoError> {
    if lines != nobs {
        return Err(IoError::Count {
            path: path.to_path_buf(),
            line: 0,
            expected: format!("{nobs} observations (header)"),
            found: format!("{lines} data lines (truncated file?)"),
        });
    }
    if nobs <= np {
        return Err(format_error(
            path,
            0,
            format!("{nobs} observations for {np} parameters: no degrees of freedom"),
        ));
    }
    Ok(())
}

/// The header's count is informative only: n - p is what the certified
/// residual standard deviation uses (Rat43's header is off by two).
fn dof_warnings(path: &Path, dof: usize, nobs: usize, np: usize) -> Vec<String> {
    let mut warnings = Vec::new();
    if dof + np != nobs {
        warnings.push(format!(
            "{}: the header says {dof} degrees of freedom, but {nobs} observations and {} parameters give {}; using {}",
            path.display(),
            np,
            nobs - np,
            nobs - np
        ));
    }
    warnings
}

/// Every `.dat` file of a folder, read and sorted by name.
pub fn read_dir(dir: &Path) -> Result<Vec<NistDataset>, IoError> {
    let rd = std::fs::read_dir(dir).map_err(|source| IoError::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    let mut paths: Vec<PathBuf> = rd
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "dat"))
        .collect();
    paths.sort();
    paths.iter().map(|p| read(p)).collect()
}
