//! The judge camera of the appearance spec: a pinhole (perspective) camera
//! placed by `look_at`, with a horizontal field of view, one ray through
//! each pixel centre.
//!
//! Why: a lookdev user sees a BRDF on a sphere through a perspective camera,
//! so the view direction changes across the sphere (unlike the orthographic
//! [`crate::sphere`] figures). Matching Mitsuba's `perspective` sensor
//! (`fov_axis = "x"`, square film) lets our renders be compared with the
//! reference renders pixel for pixel. Image `x` grows to the camera's right,
//! image `y` grows downwards (row 0 is the top row).

use nalgebra::Vector3;

use crate::RenderError;

/// A perspective camera: position, orthonormal right/up/forward axes and the
/// tangent of half the field of view.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// position of the pinhole
    pub origin: Vector3<f64>,
    /// unit vector towards the image's right edge
    pub right: Vector3<f64>,
    /// unit vector towards the image's top edge
    pub up: Vector3<f64>,
    /// unit viewing direction
    pub forward: Vector3<f64>,
    /// `tan(fov / 2)`
    pub tan_half_fov: f64,
}

impl Camera {
    /// A camera at `origin` looking at `target`, `up` giving the vertical,
    /// with the field of view `fov_deg` (degrees, across the image width).
    pub fn look_at(
        origin: Vector3<f64>,
        target: Vector3<f64>,
        up: Vector3<f64>,
        fov_deg: f64,
    ) -> Result<Camera, RenderError> {
        let forward = (target - origin).try_normalize(1e-12).ok_or_else(|| {
            RenderError::Invalid("look_at: origin equals target: move the camera".into())
        })?;
        let right = forward.cross(&up).try_normalize(1e-12).ok_or_else(|| {
            RenderError::Invalid("look_at: up is parallel to the view: choose another up".into())
        })?;
        if !(fov_deg > 0.0 && fov_deg < 180.0) {
            return Err(RenderError::Invalid(format!(
                "look_at: fov_deg = {fov_deg}: use a field of view in (0, 180) degrees"
            )));
        }
        Ok(Camera {
            origin,
            right,
            up: right.cross(&forward),
            forward,
            tan_half_fov: (fov_deg.to_radians() * 0.5).tan(),
        })
    }

    /// The judge camera: at `(0, 0, 6)` looking at the origin, up `+y`,
    /// field of view 22 degrees.
    pub fn judge() -> Camera {
        let tan_half_fov = (22.0_f64.to_radians() * 0.5).tan();
        Camera {
            origin: Vector3::new(0.0, 0.0, 6.0),
            right: Vector3::x(),
            up: Vector3::y(),
            forward: -Vector3::z(),
            tan_half_fov,
        }
    }

    /// Unit direction of the ray through the centre of pixel `(px, py)` of a
    /// `size x size` image.
    pub fn ray(&self, px: usize, py: usize, size: usize) -> Vector3<f64> {
        self.ray_at(px as f64 + 0.5, py as f64 + 0.5, size)
    }

    /// Unit direction of the ray through the film position `(x, y)` in
    /// pixels (`(px + 0.5, py + 0.5)` is the centre of pixel `(px, py)`) of
    /// a `size x size` image.
    pub fn ray_at(&self, x: f64, y: f64, size: usize) -> Vector3<f64> {
        let s = size as f64;
        let x = (x / s * 2.0 - 1.0) * self.tan_half_fov;
        let y = (1.0 - y / s * 2.0) * self.tan_half_fov;
        (self.forward + self.right * x + self.up * y).normalize()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn judge_equals_look_at_and_centre_ray_hits_origin() -> Result<(), RenderError> {
        let a = Camera::judge();
        let b = Camera::look_at(
            Vector3::new(0.0, 0.0, 6.0),
            Vector3::zeros(),
            Vector3::y(),
            22.0,
        )?;
        assert!((a.right - b.right).norm() < 1e-15 && (a.up - b.up).norm() < 1e-15);
        assert!((a.tan_half_fov - b.tan_half_fov).abs() < 1e-15);
        // An odd image has a pixel centred on the axis.
        assert!((a.ray(2, 2, 5) + Vector3::z()).norm() < 1e-15);
        // The corner ray of the right edge leaves at half the fov in x.
        let r = a.ray(4, 2, 5);
        let expect = (0.8 * a.tan_half_fov).atan();
        assert!((r.x.atan2(-r.z) - expect).abs() < 1e-12);
        assert!(Camera::look_at(Vector3::zeros(), Vector3::zeros(), Vector3::y(), 22.0).is_err());
        Ok(())
    }
}
