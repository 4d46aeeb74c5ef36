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

/// The principal square root (`Re >= 0`) in closed form: `nalgebra`'s
/// goes through polar form (`atan2`, `hypot`, `sin_cos`), which made up a
/// fifth of a coloured-lobe conductor fit's time. With `r = |w|`,
/// `sqrt(w) = (t, y / 2t)` for `x >= 0` and `(|y| / 2t, sign(y) t)` for
/// `x < 0`, `t = sqrt((r + |x|) / 2)`: each branch divides by the larger
/// part, so neither cancels. `|w|` stays far from overflow here
/// (`|n|^2 <= 125` on the models' boxes).
fn principal_sqrt(w: Complex<f64>) -> Complex<f64> {
    let (x, y) = (w.re, w.im);
    let r = (x * x + y * y).sqrt();
    if r == 0.0 {
        return Complex::new(0.0, 0.0);
    }
    let t = (0.5 * (r + x.abs())).sqrt();
    if x >= 0.0 {
        Complex::new(t, y / (2.0 * t))
    } else {
        Complex::new(y.abs() / (2.0 * t), t.copysign(y))
    }
}

/// `1 / w`. The denominators here (`cos_i + z`, `n^2 cos_i + z`) are not 0
/// for `cos_i > 0`, `eta > 0`: with `k > 0` both have positive imaginary
/// parts (`z` lies in the first quadrant), with `k = 0` positive real
/// parts or, beyond the critical angle, a positive real and imaginary pair.
fn reciprocal(w: Complex<f64>) -> Complex<f64> {
    w.conj() / w.norm_sqr()
}

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
    let z = principal_sqrt(n2 - Complex::new(s2, 0.0));
    // Each denominator inverted once and reused for the ratio and its
    // derivative: complex divisions were most of this function's time.
    let inv_s = reciprocal(c + z);
    let rs = (c - z) * inv_s;
    let a = n2 * c;
    let inv_p = reciprocal(a + z);
    let rp = (a - z) * inv_p;
    let f = 0.5 * (rs.norm_sqr() + rp.norm_sqr());
    let z2 = z.norm_sqr();
    if z2 == 0.0 {
        return (f, 0.0, 0.0);
    }
    let dz = n * z.conj() / z2;
    let drs = -2.0 * c * dz * inv_s * inv_s;
    let drp = (4.0 * n * c * z - 2.0 * n2 * c * dz) * inv_p * inv_p;
    let g = rs.conj() * drs + rp.conj() * drp;
    (f, g.re, -g.im)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The closed form against `nalgebra`'s polar-form root on every
    /// quadrant, the axes and the signed zeros.
    #[test]
    fn principal_sqrt_is_the_library_s() {
        let values = [-125.0, -3.0, -0.5, -1e-9, -0.0, 0.0, 1e-9, 0.5, 3.0, 125.0];
        for &x in &values {
            for &y in &values {
                let w = Complex::new(x, y);
                let (a, b) = (principal_sqrt(w), w.sqrt());
                assert!(a.re >= 0.0, "{w}: {a}");
                assert!(
                    (a - b).norm() <= 4.0 * f64::EPSILON * b.norm(),
                    "{w}: {a} vs {b}"
                );
            }
        }
    }
}
