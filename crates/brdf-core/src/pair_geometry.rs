//! Per-sample-set geometry that does not change while a model is fitted:
//! the half-vector cosines of every direction pair, computed once and read
//! by the batch kernels of the models at every iteration.
//!
//! `H = (L + V)/|L + V|`; `nh = N.H` (clamped to `[-1, 1]`), `vh = V.H`
//! (`= L.H`), `cos2_phi_h = H_x^2/(H_x^2 + H_y^2)` (1/2 when `H = N`);
//! and the parameter-free factors of the Ashikhmin-Shirley lobe, Schlick's
//! `(1 - V.H)^5` and `1 / (V.H max(N.L, N.V))`, so its kernel does no
//! division per sample and iteration; the polar angles of `L` and `V`
//! (`atan2(|w_xy|, w_z)`, accurate at the pole), whose arc tangents the
//! shadowing terms of Bagher's SGD would otherwise take at every
//! iteration (a sixth of its fit's time).
//! A pair with `L + V = 0` or either direction at or below the horizon is
//! marked invalid (`valid[j] == false`); models return 0 there.

use crate::samples::DirPairs;

/// Structure-of-arrays half-vector geometry of a set of direction pairs.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PairGeometry {
    /// `N.H`.
    pub nh: Vec<f64>,
    /// `V.H`.
    pub vh: Vec<f64>,
    /// `cos^2 phi_h`.
    pub cos2_phi_h: Vec<f64>,
    /// `ln(min(N.H, 1))` (`-inf` where `N.H <= 0`): powers `(N.H)^e` are
    /// `exp(e ln N.H)`, so the logarithm is taken once per sample set.
    pub ln_nh: Vec<f64>,
    /// Both directions above the horizon and `L + V != 0`.
    pub valid: Vec<bool>,
    /// `(1 - V.H)^5`, `V.H` clamped to `[0, 1]` (Schlick's Fresnel weight).
    pub schlick5: Vec<f64>,
    /// `1 / (V.H max(N.L, N.V))` (0 for an invalid pair).
    pub inv_vh_max_cos: Vec<f64>,
    /// Polar angle of `L`, `atan2(|L_xy|, L_z)`.
    pub theta_i: Vec<f64>,
    /// Polar angle of `V`, `atan2(|V_xy|, V_z)`.
    pub theta_o: Vec<f64>,
}

impl PairGeometry {
    /// The geometry of every pair of `pairs`.
    pub fn new(pairs: &DirPairs) -> Self {
        let n = pairs.len();
        let mut g = PairGeometry {
            nh: vec![0.0; n],
            vh: vec![0.0; n],
            cos2_phi_h: vec![0.5; n],
            ln_nh: vec![f64::NEG_INFINITY; n],
            valid: vec![false; n],
            schlick5: vec![1.0; n],
            inv_vh_max_cos: vec![0.0; n],
            theta_i: (0..n)
                .map(|j| polar(pairs.lx[j], pairs.ly[j], pairs.lz[j]))
                .collect(),
            theta_o: (0..n)
                .map(|j| polar(pairs.vx[j], pairs.vy[j], pairs.vz[j]))
                .collect(),
        };
        for j in 0..n {
            let (sx, sy, sz) = (
                pairs.lx[j] + pairs.vx[j],
                pairs.ly[j] + pairs.vy[j],
                pairs.lz[j] + pairs.vz[j],
            );
            let len = (sx * sx + sy * sy + sz * sz).sqrt();
            if !(len > 0.0) {
                continue;
            }
            let (hx, hy, hz) = (sx / len, sy / len, sz / len);
            let r2 = hx * hx + hy * hy;
            g.nh[j] = hz.clamp(-1.0, 1.0);
            g.vh[j] = pairs.vx[j] * hx + pairs.vy[j] * hy + pairs.vz[j] * hz;
            g.cos2_phi_h[j] = if r2 > 0.0 { hx * hx / r2 } else { 0.5 };
            if g.nh[j] > 0.0 {
                g.ln_nh[j] = g.nh[j].min(1.0).ln();
            }
            g.valid[j] = pairs.lz[j] > 0.0 && pairs.vz[j] > 0.0;
            let m = 1.0 - g.vh[j].clamp(0.0, 1.0);
            g.schlick5[j] = m * m * m * m * m;
            if g.valid[j] {
                g.inv_vh_max_cos[j] = 1.0 / (g.vh[j] * pairs.lz[j].max(pairs.vz[j]));
            }
        }
        g
    }

    /// Number of pairs.
    pub fn len(&self) -> usize {
        self.nh.len()
    }

    /// True when there are no pairs.
    pub fn is_empty(&self) -> bool {
        self.nh.is_empty()
    }
}

/// Polar angle of a unit direction (`atan2(|w_xy|, w_z)`, accurate at the
/// pole, where `acos(w_z)` is not).
fn polar(x: f64, y: f64, z: f64) -> f64 {
    (x * x + y * y).sqrt().atan2(z)
}

#[cfg(test)]
mod tests {
    use super::PairGeometry;
    use crate::samples::DirPairs;

    /// The polar angles are the directions' arc cosines, computed
    /// independently, from the pole to the horizon.
    #[test]
    fn polar_angles_are_the_arc_cosines_of_the_z_components() {
        let mut pairs = DirPairs::with_capacity(8);
        for k in 0..8 {
            let (ti, to) = (0.2 * k as f64, 1.5 - 0.19 * k as f64);
            let (pi, po) = (0.7 * k as f64, 2.0 + 0.3 * k as f64);
            let l = [ti.sin() * pi.cos(), ti.sin() * pi.sin(), ti.cos()];
            let v = [to.sin() * po.cos(), to.sin() * po.sin(), to.cos()];
            pairs.push(&l.into(), &v.into());
        }
        let g = PairGeometry::new(&pairs);
        for k in 0..8 {
            assert!(
                (g.theta_i[k] - pairs.lz[k].acos()).abs() < 1e-7,
                "theta_i {k}"
            );
            assert!(
                (g.theta_o[k] - pairs.vz[k].acos()).abs() < 1e-7,
                "theta_o {k}"
            );
            assert!((g.theta_i[k] - 0.2 * k as f64).abs() < 1e-12, "theta_i {k}");
        }
    }
}
