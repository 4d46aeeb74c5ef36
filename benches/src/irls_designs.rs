//! The IRLS designs, shared by the criterion bench
//! (`benches/irls.rs`) and the side-by-side binary `irls_peer`: Kurt's
//! degree-7 polynomial designs of the isotropic CUReT materials, a
//! fixed-seed synthetic tall design with gross outliers, and their export
//! for `benches/peers/irls_statsmodels.py` (row-major little-endian `f64`,
//! the response as the last column, plus `manifest.json`).

use std::path::Path;

use brdf_core::SampleSet;
use brdf_models::{ModelConfig, build_for};
use faer::Mat;

use crate::peers::PeerError;

/// A named design `X` and response `y`.
pub struct Design {
    /// Name (`curet#N` or `generated-MxP`: the fixed-seed design).
    pub name: String,
    /// The design matrix.
    pub x: Mat<f64>,
    /// The response.
    pub y: Vec<f64>,
}

/// Kurt's degree-7 polynomial design of one grey CUReT sample set, built as
/// `brdf-fit`'s `pipeline::fit_all_linear` builds it (columns that are zero on every
/// row dropped; rows scaled by `sqrt(w) cos_i`).
pub fn polynomial_design(set: &SampleSet) -> Result<Design, PeerError> {
    let config = ModelConfig {
        channels: 1,
        degree: 7,
        ..ModelConfig::default()
    };
    let model = build_for("polynomial", &config, set.pairs())?;
    let (n, np) = (set.len(), model.n_params());
    let zero = vec![0.0; np];
    let mut offset = vec![0.0; n];
    let mut jac = vec![0.0; n * np];
    model.eval_grad_batch_at(&zero, set.pairs(), &mut offset, &mut jac);
    let cols: Vec<usize> = (0..np)
        .filter(|&k| (0..n).any(|j| jac[j * np + k] != 0.0))
        .collect();
    let (w, lz, v) = (set.weights(), &set.pairs().lz, set.channel(0));
    let s: Vec<f64> = (0..n).map(|j| w[j].sqrt() * lz[j]).collect();
    Ok(Design {
        name: set.name.split(' ').next().unwrap_or("curet").to_string(),
        x: Mat::from_fn(n, cols.len(), |j, k| s[j] * jac[j * np + cols[k]]),
        y: (0..n).map(|j| s[j] * (v[j] - offset[j])).collect(),
    })
}

/// The CUReT sample number of a set named `curet#N ...`.
fn curet_number(set: &SampleSet) -> Option<u32> {
    set.name
        .split(' ')
        .next()
        .and_then(|t| t.strip_prefix("curet#"))
        .and_then(|n| n.parse().ok())
}

/// The design of every isotropic CUReT material (Kurt's 52) read from
/// `data/curet` (invalid samples and those beyond the 80-degree limit
/// dropped), in sample order; with `only`, just those sample numbers.
pub fn curet_designs(data: &Path, only: Option<&[u32]>) -> Result<Vec<Design>, PeerError> {
    let dir = data.join("curet");
    let sets = brdf_io::curet::read_grey(&dir.join("abrdf.dat"), &dir.join("table.txt"))?;
    sets.iter()
        .filter(|s| {
            curet_number(s).is_some_and(|n| {
                brdf_io::curet::is_isotropic(n) && only.is_none_or(|o| o.contains(&n))
            })
        })
        .map(|s| {
            let (s, _) = s.filter_invalid(false);
            let (s, _) = s.filter_angle_limit(80f64.to_radians());
            polynomial_design(&s)
        })
        .collect()
}

/// SplitMix64: a fixed-seed generator (uniform in [0, 1)).
struct SplitMix(u64);

