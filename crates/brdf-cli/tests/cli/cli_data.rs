//! The `brdf info` and `brdf resample` commands, run as a user would: on
//! brdf-io's self-written fixtures and temporary files always, on the real
//! files when `BRDF_DATA` is set.

use crate::common;

use common::brdf;

use std::path::{Path, PathBuf};

use serde_json::Value;

/// `brdf info PATH --json`, parsed.
fn info(path: &str) -> Value {
    let (ok, out, err) = brdf(&["info", path, "--json"]);
    assert!(ok, "info {path}: {err}");
    serde_json::from_str(&out).unwrap()
}

fn tmp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("brdf-cli-data-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn fixture(rel: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../brdf-io/tests/fixtures")
        .join(rel)
        .display()
        .to_string()
}

fn range(v: &Value, key: &str) -> (f64, f64) {
    (v[key][0].as_f64().unwrap(), v[key][1].as_f64().unwrap())
}

#[test]
fn info_reports_a_self_written_cornell_file() {
    // two.brdf: two records, theta_i 10 and 50 deg, phi_i 0.
    let v = info(&fixture("cornell/two.brdf"));
    assert_eq!(v["format"], "Cornell");
    assert_eq!(v["samples"], 2);
    assert_eq!(v["channels"], serde_json::json!(["r", "g", "b"]));
    assert_eq!(
        (v["negative"].as_u64(), v["non_finite"].as_u64()),
        (Some(0), Some(0))
    );
    let (a, b) = range(&v, "theta_i_deg");
    assert!(
        (a - 10.0).abs() < 1e-4 && (b - 50.0).abs() < 1e-4,
        "{a} {b}"
    );
    assert_eq!(range(&v, "phi_i_deg"), (0.0, 0.0));
    let (lo, hi) = range(&v, "value_range");
    assert!(lo > 0.0 && hi > lo, "{lo} {hi}");
}

#[test]
fn bad_files_are_errors_naming_the_file() {
    let missing = tmp("missing.brdf");
    let unknown = tmp("data.xyz");
    std::fs::write(&unknown, "1 2 3").unwrap();
    let truncated = tmp("truncated.brdf");
    let text = std::fs::read_to_string(fixture("cornell/two.brdf")).unwrap();
    std::fs::write(&truncated, &text[..text.len() / 2]).unwrap();
    for p in [&missing, &unknown, &truncated] {
        let s = p.display().to_string();
        let (ok, _, err) = brdf(&["info", &s]);
        assert!(!ok, "{s} accepted");
        assert!(err.contains("error:") && err.contains(&s), "{s}: {err}");
        assert!(!err.contains("panicked"), "{err}");
    }
}

#[test]
fn csv_samples_resample_to_csv_exactly_and_not_onto_a_grid() {
    let input = tmp("in.csv");
    std::fs::write(
        &input,
        "theta_i,phi_i,theta_o,phi_o,r,g,b,weight\n\
         0.1,0,0.2,3,0.5,0.25,0.125,1\n\
         0.3,1,0.4,2,0.1,0.2,0.3,0.5\n\
         1.2,-2,0.7,0.5,1e-3,2.5e-7,-0.01,2\n",
    )
    .unwrap();
    let output = tmp("out.csv");
    let (i, o) = (input.display().to_string(), output.display().to_string());
    let (ok, stdout, err) = brdf(&["resample", "--from", &i, "--to", "csv", &o]);
    assert!(ok, "{err}");
    assert!(stdout.contains("wrote"), "{stdout}");
    let a = brdf_io::csv_samples::read(&input).unwrap();
    let b = brdf_io::csv_samples::read(&output).unwrap();
    assert_eq!(a.len(), 3);
    assert_eq!(a.values_channel_major(), b.values_channel_major());
    assert_eq!(a.weights(), b.weights());
    // Directions are written as angles: equal to rounding.
    for j in 0..a.len() {
        let d = (a.pairs().l(j) - b.pairs().l(j)).norm() + (a.pairs().v(j) - b.pairs().v(j)).norm();
        assert!(d < 1e-14, "sample {j}: {d}");
    }
    // The negative value is data: kept and counted.
    assert_eq!(info(&o)["negative"], 1);
    // Scattered samples cannot go onto a grid without an interpolation.
    let (ok, _, err) = brdf(&["resample", "--from", &i, "--to", "merl", &o]);
    assert!(!ok && err.contains("scattered"), "{err}");
    let (ok, _, err) = brdf(&["resample", "--from", &i, "--to", "png", &o]);
    assert!(
        !ok && err.contains("expected merl, sopp-grid or csv"),
        "{err}"
    );
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn real_files_info_and_resample() {
    let curet = common::data_file("curet/abrdf.dat");
    let file = |rel: &str| {
        let p = common::data_file(rel);
        p.display().to_string()
    };
    // CUReT: the darkest sample keeps its 28 negative values.
    let v = info(&format!("{}#61", curet.display()));
    assert_eq!(
        (v["format"].as_str(), v["samples"].as_u64()),
        (Some("Curet"), Some(205))
    );
    assert_eq!(v["channels"], serde_json::json!(["grey"]));
    assert_eq!(v["negative"], 28);
    for name in ["cayman", "mystique", "krylon_blue", "acryl_blue"] {
        let v = info(&file(&format!("cornell/{name}.brdf")));
        assert_eq!(v["samples"], 1439, "{name}");
        // theta_i takes 8 values, 10..80 deg.
        let (a, b) = range(&v, "theta_i_deg");
        assert!(
            (a - 10.0).abs() < 1e-3 && (b - 80.0).abs() < 1e-3,
            "{name}: {a} {b}"
        );
    }
    // RGL -> Sopp grid and MERL: complete, finite, non-negative tables.
    let paper = file("rgl/paper_white_rgb.bsdf");
    let grid = tmp("paper.csv").display().to_string();
    let merl = tmp("paper.binary").display().to_string();
    for (to, out, format) in [("sopp-grid", &grid, "SoppGrid"), ("merl", &merl, "Merl")] {
        let (ok, _, err) = brdf(&["resample", "--from", &paper, "--to", to, out]);
        assert!(ok, "{to}: {err}");
        let v = info(out);
        assert_eq!(v["format"], format);
        assert_eq!(
            (v["negative"].as_u64(), v["non_finite"].as_u64()),
            (Some(0), Some(0))
        );
        let (lo, hi) = range(&v, "value_range");
        assert!(lo >= 0.0 && hi.is_finite() && hi > 0.2, "{to}: {lo} {hi}");
    }
    // The grid holds every node: 19 lights x 37 x 36 camera directions.
    assert_eq!(info(&grid)["samples"], 19 * 37 * 36);
    let _ = std::fs::remove_file(&merl);
}

/// A selection by image (the default on RGL data) has no use for the
/// options of a selection by L2: each is refused before any fit, naming
/// the option and the way to a selection by L2, never ignored.
#[test]
#[ignore = "needs BRDF_DATA"]
fn options_of_a_selection_by_l2_are_refused_in_a_selection_by_image() {
    let data = common::data_file("rgl/paper_white_rgb.bsdf");
    let data = data.display().to_string();
    for extra in [
        &["--tolerance", "0.2"][..],
        &["--grey"],
        &["--exhaustive"],
        &["--max-parameters", "4"],
    ] {
        let mut args = vec!["select", "--data", &data, "--quiet"];
        args.extend_from_slice(extra);
        let (ok, out, err) = common::brdf(&args);
        assert!(!ok, "{out}");
        assert!(
            err.contains(&format!("{} applies to a selection by L2", extra[0]))
                && err.contains("--by-l2"),
            "{err}"
        );
    }
}
