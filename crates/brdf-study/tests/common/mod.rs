//! Shared by the study's library tests (each test crate uses some of
//! it, hence the allowance).
#![allow(dead_code)]

use std::path::PathBuf;

/// The measured file `rel` under `BRDF_DATA`: `None` (said on stderr) when
/// the variable is unset; a loud failure when it is set and the file is
/// missing.
pub fn data_file(rel: &str) -> Option<PathBuf> {
    let Some(root) = std::env::var_os("BRDF_DATA") else {
        eprintln!("skipped: BRDF_DATA is not set");
        return None;
    };
    let path = PathBuf::from(root).join(rel);
    assert!(
        path.exists(),
        "BRDF_DATA is set but {} is missing",
        path.display()
    );
    Some(path)
}
