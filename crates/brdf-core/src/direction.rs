//! Unit directions in the local shading frame and their spherical angles.
//!
//! Convention (see `docs/conventions.md`): the surface normal is `+z`, the
//! tangent `+x`, the bitangent `+y`. A direction `(theta, phi)` is
//! `(sin theta cos phi, sin theta sin phi, cos theta)`; both `L` (towards the
//! light) and `V` (towards the viewer) point away from the surface.

use nalgebra::{Unit, Vector3};

use crate::CoreError;

/// `(sin theta cos phi, sin theta sin phi, cos theta)`.
///
/// ```
/// let v = brdf_core::spherical_to_cartesian(std::f64::consts::FRAC_PI_2, 0.0);
/// assert!((v.x - 1.0).abs() < 1e-15 && v.z.abs() < 1e-15);
/// ```
#[inline]
pub fn spherical_to_cartesian(theta: f64, phi: f64) -> Vector3<f64> {
    let (st, ct) = theta.sin_cos();
    let (sp, cp) = phi.sin_cos();
    Vector3::new(st * cp, st * sp, ct)
}

/// Polar angle `theta = atan2(sqrt(x^2 + y^2), z)` (accurate near the pole and
/// the horizon, unlike `acos(z)`) and azimuth `phi = atan2(y, x)` in
/// `(-pi, pi]` (`0` at the pole) of a unit vector.
#[inline]
pub fn cartesian_to_spherical(v: &Vector3<f64>) -> (f64, f64) {
    let rho = v.x.hypot(v.y);
    let theta = rho.atan2(v.z);
    let phi = if rho == 0.0 { 0.0 } else { v.y.atan2(v.x) };
    (theta, phi)
}

/// A unit direction. It can only be built normalised (as nalgebra's `Unit`):
/// [`Direction::try_new`] rejects zero and non-finite vectors.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Direction(Unit<Vector3<f64>>);

impl Direction {
    /// Normalise `v`; fails for a zero, tiny or non-finite vector.
    pub fn try_new(v: Vector3<f64>) -> Result<Self, CoreError> {
        let bad = |reason| CoreError::InvalidDirection {
            x: v.x,
            y: v.y,
            z: v.z,
            reason,
        };
        if !(v.x.is_finite() && v.y.is_finite() && v.z.is_finite()) {
            return Err(bad("components must be finite"));
        }
        Unit::try_new(v, 1e-300)
            .map(Direction)
            .ok_or_else(|| bad("the vector has zero length"))
    }

    /// The direction with polar angle `theta` and azimuth `phi` (radians).
    pub fn from_spherical(theta: f64, phi: f64) -> Result<Self, CoreError> {
        if !(theta.is_finite() && phi.is_finite()) {
            return Err(CoreError::InvalidAngles {
                theta,
                phi,
                reason: "angles must be finite",
            });
        }
        Ok(Direction(Unit::new_unchecked(spherical_to_cartesian(
            theta, phi,
        ))))
    }

    /// Wrap a vector already known to be of unit length (not checked).
    pub fn new_unchecked(v: Vector3<f64>) -> Self {
        Direction(Unit::new_unchecked(v))
    }

    /// Polar angle from the normal, in `[0, pi]`.
    pub fn theta(&self) -> f64 {
        cartesian_to_spherical(&self.0).0
    }

    /// Azimuth from the tangent, in `(-pi, pi]`.
    pub fn phi(&self) -> f64 {
        cartesian_to_spherical(&self.0).1
    }

    /// The unit vector.
    pub fn vector(&self) -> &Vector3<f64> {
        &self.0
    }

    /// `cos theta = z`.
    pub fn cos_theta(&self) -> f64 {
        self.0.z
    }

    /// True when the direction lies strictly above the surface (`z > 0`).
    pub fn is_above_horizon(&self) -> bool {
        self.0.z > 0.0
    }
}

impl std::ops::Deref for Direction {
    type Target = Vector3<f64>;
    fn deref(&self) -> &Vector3<f64> {
        &self.0
    }
}
