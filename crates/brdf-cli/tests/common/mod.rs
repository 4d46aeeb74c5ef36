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
