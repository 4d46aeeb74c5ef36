//! Rusinkiewicz half/difference angles: hand-derived values and round trips,
//! including the pole and grazing angles.

use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

use brdf_core::{Direction, HalfDiff, spherical_to_cartesian};
use nalgebra::Vector3;
use proptest::prelude::*;

fn close(a: &Vector3<f64>, b: &Vector3<f64>, tol: f64) -> bool {
    (a - b).norm() <= tol
}

#[test]
fn spherical_round_trip_and_known_vectors() {
    let v = spherical_to_cartesian(FRAC_PI_2, FRAC_PI_2);
    assert!(close(&v, &Vector3::y(), 1e-15));
    let d = Direction::from_spherical(0.3, -2.0).unwrap();
    assert!((d.theta() - 0.3).abs() < 1e-15);
    assert!((d.phi() + 2.0).abs() < 1e-15);
    // At the pole the azimuth is reported as 0.
    assert_eq!(
        Direction::try_new(Vector3::new(0.0, 0.0, 2.0))
            .unwrap()
            .phi(),
        0.0
    );
    assert!(Direction::try_new(Vector3::zeros()).is_err());
    assert!(Direction::try_new(Vector3::new(f64::NAN, 0.0, 1.0)).is_err());
    assert!(Direction::from_spherical(f64::INFINITY, 0.0).is_err());
}

#[test]
fn mirror_configuration_has_half_vector_at_the_normal() {
    // L at (theta, 0), V at (theta, pi): H = N, so theta_h = 0, and D is L
    // rotated by -phi_h about N: theta_d = theta, phi_d = phi_L - phi_h. At
    // the pole phi_h is whatever rounding makes it (sin pi is not 0 in f64),
    // so the invariant is phi_d + phi_h = phi_L (mod 2 pi).
    let t = 0.7;
    let l = spherical_to_cartesian(t, 0.0);
    let v = spherical_to_cartesian(t, PI);
    let hd = HalfDiff::from_directions(&l, &v).unwrap();
    assert!(hd.theta_h.abs() < 1e-15);
    assert!((hd.theta_d - t).abs() < 1e-14);
    let s = (hd.phi_d + hd.phi_h).rem_euclid(2.0 * PI);
    assert!(s.min(2.0 * PI - s) < 1e-14);
}

#[test]
fn retro_reflection_has_zero_difference_angle() {
    // L = V: H = L, D is the pole, theta_d = 0.
    let l = spherical_to_cartesian(1.1, 0.4);
    let hd = HalfDiff::from_directions(&l, &l).unwrap();
    assert!((hd.theta_h - 1.1).abs() < 1e-14);
    assert!((hd.phi_h - 0.4).abs() < 1e-14);
    assert!(hd.theta_d.abs() < 1e-7);
}

#[test]
fn hand_derived_in_plane_example() {
    // L at theta 60 deg, V at theta 0 (both in the x-z plane, phi = 0):
    // H bisects them at theta_h = 30 deg, phi_h = 0; L is 30 deg from H
    // towards +x, so theta_d = 30 deg, phi_d = 0.
    let l = spherical_to_cartesian(PI / 3.0, 0.0);
    let v = Vector3::z();
    let hd = HalfDiff::from_directions(&l, &v).unwrap();
    assert!((hd.theta_h - PI / 6.0).abs() < 1e-14);
    assert!(hd.phi_h.abs() < 1e-14);
    assert!((hd.theta_d - PI / 6.0).abs() < 1e-14);
    assert!(hd.phi_d.abs() < 1e-14);
    // Out of plane: L at (90 deg, 90 deg) = +y, V = +z. H = (0, 1, 1)/sqrt 2:
    // theta_h = 45 deg, phi_h = 90 deg. Rotating L by -90 deg about z gives
    // +x; by -45 deg about y gives (cos 45, 0, sin 45): theta_d = 45 deg, phi_d = 0.
    let hd = HalfDiff::from_directions(&Vector3::y(), &Vector3::z()).unwrap();
    assert!((hd.theta_h - FRAC_PI_4).abs() < 1e-14);
    assert!((hd.phi_h - FRAC_PI_2).abs() < 1e-14);
    assert!((hd.theta_d - FRAC_PI_4).abs() < 1e-14);
    assert!(hd.phi_d.abs() < 1e-14);
}

#[test]
fn opposite_directions_have_no_half_vector() {
    assert!(HalfDiff::from_directions(&Vector3::x(), &(-Vector3::x())).is_none());
}

#[test]
fn round_trip_at_the_pole_and_grazing() {
    let cases = [
        (0.0, 0.0, 0.0, 0.0),
        (0.0, 0.0, 0.5, 1.0),
        (FRAC_PI_2 - 1e-6, 0.3, FRAC_PI_2 - 1e-6, 0.3 + PI),
        (FRAC_PI_2 - 1e-6, 0.0, FRAC_PI_2 - 1e-6, 1e-3),
        (1e-9, 2.0, FRAC_PI_2 - 1e-9, -1.0),
    ];
    for (ti, pi_, to, po) in cases {
        let l = spherical_to_cartesian(ti, pi_);
        let v = spherical_to_cartesian(to, po);
        let hd = HalfDiff::from_directions(&l, &v).unwrap();
        let (l2, v2) = hd.to_directions();
        // H = (L + V)/|L + V| loses relative accuracy eps/|L + V| as L -> -V
        // (the conversion's condition number); the tolerance says so.
        let tol = 1e-14 / (l + v).norm();
        assert!(close(&l, &l2, tol), "L {l:?} -> {l2:?}");
        assert!(close(&v, &v2, tol), "V {v:?} -> {v2:?}");
    }
}

proptest! {
    #[test]
    fn round_trip_directions(ti in 0.0..FRAC_PI_2, pi_ in -PI..PI, to in 0.0..FRAC_PI_2, po in -PI..PI) {
        let l = spherical_to_cartesian(ti, pi_);
        let v = spherical_to_cartesian(to, po);
        let hd = HalfDiff::from_directions(&l, &v).unwrap();
        let (l2, v2) = hd.to_directions();
        prop_assert!(close(&l, &l2, 1e-12));
        prop_assert!(close(&v, &v2, 1e-12));
    }

    #[test]
    fn round_trip_angles(th in 1e-6..(FRAC_PI_2 - 1e-6), ph in -3.1..3.1f64, td in 1e-6..(FRAC_PI_2 - 1e-6), pd in -3.1..3.1f64) {
        let hd = HalfDiff { theta_h: th, phi_h: ph, theta_d: td, phi_d: pd };
        let (l, v) = hd.to_directions();
        let back = HalfDiff::from_directions(&l, &v).unwrap();
        prop_assert!((back.theta_h - th).abs() < 1e-9);
        prop_assert!((back.phi_h - ph).abs() < 1e-9);
        prop_assert!((back.theta_d - td).abs() < 1e-9);
        prop_assert!((back.phi_d - pd).abs() < 1e-9);
    }
}
