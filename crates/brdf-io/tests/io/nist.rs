//! NIST StRD `.dat` reader: a self-written fixture, bad input, and every
//! real file when `BRDF_DATA` is set.

use std::path::{Path, PathBuf};

use brdf_io::IoError;
use brdf_io::nist;

fn fixture() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/nist/Line3.dat")
}

#[test]
fn fixture_reads_every_field() {
    let d = nist::read(&fixture()).unwrap();
    assert_eq!(d.name, "Line3");
    assert_eq!(d.starts, [vec![1.0, 0.5], vec![2.0, 0.25]]);
    assert_eq!(d.certified, vec![3.0, 0.2]);
    assert_eq!(d.certified_sd, vec![0.1, 0.02]);
    assert_eq!(d.rss, 0.01);
    assert_eq!(d.residual_sd, 0.1);
    assert_eq!(d.dof, 1);
    assert_eq!(d.n_predictors, 1);
    assert_eq!(d.y, vec![0.5, 1.0, 1.5]);
    assert_eq!(d.x, vec![1.0, 2.0, 4.0]);
    assert!(d.model_text.contains("y = b1*(1-exp[-b2*x])"));
}

#[test]
fn bad_input_names_the_line() {
    let good = std::fs::read_to_string(fixture()).unwrap();
    let p = Path::new("bad.dat");
    // Truncated: one data line missing.
    let truncated: String = good
        .lines()
        .take(good.lines().count() - 1)
        .collect::<Vec<_>>()
        .join("\n");
    match nist::parse(p, &truncated) {
        Err(IoError::Count { found, .. }) => assert!(found.contains("2 data lines"), "{found}"),
        other => panic!("{other:?}"),
    }
    // Non-numeric data field on line 22.
    let bad = good.replace("      1.0             2", "      1.0             two");
    match nist::parse(p, &bad) {
        Err(IoError::NotANumber { line, text, .. }) => {
            assert_eq!(line, 22);
            assert_eq!(text, "two");
        }
        other => panic!("{other:?}"),
    }
    // A parameter line with three numbers.
    let bad = good.replace("0.25          2.0000000000E-01", "2.0000000000E-01");
    assert!(matches!(
        nist::parse(p, &bad),
        Err(IoError::Count { line: 13, .. })
    ));
    // NaN in the data.
    let bad = good.replace("      1.5             4", "      NaN             4");
    assert!(matches!(
        nist::parse(p, &bad),
        Err(IoError::NotFinite { line: 23, .. })
    ));
    // Missing header value.
    let bad = good.replace("Residual Sum of Squares:", "Residual Sum:");
    assert!(matches!(nist::parse(p, &bad), Err(IoError::Format { .. })));
    // Empty file.
    assert!(nist::parse(p, "").is_err());
    // Missing file.
    assert!(matches!(
        nist::read(Path::new("/nonexistent/x.dat")),
        Err(IoError::Io { .. })
    ));
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn real_files_match_the_index() {
    let root = std::env::var_os("BRDF_DATA")
        .expect("BRDF_DATA is not set: this test reads the measured data");
    let dir = PathBuf::from(root).join("nist_strd");
    let index = std::fs::read_to_string(dir.join("INDEX.tsv"))
        .unwrap_or_else(|e| panic!("BRDF_DATA is set but {}/INDEX.tsv: {e}", dir.display()));
    let sets = nist::read_dir(&dir).unwrap();
    assert_eq!(sets.len(), 22, "the shared folder holds 22 StRD problems");
    for line in index.lines().skip(1) {
        let f: Vec<&str> = line.split('\t').collect();
        let d = sets
            .iter()
            .find(|d| d.name == f[0])
            .unwrap_or_else(|| panic!("{} listed in INDEX.tsv but not read", f[0]));
        assert_eq!(
            d.certified.len(),
            f[2].parse::<usize>().unwrap(),
            "{}",
            f[0]
        );
        assert_eq!(d.y.len(), f[3].parse::<usize>().unwrap(), "{}", f[0]);
        let cert: Vec<f64> = f[9]
            .split_whitespace()
            .map(|v| v.parse().unwrap())
            .collect();
        assert_eq!(d.certified, cert, "{}", f[0]);
        assert_eq!(d.rss, f[11].parse::<f64>().unwrap(), "{}", f[0]);
    }
}

/// NIST's own `Rat43.dat` (public domain, NIST ITL StRD; data from line 61,
/// as published) says 9 degrees of freedom for 15 observations and 4
/// parameters; its certified residual standard deviation
/// `2.8262414662E+01 = sqrt(8.7864049080E+03 / 11)` uses n - p = 11. The
/// reader accepts the file, uses n - p and says so.
#[test]
fn rat43_header_with_wrong_degrees_of_freedom_is_read_with_n_minus_p_and_a_warning() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/nist/Rat43.dat");
    let d = brdf_io::nist::read(&path).unwrap();
    assert_eq!(d.y.len(), 15);
    assert_eq!(d.certified.len(), 4);
    assert_eq!(d.dof, 11);
    assert_eq!(d.starts[1], vec![700.0, 5.0, 0.75, 1.3]);
    assert_eq!(d.warnings.len(), 1, "{:?}", d.warnings);
    let w = &d.warnings[0];
    assert!(
        w.contains("Rat43.dat") && w.contains("9 degrees of freedom") && w.contains("using 11"),
        "{w}"
    );
    // The certified residual standard deviation agrees with n - p, not 9.
    let sd = (d.rss / d.dof as f64).sqrt();
    assert!(
        (sd / d.residual_sd - 1.0).abs() < 1e-9,
        "{sd} vs {}",
        d.residual_sd
    );
    // A consistent file gets no warning.
    let line3 = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/nist/Line3.dat");
    assert!(brdf_io::nist::read(&line3).unwrap().warnings.is_empty());
}
