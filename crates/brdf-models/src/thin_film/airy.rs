//! The colour of a thin film over a dielectric base at one cosine of
//! incidence, and its derivatives in the film's thickness, the film's index
//! and the base's index.
//!
//! With `mu = cos theta1` in the ambient (index 1), `s2 = 1 - mu^2`,
//! `u = n2 cos theta2 = sqrt(n2^2 - s2)` and `w = n3 cos theta3 =
//! sqrt(n3^2 - s2)` (Snell), the Fresnel amplitudes are real (no index is
//! complex and no total reflection is possible from an ambient of index 1):
//!
//! - s: `r12 = (mu - u) / (mu + u)`, `r23 = (u - w) / (u + w)`;
//! - p: `r12 = (n2^2 mu - u) / (n2^2 mu + u)`,
//!   `r23 = (n3^2 u - n2^2 w) / (n3^2 u + n2^2 w)`,
//!
//! one sign convention for both interfaces, so Stokes' relations
//! (`r21 = -r12`, `t12 t21 = 1 - r12^2`) hold. Summing the film's multiple
//! reflections (Airy) gives, per polarisation, with `c = cos phi`,
//!
//! `R = (a^2 + b^2 + 2 a b c) / (1 + a^2 b^2 + 2 a b c)`, `a = r12`, `b = r23`,
//!
//! the phase `phi = 4 pi u d k` at wavenumber `k = 1 / lambda`. The film
//! reflects `(R_s + R_p) / 2`; its colour is that spectrum weighted by the
//! nodes of [`super::spectral`], clamped to `[0, 1]` as Cycles clamps it.
//! Because the phase is linear in `k` and the nodes are uniform in `k`,
//! `e^{i phi}` advances from node to node by one complex rotation.
//!
//! Derivatives: `dR/da`, `dR/db` and `dR/dphi = -2 a b sin(phi) (M - N) / M^2`
//! (`N`, `M` the numerator and denominator above), with `du/dn2 = n2 / u`,
//! `dw/dn3 = n3 / w` and `dphi/dd = 4 pi u k`, `dphi/dn2 = 4 pi d k n2 / u`.

use std::f64::consts::PI;

use super::spectral::{DK, K0, NODES, WEIGHTS};

/// Which row of [`WEIGHTS`] each channel reads: linear sRGB for three
/// channels, luminance for one.
pub fn weight_rows(channels: usize) -> &'static [usize] {
    if channels == 3 { &[0, 1, 2] } else { &[3] }
}

/// A film's colour in up to three channels at one cosine and its
/// derivatives in (thickness, film index, base index).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FilmColour {
    /// Reflectance per channel, in `[0, 1]`.
    pub value: [f64; 3],
    /// `d value / d (thickness, film index, base index)` per channel (0
    /// where the value is clamped).
    pub grad: [[f64; 3]; 3],
}

/// One interface amplitude and its derivatives in the two indices.
#[derive(Clone, Copy, Debug)]
struct Amp {
    r: f64,
    d_n2: f64,
    d_n3: f64,
}

/// `(a, b)` for s and p at `mu`, with the film's `u`.
fn amplitudes(mu: f64, n2: f64, n3: f64) -> ([Amp; 2], [Amp; 2], f64) {
    let s2 = (1.0 - mu * mu).max(0.0);
    let u = (n2 * n2 - s2).sqrt();
    let w = (n3 * n3 - s2).sqrt();
    let (du, dw) = (n2 / u, n3 / w);
    // (x - y) / (x + y) and its derivatives in x and y.
    let ratio = |x: f64, y: f64| {
        let q = x + y;
        ((x - y) / q, 2.0 * y / (q * q), -2.0 * x / (q * q))
    };
    let (a_s, _, a_s_y) = ratio(mu, u);
    let (b_s, b_s_x, b_s_y) = ratio(u, w);
    let p = n2 * n2 * mu;
    let (a_p, a_p_x, a_p_y) = ratio(p, u);
    let (big_a, big_b) = (n3 * n3 * u, n2 * n2 * w);
    let (b_p, b_p_x, b_p_y) = ratio(big_a, big_b);
    let a = [
        Amp {
            r: a_s,
            d_n2: a_s_y * du,
            d_n3: 0.0,
        },
        Amp {
            r: a_p,
            d_n2: a_p_x * 2.0 * n2 * mu + a_p_y * du,
            d_n3: 0.0,
        },
    ];
    let b = [
        Amp {
            r: b_s,
            d_n2: b_s_x * du,
            d_n3: b_s_y * dw,
        },
        Amp {
            r: b_p,
            d_n2: b_p_x * n3 * n3 * du + b_p_y * 2.0 * n2 * w,
            d_n3: b_p_x * 2.0 * n3 * u + b_p_y * n2 * n2 * dw,
        },
    ];
    (a, b, u)
}

