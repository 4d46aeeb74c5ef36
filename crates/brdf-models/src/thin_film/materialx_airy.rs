//! A thin film's colour as MaterialX 1.39 computes it for a
//! `dielectric_bsdf` with `thinfilm_thickness` and `thinfilm_ior` (its
//! GLSL `mx_fresnel_airy`, after Belcour & Barla 2017), so that the
//! `film*-materialx` models are the BRDF MaterialX renders.
//!
//! Where [`super::airy`] integrates Airy's reflectance over the spectrum,
//! MaterialX sums the series in the Fourier domain: per polarisation the
//! DC term `R12 + T12^2 R23 / (1 - R12 R23)` plus two orders `m = 1, 2` of
//! `2 C_m S(m opd, m phase)`, with `C_m = (R - T12) r123^m`, `r123 =
//! sqrt(R12 R23)`, the optical path difference `opd = 2 n2 cos theta2 d`
//! and `S` the Fourier transform of the CIE 1931 matching functions as
//! MaterialX fits them (one Gaussian per function, two for `x`, normalised
//! by 1.0685e-7). The interface reflectances are the dielectric's per
//! polarisation (ambient index 1 to the film, the film to the base as a
//! conductor of zero extinction), the phase shifts Belcour & Barla's (`pi`
//! at the first interface beyond Brewster's angle for p, and the base's
//! conductor phase). The XYZ result goes to RGB by MaterialX's XYZ to CIE
//! RGB matrix (equal-energy white) and is clamped to `[0, 1]`; one channel
//! reads `Y`. A film of zero thickness switches MaterialX to the plain
//! dielectric Fresnel of the base, as here.
//!
//! Derivatives in thickness and indices are central differences of the
//! unclamped closed form (steps of 1e-4 nm and 1e-7 in index; the tests
//! compare them with wider steps), zero where the value is clamped.

use std::f64::consts::PI;

use brdf_core::fresnel::fresnel_dielectric;

use super::airy::FilmColour;

/// MaterialX's `XYZ_TO_RGB`, row by row (its GLSL lists the columns).
const XYZ_TO_RGB: [[f64; 3]; 3] = [
    [2.3706743, -0.9000405, -0.4706338],
    [-0.5138850, 1.4253036, 0.0885814],
    [0.0052982, -0.0146949, 1.0093968],
];

/// Orders of the series MaterialX sums (`hwAiryFresnelIterations`, 2 by
/// default).
const ORDERS: usize = 2;

/// `(Rp, Rs)` of a dielectric interface of relative index `eta` at `cos`.
fn dielectric_polarised(cos: f64, eta: f64) -> (f64, f64) {
    let c2 = cos.clamp(0.0, 1.0).powi(2);
    let s2 = 1.0 - c2;
    let t0 = (eta * eta - s2).max(0.0);
    let t1 = t0 + c2;
    let t2 = 2.0 * t0.sqrt() * cos;
    let rs = (t1 - t2) / (t1 + t2);
    let t3 = c2 * t0 + s2 * s2;
    let t4 = t2 * s2;
    (rs * (t3 - t4) / (t3 + t4), rs)
}

/// MaterialX's fitted spectral sensitivity (XYZ) at optical path
/// difference `opd` (metres) with phase shift `shift`.
fn sensitivity(opd: f64, shift: f64) -> [f64; 3] {
    const VAL: [f64; 3] = [5.4856e-13, 4.4201e-13, 5.2481e-13];
    const POS: [f64; 3] = [1.6810e+06, 1.7953e+06, 2.2084e+06];
    const VAR: [f64; 3] = [4.3278e+09, 9.3046e+09, 6.6121e+09];
    let phase = 2.0 * PI * opd;
    let gauss = |val: f64, pos: f64, var: f64| {
        val * (2.0 * PI * var).sqrt() * (pos * phase + shift).cos() * (-var * phase * phase).exp()
    };
    let mut xyz = [0.0; 3];
    for k in 0..3 {
        xyz[k] = gauss(VAL[k], POS[k], VAR[k]);
    }
    xyz[0] += gauss(9.7470e-14, 2.2399e+06, 4.5282e+09);
    xyz.map(|v| v / 1.0685e-7)
}

/// The film's reflectance in XYZ, unclamped: MaterialX's series for a film
/// of thickness `d` nm and index `n2` over a base of index `n3` at `cos`.
fn airy_xyz(cos: f64, d: f64, n2: f64, n3: f64) -> [f64; 3] {
    let eta2 = n2.max(1.0);
    let cos_t = (1.0 - (1.0 - cos * cos) / (eta2 * eta2)).sqrt();
    let r12 = dielectric_polarised(cos, eta2);
    // The base as a conductor of zero extinction seen from the film.
    let r23 = dielectric_polarised(cos_t, n3 / eta2);
    // Phase shifts: at the first interface pi for s, and for p beyond
    // Brewster's angle; at the base MaterialX's conductor phase, which for
    // zero extinction is 0 or pi.
    let cos_b = eta2.atan().cos();
    let phi21 = (if cos < cos_b { 0.0 } else { PI }, PI);
    let s2 = 1.0 - cos_t * cos_t;
    let a = n3 * n3 - eta2 * eta2 * s2;
    let (u, v) = (((a + a.abs()) / 2.0).sqrt(), ((a.abs() - a) / 2.0).sqrt());
    let phi23s = (2.0 * eta2 * v * cos_t).atan2(u * u + v * v - (eta2 * cos_t).powi(2));
    let phi23p = (-2.0 * eta2 * n3 * n3 * cos_t * v)
        .atan2((n3 * n3 * cos_t).powi(2) - eta2 * eta2 * (u * u + v * v));
    let opd = 2.0 * eta2 * cos_t * d * 1e-9;
    let mut xyz = [0.0; 3];
    for (r12, r23, phi23, phi21) in [
        (r12.0, r23.0, phi23p, phi21.0),
        (r12.1, r23.1, phi23s, phi21.1),
    ] {
        let t121 = 1.0 - r12;
        let r123 = (r12 * r23).sqrt().max(0.0);
        let dc = t121 * t121 * r23 / (1.0 - r12 * r23);
        let mut cm = dc - t121;
        let mut sum = [r12 + dc; 3];
        for m in 1..=ORDERS {
            let m = m as f64;
            cm *= r123;
            let s = sensitivity(m * opd, m * (phi23 + phi21));
            for k in 0..3 {
                sum[k] += cm * 2.0 * s[k];
            }
        }
        for k in 0..3 {
            xyz[k] += 0.5 * sum[k];
        }
    }
    xyz
}

