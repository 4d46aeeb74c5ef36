//! Shared by the RGL tests: the measured files under `BRDF_DATA`.

use std::path::PathBuf;

/// `$BRDF_DATA/rgl/NAME`. The tests that call this are
/// `#[ignore = "needs BRDF_DATA"]`; run with `--include-ignored`, they fail
/// loudly when the variable is unset or the file is missing.
pub fn data(name: &str) -> PathBuf {
    let root = std::env::var_os("BRDF_DATA")
        .unwrap_or_else(|| panic!("BRDF_DATA is not set: this test reads $BRDF_DATA/rgl/{name}"));
    let p = PathBuf::from(root).join("rgl").join(name);
    assert!(
        p.exists(),
        "BRDF_DATA is set but {} is missing",
        p.display()
    );
    p
}
