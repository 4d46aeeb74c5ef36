//! MERL `.binary` BRDFs (Matusik, Pfister, Brand & McMillan 2003): three
//! little-endian `i32` dimensions `90, 90, 180` (`theta_h`, `theta_d`,
//! `phi_d` bins), then `3 x 1,458,000` little-endian `f64` in planar order R,
//! G, B, index `i_h * 90 * 180 + i_d * 180 + i_phi` with
//! `i_h = floor(sqrt(theta_h / (pi/2)) * 90)`, `i_d = floor(theta_d / (pi/2) * 90)`,
//! `i_phi = floor(phi_d / pi * 180)` after folding `phi_d` into `[0, pi)` by
//! reciprocity; indices clamped to range. Stored values are scaled by
//! `1/1500`, `1.15/1500`, `1.66/1500` for R, G, B to give 1/sr; negative
//! values mark invalid bins.
//!
//! [`Merl`] holds the table in 1/sr, evaluates `f(L, V)` by bin lookup
//! (it implements [`Brdf`]), is written back exactly, can be made from any
//! evaluable BRDF by sampling it at the bin centres ([`Merl::resample`]),
//! and gives its valid bins as samples with solid-angle weights
//! ([`Merl::to_samples`]).

use std::f64::consts::{FRAC_PI_2, PI};
use std::path::Path;

use brdf_core::weights::merl_bin_solid_angle;
use brdf_core::{Brdf, Direction, HalfDiff, SampleSet};
use nalgebra::Vector3;

use crate::IoError;

/// Bins per dimension.
pub const DIMS: (usize, usize, usize) = (90, 90, 180);
/// Number of bins.
pub const BINS: usize = 90 * 90 * 180;
/// Channel scale factors (stored value times scale = 1/sr).
pub const SCALE: [f64; 3] = [1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0];

/// A MERL table in 1/sr (planar R, G, B; negative = invalid bin).
#[derive(Clone, Debug, PartialEq)]
pub struct Merl {
    values: Vec<f64>,
}

/// Bin index of a direction pair (`None` below the horizon).
pub fn bin_of(l: &Vector3<f64>, v: &Vector3<f64>) -> Option<usize> {
    if !(l.z > 0.0 && v.z > 0.0) {
        return None;
    }
    let hd = HalfDiff::from_directions(l, v)?;
    let (nh, nd, np) = DIMS;
    let ih = ((hd.theta_h / FRAC_PI_2).max(0.0).sqrt() * nh as f64).floor() as isize;
    let id = (hd.theta_d / FRAC_PI_2 * nd as f64).floor() as isize;
    let mut pd = hd.phi_d;
    if pd < 0.0 {
        pd += PI;
    }
    if pd >= PI {
        pd -= PI;
    }
    let ip = (pd / PI * np as f64).floor() as isize;
    let c = |i: isize, n: usize| i.clamp(0, n as isize - 1) as usize;
    Some(c(ih, nh) * nd * np + c(id, nd) * np + c(ip, np))
}

/// The centre of bin `(i_h, i_d, i_phi)` as a direction pair (`phi_h = 0`).
pub fn bin_centre(ih: usize, id: usize, ip: usize) -> (Vector3<f64>, Vector3<f64>) {
    let (nh, nd, np) = DIMS;
    let x = (ih as f64 + 0.5) / nh as f64;
    let hd = HalfDiff {
        theta_h: x * x * FRAC_PI_2,
        phi_h: 0.0,
        theta_d: (id as f64 + 0.5) / nd as f64 * FRAC_PI_2,
        phi_d: (ip as f64 + 0.5) / np as f64 * PI,
    };
    hd.to_directions()
}

impl Merl {
    /// A table from planar values in 1/sr (`3 * BINS`).
    pub fn from_values(values: Vec<f64>) -> Result<Self, IoError> {
        if values.len() != 3 * BINS {
            return Err(IoError::Count {
                path: "<memory>".into(),
                line: 0,
                expected: format!("{} values", 3 * BINS),
                found: values.len().to_string(),
            });
        }
        Ok(Self { values })
    }

    /// The planar values in 1/sr.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// Number of invalid (negative) bins, counted per channel.
    pub fn invalid_count(&self) -> usize {
        self.values.iter().filter(|v| **v < 0.0).count()
    }

    /// RGB of a direction pair; `None` below the horizon or in an invalid bin.
    pub fn lookup(&self, l: &Vector3<f64>, v: &Vector3<f64>) -> Option<[f64; 3]> {
        let b = bin_of(l, v)?;
        let rgb = [
            self.values[b],
            self.values[BINS + b],
            self.values[2 * BINS + b],
        ];
        if rgb.iter().any(|x| *x < 0.0) {
            None
        } else {
            Some(rgb)
        }
    }

