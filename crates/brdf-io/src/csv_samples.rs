//! Generic CSV samples, so users can bring their own measurements: a header
//! `theta_i,phi_i,theta_o,phi_o,<one column per channel>,weight` (angles in
//! radians, values in 1/sr), then one sample per row. Angles in degrees
//! are read when the header says so (`theta_i_deg,phi_i_deg,theta_o_deg,
//! phi_o_deg,...`); a radian column holding a polar angle above pi or an
//! azimuth beyond +-2 pi (degrees, most likely) is an error naming the
//! line, never read as radians. The `weight` column may be left out:
//! every sample then weighs 1 (scattered samples carry no cell sizes), and
//! the set's [`SampleSet::notes`] says so for the caller to print. Written
//! with the
//! shortest representation that reads back to the same `f64`, so a
//! write/read round trip is exact.

use std::path::Path;

use brdf_core::{Direction, SampleSet, cartesian_to_spherical};

use crate::IoError;

/// Read a CSV sample file.
pub fn read(path: &Path) -> Result<SampleSet, IoError> {
    let text = std::fs::read_to_string(path).map_err(|source| IoError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    parse(path, &text)
}

/// Parse CSV text (`path` only names it in errors).
pub fn parse(path: &Path, text: &str) -> Result<SampleSet, IoError> {
    let mut rdr = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .from_reader(text.as_bytes());
    let columns = Columns::read(path, &mut rdr)?;
    let mut set = columns.empty_set(path);
    for (i, rec) in rdr.records().enumerate() {
        let line = i + 2;
        let rec = rec.map_err(|e| IoError::Format {
            path: path.to_path_buf(),
            line,
            reason: e.to_string(),
        })?;
        let v = columns.values(path, line, &rec)?;
        columns.push(path, line, v, &mut set)?;
    }
    if set.is_empty() {
        return Err(IoError::Format {
            path: path.to_path_buf(),
            line: 1,
            reason: "no samples".into(),
        });
    }
    Ok(set)
}

/// The layout of a sample file, from its header.
struct Columns {
    header: Vec<String>,
    /// Whether the angles are in degrees (the `*_deg` names).
    degrees: bool,
    /// Whether the last column is `weight`.
    weighted: bool,
    /// The end of the channel columns, which start at 4.
    end: usize,
}

impl Columns {
    fn read(path: &Path, rdr: &mut csv::Reader<&[u8]>) -> Result<Self, IoError> {
        let header: Vec<String> = rdr
            .headers()
            .map_err(|e| IoError::Format {
                path: path.to_path_buf(),
                line: 1,
                reason: e.to_string(),
            })?
            .iter()
            .map(str::to_string)
            .collect();
        let n = header.len();
        let degrees =
            n >= 4 && header[..4] == ["theta_i_deg", "phi_i_deg", "theta_o_deg", "phi_o_deg"];
        let weighted = n >= 1 && header[n - 1] == "weight";
        // Columns holding values: the channels end before `weight` when there is one.
        let end = if weighted { n - 1 } else { n };
        if end < 5 || !(degrees || header[..4] == ["theta_i", "phi_i", "theta_o", "phi_o"]) {
            return Err(IoError::Format {
                path: path.to_path_buf(),
                line: 1,
                reason: format!(
                    "header must be theta_i,phi_i,theta_o,phi_o,<channels...>[,weight] (radians) or theta_i_deg,phi_i_deg,theta_o_deg,phi_o_deg,<channels...>[,weight]; found {}",
                    header.join(",")
                ),
            });
        }
        Ok(Columns {
            header,
            degrees,
            weighted,
            end,
        })
    }

    /// The set the samples go into, named after the file, with a note when
    /// the weights are made up (the caller prints it).
    fn empty_set(&self, path: &Path) -> SampleSet {
        let channels: Vec<String> = self.header[4..self.end].to_vec();
        let name = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        let mut set = SampleSet::new(format!("csv#{name}"), path.display().to_string(), channels);
        if !self.weighted {
            set.notes.push(format!(
                "{}: no weight column; every sample weighted 1",
                path.display()
            ));
        }
        set
    }

    /// The numbers of one record, which must have a field per column.
    fn values(
        &self,
        path: &Path,
        line: usize,
        rec: &csv::StringRecord,
    ) -> Result<Vec<f64>, IoError> {
        let n = self.header.len();
        if rec.len() != n {
            return Err(IoError::Count {
                path: path.to_path_buf(),
                line,
                expected: format!("{n} fields"),
                found: rec.len().to_string(),
            });
        }
        let mut v = Vec::with_capacity(n);
        for (k, t) in rec.iter().enumerate() {
            let x: f64 = t.parse().map_err(|_| IoError::NotANumber {
                path: path.to_path_buf(),
                line,
                field: k + 1,
                text: t.to_string(),
            })?;
            // NaN values are data to be counted and filtered; NaN angles
            // and weights are errors.
            if !x.is_finite() && (k < 4 || (self.weighted && k == n - 1)) {
                return Err(IoError::NotFinite {
                    path: path.to_path_buf(),
                    line,
                    field: k + 1,
                    value: x,
                });
            }
            v.push(x);
        }
        Ok(v)
    }

    /// Add the sample of record values `v` (angles in the header's unit).
    fn push(
        &self,
        path: &Path,
        line: usize,
        mut v: Vec<f64>,
        set: &mut SampleSet,
    ) -> Result<(), IoError> {
        let bad = |what: &str, e: String| IoError::Format {
            path: path.to_path_buf(),
            line,
            reason: format!("{what}: {e}"),
        };
        check_angles(path, line, &self.header, &v[..4], self.degrees)?;
        if self.degrees {
            for a in &mut v[..4] {
                *a = a.to_radians();
            }
        }
        let l = Direction::from_spherical(v[0], v[1])
            .map_err(|e| bad("incident direction", e.to_string()))?;
        let o = Direction::from_spherical(v[2], v[3])
            .map_err(|e| bad("outgoing direction", e.to_string()))?;
        let weight = if self.weighted {
            v[self.header.len() - 1]
        } else {
            1.0
        };
        set.push(&l, &o, &v[4..self.end], weight)
            .map_err(|e| bad("sample", e.to_string()))
    }
}

/// Refuse angles outside their range in the header's unit: a polar angle
/// outside `[0, pi]` (`[0, 180]` degrees), an azimuth beyond `+-2 pi`
/// (`+-360` degrees). In a radian file such values are almost always
/// degrees, which read as radians would put samples anywhere.
fn check_angles(
    path: &Path,
    line: usize,
    header: &[String],
    a: &[f64],
    degrees: bool,
) -> Result<(), IoError> {
    use std::f64::consts::{PI, TAU};
    let (polar, azimuth, unit) = if degrees {
        (180.0, 360.0, "degrees")
    } else {
        (PI, TAU, "radians")
    };
    for (k, x) in a.iter().enumerate() {
        let limit = if k % 2 == 0 { polar } else { azimuth };
        let ok = if k % 2 == 0 {
            (0.0..=polar).contains(x)
        } else {
            x.abs() <= azimuth
        };
        if !ok {
            let hint = if degrees {
                String::new()
            } else {
                " (degrees? name the columns theta_i_deg,phi_i_deg,theta_o_deg,phi_o_deg)"
                    .to_string()
            };
            return Err(IoError::Format {
                path: path.to_path_buf(),
                line,
                reason: format!(
                    "{} = {} is outside {}{} {unit}{hint}",
                    header[k],
                    crate::error::short(*x),
                    if k % 2 == 0 { "0.." } else { "+-" },
                    crate::error::short(limit),
                ),
            });
        }
    }
    Ok(())
}

/// Write a sample set as CSV.
pub fn write(path: &Path, set: &SampleSet) -> Result<(), IoError> {
    let io = |e: std::io::Error| IoError::Io {
        path: path.to_path_buf(),
        source: e,
    };
    let mut w =
        csv::Writer::from_path(path).map_err(|e| io(std::io::Error::other(e.to_string())))?;
    let mut header = vec![
        "theta_i".to_string(),
        "phi_i".into(),
        "theta_o".into(),
        "phi_o".into(),
    ];
    header.extend(set.channel_names.iter().cloned());
    header.push("weight".into());
    w.write_record(&header)
        .map_err(|e| io(std::io::Error::other(e.to_string())))?;
    let p = set.pairs();
    for j in 0..set.len() {
        let (ti, pi) = cartesian_to_spherical(&p.l(j));
        let (to, po) = cartesian_to_spherical(&p.v(j));
        let mut rec = vec![
            ti.to_string(),
            pi.to_string(),
            to.to_string(),
            po.to_string(),
        ];
        for c in 0..set.channels() {
            rec.push(set.channel(c)[j].to_string());
        }
        rec.push(set.weights()[j].to_string());
        w.write_record(&rec)
            .map_err(|e| io(std::io::Error::other(e.to_string())))?;
    }
    w.flush().map_err(io)
}
