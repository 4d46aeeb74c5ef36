//! CUReT measurement geometry against vectors computed independently from
//! the raw rows of `table.txt` (`tests/fixtures/curet_real/directions.py`,
//! output `directions.txt`): the light and camera directions of eight named
//! measurements, azimuths included. A swapped column pair or a sign slip in
//! an azimuth changes them. Runs when `BRDF_DATA` is set.

use std::path::PathBuf;

use brdf_io::curet;

#[test]
#[ignore = "needs BRDF_DATA"]
fn named_curet_measurements_have_the_independent_directions() {
    let root = std::env::var_os("BRDF_DATA")
        .expect("BRDF_DATA is not set: this test reads the measured data");
    let table = PathBuf::from(root).join("curet").join("table.txt");
    assert!(
        table.exists(),
        "BRDF_DATA is set but {} is missing",
        table.display()
    );
    let dirs = curet::read_table(&table).unwrap();
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/curet_real/directions.txt"
    ))
    .unwrap();
    let mut n = 0;
    for line in text.lines().filter(|l| !l.starts_with('#')) {
        let f: Vec<f64> = line
            .split_whitespace()
            .map(|s| s.parse().unwrap())
            .collect();
        let k = f[0] as usize;
        let (l, v) = &dirs[k - 1];
        for i in 0..3 {
            assert!(
                (l[i] - f[1 + i]).abs() <= 1e-12,
                "measurement {k}: wi {:?} vs {:?}",
                l.vector(),
                &f[1..4]
            );
            assert!(
                (v[i] - f[4 + i]).abs() <= 1e-12,
                "measurement {k}: wo {:?} vs {:?}",
                v.vector(),
                &f[4..7]
            );
        }
        // Azimuths as in the table (modulo 2 pi; at theta = 0 none).
        let same_angle = |a: f64, b: f64| {
            let d = (a - b).rem_euclid(2.0 * std::f64::consts::PI);
            d.min(2.0 * std::f64::consts::PI - d) <= 1e-9
        };
        assert!(
            same_angle(l.phi(), f[7]),
            "measurement {k}: phi_i {} vs {}",
            l.phi(),
            f[7]
        );
        assert!(
            same_angle(v.phi(), f[8]),
            "measurement {k}: phi_o {} vs {}",
            v.phi(),
            f[8]
        );
        n += 1;
    }
    assert_eq!(n, 8);
}
