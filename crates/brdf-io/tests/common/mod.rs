//! Shared by the RGL tests: the measured files under `BRDF_DATA`.

use std::path::PathBuf;

/// `$BRDF_DATA/rgl/NAME`, or `None` when `BRDF_DATA` is unset (the test
/// then says it was skipped); a loud failure when it is set and the file is
/// missing.
pub fn data(name: &str) -> Option<PathBuf> {
    let root = std::env::var_os("BRDF_DATA")?;
    let p = PathBuf::from(root).join("rgl").join(name);
    assert!(
        p.exists(),
        "BRDF_DATA is set but {} is missing",
        p.display()
    );
    Some(p)
}
