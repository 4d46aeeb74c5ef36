//! Exact unpolarised Fresnel reflectance of a conductor (complex index
//! `n = eta + i k`), with its derivatives in `eta` and `k`.
//!
//! With `z = sqrt(n^2 - sin^2 theta_i)` (principal branch, so `Re z >= 0`
//! for `eta > 0`, `k >= 0`), the amplitude ratios are
//! `r_s = (cos_i - z) / (cos_i + z)` and `r_p = (n^2 cos_i - z) / (n^2 cos_i + z)`,
//! and `F = (|r_s|^2 + |r_p|^2) / 2` (Born & Wolf, "Principles of Optics",
//! sec. 14.2; pbrt-v4 `FrComplex`). For `k = 0`, `eta >= 1` this is the
//! dielectric reflectance of [`crate::fresnel::fresnel_dielectric`].
//!
//! `r_s`, `r_p` are holomorphic in `n`, so with `r' = dr/dn`:
//! `d|r|^2/d eta = 2 Re(conj(r) r')` and `d|r|^2/dk = -2 Im(conj(r) r')`;
//! `dz/dn = n / z`, `dr_s/dn = -2 cos_i z' / (cos_i + z)^2`,
//! `dr_p/dn = (4 n cos_i z - 2 n^2 cos_i z') / (n^2 cos_i + z)^2`.

use nalgebra::Complex;

/// `F(cos_i; eta, k)`, `cos_i` clamped to `[0, 1]`.
///
/// ```
/// use brdf_core::fresnel_conductor::fresnel_conductor;
/// // Normal incidence: ((eta - 1)^2 + k^2) / ((eta + 1)^2 + k^2).
/// let f = fresnel_conductor(1.0, 0.2, 3.0);
/// assert!((f - (0.64 + 9.0) / (1.44 + 9.0)).abs() < 1e-14);
/// ```
pub fn fresnel_conductor(cos_i: f64, eta: f64, k: f64) -> f64 {
    fresnel_conductor_grad(cos_i, eta, k).0
}

/// `(F, dF/d eta, dF/dk)` of [`fresnel_conductor`]. At grazing incidence
/// (`cos_i = 0`) `F = 1` and both derivatives are 0; where `z = 0`
/// (`k = 0` and `eta = sin theta_i`, the critical angle) the derivatives are
/// reported as 0 (the one-sided limits are infinite).
pub fn fresnel_conductor_grad(cos_i: f64, eta: f64, k: f64) -> (f64, f64, f64) {
    let c = cos_i.clamp(0.0, 1.0);
    if c == 0.0 {
        return (1.0, 0.0, 0.0);
    }
    let s2 = (1.0 - c * c).max(0.0);
    let n = Complex::new(eta, k);
    let n2 = n * n;
    let z = (n2 - Complex::new(s2, 0.0)).sqrt();
    let rs = (c - z) / (c + z);
    let a = n2 * c;
    let rp = (a - z) / (a + z);
    let f = 0.5 * (rs.norm_sqr() + rp.norm_sqr());
    if z.norm_sqr() == 0.0 {
        return (f, 0.0, 0.0);
    }
    let dz = n / z;
    let drs = -2.0 * c * dz / ((c + z) * (c + z));
    let drp = (4.0 * n * c * z - 2.0 * n2 * c * dz) / ((a + z) * (a + z));
    let g = rs.conj() * drs + rp.conj() * drp;
    (f, g.re, -g.im)
}
