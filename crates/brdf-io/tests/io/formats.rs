//! Cornell, CSV samples, MERL and Sopp's grid: self-written fixtures,
//! round trips, bad input, and the real Cornell files when `BRDF_DATA` is
//! set.

use std::path::{Path, PathBuf};

use brdf_core::{Brdf, Direction, SampleSet, spherical_to_cartesian};
use brdf_io::cornell::{self, CornellColour};
use brdf_io::{IoError, csv_samples, merl, sopp_grid};
use nalgebra::Vector3;

fn fixture(p: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(p)
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("brdf-io-formats-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d.join(name)
}

/// A small analytic BRDF (Lambert plus a Phong lobe) with distinct channels.
struct Glossy;
impl Brdf for Glossy {
    fn channels(&self) -> usize {
        3
    }
    fn eval(&self, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        if !(l.z > 0.0 && v.z > 0.0) {
            out[..3].fill(0.0);
            return;
        }
        let c = (-l.x * v.x - l.y * v.y + l.z * v.z).max(0.0);
        let lobe = 12.0 / (2.0 * std::f64::consts::PI) * c.powi(10);
        for (k, o) in out[..3].iter_mut().enumerate() {
            *o = (0.1 + 0.1 * k as f64) / std::f64::consts::PI + 0.3 * lobe;
        }
    }
}

#[test]
fn cornell_fixture_flat_spectrum_is_grey_with_exact_luminance() {
    let y = cornell::read(&fixture("cornell/two.brdf"), CornellColour::Luminance).unwrap();
    assert_eq!(y.len(), 2);
    assert!(
        (y.channel(0)[0] - 0.25).abs() < 1e-12,
        "Y of a flat 0.25 spectrum: {}",
        y.channel(0)[0]
    );
    let rgb = cornell::read(&fixture("cornell/two.brdf"), CornellColour::Rgb).unwrap();
    for c in 0..3 {
        assert!(
            (rgb.channel(c)[0] / 0.25 - 1.0).abs() < 0.02,
            "channel {c}: {}",
            rgb.channel(c)[0]
        );
    }
    // The ramp (red-heavy) spectrum is redder than blue.
    assert!(rgb.channel(0)[1] > rgb.channel(2)[1]);
    // Directions: theta_i = 10 deg, phi_s = pi.
    assert!((rgb.pairs().lz[0] - 10f64.to_radians().cos()).abs() < 1e-6);
}

#[test]
fn cornell_bad_input() {
    let good = std::fs::read_to_string(fixture("cornell/two.brdf")).unwrap();
    let p = Path::new("bad.brdf");
    let truncated = &good[..good.len() - 20];
    assert!(matches!(
        cornell::parse(p, truncated, CornellColour::Rgb),
        Err(IoError::Count { .. })
    ));
    let bad = good.replace("0.250000", "0.2x0000");
    assert!(matches!(
        cornell::parse(p, &bad, CornellColour::Rgb),
        Err(IoError::NotANumber { line: 11, .. })
    ));
    let bad = good.replacen("31\r\n", "30\r\n", 1);
    assert!(matches!(
        cornell::parse(p, &bad, CornellColour::Rgb),
        Err(IoError::Format { .. })
    ));
    assert!(cornell::parse(p, "", CornellColour::Rgb).is_err());
    assert!(cornell::read(Path::new("/nonexistent.brdf"), CornellColour::Rgb).is_err());
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn cornell_real_files() {
    let root = std::env::var_os("BRDF_DATA")
        .expect("BRDF_DATA is not set: this test reads the measured data");
    for name in ["cayman", "mystique", "krylon_blue", "acryl_blue"] {
        let p = PathBuf::from(&root).join(format!("cornell/{name}.brdf"));
        assert!(
            p.exists(),
            "BRDF_DATA is set but {} is missing",
            p.display()
        );
        let s = cornell::read(&p, CornellColour::Rgb).unwrap();
        assert_eq!(s.len(), 1439, "{name}");
        assert_eq!(s.count_non_finite(), 0);
        // theta_i takes 8 values, 10..80 degrees; phi_i is 0.
        let mut ti: Vec<i64> = (0..s.len())
            .map(|j| (s.pairs().lz[j].acos().to_degrees()).round() as i64)
            .collect();
        ti.sort();
        ti.dedup();
        assert_eq!(ti, vec![10, 20, 30, 40, 50, 60, 70, 80], "{name}");
        let y = cornell::read(&p, CornellColour::Luminance).unwrap();
        assert!(y.value_range().unwrap().1 > 0.0);
    }
}

#[test]
fn csv_round_trip_is_exact_and_bad_rows_are_named() {
    let mut s = SampleSet::new("t", "test", vec!["r".into(), "g".into()]);
    for k in 0..20 {
        let l = Direction::from_spherical(0.05 * k as f64, 0.3 * k as f64 - 2.0).unwrap();
        let v = Direction::from_spherical(1.2 - 0.05 * k as f64, 0.1 * k as f64).unwrap();
        s.push(
            &l,
            &v,
            &[0.1 * k as f64 + 1e-17, -0.001 * k as f64],
            0.5 + k as f64,
        )
        .unwrap();
    }
    let p = tmp("round.csv");
    csv_samples::write(&p, &s).unwrap();
    let r = csv_samples::read(&p).unwrap();
    assert_eq!(r.len(), 20);
    assert_eq!(r.channel_names, vec!["r".to_string(), "g".into()]);
    for c in 0..2 {
        assert_eq!(r.channel(c), s.channel(c));
    }
    assert_eq!(r.weights(), s.weights());
    for j in 0..20 {
        assert!((r.pairs().l(j) - s.pairs().l(j)).norm() < 1e-15);
    }
    let q = Path::new("x.csv");
    assert!(matches!(
        csv_samples::parse(q, "a,b\n1,2\n"),
        Err(IoError::Format { line: 1, .. })
    ));
    let h = "theta_i,phi_i,theta_o,phi_o,grey,weight\n";
    assert!(matches!(
        csv_samples::parse(q, &format!("{h}0,0,0,0,zero,1\n")),
        Err(IoError::NotANumber {
            line: 2,
            field: 5,
            ..
        })
    ));
    assert!(matches!(
        csv_samples::parse(q, &format!("{h}0,0,0,0,1,1\n0,0,0\n")),
        Err(IoError::Format { line: 3, .. }) | Err(IoError::Count { line: 3, .. })
    ));
    assert!(matches!(
        csv_samples::parse(q, &format!("{h}NaN,0,0,0,1,1\n")),
        Err(IoError::NotFinite { .. })
    ));
    assert!(csv_samples::parse(q, &format!("{h}0,0,0,0,1,-1\n")).is_err());
    assert!(csv_samples::parse(q, h).is_err());
    // A NaN value is data (kept and counted), not an error.
    let s = csv_samples::parse(q, &format!("{h}0,0,0.1,0,NaN,1\n")).unwrap();
    assert_eq!(s.count_non_finite(), 1);
}

#[test]
fn merl_round_trip_lookup_and_weights() {
    let m = merl::Merl::resample(&Glossy);
    // At bin centres the lookup gives the resampled model exactly.
    for (ih, id, ip) in [
        (0, 0, 0),
        (10, 20, 30),
        (45, 60, 90),
        (89, 5, 179),
        (70, 85, 10),
    ] {
        let (l, v) = merl::bin_centre(ih, id, ip);
        if !(l.z > 0.0 && v.z > 0.0) {
            continue;
        }
        let mut f = [0.0; 3];
        Glossy.eval(&l, &v, &mut f);
        assert_eq!(merl::bin_of(&l, &v), Some(ih * 90 * 180 + id * 180 + ip));
        assert_eq!(m.lookup(&l, &v).unwrap(), f);
    }
    // Reciprocity folding: phi_d and phi_d + pi share a bin.
    let l = spherical_to_cartesian(0.4, 0.2);
    let v = spherical_to_cartesian(0.7, 2.5);
    assert_eq!(merl::bin_of(&l, &v), merl::bin_of(&v, &l));
    // Bins whose centre lies below the horizon are invalid.
    assert!(m.invalid_count() > 0);
    let p = tmp("glossy.binary");
    merl::write(&p, &m).unwrap();
    let r = merl::read(&p).unwrap();
    for (a, b) in r.values().iter().zip(m.values()) {
        assert!((a - b).abs() <= 4.0 * f64::EPSILON * b.abs(), "{a} vs {b}");
    }
    // Samples carry their bin's (positive) measure; invalid bins are left
    // out and counted.
    let (s, invalid) = r.to_samples("glossy", 97);
    assert!(s.len() > 1000 && invalid > 0);
    assert!(s.weights().iter().all(|w| *w > 0.0));
    // Bad input.
    let bytes = std::fs::read(&p).unwrap();
    let q = Path::new("bad.binary");
    assert!(merl::parse(q, &bytes[..bytes.len() - 8]).is_err());
    assert!(merl::parse(q, &bytes[..5]).is_err());
    let mut wrong = bytes.clone();
    wrong[0] = 91;
    assert!(merl::parse(q, &wrong).is_err());
    let mut nan = bytes;
    nan[12..20].copy_from_slice(&f64::NAN.to_le_bytes());
    assert!(matches!(merl::parse(q, &nan), Err(IoError::Format { .. })));
}

#[test]
fn sopp_grid_round_trip_weights_and_samples() {
    let g = sopp_grid::SoppGrid::resample(&Glossy);
    assert_eq!(g.values().len(), 75_924);
    let p = tmp("grid.csv");
    sopp_grid::write(&p, &g).unwrap();
    let r = sopp_grid::read(&p).unwrap();
    assert_eq!(r, g);
    // Cell weights: the camera covers half the hemisphere (phi in [0, pi],
    // theta in [0, pi/2]), so the cells sum to pi.
    let w = sopp_grid::SoppGrid::weights();
    let total: f64 = w.iter().sum();
    assert!((total - std::f64::consts::PI).abs() < 1e-12, "{total}");
    // An interior cell has twice an edge cell's azimuth width.
    assert!((w[10 * 36 + 5] / w[10 * 36] - 2.0).abs() < 1e-12);
    let s = g.to_samples("glossy", 75.0, true);
    // Lights 0..75 (16) and cameras 0..75 (31) by 36 azimuths.
    assert_eq!(s.len(), 16 * 31 * 36);
    // Bad input.
    let text = std::fs::read_to_string(&p).unwrap();
    let q = Path::new("g.csv");
    let truncated: String = text.lines().take(100).collect::<Vec<_>>().join("\n");
    assert!(matches!(
        sopp_grid::parse(q, &truncated),
        Err(IoError::Count { .. })
    ));
    let off = text.replacen("\n0,0,0,", "\n0,1,0,", 1);
    assert!(matches!(
        sopp_grid::parse(q, &off),
        Err(IoError::Format { line: 2, .. })
    ));
    assert!(sopp_grid::parse(q, "nonsense").is_err());
}
