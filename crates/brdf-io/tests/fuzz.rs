//! Fuzzing every reader with proptest: arbitrary bytes, and valid files
//! with random corruption (truncation, byte flips, inserted garbage), must
//! give `Ok` or a typed error, never a panic. (`cargo fuzz` needs a nightly
//! toolchain, which this project's machines do not have; these property
//! tests are the fuzz targets, run on every `cargo test`: 256 cases per
//! target per run by default, more with `PROPTEST_CASES`.)

use std::path::Path;

use brdf_io::cornell::{self, CornellColour};
use brdf_io::{csv_samples, curet, merl, nist, sopp_grid};
use proptest::prelude::*;

fn cornell_text() -> String {
    std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/cornell/two.brdf"
    ))
    .unwrap()
}

fn nist_text() -> String {
    std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/nist/Line3.dat"
    ))
    .unwrap()
}

const CSV: &str =
    "theta_i,phi_i,theta_o,phi_o,r,g,weight\n0.1,0,0.2,3,0.5,0.25,1\n0.3,1,0.4,2,0.1,0.2,0.5\n";

/// Corrupt `base`: truncate at `cut`, flip the byte at `flip`, insert
/// `junk` at `at` (positions taken modulo the length).
fn corrupt(base: &[u8], cut: usize, flip: usize, junk: &[u8], at: usize) -> Vec<u8> {
    let mut v = base.to_vec();
    if !v.is_empty() {
        let i = flip % v.len();
        v[i] ^= 0x5a;
        let a = at % v.len();
        v.splice(a..a, junk.iter().copied());
        v.truncate(cut % (v.len() + 1));
    }
    v
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

proptest! {
    #[test]
    fn cornell_never_panics(bytes in proptest::collection::vec(any::<u8>(), 0..400),
                            cut in any::<usize>(), flip in any::<usize>(), at in any::<usize>()) {
        let p = Path::new("fuzz.brdf");
        let _ = cornell::parse(p, &text(&bytes), CornellColour::Rgb);
        let c = corrupt(cornell_text().as_bytes(), cut, flip, &bytes, at);
        let _ = cornell::parse(p, &text(&c), CornellColour::Luminance);
    }

    #[test]
    fn csv_never_panics(bytes in proptest::collection::vec(any::<u8>(), 0..200),
                        cut in any::<usize>(), flip in any::<usize>(), at in any::<usize>()) {
        let p = Path::new("fuzz.csv");
        let _ = csv_samples::parse(p, &text(&bytes));
        let _ = csv_samples::parse(p, &text(&corrupt(CSV.as_bytes(), cut, flip, &bytes, at)));
    }

    #[test]
    fn nist_never_panics(bytes in proptest::collection::vec(any::<u8>(), 0..200),
                         cut in any::<usize>(), flip in any::<usize>(), at in any::<usize>()) {
        let p = Path::new("fuzz.dat");
        let _ = nist::parse(p, &text(&bytes));
        let _ = nist::parse(p, &text(&corrupt(nist_text().as_bytes(), cut, flip, &bytes, at)));
    }

    #[test]
    fn sopp_grid_never_panics(bytes in proptest::collection::vec(any::<u8>(), 0..200),
                              cut in any::<usize>(), flip in any::<usize>(), at in any::<usize>()) {
        let p = Path::new("fuzz.csv");
        let base = "light_theta_deg,camera_theta_deg,camera_phi_deg,r,g,b\n0,0,0,1,1,1\n5,2.5,5.142857142857143,1,2,3\n";
        let _ = sopp_grid::parse(p, &text(&bytes));
        let _ = sopp_grid::parse(p, &text(&corrupt(base.as_bytes(), cut, flip, &bytes, at)));
    }

    #[test]
    fn merl_never_panics(bytes in proptest::collection::vec(any::<u8>(), 0..64), header in any::<bool>()) {
        let p = Path::new("fuzz.binary");
        let mut b = Vec::new();
        if header {
            for d in [90i32, 90, 180] {
                b.extend_from_slice(&d.to_le_bytes());
            }
        }
        b.extend_from_slice(&bytes);
        prop_assert!(merl::parse(p, &b).is_err());
    }

    #[test]
    fn curet_files_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..300)) {
        let dir = std::env::temp_dir().join(format!("brdf-io-fuzz-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let t = dir.join("table.txt");
        let a = dir.join("abrdf.dat");
        std::fs::write(&t, &bytes).unwrap();
        std::fs::write(&a, &bytes).unwrap();
        let _ = curet::read_table(&t);
        let _ = curet::read_values(&a);
        let _ = curet::read_grey(&a, &t);
    }
}
