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
//! In real numbers (what is computed): with `w = n^2 - sin^2 = x + i y`,
//! `z = (z_r, z_i)`, `|z|^2 = |w| = r` and `A = n^2 cos_i`,
//! `|u -+ z|^2 = |u|^2 -+ 2 Re(u conj(z)) + r`, so each `|r|^2` is a
//! quotient of two real numbers `N / D`.
//!
//! Derivatives: `r_s`, `r_p` are holomorphic in `n`, so with `r' = dr/dn`,
//! `d|r|^2/d eta = 2 Re(conj(r) r')` and `d|r|^2/dk = -2 Im(conj(r) r')`.
//! With `z' = n / z` and `c^2 - z^2 = 1 - n^2`,
//! `conj(r_s) r_s' = -2 c n conj(z) conj(1 - n^2) / (r D_s^2)`; with
//! `A' z - A z' = c n (n^2 - 2 sin^2) / z`,
//! `conj(r_p) r_p' = 2 c n (n^2 - 2 sin^2) conj(A^2 - z^2) conj(z) / (r D_p^2)`
//! (multiply each by `conj(u + z) / conj(u + z)`): no complex division,
//! and the value and both derivatives share two square roots and two
//! real divisions.

use nalgebra::Complex;

/// What the value and the derivatives of one `(cos_i, eta, k)` share.
struct Parts {
    c: f64,
    s2: f64,
    n: Complex<f64>,
    n2: Complex<f64>,
    /// `z` and `r = |z|^2`.
    z: Complex<f64>,
    r: f64,
    /// Numerators and denominators of `|r_s|^2` and `|r_p|^2`.
    ns: f64,
    ds: f64,
    np: f64,
    dp: f64,
    /// `1 / (D_s D_p)`.
    inv: f64,
}

impl Parts {
    /// `None` where `F = 1` and both derivatives are reported 0: grazing
    /// incidence (`cos_i = 0`) and `z = 0` (`k = 0` and `eta = sin theta_i`,
    /// the critical angle, where the one-sided limits are infinite).
    #[inline]
    fn new(cos_i: f64, eta: f64, k: f64) -> Option<Self> {
        let c = cos_i.clamp(0.0, 1.0);
        if c == 0.0 {
            return None;
        }
        let s2 = (1.0 - c * c).max(0.0);
        let n = Complex::new(eta, k);
        let n2 = n * n;
        let (x, y) = (n2.re - s2, n2.im);
        let r = (x * x + y * y).sqrt();
        if r == 0.0 {
            return None;
        }
        // The principal root (`Re z >= 0`), each branch dividing by the
        // larger part so that neither cancels: with `t = sqrt((r + |x|) / 2)`,
        // `z = (t, y / 2t)` for `x >= 0`, `(|y| / 2t, sign(y) t)` otherwise.
        // `|w|` stays far from overflow here (`|n|^2 <= 125` on the models'
        // boxes).
        let t = (0.5 * (r + x.abs())).sqrt();
        let z = if x >= 0.0 {
            Complex::new(t, y / (2.0 * t))
        } else {
            Complex::new(y.abs() / (2.0 * t), t.copysign(y))
        };
        let c2 = c * c;
        let (ps, qs) = (c2 + r, 2.0 * c * z.re);
        let (pp, qp) = (
            c2 * n2.norm_sqr() + r,
            2.0 * c * (n2.re * z.re + n2.im * z.im),
        );
        let (ds, dp) = (ps + qs, pp + qp);
        Some(Parts {
            c,
            s2,
            n,
            n2,
            z,
            r,
            ns: ps - qs,
            ds,
            np: pp - qp,
            dp,
            inv: 1.0 / (ds * dp),
        })
    }

    #[inline]
    fn value(&self) -> f64 {
        0.5 * (self.ns * self.dp + self.np * self.ds) * self.inv
    }
}

