//! Shared by the `brdf` command's integration tests (each test crate uses some of
//! it, hence the allowance).
#![allow(dead_code)]

use std::path::PathBuf;
use std::process::Command;

/// An empty scratch folder `brdf-{prefix}-{name}-{pid}` in the system's
/// temporary folder (emptied first: a folder of an earlier run is not
/// trusted). Each test module passes its own prefix, so tests running at
/// once in this binary never share one.
pub fn scratch(prefix: &str, name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("brdf-{prefix}-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("scratch folder");
    d
}

/// Which data `brdf reproduce` runs on.
#[derive(Clone, Copy)]
pub enum Data {
    /// The measured files under `BRDF_DATA`, which must be set.
    Measured,
    /// The built-in synthetic data: `BRDF_DATA` is removed from the
    /// command's environment.
    Synthetic,
}

/// Run the `brdf` binary: (success, stdout, stderr).
pub fn brdf(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_brdf"))
        .args(args)
        .output()
        .expect("the brdf binary runs");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// The measured file `rel` under `BRDF_DATA`. The tests that call this are
/// `#[ignore = "needs BRDF_DATA"]`; run with `--include-ignored`, they fail
/// loudly when the variable is unset or the file is missing, rather than
/// passing without having looked at the data.
pub fn data_file(rel: &str) -> PathBuf {
    let root = std::env::var_os("BRDF_DATA")
        .unwrap_or_else(|| panic!("BRDF_DATA is not set: this test reads $BRDF_DATA/{rel}"));
    let path = PathBuf::from(root).join(rel);
    assert!(
        path.exists(),
        "BRDF_DATA is set but {} is missing",
        path.display()
    );
    path
}

/// The mean HDR-FLIP over the light sets of an image-error JSON object
/// (`{"lights": [{"flip": ...}, ...]}`, as `--json` prints it).
pub fn mean_flip(image: &serde_json::Value) -> f64 {
    let lights = image["lights"].as_array().expect("lights");
    lights
        .iter()
        .map(|l| l["flip"].as_f64().expect("flip"))
        .sum::<f64>()
        / lights.len() as f64
}
