//! Rusinkiewicz (1998) half/difference angles, both ways.
//!
//! `H = (L + V) / |L + V|` with polar angles `(theta_h, phi_h)`. The difference
//! vector `D` is `L` expressed in the frame where `H` is the pole: rotate `L` by
//! `-phi_h` about the normal, then by `-theta_h` about the bitangent. Its polar
//! angles are `(theta_d, phi_d)`. The inverse rotates `D` back, and `V` is the
//! reflection of `L` about `H`: `V = 2 (H.L) H - L`. Derivation in
//! `docs/derivations/half_diff.md`.
//!
//! At the pole (`theta_h = 0`) `phi_h` is undefined; it is reported as `0`, and
//! the round trip `(L, V) -> HalfDiff -> (L, V)` still holds because the
//! rotation by `-phi_h` and its inverse cancel.

use nalgebra::Vector3;

use crate::direction::cartesian_to_spherical;
use crate::spherical_to_cartesian;

/// The normalised half vector `(L + V) / |L + V|`, or `None` when `L = -V`.
#[inline]
pub fn half_vector(l: &Vector3<f64>, v: &Vector3<f64>) -> Option<Vector3<f64>> {
    let h = l + v;
    let n = h.norm();
    if n > 1e-300 && n.is_finite() {
        Some(h / n)
    } else {
        None
    }
}

/// Rotate `w` by angle `a` about `+z`.
#[inline]
fn rot_z(w: &Vector3<f64>, a: f64) -> Vector3<f64> {
    let (s, c) = a.sin_cos();
    Vector3::new(c * w.x - s * w.y, s * w.x + c * w.y, w.z)
}

/// Rotate `w` by angle `a` about `+y` (the bitangent).
#[inline]
fn rot_y(w: &Vector3<f64>, a: f64) -> Vector3<f64> {
    let (s, c) = a.sin_cos();
    Vector3::new(c * w.x + s * w.z, w.y, -s * w.x + c * w.z)
}

/// Half/difference angles of a direction pair (radians).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct HalfDiff {
    /// polar angle of `H`, `[0, pi]`
    pub theta_h: f64,
    /// azimuth of `H`, `(-pi, pi]` (`0` at the pole)
    pub phi_h: f64,
    /// polar angle of `D`, `[0, pi]`
    pub theta_d: f64,
    /// azimuth of `D`, `(-pi, pi]`
    pub phi_d: f64,
}

impl HalfDiff {
    /// Half/difference angles of `(L, V)`, or `None` when `L = -V` (no half
    /// vector). Both must be unit vectors.
    pub fn from_directions(l: &Vector3<f64>, v: &Vector3<f64>) -> Option<Self> {
        let h = half_vector(l, v)?;
        let (theta_h, phi_h) = cartesian_to_spherical(&h);
        let d = rot_y(&rot_z(l, -phi_h), -theta_h);
        let (theta_d, phi_d) = cartesian_to_spherical(&d);
        Some(HalfDiff {
            theta_h,
            phi_h,
            theta_d,
            phi_d,
        })
    }

    /// The half vector `H`.
    pub fn half(&self) -> Vector3<f64> {
        spherical_to_cartesian(self.theta_h, self.phi_h)
    }

    /// `(L, V)` back from the angles.
    pub fn to_directions(&self) -> (Vector3<f64>, Vector3<f64>) {
        let d = spherical_to_cartesian(self.theta_d, self.phi_d);
        let l = rot_z(&rot_y(&d, self.theta_h), self.phi_h);
        let h = self.half();
        let v = h * (2.0 * h.dot(&l)) - l;
        (l, v)
    }
}
