//! Sopp's goniometric grid (car paints, Sopp 2017): light polar angle 0..90
//! degrees in 5-degree steps (19 values) at azimuth 180 degrees (the
//! negative x axis); camera polar 0..90 in 2.5-degree steps (37) and azimuth
//! 0..180 in 180/35-degree steps (36), from +x; RGB; `19 x 37 x 36 x 3 =
//! 75,924` values.
//!
//! [`SoppGrid::resample`] samples any evaluable BRDF on it; the grid is
//! written and read as CSV (`light_theta_deg,camera_theta_deg,camera_phi_deg,r,g,b`);
//! [`SoppGrid::weights`] gives the camera cells' solid angles (a full cell in
//! the interior, half a cell on an edge, a quarter in a corner, as the
//! cell edges halfway between nodes give); [`SoppGrid::to_samples`] turns it
//! into samples with those weights and an angle limit.

use std::path::Path;

use brdf_core::weights::grid_solid_angles;
use brdf_core::{Brdf, Direction, SampleSet, spherical_to_cartesian};

use crate::IoError;

/// Light polar angles.
pub const LIGHTS: usize = 19;
/// Camera polar angles.
pub const CAM_THETAS: usize = 37;
/// Camera azimuths.
pub const CAM_PHIS: usize = 36;

/// Light polar angle `k` in degrees.
pub fn light_theta_deg(k: usize) -> f64 {
    5.0 * k as f64
}
/// Camera polar angle `k` in degrees.
pub fn camera_theta_deg(k: usize) -> f64 {
    2.5 * k as f64
}
/// Camera azimuth `k` in degrees.
pub fn camera_phi_deg(k: usize) -> f64 {
    180.0 / 35.0 * k as f64
}

/// A grid of RGB values.
#[derive(Clone, Debug, PartialEq)]
pub struct SoppGrid {
    values: Vec<f64>,
}

fn index(il: usize, it: usize, ip: usize) -> usize {
    (il * CAM_THETAS + it) * CAM_PHIS + ip
}

impl SoppGrid {
    /// Number of grid nodes.
    pub const NODES: usize = LIGHTS * CAM_THETAS * CAM_PHIS;

    /// The light and camera directions of node `(il, it, ip)`.
    pub fn directions(
        il: usize,
        it: usize,
        ip: usize,
    ) -> (nalgebra::Vector3<f64>, nalgebra::Vector3<f64>) {
        let l = spherical_to_cartesian(light_theta_deg(il).to_radians(), std::f64::consts::PI);
        let v = spherical_to_cartesian(
            camera_theta_deg(it).to_radians(),
            camera_phi_deg(ip).to_radians(),
        );
        (l, v)
    }

    /// RGB of node `(il, it, ip)`.
    pub fn rgb(&self, il: usize, it: usize, ip: usize) -> [f64; 3] {
        let b = 3 * index(il, it, ip);
        [self.values[b], self.values[b + 1], self.values[b + 2]]
    }

    /// All values, node-major (`3 * NODES`).
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// Sample a BRDF (3 channels, or 1 copied to all) at every node.
    pub fn resample(brdf: &dyn Brdf) -> Self {
        let nc = brdf.channels();
        let mut out = vec![0.0; nc.max(1)];
        let mut values = vec![0.0; 3 * Self::NODES];
        for il in 0..LIGHTS {
            for it in 0..CAM_THETAS {
                for ip in 0..CAM_PHIS {
                    let (l, v) = Self::directions(il, it, ip);
                    brdf.eval(&l, &v, &mut out);
                    for c in 0..3 {
                        values[3 * index(il, it, ip) + c] = out[if nc == 3 { c } else { 0 }];
                    }
                }
            }
        }
        Self { values }
    }

    /// Solid angle of each camera cell, `[it * CAM_PHIS + ip]` (the camera
    /// covers half the hemisphere, `phi` in `[0, pi]`).
    pub fn weights() -> Vec<f64> {
        let th: Vec<f64> = (0..CAM_THETAS)
            .map(|k| camera_theta_deg(k).to_radians())
            .collect();
        let ph: Vec<f64> = (0..CAM_PHIS)
            .map(|k| camera_phi_deg(k).to_radians())
            .collect();
        // Node grids are strictly increasing, so this cannot fail.
        grid_solid_angles(&th, &ph).unwrap_or_else(|_| vec![0.0; CAM_THETAS * CAM_PHIS])
    }

