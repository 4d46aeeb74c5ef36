//! The exactness table (`brdf export --list`, the README's): every
//! conversion committed for the reference material is in it with the image
//! error its report gives, and every check by rendering with its HDR-FLIP.

use std::path::PathBuf;

use brdf_export::table::{REFERENCE_CONVERSIONS, markdown};

fn dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/reference/paper_white")
}

fn table_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/reference/table")
}

/// The conversion reports committed in `d`.
fn reports(d: &std::path::Path) -> Vec<PathBuf> {
    std::fs::read_dir(d)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            let n = p.file_name().unwrap().to_string_lossy();
            n.ends_with(".report.json") && !n.ends_with(".scene.report.json")
        })
        .collect()
}

#[test]
fn every_reference_conversion_is_listed_with_its_image_error() {
    // The reports of the make.sh scripts (the scene's conversion is the
    // snippet's).
    let paths: Vec<PathBuf> = reports(&dir())
        .into_iter()
        .chain(reports(&table_dir()))
        .collect();
    let mut files: Vec<String> = paths
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    files.sort();
    let mut listed: Vec<String> = REFERENCE_CONVERSIONS
        .iter()
        .map(|(m, k, _)| format!("{m}.{k}.report.json"))
        .collect();
    listed.sort();
    assert_eq!(listed, files);
    let table = markdown();
    for (m, k, text) in REFERENCE_CONVERSIONS {
        let name = format!("{m}.{k}.report.json");
        let file = paths
            .iter()
            .find(|p| p.file_name().unwrap().to_string_lossy() == name)
            .unwrap();
        assert_eq!(text, std::fs::read_to_string(file).unwrap());
        let r: serde_json::Value = serde_json::from_str(text).unwrap();
        let c = &r["conversion"];
        let flip = |light: &str| {
            c["image"]["lights"]
                .as_array()
                .unwrap()
                .iter()
                .find(|l| l["light"] == light)
                .unwrap()["flip"]
                .as_f64()
                .unwrap()
        };
        let row = format!(
            "| `{m}` | {k} | `{}` | {:.4} | {:.4} |",
            c["via"].as_str().unwrap(),
            flip("sky"),
            flip("studio")
        );
        assert!(table.contains(&row), "{row} not in\n{table}");
    }
}

#[test]
fn the_checks_by_rendering_are_listed() {
    let table = markdown();
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir().join("render_check.json")).unwrap())
            .unwrap();
    for c in r["checks"].as_array().unwrap() {
        let file = c["file"]
            .as_str()
            .unwrap()
            .trim_start_matches("paper_white/");
        let held = c["lights"]["studio"]["flip_held"].as_f64().unwrap();
        let row = format!("| `{file}` | {} |", c["renderer"].as_str().unwrap());
        assert!(table.contains(&row), "{row}");
        assert!(table.contains(&format!("{held:.4}")), "{file}");
    }
}
