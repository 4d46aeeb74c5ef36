//! A data path that does not exist gets the nearest names in its folder
//! as `did you mean ...?`, written with the folder as the path was.

use std::path::PathBuf;

fn folder(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("brdf-io-dym-{}-{tag}", std::process::id()));
    std::fs::create_dir_all(&d).expect("temp dir");
    for f in [
        "paper_white_rgb.bsdf",
        "gold-metallic-paint.binary",
        "table.txt",
        "unrelated_name.csv",
    ] {
        std::fs::write(d.join(f), b"").expect("write");
    }
    d
}

fn message(spec: &str) -> String {
    brdf_io::load(spec).expect_err("missing file").to_string()
}

#[test]
fn a_missing_name_that_prefixes_an_existing_one_is_suggested() {
    let d = folder("prefix");
    let spec = d.join("paper_white.bsdf");
    let m = message(spec.to_str().expect("utf-8"));
    let want = format!("did you mean {}?", d.join("paper_white_rgb.bsdf").display());
    assert!(m.contains(&want), "{m}");
    assert!(m.starts_with(&spec.display().to_string()), "{m}");
    assert!(!m.contains("unrelated_name"), "{m}");
}

#[test]
fn a_typo_is_suggested_by_edit_distance() {
    let d = folder("typo");
    let m = message(d.join("gold-metalic-paint.binary").to_str().expect("utf-8"));
    let want = format!(
        "did you mean {}?",
        d.join("gold-metallic-paint.binary").display()
    );
    assert!(m.contains(&want), "{m}");
    // A sample suffix is kept off the file name that is looked for.
    let m = message(&format!("{}#25", d.join("tabel.txt").display()));
    assert!(
        m.contains(&format!("did you mean {}?", d.join("table.txt").display())),
        "{m}"
    );
}

#[test]
fn nothing_near_gives_no_suggestion() {
    let d = folder("none");
    let m = message(d.join("zzzz.bsdf").to_str().expect("utf-8"));
    assert!(m.contains("does not exist"), "{m}");
    assert!(!m.contains("did you mean"), "{m}");
}

#[test]
fn the_suggestion_is_the_resolver_s_so_every_front_end_shows_it() {
    let d = folder("resolve");
    let e = brdf_io::load::resolve_path(&d.join("Paper_White_RGB.bsd")).expect_err("missing");
    assert!(e.to_string().contains("paper_white_rgb.bsdf?"), "{e}");
}