/// The film's colour at `mu` for `channels` (1 or 3) channels, thickness
/// `d` in nm, film index `n2` and base index `n3` (both at least 1).
pub fn film_colour(mu: f64, d: f64, n2: f64, n3: f64, channels: usize) -> FilmColour {
    let mu = mu.clamp(0.0, 1.0);
    let (a, b, u) = amplitudes(mu, n2, n3);
    let rows = weight_rows(channels);
    // Phase per unit wavenumber, and its derivatives.
    let g = 4.0 * PI * u * d;
    let (g_d, g_n2) = (4.0 * PI * u, 4.0 * PI * d * n2 / u);
    let (mut c, mut s) = (g * K0).cos_sin();
    let (step_c, step_s) = (g * DK).cos_sin();
    let mut acc = [[0.0; 4]; 3];
    for j in 0..NODES {
        let k = K0 + DK * j as f64;
        let (mut r, mut r_phi, mut r_n2, mut r_n3) = (0.0, 0.0, 0.0, 0.0);
        for pol in 0..2 {
            let (x, y) = (a[pol], b[pol]);
            let ab = x.r * y.r;
            let num = x.r * x.r + y.r * y.r + 2.0 * ab * c;
            let den = 1.0 + ab * ab + 2.0 * ab * c;
            let inv = 1.0 / den;
            let q = num * inv * inv;
            let d_a =
                (2.0 * x.r + 2.0 * y.r * c) * inv - q * (2.0 * x.r * y.r * y.r + 2.0 * y.r * c);
            let d_b =
                (2.0 * y.r + 2.0 * x.r * c) * inv - q * (2.0 * x.r * x.r * y.r + 2.0 * x.r * c);
            r += 0.5 * num * inv;
            r_phi += 0.5 * (-2.0 * ab * s) * (den - num) * inv * inv;
            r_n2 += 0.5 * (d_a * x.d_n2 + d_b * y.d_n2);
            r_n3 += 0.5 * d_b * y.d_n3;
        }
        let parts = [r, r_phi * g_d * k, r_n2 + r_phi * g_n2 * k, r_n3];
        for (ch, &row) in rows.iter().enumerate() {
            let wt = WEIGHTS[row][j];
            for (slot, part) in acc[ch].iter_mut().zip(parts) {
                *slot += wt * part;
            }
        }
        (c, s) = (c * step_c - s * step_s, s * step_c + c * step_s);
    }
    let mut out = FilmColour::default();
    for (ch, sums) in acc.iter().enumerate().take(rows.len()) {
        let v = sums[0];
        out.value[ch] = v.clamp(0.0, 1.0);
        if (0.0..=1.0).contains(&v) {
            out.grad[ch] = [sums[1], sums[2], sums[3]];
        }
    }
    out
}

/// `(cos, sin)` of an angle.
trait CosSin {
    fn cos_sin(self) -> (f64, f64);
}

impl CosSin for f64 {
    fn cos_sin(self) -> (f64, f64) {
        let (s, c) = self.sin_cos();
        (c, s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// With no film the colour is the base's own unpolarised Fresnel
    /// reflectance in every channel (each weight row sums to 1).
    #[test]
    fn no_film_is_the_base_fresnel() {
        for mu in [1.0, 0.8, 0.5, 0.2, 0.01] {
            let f = film_colour(mu, 0.0, 1.7, 1.5, 3);
            let want = brdf_core::fresnel::fresnel_dielectric(mu, 1.5);
            for v in f.value {
                assert!((v - want).abs() < 1e-12, "mu {mu}: {v} vs {want}");
            }
        }
    }

    /// A film of the base's own index is no film, whatever its thickness.
    #[test]
    fn index_matched_film_vanishes() {
        let f = film_colour(0.6, 333.0, 1.5, 1.5, 1);
        let want = brdf_core::fresnel::fresnel_dielectric(0.6, 1.5);
        assert!((f.value[0] - want).abs() < 1e-12);
    }

    /// The derivatives against central differences.
    #[test]
    fn derivatives_match_differences() {
        let (mu, d, n2, n3) = (0.73, 260.0, 1.8, 1.4);
        let f = film_colour(mu, d, n2, n3, 3);
        let steps = [1e-4, 1e-7, 1e-7];
        for (i, h) in steps.iter().enumerate() {
            let mut p = [d, n2, n3];
            p[i] += h;
            let hi = film_colour(mu, p[0], p[1], p[2], 3);
            p[i] -= 2.0 * h;
            let lo = film_colour(mu, p[0], p[1], p[2], 3);
            for ch in 0..3 {
                let fd = (hi.value[ch] - lo.value[ch]) / (2.0 * h);
                let an = f.grad[ch][i];
                assert!(
                    (fd - an).abs() < 1e-6 * (1.0 + an.abs()),
                    "param {i} ch {ch}: {fd} vs {an}"
                );
            }
        }
    }
}
