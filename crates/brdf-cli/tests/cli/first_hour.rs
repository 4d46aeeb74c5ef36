//! What a newcomer meets in the first hour, without the measured data: a
//! CSV without weights is read with unit weights and said to be; `brdf fit`
//! prints the command's wall time beside the solver's; a negative number is
//! taken as a value and refused by the option's own range; an unknown
//! metric is answered with every choice; another name of a model gets the
//! catalogue's name.

use std::process::Command;

fn brdf(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_brdf"))
        .args(args)
        .env_remove("BRDF_DATA")
        .output()
        .expect("brdf runs");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// A Lambert material of albedo 0.5 (f = 0.5 / pi) sampled on a small
/// grid, without a weight column.
fn lambert_csv(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("brdf-first-hour-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let mut text = String::from("theta_i,phi_i,theta_o,phi_o,grey\n");
    for i in 0..6 {
        for o in 0..6 {
            let (ti, to) = (0.1 + 0.2 * i as f64, 0.1 + 0.2 * o as f64);
            text += &format!(
                "{ti},0,{to},{},{}\n",
                0.5 * o as f64,
                0.5 / std::f64::consts::PI
            );
        }
    }
    let path = dir.join(name);
    std::fs::write(&path, text).expect("csv written");
    path
}

#[test]
fn a_csv_without_weights_is_fitted_with_unit_weights_and_says_so() {
    let csv = lambert_csv("lambert.csv");
    let data = csv.display().to_string();
    let (ok, out, err) = brdf(&["fit", "--data", &data, "--model", "lambert", "--quiet"]);
    assert!(ok, "{err}");
    assert!(
        err.contains("no weight column; every sample weighted 1"),
        "{err}"
    );
    assert!(out.contains("wall time: "), "{out}");
    // The fit recovers the albedo: kd = 0.5 exactly up to the solver's
    // tolerance (the data are the model).
    let (ok, json, err) = brdf(&[
        "fit", "--data", &data, "--model", "lambert", "--json", "--quiet",
    ]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&json).expect("json");
    let kd = v["fits"][0]["parameters"][0]["value"].as_f64().expect("kd");
    assert!((kd - 0.5).abs() < 1e-9, "kd = {kd}");
}

#[test]
fn negative_numbers_are_values_refused_by_their_range() {
    let csv = lambert_csv("negative.csv");
    let data = csv.display().to_string();
    let (ok, _, err) = brdf(&["select", "--data", &data, "--tolerance", "-1"]);
    assert!(!ok);
    assert!(
        err.contains("tolerance") && !err.contains("unexpected argument"),
        "{err}"
    );
    let (ok, _, err) = brdf(&[
        "fit", "--data", &data, "--model", "lambert", "--limit", "-5",
    ]);
    assert!(!ok);
    assert!(
        err.contains("-5") && !err.contains("unexpected argument"),
        "{err}"
    );
}

#[test]
fn an_unknown_metric_lists_every_choice() {
    let (ok, _, err) = brdf(&[
        "fit", "--data", "x.csv", "--model", "lambert", "--metric", "flip",
    ]);
    assert!(!ok);
    for choice in ["auto", "appearance", "ngan", "cube-root", "image"] {
        assert!(err.contains(choice), "{choice}: {err}");
    }
}

#[test]
fn another_name_of_a_model_suggests_the_catalogue_name() {
    let csv = lambert_csv("disney.csv");
    let data = csv.display().to_string();
    let (ok, _, err) = brdf(&["fit", "--data", &data, "--model", "disney"]);
    assert!(!ok);
    assert!(err.contains("principled"), "{err}");
}

#[test]
fn a_selection_on_huge_values_prints_no_nan() {
    // Values near 1e300: several candidates cannot be fitted (their costs
    // overflow); their rows say why, and no figure is printed as NaN.
    let dir = std::env::temp_dir().join(format!("brdf-first-hour-big-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let mut text = String::from("theta_i,phi_i,theta_o,phi_o,grey\n");
    for i in 0..6 {
        for o in 0..6 {
            let (ti, to) = (0.1 + 0.2 * i as f64, 0.1 + 0.2 * o as f64);
            let f = 1e300 * (0.5 / std::f64::consts::PI + 0.3 * ti.cos().powi(20));
            text += &format!("{ti},0,{to},{},{f:e}\n", 0.5 * o as f64);
        }
    }
    let path = dir.join("big.csv");
    std::fs::write(&path, text).expect("csv written");
    let (ok, out, err) = brdf(&["select", "--data", &path.display().to_string(), "--quiet"]);
    assert!(ok, "{err}");
    assert!(out.contains("Chosen:"), "{out}");
    // No cell is a non-finite figure (a failure's message may name NaN).
    for bad in ["| NaN |", "| inf |", "| -inf |"] {
        assert!(!out.contains(bad), "{out}");
    }
    assert!(out.contains("| - |"), "{out}");
}
