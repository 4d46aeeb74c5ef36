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
    let c = cos_i.clamp(0.0, 1.0);
    if c == 0.0 {
        return 1.0;
    }
    // w = n^2 - sin^2 = x + i y; z = sqrt(w) = (zr, zi) with |z|^2 = |w|,
    // from the same branch-wise root as `principal_sqrt`, in real numbers.
    let n2r = eta * eta - k * k;
    let y = 2.0 * eta * k;
    let x = n2r - (1.0 - c * c).max(0.0);
    let r = (x * x + y * y).sqrt();
    if r == 0.0 {
        return 1.0;
    }
    let t = (0.5 * (r + x.abs())).sqrt();
    let (zr, zi) = if x >= 0.0 {
        (t, y / (2.0 * t))
    } else {
        (y.abs() / (2.0 * t), t.copysign(y))
    };
    // |c - z|^2 / |c + z|^2 and |A - z|^2 / |A + z|^2 with A = n^2 c:
    // |u -+ z|^2 = |u|^2 -+ 2 Re(u conj(z)) + |z|^2, both ratios over one
    // division (this runs once per sample and channel at every trial point
    // of a conductor fit, where the derivatives are not needed).
    let c2 = c * c;
    let (ps, qs) = (c2 + r, 2.0 * c * zr);
    let (pp, qp) = (c2 * (n2r * n2r + y * y) + r, 2.0 * c * (n2r * zr + y * zi));
    let (ns, ds, np, dp) = (ps - qs, ps + qs, pp - qp, pp + qp);
    0.5 * (ns * dp + np * ds) / (ds * dp)
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
    // The value of the values-only path, to the bit: a solver compares
    // costs from both paths.
    let f = fresnel_conductor(c, eta, k);
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

    /// The value in real numbers against the amplitude ratios in complex
    /// numbers (`nalgebra`'s root), over metals, dielectrics beyond and
    /// below the critical angle, and grazing to normal incidence.
    #[test]
    fn value_in_real_numbers_is_the_complex_form_s() {
        for &(eta, k) in &[
            (0.2, 3.0),
            (1.5, 0.0),
            (0.6, 0.0),
            (0.01, 10.0),
            (5.0, 10.0),
            (2.5, 0.3),
            (0.9, 1e-9),
        ] {
            for i in 0..=100 {
                let c = i as f64 / 100.0;
                let n2 = Complex::new(eta, k) * Complex::new(eta, k);
                let z = (n2 - Complex::new(1.0 - c * c, 0.0)).sqrt();
                let (rs, rp) = ((c - z) / (c + z), (n2 * c - z) / (n2 * c + z));
                let b = if c == 0.0 {
                    1.0
                } else {
                    0.5 * (rs.norm_sqr() + rp.norm_sqr())
                };
                let a = fresnel_conductor(c, eta, k);
                assert_eq!(a, fresnel_conductor_grad(c, eta, k).0);
                assert!(
                    (a - b).abs() <= 1e-13 * b.abs().max(1e-3),
                    "cos {c}, eta {eta}, k {k}: {a} vs {b}"
                );
            }
        }
    }

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
