//! Every refused argument is named with its fix — angles in
//! degrees without `--degrees`, a folder or a missing path as data, a data
//! file as a saved model, zero lobes or channels, a missing or empty
//! `BRDF_DATA` for `reproduce`, an unknown image format; repeated model
//! names count once; relative data paths are looked up under `BRDF_DATA`.

use crate::common;

use std::path::Path;
use std::process::Command;

use common::{brdf, data_file};

/// Run `brdf` in `cwd` with `BRDF_DATA` set to `data` (or unset):
/// (success, stdout, stderr).
fn brdf_in(cwd: &Path, data: Option<&Path>, args: &[&str]) -> (bool, String, String) {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_brdf"));
    cmd.current_dir(cwd).args(args);
    match data {
        Some(d) => cmd.env("BRDF_DATA", d),
        None => cmd.env_remove("BRDF_DATA"),
    };
    let out = cmd.output().expect("the brdf binary runs");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn tmp(name: &str) -> std::path::PathBuf {
    common::scratch("messages", name)
}

#[test]
fn eval_refuses_degrees_given_as_radians() {
    let (ok, _, err) = brdf(&["eval", "--model", "ggx", "--wi", "30,0", "--wo", "30,180"]);
    assert!(!ok);
    assert!(
        err.contains("`--wi 30,0`: 30 is not an angle in radians (> pi/2); add --degrees"),
        "{err}"
    );
    let (ok, _, err) = brdf(&[
        "eval",
        "--model",
        "ggx",
        "--wi",
        "30,0",
        "--wo",
        "30,180",
        "--degrees",
    ]);
    assert!(ok, "{err}");
}

#[test]
fn zero_lobes_or_channels_name_the_flag() {
    for flag in ["--lobes", "--channels"] {
        let (ok, _, err) = brdf(&[
            "eval",
            "--model",
            "lafortune",
            flag,
            "0",
            "--wi",
            "0.3,0",
            "--wo",
            "0.3,3",
        ]);
        assert!(
            !ok && err.contains(flag) && err.contains("at least 1"),
            "{err}"
        );
    }
    let (ok, _, err) = brdf(&["fit", "--data", "x.csv", "--model", "ggx", "--lobes", "0"]);
    assert!(
        !ok && err.contains("--lobes") && err.contains("at least 1"),
        "{err}"
    );
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn a_folder_or_a_missing_path_as_data_says_so() {
    let root = data_file("rgl");
    let root = root.parent().expect("BRDF_DATA");
    let cwd = tmp("folder");
    let (ok, _, err) = brdf_in(
        &cwd,
        Some(root),
        &["fit", "--data", "rgl/", "--model", "ggx"],
    );
    assert!(!ok);
    assert!(
        err.contains("`rgl/` is a folder: fit one file, or `brdf batch --data rgl/`"),
        "{err}"
    );
    let (ok, _, err) = brdf_in(
        &cwd,
        Some(root),
        &["fit", "--data", "no/x.bsdf", "--model", "ggx"],
    );
    assert!(!ok && err.contains("does not exist"), "{err}");
    assert!(
        err.contains("working directory") && err.contains("BRDF_DATA"),
        "{err}"
    );
    let out = cwd.join("out").display().to_string();
    let args = [
        "batch", "--data", "nothere", "--models", "lambert", "--out", &out,
    ];
    let (ok, _, err) = brdf_in(&cwd, Some(root), &args);
    assert!(!ok && err.contains("nothere: does not exist"), "{err}");
    assert!(!cwd.join("out").exists(), "a failed batch leaves no folder");
    let _ = std::fs::remove_dir_all(&cwd);
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn relative_data_paths_are_looked_up_under_brdf_data() {
    let file = data_file("curet/abrdf.dat");
    let root = file.parent().and_then(Path::parent).expect("BRDF_DATA");
    let cwd = tmp("lookup");
    let args = ["fit", "--data", "curet/abrdf.dat#25", "--model", "lambert"];
    let (ok, _, err) = brdf_in(&cwd, Some(root), &args);
    assert!(ok, "{err}");
    let (ok, _, err) = brdf_in(&cwd, None, &args);
    assert!(
        !ok && err.contains("does not exist") && err.contains("BRDF_DATA"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&cwd);
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn a_data_file_is_not_a_saved_model() {
    let f = data_file("rgl/cc_ibiza_sunset_rgb.bsdf");
    let f = f.display().to_string();
    let (ok, _, err) = brdf(&["eval", "--load", &f, "--wi", "0.3,0", "--wo", "0.3,3"]);
    assert!(!ok);
    assert!(
        err.contains("is a data file") && err.contains("brdf fit --save"),
        "{err}"
    );
    assert!(!err.contains("UTF-8"), "{err}");
}

#[test]
fn reproduce_refuses_a_missing_or_empty_data_folder() {
    let cwd = tmp("reproduce");
    let missing = cwd.join("missing");
    let (ok, _, err) = brdf_in(&cwd, Some(&missing), &["reproduce", "--out", "r"]);
    assert!(
        !ok && err.contains("BRDF_DATA=") && err.contains("missing"),
        "{err}"
    );
    let empty = cwd.join("empty");
    std::fs::create_dir_all(&empty).expect("empty folder");
    let (ok, _, err) = brdf_in(&cwd, Some(&empty), &["reproduce", "--out", "r"]);
    assert!(
        !ok && err.contains("empty") && err.contains("BRDF_DATA="),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&cwd);
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn render_chooses_the_format_by_extension() {
    let f = data_file("rgl/cc_ibiza_sunset_rgb.bsdf");
    let f = f.display().to_string();
    let cwd = tmp("render");
    let out = |n: &str| cwd.join(n).display().to_string();
    let (ok, _, err) = brdf(&["render", "--data", &f, "--size", "32", &out("a.jpg")]);
    assert!(!ok && err.contains(".png") && err.contains(".exr"), "{err}");
    let (ok, _, err) = brdf(&["render", "--data", &f, "--size", "32", &out("a.exr")]);
    assert!(ok, "{err}");
    let exr = std::fs::read(cwd.join("a.exr")).expect("exr written");
    assert_eq!(&exr[..4], &[0x76, 0x2f, 0x31, 0x01], "OpenEXR magic");
    let _ = std::fs::remove_dir_all(&cwd);
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn repeated_model_names_are_one_fit() {
    let file = data_file("curet/abrdf.dat");
    let cwd = tmp("dedup");
    let data = format!("{}#25", file.display());
    let out = cwd.join("b").display().to_string();
    let args = [
        "batch",
        "--data",
        &data,
        "--models",
        "ggx,GGX,Lambert,lambert",
    ];
    let (ok, _, err) = brdf(&[&args[..], &["--out", &out, "--starts", "2"]].concat());
    assert!(ok, "{err}");
    assert!(err.contains("2 fits in this share"), "{err}");
    let (ok, text, err) = brdf(&[
        "select",
        "--data",
        &data,
        "--models",
        "ggx,GGX,lambert",
        "--max-parameters",
        "5",
        "--json",
    ]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&text).expect("JSON");
    let mut labels: Vec<&str> = v["candidates"]
        .as_array()
        .expect("candidates")
        .iter()
        .filter_map(|r| r["label"].as_str())
        .collect();
    labels.sort();
    assert_eq!(labels, ["ggx (1 lobe)", "lambert"], "{text}");
    let _ = std::fs::remove_dir_all(&cwd);
}
