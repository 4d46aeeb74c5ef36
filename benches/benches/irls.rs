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

use brdf_benches::irls_designs::{self, Design, synthetic};
use brdf_solve::{IrlsOptions, irls};
use criterion::{Criterion, criterion_group};

/// The design of every isotropic CUReT material (Kurt's 52), or nothing when `BRDF_DATA` is unset.
fn curet_designs() -> Vec<Design> {
    let Some(root) = std::env::var_os("BRDF_DATA") else {
        eprintln!("BRDF_DATA unset: CUReT IRLS benches skipped");
        return Vec::new();
    };
    irls_designs::curet_designs(Path::new(&root), None)
        .expect("CUReT abrdf.dat and table.txt under BRDF_DATA")
}

fn export_dir() -> PathBuf {
    std::env::var_os("BRDF_IRLS_EXPORT")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_TARGET_TMPDIR")).join("irls-designs"))
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
        capped += usize::from(!a.converged());
        println!(
            "{:9} {:>3}{:13} {:>3}{}",
            d.name,
            a.iterations,
            if a.converged() { "" } else { " (cap)" },
            b.iterations,
            if b.converged() { "" } else { " (cap)" }
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
    irls_designs::export(&all, &dir).expect("export of the IRLS designs");
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