    /// Sample any BRDF (3 channels, or 1 channel copied to all three) at the
    /// bin centres; bins whose centre has a direction below the horizon are
    /// marked invalid (`-1`).
    pub fn resample(brdf: &dyn Brdf) -> Self {
        let nc = brdf.channels();
        let (nh, nd, np) = DIMS;
        let mut values = vec![-1.0; 3 * BINS];
        let mut out = vec![0.0; nc.max(1)];
        for ih in 0..nh {
            for id in 0..nd {
                for ip in 0..np {
                    let (l, v) = bin_centre(ih, id, ip);
                    if !(l.z > 0.0 && v.z > 0.0) {
                        continue;
                    }
                    brdf.eval(&l, &v, &mut out);
                    let b = ih * nd * np + id * np + ip;
                    for c in 0..3 {
                        values[c * BINS + b] = out[if nc == 3 { c } else { 0 }];
                    }
                }
            }
        }
        Self { values }
    }

    /// The valid bins as samples at their centres, weighted by their solid
    /// angle measure; `stride` keeps every `stride`-th bin (1 = all).
    /// Returns the set and the number of invalid bins left out.
    pub fn to_samples(&self, name: &str, stride: usize) -> (SampleSet, usize) {
        let mut s = SampleSet::new(
            name,
            "MERL binary",
            vec!["r".into(), "g".into(), "b".into()],
        );
        let (nh, nd, np) = DIMS;
        let mut invalid = 0;
        let mut k = 0usize;
        for ih in 0..nh {
            for id in 0..nd {
                let w = merl_bin_solid_angle(ih, id);
                for ip in 0..np {
                    k += 1;
                    if !(k - 1).is_multiple_of(stride.max(1)) {
                        continue;
                    }
                    let b = ih * nd * np + id * np + ip;
                    let rgb = [
                        self.values[b],
                        self.values[BINS + b],
                        self.values[2 * BINS + b],
                    ];
                    let (l, v) = bin_centre(ih, id, ip);
                    if rgb.iter().any(|x| *x < 0.0 || !x.is_finite()) || !(l.z > 0.0 && v.z > 0.0) {
                        invalid += 1;
                        continue;
                    }
                    let (ld, vd) = (Direction::new_unchecked(l), Direction::new_unchecked(v));
                    if s.push(&ld, &vd, &rgb, w).is_err() {
                        invalid += 1;
                    }
                }
            }
        }
        (s, invalid)
    }
}

impl Brdf for Merl {
    fn channels(&self) -> usize {
        3
    }
    /// Bin lookup; 0 below the horizon and in invalid bins.
    fn eval(&self, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        let rgb = self.lookup(l, v).unwrap_or([0.0; 3]);
        out[..3].copy_from_slice(&rgb);
    }
}

/// Read a MERL `.binary` file.
pub fn read(path: &Path) -> Result<Merl, IoError> {
    let bytes = std::fs::read(path).map_err(|source| IoError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    parse(path, &bytes)
}

/// Parse the bytes of a MERL file (`path` only names it in errors).
pub fn parse(path: &Path, bytes: &[u8]) -> Result<Merl, IoError> {
    let fmt = |offset: usize, reason: String| IoError::Format {
        path: path.to_path_buf(),
        line: 0,
        reason: format!("byte {offset}: {reason}"),
    };
    if bytes.len() < 12 {
        return Err(fmt(bytes.len(), "truncated header (needs 12 bytes)".into()));
    }
    let dims: Vec<i32> = (0..3)
        .map(|k| {
            i32::from_le_bytes([
                bytes[4 * k],
                bytes[4 * k + 1],
                bytes[4 * k + 2],
                bytes[4 * k + 3],
            ])
        })
        .collect();
    if dims != [90, 90, 180] {
        return Err(fmt(
            0,
            format!("dimensions {dims:?}, expected [90, 90, 180]"),
        ));
    }
    let need = 12 + 3 * BINS * 8;
    if bytes.len() != need {
        return Err(fmt(
            bytes.len().min(need),
            format!(
                "file has {} bytes, a MERL table has {need} (truncated or trailing data)",
                bytes.len()
            ),
        ));
    }
    let mut values = Vec::with_capacity(3 * BINS);
    for k in 0..3 * BINS {
        let o = 12 + 8 * k;
        let mut b = [0u8; 8];
        b.copy_from_slice(&bytes[o..o + 8]);
        let x = f64::from_le_bytes(b);
        if x.is_nan() || x.is_infinite() {
            return Err(fmt(o, format!("value {x} is not finite")));
        }
        // Negative stored values mark invalid bins: keep them negative.
        values.push(if x < 0.0 { x } else { x * SCALE[k / BINS] });
    }
    Ok(Merl { values })
}

/// Write a MERL `.binary` file (values divided by the channel scales;
/// invalid bins written as stored, i.e. negative).
pub fn write(path: &Path, m: &Merl) -> Result<(), IoError> {
    let mut bytes = Vec::with_capacity(12 + 3 * BINS * 8);
    for d in [90i32, 90, 180] {
        bytes.extend_from_slice(&d.to_le_bytes());
    }
    for (k, v) in m.values.iter().enumerate() {
        let x = if *v < 0.0 { *v } else { *v / SCALE[k / BINS] };
        bytes.extend_from_slice(&x.to_le_bytes());
    }
    std::fs::write(path, bytes).map_err(|source| IoError::Io {
        path: path.to_path_buf(),
        source,
    })
}
