//! `brdf_io::materials`: what a folder, a CUReT file and a single file
//! stand for, on a folder built from the self-written fixtures.

use std::path::{Path, PathBuf};

fn fixture(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(rel)
}

/// A folder with a CUReT `abrdf.dat` (the red channel fixture, samples 25
/// and 55) and its `table.txt`, a Cornell file, a file of no known format
/// and a sub-folder.
fn folder() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("brdf-io-materials-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("sub")).unwrap();
    std::fs::copy(fixture("curet/rbrdf.dat"), dir.join("abrdf.dat")).unwrap();
    std::fs::copy(fixture("curet/table.txt"), dir.join("table.txt")).unwrap();
    std::fs::copy(fixture("cornell/two.brdf"), dir.join("two.brdf")).unwrap();
    std::fs::write(dir.join("notes.txt"), "not data").unwrap();
    std::fs::copy(fixture("cornell/two.brdf"), dir.join("sub/three.brdf")).unwrap();
    dir
}

#[test]
fn a_folder_stands_for_its_known_files_and_curet_samples_sorted() {
    let dir = folder();
    let d = dir.display().to_string();
    let got = brdf_io::materials(&d).unwrap();
    let want = [
        format!("{d}/abrdf.dat#25"),
        format!("{d}/abrdf.dat#55"),
        format!("{d}/two.brdf"),
    ];
    assert_eq!(got, want);
    // The CUReT file alone: its samples; one sample or another file: itself.
    let curet = format!("{d}/abrdf.dat");
    assert_eq!(brdf_io::materials(&curet).unwrap(), want[..2]);
    assert_eq!(brdf_io::materials(&want[1]).unwrap(), want[1..2]);
    assert_eq!(brdf_io::materials(&want[2]).unwrap(), want[2..]);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_unknown_format_is_an_error_naming_the_path() {
    let e = brdf_io::materials("nowhere/data.xyz").unwrap_err();
    assert!(e.to_string().starts_with("nowhere/data.xyz"), "{e}");
}
