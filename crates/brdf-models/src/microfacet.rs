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

/// The lobe `D G F(V.H) / (N.L N.V)` of Torrance-Sparrow and Cook-Torrance
/// with parameters `q = [m, f0]`: `distribution(g, m)` gives `D` and
/// `d ln D / dm` (`None` or `D = 0` where the distribution vanishes); the
/// derivatives `dS/dm`, `dS/df0` go into `dq`.
#[inline]
pub(crate) fn facet_lobe(
    q: &[f64],
    l: &Vector3<f64>,
    v: &Vector3<f64>,
    dq: Option<&mut [f64]>,
    distribution: impl Fn(&HalfGeometry, f64) -> Option<(f64, f64)>,
) -> f64 {
    use brdf_core::fresnel::{schlick, schlick_d_f0};
    let (m, f0) = (q[0], q[1]);
    let found = HalfGeometry::new(l, v).and_then(|g| distribution(&g, m).map(|d| (g, d)));
    let Some((g, (d, dln))) = found.filter(|(_, (d, _))| *d > 0.0) else {
        if let Some(dq) = dq {
            dq.fill(0.0);
        }
        return 0.0;
    };
    let common = d * g.shadowing() / (g.nl * g.nv);
    let s = common * schlick(f0, g.vh);
    if let Some(dq) = dq {
        dq[0] = s * dln;
        dq[1] = common * schlick_d_f0(g.vh);
    }
    s
}
