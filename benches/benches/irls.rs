//! IRLS speed (bisquare, MATLAB 2004 scale, MATLAB's coefficient test) on
//! Kurt's degree-7 polynomial designs of CUReT materials (189 rows x 15
//! columns after the 80-degree limit, rows scaled by `sqrt(w) cos_i` as
//! `brdf fit` builds them; needs `BRDF_DATA`) and on a fixed-seed synthetic
//! design of 900,000 rows x 10 columns with 5% gross outliers.
//!
//! Before the benches run, every design is written (row-major `f64`
//! little-endian, the response as the last column, plus `manifest.json`)
//! to `$BRDF_IRLS_EXPORT` (default: `irls-designs` under cargo's target
//! temporary directory), where `benches/peers/irls_statsmodels.py` reads
//! them, and a table of iteration counts of the plain MATLAB iteration and
//! the accelerated default on every CUReT material is printed.
//! With `BRDF_IRLS_FIXTURE=FILE`, the designs of CUReT samples 25, 4 and 61
//! are also written to FILE as JSON (how
//! `crates/brdf-solve/tests/fixtures/irls/curet_designs.json` is made).

use std::hint::black_box;
use std::path::{Path, PathBuf};

use brdf_core::SampleSet;
use brdf_models::{ModelConfig, build_for};
use brdf_solve::{IrlsOptions, irls};
use criterion::{Criterion, criterion_group};
use faer::Mat;

/// A named design `X` and response `y`.
struct Design {
    name: String,
    x: Mat<f64>,
    y: Vec<f64>,
}

/// Kurt's degree-7 polynomial design of one grey CUReT sample set, built as
/// `brdf-study`'s `fit_all_linear` builds it (columns that are zero on every
/// row dropped).
fn polynomial_design(set: &SampleSet) -> Design {
    let config = ModelConfig {
        channels: 1,
        degree: 7,
        ..ModelConfig::default()
    };
    let model = build_for("polynomial", &config, set.pairs()).expect("polynomial model");
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
    Design {
        name: set.name.split(' ').next().unwrap_or("curet").to_string(),
        x: Mat::from_fn(n, cols.len(), |j, k| s[j] * jac[j * np + cols[k]]),
        y: (0..n).map(|j| s[j] * (v[j] - offset[j])).collect(),
    }
}

/// The design of every isotropic CUReT material (Kurt's 52), or nothing when `BRDF_DATA` is unset.
fn curet_designs() -> Vec<Design> {
    let Some(root) = std::env::var_os("BRDF_DATA") else {
        eprintln!("BRDF_DATA unset: CUReT IRLS benches skipped");
        return Vec::new();
    };
    let dir = Path::new(&root).join("curet");
    let sets = brdf_io::curet::read_grey(&dir.join("abrdf.dat"), &dir.join("table.txt"))
        .expect("CUReT abrdf.dat and table.txt under BRDF_DATA");
    sets.iter()
        .filter(|s| {
            let n = s
                .name
                .split(' ')
                .next()
                .and_then(|t| t.strip_prefix("curet#"));
            n.and_then(|n| n.parse().ok())
                .is_some_and(brdf_io::curet::is_isotropic)
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
/// with 5% of the rows shifted by a gross error.
fn synthetic(m: usize, p: usize) -> Design {
    let mut g = SplitMix(20261201);
    let x = Mat::from_fn(m, p, |_, j| if j == 0 { 1.0 } else { 0.0 });
    let mut x = x;
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
        name: format!("synthetic-{m}x{p}"),
        x,
        y,
    }
}

fn export_dir() -> PathBuf {
    std::env::var_os("BRDF_IRLS_EXPORT")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_TARGET_TMPDIR")).join("irls-designs"))
}

/// Write the designs for the statsmodels peer script.
fn export(designs: &[&Design], dir: &Path) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
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
        std::fs::write(dir.join(&file), bytes)?;
        entries.push(format!(
            "{{\"name\": \"{}\", \"rows\": {m}, \"cols\": {p}, \"file\": \"{file}\"}}",
            d.name
        ));
    }
    std::fs::write(
        dir.join("manifest.json"),
        format!(
            "{{\"layout\": \"row-major f64 LE, response last\", \"designs\": [\n{}\n]}}\n",
            entries.join(",\n")
        ),
    )
}

