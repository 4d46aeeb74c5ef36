//! Shading-frame trigonometry, named as in pbrt so model code reads like the
//! paper. Every function takes a unit vector in the local frame (normal `+z`)
//! and guards its singular points (the pole for azimuths, the horizon for
//! tangents).

use nalgebra::Vector3;

/// `cos theta = z`.
#[inline]
pub fn cos_theta(w: &Vector3<f64>) -> f64 {
    w.z
}

/// `cos^2 theta`.
#[inline]
pub fn cos2_theta(w: &Vector3<f64>) -> f64 {
    w.z * w.z
}

/// `sin^2 theta = x^2 + y^2` (exact near the pole, unlike `1 - z^2`).
#[inline]
pub fn sin2_theta(w: &Vector3<f64>) -> f64 {
    w.x * w.x + w.y * w.y
}

/// `sin theta`.
#[inline]
pub fn sin_theta(w: &Vector3<f64>) -> f64 {
    sin2_theta(w).sqrt()
}

/// `tan^2 theta = sin^2 / cos^2`; `+inf` on the horizon.
#[inline]
pub fn tan2_theta(w: &Vector3<f64>) -> f64 {
    let c2 = cos2_theta(w);
    if c2 == 0.0 {
        f64::INFINITY
    } else {
        sin2_theta(w) / c2
    }
}

/// `cos phi`; `1` at the pole.
#[inline]
pub fn cos_phi(w: &Vector3<f64>) -> f64 {
    let s = sin_theta(w);
    if s == 0.0 {
        1.0
    } else {
        (w.x / s).clamp(-1.0, 1.0)
    }
}

/// `sin phi`; `0` at the pole.
#[inline]
pub fn sin_phi(w: &Vector3<f64>) -> f64 {
    let s = sin_theta(w);
    if s == 0.0 {
        0.0
    } else {
        (w.y / s).clamp(-1.0, 1.0)
    }
}

/// `cos(phi_a - phi_b)`; `1` when either vector is at the pole.
#[inline]
pub fn cos_dphi(a: &Vector3<f64>, b: &Vector3<f64>) -> f64 {
    let d = (sin2_theta(a) * sin2_theta(b)).sqrt();
    if d == 0.0 {
        1.0
    } else {
        ((a.x * b.x + a.y * b.y) / d).clamp(-1.0, 1.0)
    }
}

/// True when both vectors lie strictly above the surface.
#[inline]
pub fn both_above(a: &Vector3<f64>, b: &Vector3<f64>) -> bool {
    a.z > 0.0 && b.z > 0.0
}

/// True when both vectors lie on the same side of the surface.
#[inline]
pub fn same_hemisphere(a: &Vector3<f64>, b: &Vector3<f64>) -> bool {
    a.z * b.z > 0.0
}

/// Mirror direction `R = 2 (N.L) N - L` about the normal `+z`.
#[inline]
pub fn reflect_about_normal(l: &Vector3<f64>) -> Vector3<f64> {
    Vector3::new(-l.x, -l.y, l.z)
}
