//! `brdf reproduce` on a data folder that holds only part of the measured
//! data: every part whose data are absent is skipped with a
//! message naming the files it needs, the others run; a folder holding
//! nothing a selected part needs is an error saying what is needed.

use crate::common;

use common::{brdf, data_file};

fn scratch(name: &str) -> std::path::PathBuf {
    common::scratch("partial", name)
}

#[test]
fn an_empty_data_folder_names_what_the_parts_need() {
    let data = scratch("empty");
    let out = scratch("empty-out");
    let (ok, _, err) = brdf(&[
        "reproduce",
        "--data",
        data.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--only",
        "kurt_9_2,nist",
    ]);
    assert!(!ok, "nothing could run, yet it succeeded: {err}");
    assert!(
        err.contains("kurt_9_2 skipped: needs $BRDF_DATA/curet/abrdf.dat"),
        "{err}"
    );
    assert!(
        err.contains("nist skipped: needs $BRDF_DATA/nist_strd"),
        "{err}"
    );
    assert!(err.contains("nothing to reproduce"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn curet_alone_runs_its_parts_and_says_the_others_were_skipped() {
    let curet = data_file("curet");
    let data = scratch("curet");
    let out = scratch("curet-out");
    // A copy of the CUReT folder only (small: two text files).
    std::fs::create_dir_all(data.join("curet")).unwrap();
    for f in ["abrdf.dat", "table.txt"] {
        std::fs::copy(curet.join(f), data.join("curet").join(f)).unwrap();
    }
    let (ok, _, err) = brdf(&[
        "reproduce",
        "--data",
        data.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--only",
        "kurt_9_2,kurt_9_3,sopp,nist",
    ]);
    assert!(ok, "{err}");
    for skipped in [
        "kurt_9_3 skipped: needs $BRDF_DATA/rgl",
        "sopp skipped: needs $BRDF_DATA/rgl",
        "nist skipped: needs $BRDF_DATA/nist_strd",
    ] {
        assert!(err.contains(skipped), "{skipped} not said: {err}");
    }
    assert!(out.join("kurt_9_2.md").exists());
    let readme = std::fs::read_to_string(out.join("README.md")).unwrap();
    assert!(
        readme.contains("kurt_9_3") && readme.contains("rgl"),
        "{readme}"
    );
}
