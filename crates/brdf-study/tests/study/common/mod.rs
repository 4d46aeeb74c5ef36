//! Shared by the study's library tests (each test crate uses some of
//! it, hence the allowance).
#![allow(dead_code)]

use std::path::PathBuf;

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
