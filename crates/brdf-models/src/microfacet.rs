//! Pieces shared by the microfacet models (Ashikhmin-Shirley,
//! Torrance-Sparrow, Cook-Torrance): the half-vector geometry of a direction
//! pair and the Torrance-Sparrow / Cook-Torrance shadowing-masking term
//! `G = min(1, 2 (N.H)(N.V)/(V.H), 2 (N.H)(N.L)/(V.H))`.

use nalgebra::Vector3;

/// Cosines of a direction pair around its half vector `H = (L + V)/|L + V|`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HalfGeometry {
    /// `N.H` (`cos delta`).
    pub nh: f64,
    /// `N.L` (`cos_i`).
    pub nl: f64,
    /// `N.V` (`cos_o`).
    pub nv: f64,
    /// `V.H` (`= L.H`, `cos theta_d`).
    pub vh: f64,
    /// `H_x^2 / (H_x^2 + H_y^2)` (`cos^2 phi_h`; 1/2 when `H = N`).
    pub cos2_phi_h: f64,
}

impl HalfGeometry {
    /// The geometry of `(L, V)`; `None` when `L + V = 0`.
    #[inline]
    pub fn new(l: &Vector3<f64>, v: &Vector3<f64>) -> Option<Self> {
        let s = l + v;
        let len = s.norm();
        if !(len > 0.0) {
            return None;
        }
        let h = s / len;
        let r2 = h.x * h.x + h.y * h.y;
        Some(Self {
            nh: h.z.clamp(-1.0, 1.0),
            nl: l.z,
            nv: v.z,
            vh: v.dot(&h),
            cos2_phi_h: if r2 > 0.0 { h.x * h.x / r2 } else { 0.5 },
        })
    }

    /// Shadowing-masking `min(1, 2 NH NV / VH, 2 NH NL / VH)`.
    #[inline]
    pub fn shadowing(&self) -> f64 {
        if !(self.vh > 0.0) {
            return 0.0;
        }
        let k = 2.0 * self.nh / self.vh;
        1.0f64.min(k * self.nv).min(k * self.nl).max(0.0)
    }
}
