//! Shared by the `brdf` command's integration tests (each test crate uses some of
//! it, hence the allowance).
#![allow(dead_code)]

use std::path::PathBuf;
use std::process::Command;

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
