//! RGL `.bsdf` evaluation against Mitsuba 3's `measured` plugin, an
//! implementation written independently of this crate:
//! `tests/fixtures/rgl/mitsuba_measured.py` evaluated three materials of
//! `$BRDF_DATA/rgl` at 100 fixed direction pairs each (variant
//! `scalar_rgb`, f32) and `mitsuba_measured.txt` holds its output. Mitsuba
//! returns `f cos theta_v`, so `f` is multiplied by `cos theta_v` here.
//! Mitsuba does not clamp the interpolated RGB, which is slightly negative
//! at some pairs of the car-paint and yellow films; this crate clamps it at
//! 0 (documented in `rgl.rs`), so those pairs are compared with 0.
//! Runs when `BRDF_DATA` is set.

use std::path::PathBuf;

use brdf_core::Brdf;
use brdf_io::rgl::Rgl;
use nalgebra::Vector3;

/// `(file, wi, wo, Mitsuba's eval)` per line of the fixture.
type Case = (String, [f64; 3], [f64; 3], [f64; 3]);

fn fixture() -> Vec<Case> {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/rgl/mitsuba_measured.txt"
    ))
    .unwrap();
    text.lines()
        .filter(|l| !l.starts_with('#'))
        .map(|line| {
            let f: Vec<&str> = line.split_whitespace().collect();
            assert_eq!(f.len(), 10, "fixture line {line}");
            let x: Vec<f64> = f[1..].iter().map(|s| s.parse().unwrap()).collect();
            (
                f[0].to_string(),
                [x[0], x[1], x[2]],
                [x[3], x[4], x[5]],
                [x[6], x[7], x[8]],
            )
        })
        .collect()
}

/// The agreement found: at most 4.5e-6 relative over the 900 values
/// (Mitsuba works in f32 and gets its directions rounded to f32), pinned
/// with a little room.
const TOL: f64 = 1e-5;

#[test]
#[ignore = "needs BRDF_DATA"]
fn rgl_evaluation_agrees_with_mitsuba_measured() {
    let root = std::env::var_os("BRDF_DATA")
        .expect("BRDF_DATA is not set: this test reads the measured data");
    let cases = fixture();
    assert_eq!(cases.len(), 300);
    let mut files: Vec<&str> = cases.iter().map(|c| c.0.as_str()).collect();
    files.dedup();
    assert_eq!(files.len(), 3);
    let mut worst = 0.0f64;
    for name in files {
        let path = PathBuf::from(&root).join("rgl").join(name);
        assert!(
            path.exists(),
            "BRDF_DATA is set but {} is missing",
            path.display()
        );
        let rgl = Rgl::read(&path).unwrap();
        let mine: Vec<&Case> = cases.iter().filter(|c| c.0 == name).collect();
        let peak = mine.iter().flat_map(|c| c.3).fold(0.0f64, f64::max);
        let mut file_worst = 0.0f64;
        let mut clamped = 0;
        for (_, wi, wo, theirs) in mine {
            let (l, v) = (Vector3::from(*wi), Vector3::from(*wo));
            let mut out = [0.0; 3];
            rgl.eval(&l, &v, &mut out);
            for ch in 0..3 {
                let ours = out[ch] * v.z;
                if theirs[ch] < 0.0 {
                    clamped += 1;
                }
                let want = theirs[ch].max(0.0);
                // Relative to the value, with a floor at 1e-4 of the
                // file's largest value for the near-zero ones.
                let err = (ours - want).abs() / want.max(1e-4 * peak);
                file_worst = file_worst.max(err);
                assert!(
                    err <= TOL,
                    "{name} channel {ch} at wi {wi:?} wo {wo:?}: {ours} vs Mitsuba {} (relative {err:.2e})",
                    theirs[ch]
                );
            }
        }
        eprintln!("{name}: largest relative difference {file_worst:.3e}, {clamped} values clamped");
        worst = worst.max(file_worst);
        // A few, not a systematic sign error.
        assert!(
            clamped <= 40,
            "{name}: {clamped} of 300 Mitsuba values negative"
        );
    }
    eprintln!("largest relative difference over all files {worst:.3e}");
}
