//! `brdf batch`: two shards merged give the same fits as one run; a rerun
//! skips what is done (resumable); a truncated last line from a killed run
//! is refitted; bad shard specs and unknown models are errors naming them;
//! each fit is the one `brdf fit` makes, image errors included.

use crate::common;

use common::{brdf, data_file};

fn rows(dir: &std::path::Path) -> Vec<String> {
    // Drop the seconds column: measured, not reproducible.
    std::fs::read_to_string(dir.join("summary.csv"))
        .expect("summary written")
        .lines()
        .map(|l| {
            l.rsplit_once(',')
                .map(|(a, _)| a.to_string())
                .unwrap_or_default()
        })
        .collect()
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn shards_merge_to_one_run_and_reruns_resume() {
    let (curet, rgl) = (data_file("curet/abrdf.dat"), data_file("rgl"));
    let tmp = std::env::temp_dir().join(format!("brdf-batch-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&tmp);
    let (c, r) = (curet.display().to_string(), rgl.display().to_string());
    let dir = |n: &str| tmp.join(n).display().to_string();
    let base = [
        "batch",
        "--data",
        &c,
        &r,
        "--models",
        "Lambert,blinn_phong",
        "--channels",
        "grey",
        "--starts",
        "3",
        "--out",
    ];
    let run = |out: &str, extra: &[&str]| {
        let mut a: Vec<&str> = base.to_vec();
        a.push(out);
        a.extend_from_slice(extra);
        let (ok, _, err) = brdf(&a);
        assert!(ok, "{err}");
        err
    };
    run(&dir("all"), &[]);
    run(&dir("s1"), &["--shard", "1/2"]);
    run(&dir("s2"), &["--shard", "2/2"]);
    let (ok, _, err) = brdf(&[
        "batch",
        "--merge",
        &dir("s1"),
        &dir("s2"),
        "--out",
        &dir("m"),
    ]);
    assert!(ok, "{err}");
    let all = rows(&tmp.join("all"));
    // 61 CUReT samples + 5 RGL files, 2 models, plus the header.
    assert_eq!(all.len(), 1 + 66 * 2);
    assert_eq!(all, rows(&tmp.join("m")));
    // Resume: nothing to do; then lose the last line half-written.
    assert!(run(&dir("all"), &[]).contains("132 already"));
    let fits = tmp.join("all").join("fits.jsonl");
    let text = std::fs::read_to_string(&fits).unwrap();
    let cut = text.trim_end().rfind('\n').unwrap() + 20;
    std::fs::write(&fits, &text[..cut]).unwrap();
    assert!(run(&dir("all"), &[]).contains("1 to run"));
    assert_eq!(all, rows(&tmp.join("all")));
    let _ = std::fs::remove_dir_all(&tmp);
}

#[test]
fn bad_requests_name_what_is_wrong() {
    let tmp = std::env::temp_dir().join(format!("brdf-batch-bad-{}", std::process::id()));
    let out = tmp.display().to_string();
    let (ok, _, err) = brdf(&[
        "batch", "--data", "x.csv", "--models", "lambert", "--out", &out, "--shard", "3/2",
    ]);
    assert!(!ok && err.contains("--shard 3/2"), "{err}");
    let (ok, _, err) = brdf(&[
        "batch",
        "--data",
        "x.csv",
        "--models",
        "blin-phong",
        "--out",
        &out,
    ]);
    assert!(!ok && err.contains("did you mean `blinn-phong`"), "{err}");
    let _ = std::fs::remove_dir_all(&tmp);
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn each_fit_is_brdf_fits_with_its_image_errors() {
    // A renderer model on data that can be rendered is fitted for
    // appearance, as `brdf fit` does by default, and the line carries the
    // same image errors as `brdf fit --json`; scattered data carry the
    // note why none can be formed, and the summary shows "-" there.
    let (paper, curet) = (
        data_file("rgl/paper_white_rgb.bsdf"),
        data_file("curet/abrdf.dat"),
    );
    let tmp = std::env::temp_dir().join(format!("brdf-batch-image-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&tmp);
    let (p, c) = (
        paper.display().to_string(),
        format!("{}#25", curet.display()),
    );
    let out = tmp.display().to_string();
    let (ok, _, err) = brdf(&[
        "batch", "--data", &p, &c, "--models", "ggx", "--out", &out, "--quiet",
    ]);
    assert!(ok, "{err}");
    let text = std::fs::read_to_string(tmp.join("fits.jsonl")).expect("fits.jsonl");
    let lines: Vec<serde_json::Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).expect("json line"))
        .collect();
    let of = |name: &str| {
        lines
            .iter()
            .find(|v| v["data"].as_str().is_some_and(|d| d.contains(name)))
            .unwrap_or_else(|| panic!("no line of {name} in {text}"))
    };
    let (rgl, scattered) = (of("paper_white"), of("abrdf"));
    let (ok, fit, err) = brdf(&["fit", "--data", &p, "--model", "ggx", "--json", "--quiet"]);
    assert!(ok, "{err}");
    let fit: serde_json::Value = serde_json::from_str(&fit).expect("json");
    assert_eq!(rgl["image_error"], fit["image_errors"][0]);
    assert_eq!(rgl["fit"]["ngan_l2"], fit["fits"][0]["ngan_l2"]);
    let chosen = fit["candidates"][0]
        .as_array()
        .and_then(|c| c.iter().find(|c| c["chosen"] == true))
        .expect("chosen candidate");
    assert_eq!(rgl["for_appearance"]["objective"], chosen["objective"]);
    assert!(scattered["image_error"].is_null());
    assert!(
        scattered["image_note"]
            .as_str()
            .is_some_and(|n| n.contains("no image error")),
        "{scattered}"
    );
    let summary = std::fs::read_to_string(tmp.join("summary.csv")).expect("summary");
    let header: Vec<&str> = summary.lines().next().expect("header").split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).expect(name);
    let (sky, studio) = (col("FLIP sky"), col("FLIP studio"));
    for line in summary.lines().skip(1) {
        let cells: Vec<&str> = line.split(',').collect();
        if line.contains("abrdf") {
            assert_eq!((cells[sky], cells[studio]), ("-", "-"), "{line}");
        } else {
            let flip: f64 = cells[sky].parse().expect("a FLIP");
            let expected = fit["image_errors"][0]["lights"][0]["flip"]
                .as_f64()
                .expect("flip");
            assert!((flip - expected).abs() <= 1e-3 * expected, "{line}");
        }
    }
    // The batch's report shows the line's image errors (the pages render
    // on the judge's film, as the batch did) and its whole-fit seconds.
    let (ok, _, err) = brdf(&["report", "--batch", &out, "--quiet"]);
    assert!(ok, "{err}");
    let index = std::fs::read_to_string(tmp.join("report").join("index.html")).expect("index");
    let row = index
        .split("<tr>")
        .find(|r| r.contains("paper_white"))
        .expect("paper_white's row");
    let values: Vec<f64> = row
        .split("data-value=\"")
        .skip(1)
        .map(|v| {
            v.split('"')
                .next()
                .and_then(|x| x.parse().ok())
                .expect("a number")
        })
        .collect();
    let mean = common::mean_flip(&rgl["image_error"]);
    let seconds = rgl["seconds"].as_f64().expect("seconds");
    // Columns: Ngan L2, FLIP, dE (max), seconds.
    assert!(
        (values[1] - mean).abs() <= 1e-12 * mean,
        "{values:?} vs {mean}"
    );
    assert!(
        (values[3] - seconds).abs() <= 1e-9 * seconds,
        "{values:?} vs {seconds}"
    );
    let _ = std::fs::remove_dir_all(&tmp);
}

/// Data outside `$BRDF_DATA`, given by an absolute folder: the fits name
/// the file by its name only (no machine path), so `brdf batch --report`
/// looks for it in the batch's own `--data` folders, and `brdf report
/// --batch` needs them again with `--data-dir` (without it, the page is
/// skipped with a message naming the option).
#[test]
fn batch_reports_find_data_given_by_an_absolute_folder() {
    let tmp = std::env::temp_dir().join(format!("brdf-batch-datadir-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&tmp);
    let data = tmp.join("my data");
    std::fs::create_dir_all(&data).unwrap();
    // Lambert kd = 0.4 (0.4 / pi 1/sr) at 36 pairs.
    let mut csv = String::from("theta_i_deg,phi_i_deg,theta_o_deg,phi_o_deg,value,weight\n");
    for i in 0..6 {
        for o in 0..6 {
            let v = 0.4 / std::f64::consts::PI;
            csv += &format!("{},0,{},{},{v},1\n", 10 * i, 5 + 12 * o, 30 * o);
        }
    }
    std::fs::write(data.join("paint.csv"), csv).unwrap();
    let (data_s, out) = (data.display().to_string(), tmp.join("out"));
    let out_s = out.display().to_string();
    let (ok, _, err) = brdf(&[
        "batch",
        "--data",
        &data_s,
        "--models",
        "lambert",
        "--channels",
        "grey",
        "--out",
        &out_s,
        "--report",
        "--quiet",
    ]);
    assert!(ok, "{err}");
    assert!(err.contains("and 1 fit pages"), "{err}");
    let fits = std::fs::read_to_string(out.join("fits.jsonl")).unwrap();
    assert!(fits.contains("\"data\":\"paint.csv\""), "{fits}");
    let again = tmp.join("again").join("index.html").display().to_string();
    let (ok, _, err) = brdf(&["report", "--batch", &out_s, "--out", &again, "--quiet"]);
    assert!(ok, "{err}");
    assert!(
        err.contains("and 0 fit pages") && err.contains("--data-dir DIR"),
        "{err}"
    );
    let (ok, _, err) = brdf(&[
        "report",
        "--batch",
        &out_s,
        "--out",
        &again,
        "--data-dir",
        &data_s,
        "--quiet",
    ]);
    assert!(ok, "{err}");
    assert!(err.contains("and 1 fit pages"), "{err}");
    let _ = std::fs::remove_dir_all(&tmp);
}

/// `brdf batch --polish` fits as `brdf fit --polish`: the same image
/// errors, the polish's candidate among the fit's.
#[test]
#[ignore = "needs BRDF_DATA"]
fn a_polished_batch_fit_is_brdf_fit_polish() {
    let paper = data_file("rgl/paper_white_rgb.bsdf");
    let tmp = std::env::temp_dir().join(format!("brdf-batch-polish-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&tmp);
    let (p, out) = (paper.display().to_string(), tmp.display().to_string());
    let (ok, _, err) = brdf(&[
        "batch", "--data", &p, "--models", "ggx", "--out", &out, "--quiet", "--polish",
    ]);
    assert!(ok, "{err}");
    let text = std::fs::read_to_string(tmp.join("fits.jsonl")).expect("fits.jsonl");
    let line: serde_json::Value = serde_json::from_str(text.trim()).expect("one json line");
    let (ok, fit, err) = brdf(&[
        "fit", "--data", &p, "--model", "ggx", "--json", "--quiet", "--polish",
    ]);
    assert!(ok, "{err}");
    let fit: serde_json::Value = serde_json::from_str(&fit).expect("json");
    assert_eq!(line["image_error"], fit["image_errors"][0]);
    let candidates = fit["candidates"][0].as_array().expect("candidates");
    assert!(candidates.iter().any(|c| c["objective"] == "flip"));
    assert_eq!(line["for_appearance"]["candidates"], candidates.len());
    let _ = std::fs::remove_dir_all(&tmp);
}
