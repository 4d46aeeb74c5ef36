//! Quick fuzzing of every reader with proptest, run on every `cargo test`:
//! arbitrary bytes, and valid files with random corruption (truncation,
//! byte flips, inserted garbage), must give `Ok` or a typed error, never a
//! panic. 256 cases per target per run by default, more with
//! `PROPTEST_CASES`. The coverage-guided counterparts are the cargo-fuzz
//! (libFuzzer) targets in `crates/brdf-io/fuzz/`, which need a nightly
//! toolchain and are run by hand (see `fuzz/README.md`).

use std::path::Path;

use brdf_core::Brdf;
use brdf_io::cornell::{self, CornellColour};
use brdf_io::rgl::{Field, Rgl, TensorFile};
use brdf_io::{csv_samples, curet, merl, nist, sopp_grid};
use nalgebra::Vector3;
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
    fn curet_never_panics(bytes in proptest::collection::vec(any::<u8>(), 0..300),
                          cut in any::<usize>(), flip in any::<usize>(), at in any::<usize>()) {
        let t = Path::new("table.txt");
        let a = Path::new("abrdf.dat");
        let _ = curet::parse_table(t, &text(&bytes));
        let _ = curet::parse_values(a, &text(&bytes));
        let table = curet_fixture("table.txt");
        let _ = curet::parse_table(t, &text(&corrupt(table.as_bytes(), cut, flip, &bytes, at)));
        let values = curet_fixture("rbrdf.dat");
        let _ = curet::parse_values(a, &text(&corrupt(values.as_bytes(), cut, flip, &bytes, at)));
    }

    #[test]
    fn rgl_never_panics(bytes in proptest::collection::vec(any::<u8>(), 0..200),
                        cut in any::<usize>(), flip in any::<usize>(), at in any::<usize>()) {
        let p = Path::new("fuzz.bsdf");
        let _ = Rgl::parse(p, &bytes);
        let tiny = tiny_rgl();
        prop_assert!(Rgl::parse(p, &tiny).is_ok());
        if let Ok(m) = Rgl::parse(p, &corrupt(&tiny, cut, flip, &bytes, at)) {
            let mut out = [0.0; 3];
            let l = Vector3::new(0.3, 0.1, 0.95).normalize();
            let v = Vector3::new(-0.5, 0.2, 0.8).normalize();
            m.eval(&l, &v, &mut out);
        }
    }
}

fn curet_fixture(name: &str) -> String {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/curet");
    std::fs::read_to_string(dir.join(name)).unwrap()
}

/// A valid RGL material of constant 2 x 2 tables.
fn tiny_rgl() -> Vec<u8> {
    let f = |shape: &[usize], x: f32| {
        let n: usize = shape.iter().product();
        let bytes = (0..n).flat_map(|_| x.to_le_bytes()).collect();
        Field {
            dtype: 10,
            shape: shape.to_vec(),
            bytes,
        }
    };
    let fields = [
        ("phi_i", f(&[1], 0.0)),
        ("theta_i", f(&[2], 0.5)),
        ("ndf", f(&[2, 2], 1.0)),
        ("sigma", f(&[2, 2], 1.0)),
        ("vndf", f(&[1, 2, 2, 2], 1.0)),
        ("rgb", f(&[1, 2, 3, 2, 2], 0.5)),
    ];
    TensorFile {
        fields: fields
            .into_iter()
            .map(|(n, f)| (n.to_string(), f))
            .collect(),
    }
    .to_bytes()
    .unwrap()
}
