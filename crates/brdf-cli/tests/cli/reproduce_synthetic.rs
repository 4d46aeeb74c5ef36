//! Without measured data `brdf reproduce` runs the built-in synthetic
//! demonstration, which stands in for CUReT and Cornell only: the parts
//! that need other data are said to be skipped before anything is
//! announced, never announced and then skipped.

use std::process::Command;

fn brdf(args: &[&str]) -> (bool, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_brdf"))
        .args(args)
        .env_remove("BRDF_DATA")
        .output()
        .expect("brdf runs");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn parts_without_a_synthetic_stand_in_are_skipped_not_announced() {
    let out = std::env::temp_dir().join(format!("brdf-synthetic-skips-{}", std::process::id()));
    let out_arg = out.display().to_string();
    let (ok, err) = brdf(&["reproduce", "--only", "new_models,sopp", "--out", &out_arg]);
    assert!(!ok, "{err}");
    for part in ["new_models", "sopp"] {
        assert!(
            err.contains(&format!(
                "{part} skipped: needs measured data ($BRDF_DATA/rgl)"
            )),
            "{err}"
        );
        assert!(!err.contains(&format!("brdf reproduce: {part} (")), "{err}");
    }
    assert!(err.contains("set BRDF_DATA"), "{err}");
    let _ = std::fs::remove_dir_all(&out);
}
