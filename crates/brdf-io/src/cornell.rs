//! Cornell Program of Computer Graphics gonioreflectometer files (`.brdf`):
//! `#` comment lines, the number of wavelengths (31), the wavelengths
//! (400..700 nm), then records of `theta_i phi_i theta_s phi_s` (radians)
//! and one spectral BRDF value (1/sr) per wavelength. CRLF line ends are
//! accepted. Spectra become linear sRGB or luminance `Y` through
//! [`crate::colour`] (CIE 1931 2-degree observer, D65).

use std::path::Path;

use brdf_core::{Direction, SampleSet};

use crate::IoError;
use crate::colour::{WAVELENGTHS, spectrum_to_xyz, xyz_to_srgb};

/// Which colour representation to produce.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CornellColour {
    /// Linear sRGB (3 channels).
    Rgb,
    /// Luminance `Y` (1 channel).
    Luminance,
}

/// Read a Cornell `.brdf` file.
pub fn read(path: &Path, colour: CornellColour) -> Result<SampleSet, IoError> {
    let bytes = std::fs::read(path).map_err(|source| IoError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let text = String::from_utf8(bytes).map_err(|e| IoError::Format {
        path: path.to_path_buf(),
        line: 0,
        reason: format!(
            "not UTF-8 text (byte offset {})",
            e.utf8_error().valid_up_to()
        ),
    })?;
    parse(path, &text, colour)
}

/// Parse the text of a Cornell file (`path` only names it in errors).
pub fn parse(path: &Path, text: &str, colour: CornellColour) -> Result<SampleSet, IoError> {
    let tokens = Tokens::new(path, text);
    let records = tokens.check_header()?;
    let channels = match colour {
        CornellColour::Rgb => vec!["r".into(), "g".into(), "b".into()],
        CornellColour::Luminance => vec!["Y".into()],
    };
    let name = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let mut set = SampleSet::new(
        format!("cornell#{name}"),
        format!("{} (CIE 1931 2-deg, D65, linear sRGB)", path.display()),
        channels,
    );
    for r in 0..records {
        tokens.push_record(HEADER_TOKENS + RECORD_TOKENS * r, colour, &mut set)?;
    }
    Ok(set)
}

/// Numbers before the first record: the wavelength count and the 31
/// wavelengths.
const HEADER_TOKENS: usize = 32;

/// Numbers per record: four angles and a value per wavelength.
const RECORD_TOKENS: usize = 35;

/// The numbers of a file as text with their 1-based line numbers, comments
/// removed. The wavelength list wraps across lines (19 and 12 in the
/// Cornell files), so the file is one stream of numbers, read by position.
struct Tokens<'a> {
    path: &'a Path,
    tokens: Vec<(usize, &'a str)>,
}

impl<'a> Tokens<'a> {
    fn new(path: &'a Path, text: &'a str) -> Self {
        let mut tokens: Vec<(usize, &str)> = Vec::new();
        for (i, line) in text.lines().enumerate() {
            let line = line.split('#').next().unwrap_or("");
            tokens.extend(line.split_whitespace().map(|t| (i + 1, t)));
        }
        Tokens { path, tokens }
    }

    /// The line of the last token (0 for an empty file), where a short
    /// file is reported.
    fn last_line(&self) -> usize {
        self.tokens.last().map_or(0, |t| t.0)
    }

    /// Token `k` as a finite number.
    fn num(&self, k: usize) -> Result<f64, IoError> {
        let path = self.path;
        let (line, t) = self.tokens.get(k).copied().ok_or_else(|| IoError::Format {
            path: path.to_path_buf(),
            line: self.last_line(),
            reason: "unexpected end of file (truncated?)".into(),
        })?;
        let v: f64 = t.parse().map_err(|_| IoError::NotANumber {
            path: path.to_path_buf(),
            line,
            field: 0,
            text: t.to_string(),
        })?;
        if !v.is_finite() {
            return Err(IoError::NotFinite {
                path: path.to_path_buf(),
                line,
                field: 0,
                value: v,
            });
        }
        Ok(v)
    }

    /// Check the wavelength count and the wavelengths (the colour
    /// conversion is tabulated at exactly those), and that whole records
    /// follow; returns the number of records.
    fn check_header(&self) -> Result<usize, IoError> {
        let path = self.path;
        let nw = self.num(0)?;
        if nw != 31.0 {
            return Err(IoError::Format {
                path: path.to_path_buf(),
                line: self.tokens[0].0,
                reason: format!("{nw} wavelengths; this reader supports the 31 of 400..700 nm"),
            });
        }
        for k in 0..31 {
            let w = self.num(1 + k)?;
            if w != WAVELENGTHS[k] {
                return Err(IoError::Format {
                    path: path.to_path_buf(),
                    line: self.tokens[1 + k].0,
                    reason: format!("wavelength {} is {w}, expected {}", k + 1, WAVELENGTHS[k]),
                });
            }
        }
        let rest = self.tokens.len() - HEADER_TOKENS;
        if rest == 0 || !rest.is_multiple_of(RECORD_TOKENS) {
            return Err(IoError::Count {
                path: path.to_path_buf(),
                line: self.last_line(),
                expected: "records of 35 numbers".into(),
                found: format!("{rest} numbers after the header (truncated record?)"),
            });
        }
        Ok(rest / RECORD_TOKENS)
    }

    /// Add the record starting at token `b`: its spectrum becomes colour
    /// channels, and the record's first line names it in errors.
    fn push_record(
        &self,
        b: usize,
        colour: CornellColour,
        set: &mut SampleSet,
    ) -> Result<(), IoError> {
        let path = self.path;
        let ang = [
            self.num(b)?,
            self.num(b + 1)?,
            self.num(b + 2)?,
            self.num(b + 3)?,
        ];
        let mut spec = [0.0; 31];
        for k in 0..31 {
            spec[k] = self.num(b + 4 + k)?;
        }
        let line = self.tokens[b].0;
        let l = Direction::from_spherical(ang[0], ang[1]).map_err(|e| IoError::Format {
            path: path.to_path_buf(),
            line,
            reason: format!("incident direction: {e}"),
        })?;
        let v = Direction::from_spherical(ang[2], ang[3]).map_err(|e| IoError::Format {
            path: path.to_path_buf(),
            line,
            reason: format!("scattered direction: {e}"),
        })?;
        let xyz = spectrum_to_xyz(&spec);
        let vals: Vec<f64> = match colour {
            CornellColour::Rgb => xyz_to_srgb(xyz).to_vec(),
            CornellColour::Luminance => vec![xyz[1]],
        };
        set.push(&l, &v, &vals, 1.0).map_err(|e| IoError::Format {
            path: path.to_path_buf(),
            line,
            reason: e.to_string(),
        })
    }
}