/// JSON of selected CUReT designs for brdf-solve's tests.
fn write_fixture(designs: &[Design], file: &Path) -> std::io::Result<()> {
    let pick = ["curet#25", "curet#4", "curet#61"];
    let mut parts = Vec::new();
    for name in pick {
        let Some(d) = designs.iter().find(|d| d.name == name) else {
            continue;
        };
        let rows: Vec<String> = (0..d.x.nrows())
            .map(|i| {
                let r: Vec<String> = (0..d.x.ncols())
                    .map(|j| format!("{:e}", d.x[(i, j)]))
                    .collect();
                format!("[{}]", r.join(", "))
            })
            .collect();
        let y: Vec<String> = d.y.iter().map(|v| format!("{v:e}")).collect();
        parts.push(format!(
            "{{\"name\": \"{name}\", \"X\": [\n{}\n], \"y\": [{}]}}",
            rows.join(",\n"),
            y.join(", ")
        ));
    }
    std::fs::write(
        file,
        format!(
            "{{\"generator\": \"benches/benches/irls.rs with BRDF_IRLS_FIXTURE (see export_curet.sh)\",\n\"designs\": [\n{}\n]}}\n",
            parts.join(",\n")
        ),
    )
}

/// Iterations of the plain MATLAB loop and of the default, per material.
fn iteration_table(designs: &[Design]) {
    let plain = IrlsOptions {
        acceleration: false,
        ..IrlsOptions::default()
    };
    let mut capped = 0;
    println!("material  plain(cap 50)  default");
    for d in designs {
        let a = irls(d.x.as_ref(), &d.y, &plain).expect("plain IRLS");
        let b = irls(d.x.as_ref(), &d.y, &IrlsOptions::default()).expect("IRLS");
        capped += usize::from(!a.converged);
        println!(
            "{:9} {:>3}{:13} {:>3}{}",
            d.name,
            a.iterations,
            if a.converged { "" } else { " (cap)" },
            b.iterations,
            if b.converged { "" } else { " (cap)" }
        );
    }
    println!("plain loop at the cap on {capped} of {}", designs.len());
}

fn benches(c: &mut Criterion) {
    let curet = curet_designs();
    let big = synthetic(900_000, 10);
    let dir = export_dir();
    let mut all: Vec<&Design> = curet.iter().collect();
    all.push(&big);
    export(&all, &dir).expect("export of the IRLS designs");
    eprintln!("IRLS designs written to {}", dir.display());
    if let Some(f) = std::env::var_os("BRDF_IRLS_FIXTURE") {
        write_fixture(&curet, Path::new(&f)).expect("fixture");
    }
    iteration_table(&curet);
    let plain = IrlsOptions {
        acceleration: false,
        ..IrlsOptions::default()
    };
    let mut g = c.benchmark_group("irls");
    for d in curet
        .iter()
        .filter(|d| ["curet#25", "curet#4"].contains(&d.name.as_str()))
    {
        g.bench_function(format!("{}/plain", d.name), |b| {
            b.iter(|| irls(d.x.as_ref(), black_box(&d.y), &plain))
        });
        g.bench_function(format!("{}/default", d.name), |b| {
            b.iter(|| irls(d.x.as_ref(), black_box(&d.y), &IrlsOptions::default()))
        });
    }
    g.sample_size(10);
    g.bench_function(format!("{}/default", big.name), |b| {
        b.iter(|| irls(big.x.as_ref(), black_box(&big.y), &IrlsOptions::default()))
    });
    g.finish();
}

criterion_group!(irls_benches, benches);

fn main() {
    irls_benches();
    Criterion::default().configure_from_args().final_summary();
}
