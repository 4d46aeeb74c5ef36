//! The judge scene's geometry: which pixels see the unit sphere at the
//! origin, and at each such pixel the surface point, its shading frame and
//! the direction back to the camera.
//!
//! Why: every light set and every BRDF shares this geometry, so it is
//! computed once. The shading frame follows [`crate::sphere`]: normal = the
//! point (unit sphere), tangent = world `+x` made orthogonal to the normal, so
//! anisotropic models see a continuous tangent field and the two renderers
//! agree on orientation.

use brdf_core::Frame;
use nalgebra::Vector3;

use crate::camera::Camera;

/// One pixel whose centre ray hits the sphere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphereHit {
    /// pixel index `py * size + px`
    pub pixel: usize,
    /// the hit point (world; on the unit sphere it is also the normal)
    pub point: Vector3<f64>,
    /// shading frame: `z` = normal, `x` = world `+x` made orthogonal to it
    pub frame: Frame,
    /// unit world direction from the point towards the camera
    pub view: Vector3<f64>,
}

/// The shading frame of a unit-sphere point with normal `n` (as in
/// [`crate::sphere::render_sphere`]).
pub fn sphere_frame(n: Vector3<f64>) -> Frame {
    if n.x.abs() > 1.0 - 1e-9 {
        Frame::from_z(n)
    } else {
        Frame::from_xz(Vector3::x(), n)
    }
}

/// The first hit of the ray `origin + t dir` (`dir` unit) with the unit
/// sphere at the origin, if any in front of the origin.
pub fn intersect_unit_sphere(origin: &Vector3<f64>, dir: &Vector3<f64>) -> Option<Vector3<f64>> {
    let b = origin.dot(dir);
    let c = origin.norm_squared() - 1.0;
    let disc = b * b - c;
    if disc < 0.0 {
        return None;
    }
    let t = -b - disc.sqrt();
    (t > 0.0).then(|| origin + dir * t)
}

/// The hit of the ray from `camera` in unit direction `dir`, credited to
/// `pixel`, if the ray meets the sphere.
pub fn hit_of(camera: &Camera, pixel: usize, dir: &Vector3<f64>) -> Option<SphereHit> {
    let p = intersect_unit_sphere(&camera.origin, dir)?;
    let n = p.normalize();
    Some(SphereHit {
        pixel,
        point: n,
        frame: sphere_frame(n),
        view: -dir,
    })
}

/// Every pixel of a `size x size` image from `camera` that sees the unit
/// sphere, in pixel order (row by row, top row first).
pub fn sphere_hits(camera: &Camera, size: usize) -> Vec<SphereHit> {
    let mut hits = Vec::new();
    for py in 0..size {
        for px in 0..size {
            let dir = camera.ray(px, py, size);
            hits.extend(hit_of(camera, py * size + px, &dir));
        }
    }
    hits
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centre_pixel_hits_the_pole_facing_the_camera() {
        let hits = sphere_hits(&Camera::judge(), 65);
        let centre = hits.iter().find(|h| h.pixel == 32 * 65 + 32);
        let Some(h) = centre else {
            panic!("centre pixel misses the sphere");
        };
        assert!((h.point - Vector3::z()).norm() < 1e-14);
        assert!((h.view - Vector3::z()).norm() < 1e-14);
        // The silhouette radius in pixels: tan(asin(1/6)) / tan(11 deg) * 32.5.
        let r = (1.0_f64 / 35.0).sqrt() / 11.0_f64.to_radians().tan() * 32.5;
        let expect = std::f64::consts::PI * r * r;
        assert!((hits.len() as f64 - expect).abs() / expect < 0.03);
        for h in &hits {
            assert!(h.frame.z.dot(&h.view) > 0.0);
            assert!(h.frame.x.dot(&h.frame.z).abs() < 1e-12);
        }
    }
}
