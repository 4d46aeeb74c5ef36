//! End to end on measured data (needs BRDF_DATA): `brdf fit`
//! of `rgl/paper_white_rgb.bsdf` in GGX and in principled, then `brdf
//! export` of each fit to Mitsuba 3, pbrt-v4, glTF and MaterialX. The fits
//! must reproduce the committed ones in
//! `crates/brdf-export/tests/reference/paper_white/` (whose exports Mitsuba
//! and the validators checked, see `tests/paper_white.rs` there), and every
//! export must be written, exactly or with its conversion error reported
//! as committed. About a minute (the principled fit).

use crate::common;

use std::path::PathBuf;

use common::{brdf, data_file};

fn reference(name: &str) -> serde_json::Value {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../brdf-export/tests/reference/paper_white")
        .join(name);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    serde_json::from_str(&text).expect("reference JSON")
}

/// Whether the committed conversion of `name` (a `M.KIND.report.json`) had
/// to be forced (false where there is none: the export is exact).
fn committed_forced(name: &str) -> bool {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../brdf-export/tests/reference/paper_white")
        .join(name);
    path.exists() && reference(name)["conversion"]["forced"].as_bool() == Some(true)
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * b.abs().max(1e-3)
}

// One test per model, so that the two fits run side by side.
#[test]
#[ignore = "needs BRDF_DATA"]
fn paper_white_ggx_fit_exports_to_all_four_formats() {
    fit_and_export("ggx");
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn paper_white_principled_fit_exports_to_all_four_formats() {
    fit_and_export("principled");
}

fn fit_and_export(m: &str) {
    let data = data_file("rgl/paper_white_rgb.bsdf");
    let dir = std::env::temp_dir().join(format!("brdf-export-pw-{}-{m}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let s = |p: &PathBuf| p.to_str().expect("utf-8 path").to_string();
    let saved = dir.join(format!("{m}.json"));
    let saved_s = s(&saved);
    let (ok, _, stderr) = brdf(&[
        "fit",
        "--data",
        &s(&data),
        "--model",
        m,
        // The fixtures are Ngan-L2 fits (their exports are converted
        // for appearance); the default for renderer models is the
        // appearance fit, tested in appearance.rs.
        "--metric",
        "ngan",
        "--starts",
        "4",
        "--save",
        &s(&saved),
    ]);
    assert!(ok, "{stderr}");
    let ours: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&saved).expect("saved")).expect("JSON");
    let committed = reference(&format!("{m}.json"));
    assert_eq!(ours["provenance"]["data"], "rgl/paper_white_rgb.bsdf");
    for (a, b) in ours["parameters"]
        .as_array()
        .expect("parameters")
        .iter()
        .zip(committed["parameters"].as_array().expect("parameters"))
    {
        assert_eq!(a["name"], b["name"]);
        let (x, y) = (
            a["value"].as_f64().expect("value"),
            b["value"].as_f64().expect("value"),
        );
        assert!(close(x, y, 1e-6), "{m} {}: {x} vs committed {y}", a["name"]);
    }
    for t in ["mitsuba", "pbrt", "gltf", "materialx"] {
        let out = dir.join(format!("{m}.{t}"));
        let conv_file = format!("{m}.{t}.report.json");
        let mut args = vec!["export", "--from", &saved_s, "--to", t];
        let (out_s, forced) = (s(&out), committed_forced(&conv_file));
        args.extend([out_s.as_str(), "--json"]);
        if forced {
            // Beyond the conversion limits: refused, naming the better route,
            // unless --force.
            let (ok, _, stderr) = brdf(&args);
            assert!(!ok && stderr.contains("--force"), "{m} -> {t}: {stderr}");
            args.push("--force");
        }
        let (ok, stdout, stderr) = brdf(&args);
        assert!(ok, "{m} -> {t}: {stderr}");
        assert!(std::fs::metadata(&out).expect("written").len() > 0);
        let report: serde_json::Value = serde_json::from_str(&stdout).expect("JSON");
        let converted = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("../brdf-export/tests/reference/paper_white")
            .join(&conv_file)
            .exists();
        assert_eq!(report["exact"], !converted, "{m} -> {t}");
        if converted {
            // Written with a warning beyond the warning limits, which
            // names the renderer's own route.
            let warned = report["conversion"]["warned"].as_bool().expect("warned");
            let says = report["warnings"]
                .as_array()
                .expect("warnings")
                .iter()
                .filter_map(|w| w.as_str())
                .any(|w| w.contains("renders differently") && w.contains("--for"));
            assert_eq!(warned, says, "{m} -> {t}: {report}");
            let want = reference(&conv_file)["conversion"]["relative_l2"]
                .as_f64()
                .expect("number");
            let got = report["conversion"]["relative_l2"]
                .as_f64()
                .expect("number");
            assert!(
                close(got, want, 1e-3),
                "{m} -> {t}: relative L2 {got} vs committed {want}"
            );
        }
    }
}