/// `F(cos_i; eta, k)`, `cos_i` clamped to `[0, 1]`.
///
/// ```
/// use brdf_core::fresnel_conductor::fresnel_conductor;
/// // Normal incidence: ((eta - 1)^2 + k^2) / ((eta + 1)^2 + k^2).
/// let f = fresnel_conductor(1.0, 0.2, 3.0);
/// assert!((f - (0.64 + 9.0) / (1.44 + 9.0)).abs() < 1e-14);
/// ```
#[inline]
pub fn fresnel_conductor(cos_i: f64, eta: f64, k: f64) -> f64 {
    Parts::new(cos_i, eta, k).map_or(1.0, |p| p.value())
}

/// `(F, dF/d eta, dF/dk)` of [`fresnel_conductor`] (the value the same to
/// the bit: a solver compares costs from both). At grazing incidence
/// (`cos_i = 0`) `F = 1` and both derivatives are 0; where `z = 0` (`k = 0`
/// and `eta = sin theta_i`, the critical angle) the derivatives are
/// reported as 0 (the one-sided limits are infinite).
#[inline]
pub fn fresnel_conductor_grad(cos_i: f64, eta: f64, k: f64) -> (f64, f64, f64) {
    let Some(p) = Parts::new(cos_i, eta, k) else {
        return (1.0, 0.0, 0.0);
    };
    let one = Complex::new(1.0, 0.0);
    let s2 = Complex::new(p.s2, 0.0);
    // 1 / (r D_s^2) and 1 / (r D_p^2) from the shared 1 / (D_s D_p).
    let q = p.inv * p.inv / p.r;
    let (ws, wp) = (p.dp * p.dp * q, p.ds * p.ds * q);
    let cnz = p.c * p.n * p.z.conj();
    let gs = -2.0 * ws * cnz * (one - p.n2).conj();
    let a = p.n2 * p.c;
    let gp = 2.0 * wp * cnz * (p.n2 - 2.0 * s2) * (a * a - p.n2 + s2).conj();
    let g = gs + gp;
    (p.value(), g.re, -g.im)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `F` and `conj(r) dr/dn` summed over both polarisations, in complex
    /// numbers with `nalgebra`'s root and divisions: the textbook form the
    /// real-number one rewrites.
    fn complex_reference(c: f64, eta: f64, k: f64) -> (f64, f64, f64) {
        let n = Complex::new(eta, k);
        let n2 = n * n;
        let z = (n2 - Complex::new(1.0 - c * c, 0.0)).sqrt();
        let (rs, rp) = ((c - z) / (c + z), (n2 * c - z) / (n2 * c + z));
        let dz = n / z;
        let drs = -2.0 * c * dz / ((c + z) * (c + z));
        let drp = (4.0 * n * c * z - 2.0 * n2 * c * dz) / ((n2 * c + z) * (n2 * c + z));
        let g = rs.conj() * drs + rp.conj() * drp;
        (0.5 * (rs.norm_sqr() + rp.norm_sqr()), g.re, -g.im)
    }

    /// The real-number value and derivatives against the complex form,
    /// over metals, dielectrics beyond and below the critical angle, and
    /// near-grazing to normal incidence; the value of both paths the same
    /// to the bit.
    #[test]
    fn real_numbers_give_the_complex_form_s_values_and_derivatives() {
        for &(eta, k) in &[
            (0.2, 3.0),
            (1.5, 0.0),
            (0.6, 0.0),
            (0.01, 10.0),
            (5.0, 10.0),
            (2.5, 0.3),
            (0.9, 1e-9),
        ] {
            for i in 1..=100 {
                let c = i as f64 / 100.0;
                let (f, de, dk) = fresnel_conductor_grad(c, eta, k);
                assert_eq!(f, fresnel_conductor(c, eta, k));
                let (rf, rde, rdk) = complex_reference(c, eta, k);
                let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs().max(1e-2);
                assert!(close(f, rf), "cos {c}, eta {eta}, k {k}: F {f} vs {rf}");
                assert!(
                    close(de, rde),
                    "cos {c}, eta {eta}, k {k}: dF/deta {de} vs {rde}"
                );
                assert!(
                    close(dk, rdk),
                    "cos {c}, eta {eta}, k {k}: dF/dk {dk} vs {rdk}"
                );
            }
        }
        assert_eq!(fresnel_conductor_grad(0.0, 0.2, 3.0), (1.0, 0.0, 0.0));
    }
}
