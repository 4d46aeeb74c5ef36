//! Sopp's grid against hand-computed values: node directions (light at
//! azimuth 180 deg, camera azimuth `k 180/35` deg from +x), the value a
//! resampled BRDF stores at a node, the angles written for a node, and
//! camera cell solid angles `(cos t0 - cos t1)(p1 - p0)` with edges halfway
//! between nodes.

use brdf_core::Brdf;
use brdf_io::sopp_grid::{self, CAM_PHIS, CAM_THETAS, LIGHTS, SoppGrid};
use nalgebra::Vector3;

/// `(il, it, ip)`, `L`, `V`: by hand, `L = (-sin 5il, 0, cos 5il)`,
/// `V = (sin t cos p, sin t sin p, cos t)` with `t = 2.5 it`, `p = ip 180/35`
/// (degrees), evaluated on a calculator.
/// `((il, it, ip), L, V)`.
type Node = ((usize, usize, usize), [f64; 3], [f64; 3]);

// The literals are the hand-computed values, 1/sqrt(2) included.
#[allow(clippy::approx_constant)]
const NODES: [Node; 6] = [
    ((0, 0, 0), [0.0, 0.0, 1.0], [0.0, 0.0, 1.0]),
    (
        (2, 4, 7),
        [-0.17364817766693033, 0.0, 0.984807753012208],
        [0.14048432677478684, 0.10206783792008485, 0.984807753012208],
    ),
    (
        (3, 12, 10),
        [-0.25881904510252074, 0.0, 0.9659258262890683],
        [0.31174490092936674, 0.39091574123401485, 0.8660254037844387],
    ),
    (
        (9, 18, 35),
        [-0.7071067811865475, 0.0, 0.7071067811865476],
        [-0.7071067811865475, 0.0, 0.7071067811865476],
    ),
    ((18, 36, 35), [-1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]),
    (
        (18, 20, 1),
        [-1.0, 0.0, 0.0],
        [0.7629605734044002, 0.06866769447050076, 0.6427876096865394],
    ),
];

/// A BRDF that returns coordinates of its directions (shifted positive).
struct Coordinates;

impl Brdf for Coordinates {
    fn channels(&self) -> usize {
        3
    }
    fn eval(&self, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        out[0] = 2.0 + l.x;
        out[1] = 2.0 + v.x;
        out[2] = 2.0 + v.y;
    }
}

#[test]
fn node_directions_are_the_hand_computed_ones() {
    assert_eq!((LIGHTS, CAM_THETAS, CAM_PHIS), (19, 37, 36));
    assert_eq!(SoppGrid::NODES * 3, 75_924);
    let g = SoppGrid::resample(&Coordinates);
    for ((il, it, ip), l, v) in NODES {
        let (gl, gv) = SoppGrid::directions(il, it, ip);
        for i in 0..3 {
            assert!(
                (gl[i] - l[i]).abs() <= 1e-15,
                "node {il} {it} {ip}: L {gl:?} vs {l:?}"
            );
            assert!(
                (gv[i] - v[i]).abs() <= 1e-15,
                "node {il} {it} {ip}: V {gv:?} vs {v:?}"
            );
        }
        let rgb = g.rgb(il, it, ip);
        let want = [2.0 + l[0], 2.0 + v[0], 2.0 + v[1]];
        for c in 0..3 {
            assert!(
                (rgb[c] - want[c]).abs() <= 1e-15,
                "node {il} {it} {ip} value {rgb:?} vs {want:?}"
            );
        }
    }
}

#[test]
fn written_rows_name_the_node_angles() {
    let g = SoppGrid::resample(&Coordinates);
    let path = std::env::temp_dir().join(format!("brdf-io-sopp-nodes-{}.csv", std::process::id()));
    sopp_grid::write(&path, &g).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    std::fs::remove_file(&path).unwrap();
    let rows: Vec<Vec<f64>> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|s| s.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 19 * 37 * 36);
    // Node (2, 4, 7): light 10 deg, camera 10 deg at 36 deg azimuth.
    let row = rows
        .iter()
        .find(|r| r[0] == 10.0 && r[1] == 10.0 && (r[2] - 36.0).abs() < 1e-12)
        .expect("a row for light 10, camera 10 at azimuth 36");
    assert!((row[3] - (2.0 - 0.17364817766693033)).abs() <= 1e-15);
    assert!((row[5] - (2.0 + 0.10206783792008485)).abs() <= 1e-15);
    // The last camera azimuth is 180 deg.
    assert!(rows.iter().any(|r| (r[2] - 180.0).abs() < 1e-12));
}

#[test]
fn cell_solid_angles_are_the_hand_computed_ones() {
    let w = SoppGrid::weights();
    assert_eq!(w.len(), 37 * 36);
    let rad = |d: f64| d.to_radians();
    let dp = rad(180.0 / 35.0);
    // Interior cell it = 12 (30 deg), ip = 10: theta 28.75..31.25 deg, one
    // azimuth step wide.
    let interior = (rad(28.75).cos() - rad(31.25).cos()) * dp;
    assert!(
        (w[12 * 36 + 10] - interior).abs() <= 1e-15,
        "{} vs {interior}",
        w[12 * 36 + 10]
    );
    // Pole corner (0, 0): theta 0..1.25 deg, half an azimuth step.
    let corner = (1.0 - rad(1.25).cos()) * dp / 2.0;
    assert!((w[0] - corner).abs() <= 1e-17, "{} vs {corner}", w[0]);
    // Horizon edge (36, 17): theta 88.75..90 deg.
    let edge = rad(88.75).cos() * dp;
    assert!(
        (w[36 * 36 + 17] - edge).abs() <= 1e-15,
        "{} vs {edge}",
        w[36 * 36 + 17]
    );
    // Together: the half hemisphere the camera covers, pi.
    let total: f64 = w.iter().sum();
    assert!((total - std::f64::consts::PI).abs() <= 1e-12, "{total}");
}
