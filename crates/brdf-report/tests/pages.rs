//! The HTML of a fit page and a batch index: self-contained (no `http://`
//! or `https://` in any `src` or `href`, images as `data:` URIs), every
//! section present, and scattered data said to have no image error. Made
//! from a small generated CSV data set, so it runs without `BRDF_DATA`.

use std::path::PathBuf;

use brdf_models::saved_model::SavedModel;
use brdf_report::{FitInput, RunInfo, fit_page, write_batch_report};

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("brdf-report-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp folder");
    d
}

/// A scattered grey data set of a Blinn-Phong-like material.
fn csv_data(dir: &std::path::Path) -> String {
    let mut text = String::from("theta_i_deg,phi_i_deg,theta_o_deg,phi_o_deg,value,weight\n");
    for ti in [0i32, 30, 60, 75] {
        for to in (0..=80).step_by(10) {
            for po in [0, 90, 180, 270] {
                let v = 0.2
                    + if po == 180 && (to - ti).abs() < 15 {
                        2.0
                    } else {
                        0.0
                    };
                text.push_str(&format!("{ti},0,{to},{po},{v},1\n"));
            }
        }
    }
    let path = dir.join("samples.csv");
    std::fs::write(&path, text).expect("data written");
    path.display().to_string()
}

fn saved() -> SavedModel {
    let text = r#"{ "schema": "brdf-fit/saved-model", "version": 1,
      "model": "blinn-phong", "structure": { "channels": 1 },
      "parameters": [ { "name": "kd", "value": 0.6, "std_error": 0.01 },
                      { "name": "ks", "value": 0.5, "at_bound": "upper" },
                      { "name": "n", "value": 20.0 } ],
      "provenance": { "data": "samples.csv", "samples_used": 144, "samples_present": 144,
                      "objective": "ngan", "limit_deg": 80.0, "error": 0.1,
                      "solver": "test", "software": "test" } }"#;
    SavedModel::from_json(text, "inline").expect("valid saved model")
}

fn assert_self_contained(html: &str) {
    for bad in [
        "src=\"http://",
        "src=\"https://",
        "href=\"http://",
        "href=\"https://",
    ] {
        assert!(!html.contains(bad), "the page refers to the network: {bad}");
    }
    assert!(!html.contains("<link"), "no external stylesheet");
}

#[test]
fn a_fit_page_of_scattered_data_is_self_contained_and_complete() {
    let dir = tmp("fit");
    let data = csv_data(&dir);
    let saved = saved();
    let input = FitInput {
        data: &data,
        saved: &saved,
        fit_source: "inline",
        run: Some(RunInfo {
            seconds: 1.5,
            termination: "NOT converged: iteration limit".into(),
            ended: Some(brdf_fit::Termination::Solver(
                brdf_solve::Termination::MaxIterations,
            )),
            iterations: Some(100),
        }),
        selection: None,
    };
    let html = fit_page(&input).expect("page");
    assert_self_contained(&html);
    for id in [
        "summary", "params", "verdict", "slices", "coverage", "spheres",
    ] {
        assert!(
            html.contains(&format!("id=\"{id}\"")),
            "section {id} missing"
        );
    }
    assert_eq!(
        html.matches("<svg").count(),
        9,
        "8 polar plots and the coverage"
    );
    assert!(html.contains("no image error can be formed"));
    // `/` is escaped in attributes (`&#x2f;`), which the browser decodes.
    assert!(html.contains("src=\"data:image&#x2f;png;base64,"));
    assert!(html.contains("at upper bound"));
    assert!(html.contains("did not converge"));
    assert!(
        !html.contains("id=\"errors\""),
        "no image errors for scattered data"
    );
}

#[test]
fn a_batch_index_links_its_pages_and_sorts() {
    let dir = tmp("batch");
    let data = csv_data(&dir);
    let fit = serde_json::json!({
        "model": "blinn-phong", "objective": "ngan", "error": 0.1, "ngan_l2": 0.1,
        "solver": "test", "iterations": 3, "termination": "converged", "seconds": 0.5,
        "parameters": [ { "name": "kd", "value": 0.6 }, { "name": "ks", "value": 0.5 },
                        { "name": "n", "value": 20.0 } ],
    });
    let line = |model: &str| {
        serde_json::json!({ "data": data, "model": model, "samples_used": 144,
            "samples_present": 144, "limit_deg": 80.0, "fit": fit })
    };
    let text = format!("{}\n{}\n", line("blinn-phong"), line("no-such-model"));
    std::fs::write(dir.join("fits.jsonl"), text).expect("fits written");
    let out = dir.join("report").join("index.html");
    let mut calls = 0;
    let done = write_batch_report(&dir, &out, &[], &mut |_, _, _| calls += 1).expect("index");
    assert_eq!((done.pages, done.skipped.len(), calls), (1, 1, 3));
    let html = std::fs::read_to_string(&out).expect("index written");
    assert_self_contained(&html);
    assert!(html.contains("th class=\"sortable\""), "sortable headers");
    let page = data.replace(|c: char| !c.is_ascii_alphanumeric(), "_") + "__blinn_phong.html";
    assert!(html.contains(&format!("href=\"{page}\"")), "links its page");
    assert!(
        out.with_file_name(&page).exists(),
        "the page is beside the index"
    );
    assert!(html.contains("no-such-model"), "the failed row is listed");
}
