//! `brdf fit --for RENDERER` and `brdf select --for RENDERER` (needs
//! BRDF_DATA): among the models the renderer renders exactly (for glTF on
//! grey paper, `gltf` and `gltf-ext`: its film only where the data's hue
//! leaves every colour plane), the one of least image error, fitted for
//! appearance; `fit` writes it exactly, `select` names it, and the two
//! choose alike from the same candidates.

use crate::common;

use common::{brdf, data_file, mean_flip};
use serde_json::Value;

fn json(args: &[&str]) -> Value {
    let (ok, stdout, stderr) = brdf(args);
    assert!(ok, "brdf {}: {stderr}", args.join(" "));
    serde_json::from_str(&stdout).unwrap_or_else(|e| panic!("brdf {}: {e}", args.join(" ")))
}

/// `(model, mean FLIP)` of every candidate.
fn candidates(v: &Value) -> Vec<(String, f64)> {
    v["candidates"]
        .as_array()
        .expect("candidates")
        .iter()
        .map(|c| {
            let model = c["model"].as_str().expect("model").to_string();
            (model, mean_flip(&c["image"]))
        })
        .collect()
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn fit_and_select_for_gltf_choose_the_least_flip_among_its_exact_models() {
    let data = data_file("rgl/paper_white_rgb.bsdf");
    let data = data.to_str().expect("a UTF-8 path");
    let out = std::env::temp_dir().join(format!("brdf_for_gltf_{}.gltf", std::process::id()));
    let out_s = out.to_str().expect("a UTF-8 path");
    // A limit below the default: both commands must pass it to every fit.
    let fitted = json(&[
        "fit", "--data", data, "--for", "gltf", "--out", out_s, "--limit", "75", "--json",
        "--quiet",
    ]);
    let selected = json(&[
        "select", "--data", data, "--for", "gltf", "--limit", "75", "--json", "--quiet",
    ]);
    for v in [&fitted, &selected] {
        for c in v["candidates"].as_array().expect("candidates") {
            assert_eq!(c["limit_deg"].as_f64(), Some(75.0), "{c}");
            let count = |k: &str| c[k].as_u64().unwrap_or_else(|| panic!("{k} in {c}"));
            assert!(count("dropped_angle") > 0, "{c}");
            assert_eq!(
                count("samples") + count("dropped_invalid") + count("dropped_angle"),
                count("samples_present"),
                "{c}"
            );
        }
        let c = candidates(v);
        let names: Vec<&str> = c.iter().map(|(m, _)| m.as_str()).collect();
        assert!(
            !names.is_empty() && names.iter().all(|m| ["gltf", "gltf-ext"].contains(m)),
            "{names:?}"
        );
        let least = c
            .iter()
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .expect("a candidate");
        assert_eq!(v["choice"]["model"].as_str(), Some(least.0.as_str()), "{v}");
    }
    // The same candidates and choice from both commands (fits are
    // deterministic; their times are not compared).
    assert_eq!(candidates(&fitted), candidates(&selected));
    assert_eq!(fitted["choice"]["model"], selected["choice"]["model"]);
    // The file is the glTF material, exact: no conversion note in it.
    let text = std::fs::read_to_string(&out).expect("written");
    let _ = std::fs::remove_file(&out);
    let gltf: Value = serde_json::from_str(&text).expect("glTF JSON");
    assert!(gltf["materials"].as_array().is_some_and(|m| !m.is_empty()));
    assert!(!text.contains("converted by fitting"), "{text}");
}

/// What `--for` decides itself (the objective, the channels, the solver
/// and its starts, the models' structure) is refused when given, before
/// any data is read, rather than ignored.
#[test]
fn options_for_decides_itself_are_refused_not_ignored() {
    for extra in [
        &["--metric", "ngan"][..],
        &["--channels", "grey"],
        &["--solver", "lm"],
        &["--starts", "3"],
        &["--lobes", "2"],
        &["--report", "r.html"],
    ] {
        let mut args = vec![
            "fit",
            "--data",
            "absent.bsdf",
            "--for",
            "mitsuba",
            "--out",
            "m.xml",
        ];
        args.extend_from_slice(extra);
        let (ok, _, err) = brdf(&args);
        assert!(!ok);
        assert!(
            err.contains(extra[0]) && err.contains("cannot be used with"),
            "{err}"
        );
    }
    for extra in ["--grey", "--exhaustive"] {
        let (ok, _, err) = brdf(&["select", "--data", "absent.bsdf", "--for", "blender", extra]);
        assert!(!ok);
        assert!(
            err.contains(extra) && err.contains("cannot be used with"),
            "{err}"
        );
    }
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn select_for_a_renderer_needs_data_that_can_be_rendered() {
    let data = data_file("curet/abrdf.dat");
    let spec = format!("{}#25", data.display());
    let (ok, _, stderr) = brdf(&["select", "--data", &spec, "--for", "blender", "--quiet"]);
    assert!(!ok);
    assert!(
        stderr.contains("--for") && stderr.contains("cannot be rendered"),
        "{stderr}"
    );
}