impl SplitMix {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// `m x p` design (intercept and uniform features), `y = X beta + noise`
/// with 5% of the rows shifted by a gross error; the same in every run.
pub fn synthetic(m: usize, p: usize) -> Design {
    let mut g = SplitMix(20261201);
    let mut x = Mat::from_fn(m, p, |_, j| if j == 0 { 1.0 } else { 0.0 });
    let mut y = vec![0.0; m];
    for i in 0..m {
        let mut fit = 0.0;
        for j in 1..p {
            x[(i, j)] = 2.0 * g.next() - 1.0;
            fit += x[(i, j)] / j as f64;
        }
        let noise = 0.1 * (g.next() + g.next() + g.next() - 1.5);
        let outlier = if g.next() < 0.05 {
            20.0 * (g.next() - 0.3)
        } else {
            0.0
        };
        y[i] = 1.0 + fit + noise + outlier;
    }
    Design {
        name: format!("generated-{m}x{p}"),
        x,
        y,
    }
}

/// Write the designs to `dir` for the statsmodels peer script: one
/// `NAME.f64` per design (`#` in the name written as `-`) and
/// `manifest.json` listing name, rows, cols and file.
pub fn export(designs: &[&Design], dir: &Path) -> Result<(), PeerError> {
    let io = |path: &Path| {
        let path = path.display().to_string();
        move |source| PeerError::Io { path, source }
    };
    std::fs::create_dir_all(dir).map_err(io(dir))?;
    let mut entries = Vec::new();
    for d in designs {
        let (m, p) = (d.x.nrows(), d.x.ncols());
        let mut bytes = Vec::with_capacity(m * (p + 1) * 8);
        for i in 0..m {
            for j in 0..p {
                bytes.extend_from_slice(&d.x[(i, j)].to_le_bytes());
            }
            bytes.extend_from_slice(&d.y[i].to_le_bytes());
        }
        let file = format!("{}.f64", d.name.replace('#', "-"));
        let path = dir.join(&file);
        std::fs::write(&path, bytes).map_err(io(&path))?;
        entries.push(serde_json::json!({"name": d.name, "rows": m, "cols": p, "file": file}));
    }
    let manifest = serde_json::json!({
        "layout": "row-major f64 LE, response last",
        "designs": entries,
    });
    let path = dir.join("manifest.json");
    std::fs::write(&path, format!("{manifest:#}\n")).map_err(io(&path))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The export reads back as written: row-major, the response last, and
    /// a manifest naming rows, columns and file.
    #[test]
    fn export_round_trip() {
        let d = synthetic(7, 3);
        let dir = std::env::temp_dir().join(format!("irls-designs-test-{}", std::process::id()));
        export(&[&d], &dir).expect("export");
        let bytes = std::fs::read(dir.join("generated-7x3.f64")).expect("design file");
        assert_eq!(bytes.len(), 7 * 4 * 8);
        let v: Vec<f64> = bytes
            .chunks_exact(8)
            .map(|c| f64::from_le_bytes(c.try_into().expect("8 bytes")))
            .collect();
        for i in 0..7 {
            for j in 0..3 {
                assert_eq!(v[i * 4 + j], d.x[(i, j)]);
            }
            assert_eq!(v[i * 4 + 3], d.y[i]);
        }
        let m: serde_json::Value = serde_json::from_str(
            &std::fs::read_to_string(dir.join("manifest.json")).expect("manifest"),
        )
        .expect("manifest JSON");
        let e = &m["designs"][0];
        assert_eq!(e["name"], "generated-7x3");
        assert_eq!((e["rows"].as_u64(), e["cols"].as_u64()), (Some(7), Some(3)));
        assert_eq!(e["file"], "generated-7x3.f64");
        std::fs::remove_dir_all(&dir).expect("clean up");
    }

    /// The synthetic design is the same in every run and has its intercept.
    #[test]
    fn synthetic_is_deterministic() {
        let (a, b) = (synthetic(50, 4), synthetic(50, 4));
        assert_eq!(a.y, b.y);
        assert!((0..50).all(|i| a.x[(i, 0)] == 1.0 && a.x[(i, 1)].abs() <= 1.0));
    }
}