    /// Samples with light and camera polar angles at most `limit_deg`,
    /// weighted by the camera cells' solid angles (`weighted`) or 1.
    pub fn to_samples(&self, name: &str, limit_deg: f64, weighted: bool) -> SampleSet {
        let w = Self::weights();
        let mut s = SampleSet::new(
            name,
            "Sopp goniometric grid",
            vec!["r".into(), "g".into(), "b".into()],
        );
        for il in 0..LIGHTS {
            for it in 0..CAM_THETAS {
                if light_theta_deg(il) > limit_deg || camera_theta_deg(it) > limit_deg {
                    continue;
                }
                for ip in 0..CAM_PHIS {
                    let (l, v) = Self::directions(il, it, ip);
                    if !(l.z > 0.0 && v.z > 0.0) {
                        continue;
                    }
                    let wt = if weighted { w[it * CAM_PHIS + ip] } else { 1.0 };
                    let _ = s.push(
                        &Direction::new_unchecked(l),
                        &Direction::new_unchecked(v),
                        &self.rgb(il, it, ip),
                        wt,
                    );
                }
            }
        }
        s
    }
}

/// Write a grid as CSV.
pub fn write(path: &Path, g: &SoppGrid) -> Result<(), IoError> {
    let mut text = String::from("light_theta_deg,camera_theta_deg,camera_phi_deg,r,g,b\n");
    for il in 0..LIGHTS {
        for it in 0..CAM_THETAS {
            for ip in 0..CAM_PHIS {
                let [r, gg, b] = g.rgb(il, it, ip);
                text.push_str(&format!(
                    "{},{},{},{r},{gg},{b}\n",
                    light_theta_deg(il),
                    camera_theta_deg(it),
                    camera_phi_deg(ip)
                ));
            }
        }
    }
    std::fs::write(path, text).map_err(|source| IoError::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// Read a grid written by [`write`](fn@write) (every node exactly once, in any order).
pub fn read(path: &Path) -> Result<SoppGrid, IoError> {
    let text = std::fs::read_to_string(path).map_err(|source| IoError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    parse(path, &text)
}

/// Parse grid CSV text.
pub fn parse(path: &Path, text: &str) -> Result<SoppGrid, IoError> {
    let mut lines = text.lines().enumerate();
    match lines.next() {
        Some((_, h)) if h.trim() == "light_theta_deg,camera_theta_deg,camera_phi_deg,r,g,b" => {}
        _ => {
            return Err(IoError::Format {
                path: path.to_path_buf(),
                line: 1,
                reason: "header must be light_theta_deg,camera_theta_deg,camera_phi_deg,r,g,b"
                    .into(),
            });
        }
    }
    let mut values = vec![f64::NAN; 3 * SoppGrid::NODES];
    let mut seen = vec![false; SoppGrid::NODES];
    for (i, line) in lines {
        let line_no = i + 1;
        if line.trim().is_empty() {
            continue;
        }
        let f: Vec<&str> = line.split(',').map(str::trim).collect();
        if f.len() != 6 {
            return Err(IoError::Count {
                path: path.to_path_buf(),
                line: line_no,
                expected: "6 fields".into(),
                found: f.len().to_string(),
            });
        }
        let mut v = [0.0; 6];
        for k in 0..6 {
            v[k] = f[k].parse().map_err(|_| IoError::NotANumber {
                path: path.to_path_buf(),
                line: line_no,
                field: k + 1,
                text: f[k].to_string(),
            })?;
        }
        let node = |x: f64, step: f64, n: usize| -> Option<usize> {
            let k = (x / step).round();
            (k >= 0.0 && (k as usize) < n && (x - k * step).abs() < 1e-6).then_some(k as usize)
        };
        let (Some(il), Some(it), Some(ip)) = (
            node(v[0], 5.0, LIGHTS),
            node(v[1], 2.5, CAM_THETAS),
            node(v[2], 180.0 / 35.0, CAM_PHIS),
        ) else {
            return Err(IoError::Format {
                path: path.to_path_buf(),
                line: line_no,
                reason: format!(
                    "({}, {}, {}) is not a node of Sopp's grid",
                    v[0], v[1], v[2]
                ),
            });
        };
        let k = index(il, it, ip);
        if seen[k] {
            return Err(IoError::Format {
                path: path.to_path_buf(),
                line: line_no,
                reason: "node given twice".into(),
            });
        }
        seen[k] = true;
        values[3 * k..3 * k + 3].copy_from_slice(&v[3..]);
    }
    if let Some(k) = seen.iter().position(|s| !s) {
        return Err(IoError::Count {
            path: path.to_path_buf(),
            line: 0,
            expected: format!("all {} nodes", SoppGrid::NODES),
            found: format!("node {k} missing (truncated file?)"),
        });
    }
    Ok(SoppGrid { values })
}
