//! CUReT: self-written fixtures, bad input, and the real files when
//! `BRDF_DATA` is set.

use std::path::{Path, PathBuf};

use brdf_io::IoError;
use brdf_io::curet::{self, SAMPLE_NAMES, is_isotropic};

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/curet")
}

#[test]
fn rgb_fixture_reads_with_names_and_values() {
    let sets = curet::read_rgb(&fixtures()).unwrap();
    assert_eq!(sets.len(), 2);
    assert_eq!(sets[0].name, "curet#25 Quarry Tile");
    assert_eq!(sets[1].name, "curet#55 Orange Peel");
    assert_eq!(sets[0].channels(), 3);
    assert_eq!(sets[0].len(), 205);
    // Value j of sample 25 in channel c is (c+1) (0.25 + 0.001 j).
    assert!((sets[0].channel(2)[10] - 3.0 * 0.26).abs() < 1e-12);
    // Row 1 of the fixture table: theta_v = 0.1, theta_i = 0.05.
    assert!((sets[0].pairs().vz[0] - 0.1f64.cos()).abs() < 1e-6);
    assert!((sets[0].pairs().lz[0] - 0.05f64.cos()).abs() < 1e-6);
}

fn write_tmp(name: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("brdf-io-curet-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

#[test]
fn bad_input_names_file_and_line() {
    let table = fixtures().join("table.txt");
    let good = std::fs::read_to_string(&table).unwrap();
    // Truncated table.
    let t = write_tmp(
        "short.txt",
        &good.lines().take(100).collect::<Vec<_>>().join("\n"),
    );
    let e = curet::read_table(&t).unwrap_err();
    assert!(matches!(e, IoError::Count { .. }), "{e}");
    // Text in a number field on line 3.
    let mut lines: Vec<String> = good.lines().map(String::from).collect();
    lines[2] = "3 0.5 x 0.1 0.2".into();
    let t = write_tmp("text.txt", &lines.join("\n"));
    let e = curet::read_table(&t).unwrap_err();
    assert!(
        e.to_string().contains(":3: field 3 `x` is not a number"),
        "{e}"
    );
    // NaN value in a data file.
    let v = write_tmp("nan.dat", &format!("1 {}", vec!["nan"; 205].join(" ")));
    assert!(matches!(
        curet::read_values(&v),
        Err(IoError::NotFinite { line: 1, .. })
    ));
    // Wrong count and impossible sample number.
    let v = write_tmp("few.dat", "1 0.1 0.2");
    assert!(matches!(
        curet::read_values(&v),
        Err(IoError::Count { line: 1, .. })
    ));
    let v = write_tmp("num.dat", &format!("62 {}", vec!["0.1"; 205].join(" ")));
    assert!(matches!(
        curet::read_values(&v),
        Err(IoError::Format { line: 1, .. })
    ));
    assert!(matches!(
        curet::read_values(Path::new("/nonexistent/abrdf.dat")),
        Err(IoError::Io { .. })
    ));
}

#[test]
fn isotropic_set_has_52_samples() {
    assert_eq!((1..=61).filter(|&n| is_isotropic(n)).count(), 52);
    assert_eq!(SAMPLE_NAMES[32], "Slate_a");
}

#[test]
fn real_curet_files() {
    let Some(root) = std::env::var_os("BRDF_DATA") else {
        eprintln!("skipped: BRDF_DATA is not set");
        return;
    };
    let dir = PathBuf::from(root).join("curet");
    let abrdf = dir.join("abrdf.dat");
    let table = dir.join("table.txt");
    assert!(
        abrdf.exists() && table.exists(),
        "BRDF_DATA is set but {} or {} is missing",
        abrdf.display(),
        table.display()
    );
    let sets = curet::read_grey(&abrdf, &table).unwrap();
    assert_eq!(sets.len(), 61);
    assert!(sets.iter().all(|s| s.len() == 205 && s.channels() == 1));
    // The 29 slightly negative values are kept, not clamped.
    let negative: usize = sets.iter().map(|s| s.count_negative()).sum();
    assert_eq!(negative, 29);
    assert_eq!(sets[0].name, "curet#1 Felt");
    assert!((sets[0].channel(0)[0] - 0.200).abs() < 1e-12);
    // Every geometry lies above the horizon.
    assert!(
        sets[0]
            .pairs()
            .lz
            .iter()
            .chain(&sets[0].pairs().vz)
            .all(|z| *z > 0.0)
    );
}