/// The unclamped colour in `channels` channels (RGB, or `Y` for one).
fn unclamped(cos: f64, d: f64, n2: f64, n3: f64, channels: usize) -> [f64; 3] {
    if d <= 0.0 {
        return [fresnel_dielectric(cos, n3); 3];
    }
    let xyz = airy_xyz(cos, d, n2, n3);
    if channels == 1 {
        return [xyz[1], 0.0, 0.0];
    }
    XYZ_TO_RGB.map(|row| row[0] * xyz[0] + row[1] * xyz[1] + row[2] * xyz[2])
}

/// The film's colour at `mu = cos theta_d` and its derivatives in
/// (thickness, film index, base index), as MaterialX renders it.
pub fn film_colour(mu: f64, d: f64, n2: f64, n3: f64, channels: usize) -> FilmColour {
    let mu = mu.clamp(0.0, 1.0);
    let v = unclamped(mu, d, n2, n3, channels);
    let mut out = FilmColour::default();
    // Central differences; at d = 0 (MaterialX's switch) one-sided upward.
    let steps = [1e-4, 1e-7, 1e-7];
    let mut grads = [[0.0; 3]; 3];
    for (k, h) in steps.iter().enumerate() {
        let mut up = [d, n2, n3];
        let mut down = up;
        up[k] += h;
        down[k] -= h;
        let (hi, lo, span) = if k == 0 && d <= *h {
            (
                unclamped(mu, d + h, n2, n3, channels),
                unclamped(mu, d.max(f64::MIN_POSITIVE), n2, n3, channels),
                *h,
            )
        } else {
            (
                unclamped(mu, up[0], up[1], up[2], channels),
                unclamped(mu, down[0], down[1], down[2], channels),
                2.0 * h,
            )
        };
        for c in 0..channels {
            grads[c][k] = (hi[c] - lo[c]) / span;
        }
    }
    for c in 0..channels {
        out.value[c] = v[c].clamp(0.0, 1.0);
        if (0.0..=1.0).contains(&v[c]) {
            out.grad[c] = grads[c];
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_film_is_the_base_fresnel_and_a_thin_one_is_near_it() {
        let f = film_colour(0.7, 0.0, 1.6, 1.5, 3);
        let want = fresnel_dielectric(0.7, 1.5);
        assert!(f.value.iter().all(|&x| (x - want).abs() < 1e-15), "{f:?}");
        // An index-matched film changes nothing but the series' truncation
        // and the fitted sensitivities: within a few thousandths.
        let g = film_colour(0.7, 300.0, 1.5, 1.5, 3);
        assert!(g.value.iter().all(|&x| (x - want).abs() < 5e-3), "{g:?}");
    }

    #[test]
    fn derivatives_match_wider_differences() {
        for &(mu, d, n2, n3) in &[(0.9, 200.0, 1.7, 1.4), (0.4, 450.0, 2.1, 1.6)] {
            let f = film_colour(mu, d, n2, n3, 3);
            for k in 0..3 {
                let h = [1e-2, 1e-5, 1e-5][k];
                let mut up = [d, n2, n3];
                let mut down = up;
                up[k] += h;
                down[k] -= h;
                let a = unclamped(mu, up[0], up[1], up[2], 3);
                let b = unclamped(mu, down[0], down[1], down[2], 3);
                for c in 0..3 {
                    let fd = (a[c] - b[c]) / (2.0 * h);
                    assert!(
                        (f.grad[c][k] - fd).abs() < 1e-5 * (1.0 + fd.abs()),
                        "{k} {c}: {} vs {fd}",
                        f.grad[c][k]
                    );
                }
            }
        }
    }

    /// A thicker film of the same index, and so a longer path, turns the
    /// hue: MaterialX's series, like Airy's, is not one colour.
    #[test]
    fn colour_turns_with_thickness() {
        let a = film_colour(1.0, 200.0, 1.7, 1.4, 3).value;
        let b = film_colour(1.0, 300.0, 1.7, 1.4, 3).value;
        let hue = |c: [f64; 3]| (c[0] - c[2]) / (c[0] + c[1] + c[2]);
        assert!((hue(a) - hue(b)).abs() > 0.05, "{a:?} {b:?}");
    }
}
