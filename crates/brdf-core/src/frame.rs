//! Orthonormal frames: moving vectors between world space and the local
//! shading frame (normal `+z`).

use nalgebra::Vector3;

/// An orthonormal frame `(x, y, z)`; `z` is the surface normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// tangent
    pub x: Vector3<f64>,
    /// bitangent
    pub y: Vector3<f64>,
    /// normal
    pub z: Vector3<f64>,
}

impl Frame {
    /// The local frame itself.
    pub fn identity() -> Self {
        Frame {
            x: Vector3::x(),
            y: Vector3::y(),
            z: Vector3::z(),
        }
    }

    /// A frame with the given unit normal and an arbitrary but continuous
    /// tangent (Duff et al. 2017, "Building an orthonormal basis, revisited").
    pub fn from_z(z: Vector3<f64>) -> Self {
        let sign = 1.0_f64.copysign(z.z);
        let a = -1.0 / (sign + z.z);
        let b = z.x * z.y * a;
        let x = Vector3::new(1.0 + sign * z.x * z.x * a, sign * b, -sign * z.x);
        let y = Vector3::new(b, sign + z.y * z.y * a, -z.y);
        Frame { x, y, z }
    }

    /// A frame with unit normal `z` whose tangent is `x` made orthogonal to it
    /// (Gram-Schmidt). `x` must not be parallel to `z`.
    pub fn from_xz(x: Vector3<f64>, z: Vector3<f64>) -> Self {
        let x = (x - z * z.dot(&x)).normalize();
        let y = z.cross(&x);
        Frame { x, y, z }
    }

    /// Express a world vector in this frame.
    pub fn to_local(&self, v: &Vector3<f64>) -> Vector3<f64> {
        Vector3::new(v.dot(&self.x), v.dot(&self.y), v.dot(&self.z))
    }

    /// Express a local vector in world space.
    pub fn from_local(&self, v: &Vector3<f64>) -> Vector3<f64> {
        self.x * v.x + self.y * v.y + self.z * v.z
    }
}
