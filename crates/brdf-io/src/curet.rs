//! CUReT BRDF measurements (Dana, van Ginneken, Nayar & Koenderink 1999,
//! "Reflectance and texture of real-world surfaces", ACM TOG 18(1)).
//!
//! `abrdf.dat`: one line per sample, the sample number (1-61) then its 205
//! BRDF values (the mean of the R, G and B channels, 1/sr). `table.txt`: 205
//! rows `index theta_v phi_v theta_i phi_i` (radians), the measurement
//! geometry shared by every sample, in the column order the database
//! documents. The data confirm that order: the radiance offset visible in
//! the darkest sample (61) is divided by the cosine of columns 4-5, as only
//! the illumination angle is, and with the columns swapped removing it
//! would leave 125 negative BRDF values (the argument and its numbers are
//! the test `real_curet_column_order_from_the_data` in `tests/io/curet.rs`). The per-channel layout (`rbrdf.dat`, `gbrdf.dat`, `bbrdf.dat`,
//! same shape) is read by [`read_rgb`].
//!
//! Slightly negative values (29 in `abrdf.dat`) are measurement noise, i.e.
//! data: they are kept and counted, never clamped.

use std::path::Path;

use brdf_core::{Direction, SampleSet};

use crate::error::{IoError, parse_fields};

/// Measurements per sample.
pub const CONFIGURATIONS: usize = 205;

/// The 61 CUReT sample names, by number (1-based; index 0 is sample 1).
pub const SAMPLE_NAMES: [&str; 61] = [
    "Felt",
    "Polyester",
    "Terrycloth",
    "Rough Plastic",
    "Leather",
    "Sandpaper",
    "Velvet",
    "Pebbles",
    "Frosted Glass",
    "Plaster_a",
    "Plaster_b",
    "Rough Paper",
    "Artificial Grass",
    "Roof Shingle",
    "Aluminum Foil",
    "Cork",
    "Rough Tile",
    "Rug_a",
    "Rug_b",
    "Styrofoam",
    "Sponge",
    "Lambswool",
    "Lettuce Leaf",
    "Rabbit Fur",
    "Quarry Tile",
    "Loofa",
    "Insulation",
    "Crumpled Paper",
    "Polyester (zoomed)",
    "Plaster_b (zoomed)",
    "Rough Paper (zoomed)",
    "Roof Shingle (zoomed)",
    "Slate_a",
    "Slate_b",
    "Painted Spheres",
    "Limestone",
    "Brick_a",
    "Ribbed Paper",
    "Human Skin",
    "Straw",
    "Brick_b",
    "Corduroy",
    "Salt Crystals",
    "Linen",
    "Concrete_a",
    "Cotton",
    "Stones",
    "Brown Bread",
    "Concrete_b",
    "Concrete_c",
    "Corn Husk",
    "White Bread",
    "Plant",
    "Wood_a",
    "Orange Peel",
    "Wood_b",
    "Peacock Feather",
    "Tree Bark",
    "Cracker_a",
    "Cracker_b",
    "Moss",
];

/// The anisotropic samples; the other 52 form the isotropic set Kurt fitted.
pub const ANISOTROPIC: [u32; 9] = [38, 40, 42, 44, 46, 51, 54, 56, 58];

/// Whether sample `n` is in the isotropic set.
pub fn is_isotropic(n: u32) -> bool {
    (1..=61).contains(&n) && !ANISOTROPIC.contains(&n)
}

/// The finite numbers of one data line, exactly `expected` of them.
fn data_line(
    path: &Path,
    line_no: usize,
    line: &str,
    expected: usize,
    what: &str,
) -> Result<Vec<f64>, IoError> {
    let f = parse_fields(path, line_no, line)?;
    if f.len() != expected {
        return Err(IoError::Count {
            path: path.into(),
            line: line_no,
            expected: what.into(),
            found: format!("{} fields", f.len()),
        });
    }
    if let Some((i, v)) = f.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(IoError::NotFinite {
            path: path.into(),
            line: line_no,
            field: i + 1,
            value: *v,
        });
    }
    Ok(f)
}

fn read_text(path: &Path) -> Result<String, IoError> {
    std::fs::read_to_string(path).map_err(|e| IoError::Io {
        path: path.into(),
        source: e,
    })
}

/// The measurement geometry: `(L, V)` of the 205 configurations.
pub fn read_table(path: &Path) -> Result<Vec<(Direction, Direction)>, IoError> {
    parse_table(path, &read_text(path)?)
}

