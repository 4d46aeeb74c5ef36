//! Whole fits on measured data, each from the same inputs every
//! run; they need `BRDF_DATA` and say so when it is unset.
//!
//! - `fits-full-grid`: RGL paper_white on the full MERL grid (every valid
//!   bin, 80-degree limit, Ngan's rows), Ashikhmin-Shirley grey and RGB and
//!   Cook-Torrance grey from the first `brdf fit` start: the bounded solver
//!   on all parameters, and variable projection + polish. A fit takes
//!   seconds: 10 samples, short warm-up and measurement time.
//! - `fits-curet25`: `brdf fit`'s pipeline (12 Halton starts, variable
//!   projection, polish) on CUReT sample 25 per catalogue model.
//! - `nist-strd`: the certification strategy on every StRD file present,
//!   from both certified starts.

use std::hint::black_box;
use std::path::PathBuf;
use std::time::Duration;

use brdf_benches::peers::{PeerProblem, ours, problem};
use brdf_models::{ModelConfig, build};
use brdf_study::pipeline::{FitOptions, fit};
use criterion::{Criterion, criterion_group, criterion_main};

fn data_dir() -> Option<PathBuf> {
    let d = std::env::var_os("BRDF_DATA").map(PathBuf::from);
    if d.is_none() {
        eprintln!("fits: BRDF_DATA is not set; the fit benches are skipped");
    }
    d
}

fn scratch() -> PathBuf {
    let d = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("target"))
        .join("peers");
    std::fs::create_dir_all(&d).expect("scratch folder for the resampled MERL table");
    d
}

fn full_grid_case(c: &mut Criterion, prob: &PeerProblem) {
    let mut g = c.benchmark_group("fits-full-grid");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(5));
    g.bench_function(format!("{}/bounded", prob.name), |b| {
        b.iter(|| ours::bounded(black_box(prob)).expect("bounded fit"))
    });
    g.bench_function(format!("{}/varpro+polish", prob.name), |b| {
        b.iter(|| ours::varpro_polish(black_box(prob)).expect("varpro fit"))
    });
    g.finish();
}

fn full_grid(c: &mut Criterion) {
    let Some(data) = data_dir() else { return };
    let out = scratch();
    for (nc, model) in [
        (1, "ashikhmin-shirley"),
        (3, "ashikhmin-shirley"),
        (1, "cook-torrance"),
    ] {
        let prob = problem::paper_white(&data, &out, nc, model).expect("paper_white problem");
        full_grid_case(c, &prob);
    }
}

fn curet(c: &mut Criterion) {
    let Some(data) = data_dir() else { return };
    let dir = data.join("curet");
    let sets = brdf_io::curet::read_grey(&dir.join("abrdf.dat"), &dir.join("table.txt"))
        .expect("CUReT files");
    let set = sets
        .into_iter()
        .find(|s| s.name.starts_with("curet#25 "))
        .expect("CUReT sample 25");
    let (set, _) = set.filter_angle_limit(problem::LIMIT_DEG.to_radians());
    let opts = FitOptions::default();
    let mut g = c.benchmark_group("fits-curet25");
    g.sample_size(20).measurement_time(Duration::from_secs(3));
    for name in [
        "ashikhmin-shirley",
        "cook-torrance",
        "ward",
        "blinn-phong",
        "lafortune",
        "oren-nayar",
    ] {
        let Ok(model) = build(name, &ModelConfig::default()) else {
            eprintln!("fits: model `{name}` is not in this build; skipped");
            continue;
        };
        g.bench_function(name, |b| {
            b.iter(|| {
                let mut m = model.clone_box();
                fit(m.as_mut(), black_box(&set), &opts).expect("CUReT fit")
            })
        });
    }
    g.finish();
}

fn nist(c: &mut Criterion) {
    let Some(data) = data_dir() else { return };
    let sets = brdf_io::nist::read_dir(&data.join("nist_strd")).expect("StRD files");
    let strategies = brdf_study::nist::strategies();
    let mut g = c.benchmark_group("nist-strd");
    g.sample_size(20);
    g.bench_function(format!("all-{}-files-both-starts", sets.len()), |b| {
        b.iter(|| {
            for ds in &sets {
                black_box(brdf_study::nist::run_dataset(ds, &strategies).expect("StRD run"));
            }
        })
    });
    g.finish();
}

criterion_group!(benches, full_grid, curet, nist);
criterion_main!(benches);
