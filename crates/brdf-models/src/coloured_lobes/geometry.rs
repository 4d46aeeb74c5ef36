//! The isotropic GGX lobe `S(alpha) = D G2 / (4 cos_i cos_o)` of one
//! direction pair, for several widths at once: the cosines and tangents it
//! needs are computed once per pair ([`LobeGeometry::new`]), each lobe then
//! costs one square root per direction for `Lambda` and no trigonometry.
//!
//! With `c = N.H`, `t = tan^2 theta` of a direction:
//! `D = alpha^2 / (pi (c^2 (alpha^2 - 1) + 1)^2)` (Walter et al. 2007),
//! `Lambda = (sqrt(1 + alpha^2 t) - 1) / 2` (Heitz 2014), written as
//! `alpha^2 t / (2 (sqrt(1 + alpha^2 t) + 1))` so that small `alpha^2 t`
//! does not cancel. The width derivative is taken through the logarithm:
//! `d ln D / d alpha = 2 / alpha - 4 alpha c^2 / (c^2 (alpha^2 - 1) + 1)`,
//! `d Lambda / d alpha = alpha t / (2 sqrt(1 + alpha^2 t))`.

use std::f64::consts::PI;

use nalgebra::Vector3;

use crate::ggx::Masking;

/// What every lobe of one direction pair shares.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LobeGeometry {
    /// `N.H` squared.
    pub cos_h2: f64,
    /// `tan^2` of the incident direction.
    pub tan2_i: f64,
    /// `tan^2` of the outgoing direction.
    pub tan2_o: f64,
    /// `V.H = L.H`, the Fresnel cosine `cos theta_d`, in `[0, 1]`.
    pub cos_d: f64,
    /// `1 / (4 cos_i cos_o)`.
    pub inv_4_cos: f64,
    /// `N.L` of the first direction (the viewer's in renderers' order, the
    /// `N.V` of MaterialX's energy compensation).
    pub cos_first: f64,
}

impl LobeGeometry {
    /// The pair's geometry; `None` when either direction is on or below the
    /// horizon (the model is 0 there).
    #[inline]
    pub fn new(l: &Vector3<f64>, v: &Vector3<f64>) -> Option<Self> {
        if !(l.z > 0.0 && v.z > 0.0) {
            return None;
        }
        Some(Self::unchecked(l, v))
    }

    /// [`LobeGeometry::new`] without the horizon test: meaningful only
    /// where both directions are above the horizon (a batch computes it
    /// branch-free for every pair and keeps only those).
    #[inline(always)]
    pub fn unchecked(l: &Vector3<f64>, v: &Vector3<f64>) -> Self {
        // Above the horizon l + v has a positive z, never zero length.
        let s = l + v;
        let len2 = s.norm_squared();
        let cos_d = (v.dot(&s) / len2.sqrt()).clamp(0.0, 1.0);
        let tan2 = |z: f64| ((1.0 - z * z) / (z * z)).max(0.0);
        LobeGeometry {
            cos_h2: s.z * s.z / len2,
            tan2_i: tan2(l.z),
            tan2_o: tan2(v.z),
            cos_d,
            inv_4_cos: 0.25 / (l.z * v.z),
            cos_first: l.z,
        }
    }

    /// `(S, dS/d alpha)` of the lobe of width `alpha > 0`.
    #[inline(always)]
    pub fn lobe(&self, alpha: f64, masking: Masking) -> (f64, f64) {
        let a2 = alpha * alpha;
        let den = self.cos_h2 * (a2 - 1.0) + 1.0;
        let d = a2 / (PI * den * den);
        let dln_d = 2.0 / alpha - 4.0 * alpha * self.cos_h2 / den;
        let lambda = |t: f64| {
            let r = (1.0 + a2 * t).sqrt();
            (a2 * t / (2.0 * (r + 1.0)), alpha * t / (2.0 * r))
        };
        let (li, dli) = lambda(self.tan2_i);
        let (lo, dlo) = lambda(self.tan2_o);
        let (g, dln_g) = match masking {
            Masking::HeightCorrelated => {
                let g = 1.0 / (1.0 + li + lo);
                (g, -g * (dli + dlo))
            }
            Masking::Separable => {
                let (gi, go) = (1.0 / (1.0 + li), 1.0 / (1.0 + lo));
                (gi * go, -(dli * gi + dlo * go))
            }
        };
        let s = d * g * self.inv_4_cos;
        (s, s * (dln_d + dln_g))
    }
}
