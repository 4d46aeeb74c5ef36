//! `brdf report` and `--report`: usage errors name the fix; on the
//! measured data (when `BRDF_DATA` is set) `brdf fit --report` and
//! `brdf report --fit` write self-contained pages with every section, and
//! scattered CUReT data get a page that says no image error can be formed.

use crate::common;

use common::{brdf, data_file};

fn tmp(name: &str) -> std::path::PathBuf {
    common::scratch("report-cli", name)
}

fn read(path: &std::path::Path) -> String {
    std::fs::read_to_string(path).expect("report written")
}

fn assert_page(html: &str, sections: &[&str]) {
    for bad in ["src=\"http", "href=\"http", "<link"] {
        assert!(!html.contains(bad), "not self-contained: {bad}");
    }
    for id in sections {
        assert!(
            html.contains(&format!("id=\"{id}\"")),
            "section {id} missing"
        );
    }
}

#[test]
fn usage_errors_name_the_fix() {
    let (ok, _, err) = brdf(&["report"]);
    assert!(!ok);
    assert!(
        err.contains("--data DATA --fit FIT.json, or --batch DIR"),
        "{err}"
    );
    let dir = tmp("usage");
    let missing = dir.join("missing.json").display().to_string();
    let (ok, _, err) = brdf(&["report", "--data", "x.csv", "--fit", &missing]);
    assert!(!ok && err.contains("missing.json"), "{err}");
    let (ok, _, err) = brdf(&["report", "--batch", &dir.display().to_string()]);
    assert!(
        !ok && err.contains("run `brdf batch --out DIR` first"),
        "{err}"
    );
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn fit_report_and_report_command_on_dense_data() {
    let paper = data_file("rgl/paper_white_rgb.bsdf");
    let dir = tmp("dense");
    let (json, html) = (dir.join("fit.json"), dir.join("fit.html"));
    let p = paper.display().to_string();
    let (ok, out, err) = brdf(&[
        "fit",
        "--data",
        &p,
        "--model",
        "ggx",
        "--starts",
        "2",
        "--quiet",
        "--save",
        &json.display().to_string(),
        "--report",
        &html.display().to_string(),
        "--json",
    ]);
    assert!(ok, "{err}");
    let fit: serde_json::Value = serde_json::from_str(&out).expect("fit JSON");
    let all = [
        "summary", "params", "verdict", "slices", "coverage", "spheres", "errors",
    ];
    let page = read(&html);
    assert_page(&page, &all);
    assert!(page.contains("how the fit ended"));
    let again = dir.join("again.html");
    let (ok, _, err) = brdf(&[
        "report",
        "--data",
        &p,
        "--fit",
        &json.display().to_string(),
        "--out",
        &again.display().to_string(),
    ]);
    assert!(ok, "{err}");
    let again = read(&again);
    assert_page(&again, &all);
    // The page of `--report` is made by the judge of the fit's image
    // errors: its table is the fit's errors, and a fresh judge
    // (`brdf report`) gives the same table.
    let table = |html: &str| -> String {
        let from = html.find("id=\"errors\"").expect("errors table");
        let to = from + html[from..].find("</table>").expect("table end");
        html[from..to].to_string()
    };
    assert_eq!(table(&page), table(&again));
    for light in fit["image_errors"][0]["lights"].as_array().expect("lights") {
        let flip = light["flip"].as_f64().expect("flip");
        let cell = format!("<td class=\"num\">{flip:.3}</td>");
        assert!(table(&page).contains(&cell), "{cell} in {}", table(&page));
    }
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn scattered_data_have_no_image_error() {
    let curet = data_file("curet/abrdf.dat");
    let dir = tmp("scattered");
    let html = dir.join("curet.html");
    let spec = format!("{}#25", curet.display());
    let (ok, _, err) = brdf(&[
        "fit",
        "--data",
        &spec,
        "--model",
        "lambert",
        "--quiet",
        "--report",
        &html.display().to_string(),
    ]);
    assert!(ok, "{err}");
    let page = read(&html);
    assert_page(
        &page,
        &[
            "summary", "params", "verdict", "slices", "coverage", "spheres",
        ],
    );
    assert!(page.contains("no image error can be formed"));
    assert!(!page.contains("id=\"errors\""));
}

/// A selection by image (the default on RGL data) shows in the report as
/// what it chose by: every candidate's image errors, with the choice
/// marked, the numbers those of `brdf select --json`; a selection of
/// another file is refused.
#[test]
#[ignore = "needs BRDF_DATA"]
fn a_selection_by_image_shows_each_candidates_image_errors() {
    let p = data_file("rgl/paper_white_rgb.bsdf").display().to_string();
    let dir = tmp("by-image");
    let (select, fit, html) = (
        dir.join("select.json"),
        dir.join("fit.json"),
        dir.join("page.html"),
    );
    let (ok, out, err) = brdf(&[
        "select",
        "--data",
        &p,
        "--models",
        "lambert,gltf",
        "--json",
        "--quiet",
    ]);
    assert!(ok, "{err}");
    std::fs::write(&select, &out).expect("selection written");
    let v: serde_json::Value = serde_json::from_str(&out).expect("select JSON");
    let chosen = v["choice"]["label"].as_str().expect("choice").to_string();
    let (ok, _, err) = brdf(&[
        "fit",
        "--data",
        &p,
        "--model",
        &chosen,
        "--quiet",
        "--save",
        &fit.display().to_string(),
    ]);
    assert!(ok, "{err}");
    let report = |data: &str| {
        brdf(&[
            "report",
            "--data",
            data,
            "--fit",
            &fit.display().to_string(),
            "--select",
            &select.display().to_string(),
            "--out",
            &html.display().to_string(),
            "--quiet",
        ])
    };
    let (ok, _, err) = report(&p);
    assert!(ok, "{err}");
    let page = read(&html);
    assert_page(&page, &["selection"]);
    assert!(page.contains("Chosen by image error"));
    assert!(page.contains(&format!("<strong>{chosen}</strong> (chosen)")));
    for c in v["candidates"].as_array().expect("candidates") {
        let lights = c["image"]["lights"].as_array().expect("lights");
        let mean = lights
            .iter()
            .map(|l| l["flip"].as_f64().expect("flip"))
            .sum::<f64>()
            / lights.len() as f64;
        let used = format!("{} of {}", c["samples"], c["samples_present"]);
        assert!(page.contains(&format!("<td>{mean:.4}</td>")), "{mean:.4}");
        assert!(page.contains(&used), "{used}");
    }
    let other = data_file("rgl/colodur_napoli_4f_rgb.bsdf")
        .display()
        .to_string();
    let (ok, _, err) = report(&other);
    assert!(!ok && err.contains("not on the report's data"), "{err}");
}
