//! The `brdf models` and `brdf eval` commands, run as a user would.

use crate::common;

use common::brdf;

use std::process::Command;

#[test]
fn models_json_lists_lambert_with_its_box() {
    let (ok, out, err) = brdf(&["models", "--json"]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let lambert = v
        .as_array()
        .unwrap()
        .iter()
        .find(|m| m["name"] == "lambert")
        .unwrap();
    assert_eq!(lambert["parameters"][0]["name"], "kd");
    assert_eq!(lambert["parameters"][0]["upper"], 1.0);
    assert_eq!(lambert["parameters"][0]["linear"], true);
}

#[test]
fn eval_json_gives_kd_over_pi() {
    let (ok, out, err) = brdf(&[
        "eval",
        "--model",
        "lambert",
        "--params",
        "kd=0.5",
        "--wi",
        "30,0",
        "--wo",
        "60,180",
        "--degrees",
        "--json",
    ]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let f = v["channels"][0].as_f64().unwrap();
    assert!((f - 0.5 / std::f64::consts::PI).abs() < 1e-15);
    // Three channels, per-channel names.
    let (ok, out, err) = brdf(&[
        "eval",
        "--model",
        "lambert",
        "--channels",
        "3",
        "--params",
        "kd_g=1",
        "--wi",
        "0.1,0",
        "--wo",
        "0.2,1",
        "--json",
    ]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert!((v["channels"][1].as_f64().unwrap() - 1.0 / std::f64::consts::PI).abs() < 1e-15);
}

#[test]
fn eval_rejects_bad_input_with_a_message() {
    let (ok, _, err) = brdf(&[
        "eval", "--model", "lambert", "--params", "kd=2", "--wi", "0,0", "--wo", "0,0",
    ]);
    assert!(!ok);
    assert!(err.contains("`kd` = 2 is outside its box [0, 1]"), "{err}");
    let (ok, _, err) = brdf(&["eval", "--model", "nope", "--wi", "0,0", "--wo", "0,0"]);
    assert!(!ok);
    // The resolver's answer (no near name to suggest here).
    assert!(err.contains("no model `nope`"), "{err}");
    let (ok, _, err) = brdf(&["eval", "--model", "lambert", "--wi", "x,0", "--wo", "0,0"]);
    assert!(!ok);
    assert!(err.contains("not a number"), "{err}");
    let (ok, _, err) = brdf(&[
        "eval", "--model", "lambert", "--params", "kd", "--wi", "0,0", "--wo", "0,0",
    ]);
    assert!(!ok);
    assert!(err.contains("name=value"), "{err}");
}

/// A reader that stops early (`brdf models | head -1`) ends the command
/// quietly and successfully, not with a panic.
#[test]
fn closed_stdout_is_not_a_panic() {
    use std::process::Stdio;
    // The read end is closed before the command starts, so its first write
    // fails, every time.
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let out = Command::new(env!("CARGO_BIN_EXE_brdf"))
        .arg("models")
        .stdout(Stdio::from(writer))
        .stderr(Stdio::piped())
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{:?}: {err}", out.status);
    assert!(!err.contains("panicked"), "{err}");
}

/// `brdf eval --model NAME` at normal incidence, as (success, stdout, stderr).
fn eval_named(name: &str) -> (bool, String, String) {
    brdf(&[
        "eval", "--model", name, "--wi", "0,0", "--wo", "0,0", "--json",
    ])
}

#[test]
fn eval_takes_the_display_name() {
    let (ok, out, err) = eval_named("Blinn-Phong");
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["model"], "blinn-phong");
}

#[test]
fn eval_takes_underscores_for_hyphens() {
    let (ok, out, err) = eval_named("blinn_phong");
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["model"], "blinn-phong");
}

#[test]
fn eval_suggests_the_nearest_name_for_a_typo() {
    let (ok, _, err) = eval_named("blin-phong");
    assert!(!ok);
    assert!(err.contains("did you mean `blinn-phong`"), "{err}");
    assert!(
        err.lines().count() == 1,
        "one line, not the catalogue: {err}"
    );
}

#[test]
fn batch_resolves_names_with_the_same_suggestion() {
    let out = std::env::temp_dir().join(format!("brdf-batch-names-{}", std::process::id()));
    let (ok, _, err) = brdf(&[
        "batch",
        "--data",
        "nowhere",
        "--models",
        "blin-phong",
        "--out",
        &out.display().to_string(),
    ]);
    let _ = std::fs::remove_dir_all(&out);
    assert!(!ok);
    assert!(err.contains("did you mean `blinn-phong`"), "{err}");
}