/// [`read_table`] on the text of a `table.txt` (`path` only names it in
/// errors).
pub fn parse_table(path: &Path, text: &str) -> Result<Vec<(Direction, Direction)>, IoError> {
    let mut out = Vec::with_capacity(CONFIGURATIONS);
    for (k, line) in text.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        let f = data_line(
            path,
            k + 1,
            line,
            5,
            "5 fields (index theta_v phi_v theta_i phi_i)",
        )?;
        if f[0] != (out.len() + 1) as f64 {
            return Err(IoError::Format {
                path: path.into(),
                line: k + 1,
                reason: format!(
                    "index {} out of sequence (expected {})",
                    f[0],
                    out.len() + 1
                ),
            });
        }
        let dir = |t: f64, p: f64| {
            Direction::from_spherical(t, p).map_err(|e| IoError::Format {
                path: path.into(),
                line: k + 1,
                reason: e.to_string(),
            })
        };
        let v = dir(f[1], f[2])?;
        let l = dir(f[3], f[4])?;
        out.push((l, v));
    }
    if out.len() != CONFIGURATIONS {
        return Err(IoError::Count {
            path: path.into(),
            line: 0,
            expected: format!("{CONFIGURATIONS} rows"),
            found: format!("{} rows", out.len()),
        });
    }
    Ok(out)
}

/// One channel file: sample number -> 205 values, in file order.
pub fn read_values(path: &Path) -> Result<Vec<(u32, Vec<f64>)>, IoError> {
    parse_values(path, &read_text(path)?)
}

/// [`read_values`] on the text of a channel file (`path` only names it in
/// errors).
pub fn parse_values(path: &Path, text: &str) -> Result<Vec<(u32, Vec<f64>)>, IoError> {
    let mut out: Vec<(u32, Vec<f64>)> = Vec::new();
    for (k, line) in text.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        let f = data_line(
            path,
            k + 1,
            line,
            CONFIGURATIONS + 1,
            "sample number and 205 values",
        )?;
        let n = f[0];
        if !((1.0..=61.0).contains(&n) && n.fract() == 0.0) {
            return Err(IoError::Format {
                path: path.into(),
                line: k + 1,
                reason: format!("sample number {n} is not in 1..=61"),
            });
        }
        if out.iter().any(|(m, _)| *m as f64 == n) {
            return Err(IoError::Format {
                path: path.into(),
                line: k + 1,
                reason: format!("sample {n} appears twice"),
            });
        }
        out.push((n as u32, f[1..].to_vec()));
    }
    Ok(out)
}

fn sample_set(
    number: u32,
    geometry: &[(Direction, Direction)],
    channels: &[&[f64]],
    names: Vec<String>,
    provenance: String,
) -> Result<SampleSet, IoError> {
    let label = SAMPLE_NAMES
        .get(number as usize - 1)
        .copied()
        .unwrap_or("?");
    let mut set = SampleSet::new(format!("curet#{number} {label}"), provenance, names);
    let mut buf = vec![0.0; channels.len()];
    for (j, (l, v)) in geometry.iter().enumerate() {
        for (c, ch) in channels.iter().enumerate() {
            buf[c] = ch[j];
        }
        set.push(l, v, &buf, 1.0).map_err(|e| IoError::Format {
            path: "".into(),
            line: 0,
            reason: e.to_string(),
        })?;
    }
    Ok(set)
}

/// Every sample of `abrdf.dat` (with `table.txt` beside it) as a grey sample
/// set, in file order.
pub fn read_grey(abrdf: &Path, table: &Path) -> Result<Vec<SampleSet>, IoError> {
    let geometry = read_table(table)?;
    read_values(abrdf)?
        .into_iter()
        .map(|(n, vals)| {
            sample_set(
                n,
                &geometry,
                &[&vals],
                vec!["grey".into()],
                format!(
                    "CUReT {} (mean of R, G, B) with {}",
                    abrdf.display(),
                    table.display()
                ),
            )
        })
        .collect()
}

/// Every sample of the per-channel files `rbrdf.dat`, `gbrdf.dat`,
/// `bbrdf.dat` (with `table.txt`) in `dir`, as RGB sample sets. The three
/// files must list the same samples in the same order.
pub fn read_rgb(dir: &Path) -> Result<Vec<SampleSet>, IoError> {
    let table = dir.join("table.txt");
    let geometry = read_table(&table)?;
    let r = read_values(&dir.join("rbrdf.dat"))?;
    let g = read_values(&dir.join("gbrdf.dat"))?;
    let b = read_values(&dir.join("bbrdf.dat"))?;
    if r.len() != g.len() || r.len() != b.len() {
        return Err(IoError::Count {
            path: dir.into(),
            line: 0,
            expected: format!("{} samples in each channel file", r.len()),
            found: format!("{} / {} / {}", r.len(), g.len(), b.len()),
        });
    }
    r.iter()
        .zip(&g)
        .zip(&b)
        .enumerate()
        .map(|(k, ((r, g), b))| {
            if r.0 != g.0 || r.0 != b.0 {
                return Err(IoError::Format {
                    path: dir.into(),
                    line: k + 1,
                    reason: format!(
                        "channel files disagree on the sample number ({}, {}, {})",
                        r.0, g.0, b.0
                    ),
                });
            }
            sample_set(
                r.0,
                &geometry,
                &[&r.1, &g.1, &b.1],
                vec!["r".into(), "g".into(), "b".into()],
                format!("CUReT RGB files in {}", dir.display()),
            )
        })
        .collect()
}
