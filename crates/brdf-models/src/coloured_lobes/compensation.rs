//! MaterialX's GGX energy compensation, so that a coloured-lobe model can be
//! the BRDF MaterialX's `conductor_bsdf`, `generalized_schlick_bsdf` and
//! `dielectric_bsdf` evaluate, and its MaterialX export exact.
//!
//! MaterialX 1.39 multiplies every GGX reflection lobe by
//! `comp = 1 + F (1 - E) / E` (Turquin 2019, "Practical multiple scattering
//! compensation for microfacet models", equations 14 and 16), `F` the lobe's
//! Fresnel at the sample and `E(cos_v, alpha)` the directional albedo of a
//! white lobe (`F = 1`) seen from the viewer, `cos_v = N.V`. Its GLSL takes
//! `E` from a rational fit of Monte-Carlo albedos in `x = cos_v`, `y =
//! alpha` (its default `DIRECTIONAL_ALBEDO_METHOD`, the analytic one): two
//! ratios of quadratics in `x` and `y`, each clamped to `[0, 1]`, summed
//! ([`albedo`]; the coefficients are MaterialX's, as a formula must be to
//! match it). The factor depends on the viewer's direction only, so a
//! compensated lobe is not reciprocal; the model takes its first direction
//! as the viewer's, as renderers and this project's judge evaluate a BRDF
//! (the direction towards the camera first).
//!
//! A lobe of Fresnel `F` becomes `F (1 + F k)` with `k = 1 / E - 1`, so a
//! plain lobe's colour enters squared: in the compensated configurations
//! its `ks` is a non-linear parameter.

/// Coefficients of the numerators (`a`, `b`) and denominators (`c`, `d`) of
/// MaterialX's fit, per monomial `1, x, y, xy, x^2, y^2, x^2 y, x y^2,
/// x^2 y^2`, in the order of its `vec4`s.
const FIT: [[f64; 4]; 9] = [
    [0.1003, 0.9345, 1.0, 1.0],
    [-0.6303, -2.323, -1.765, 0.2281],
    [9.748, 2.229, 8.263, 15.94],
    [-2.038, -3.748, 11.53, -55.83],
    [29.34, 1.424, 28.96, 13.08],
    [-8.245, -0.7684, -7.507, 41.26],
    [-26.44, 1.436, -36.11, 54.9],
    [19.99, 0.2913, 15.86, 300.2],
    [-5.448, 0.6286, 33.37, -285.1],
];

/// Smallest albedo the factor divides by. The fit stays well above it over
/// the model's box (`alpha >= 0.002`, `cos_v > 0`); the floor only keeps a
/// value finite should a direction reach the horizon.
const ALBEDO_MIN: f64 = 1e-4;

/// `(E, dE/d alpha)`: the directional albedo of a white GGX lobe of width
/// `alpha` seen at `cos_v`, by MaterialX's rational fit.
#[inline(always)]
pub fn albedo(cos_v: f64, alpha: f64) -> (f64, f64) {
    let (x, y) = (
        cos_v.clamp(f64::EPSILON, 1.0),
        alpha.clamp(f64::EPSILON, 1.0),
    );
    let mono = [
        1.0,
        x,
        y,
        x * y,
        x * x,
        y * y,
        x * x * y,
        x * y * y,
        x * x * y * y,
    ];
    let dmono = [
        0.0,
        0.0,
        1.0,
        x,
        0.0,
        2.0 * y,
        x * x,
        2.0 * x * y,
        2.0 * x * x * y,
    ];
    let (mut r, mut dr) = ([0.0; 4], [0.0; 4]);
    for ((m, dm), row) in mono.iter().zip(&dmono).zip(&FIT) {
        for j in 0..4 {
            r[j] += row[j] * m;
            dr[j] += row[j] * dm;
        }
    }
    let (mut e, mut de) = (0.0, 0.0);
    for (num, den) in [(0, 2), (1, 3)] {
        let q = r[num] / r[den];
        if (0.0..=1.0).contains(&q) {
            e += q;
            de += (dr[num] * r[den] - r[num] * dr[den]) / (r[den] * r[den]);
        } else {
            // Clamped: the value is an end of [0, 1] and does not move.
            e += q.clamp(0.0, 1.0);
        }
    }
    (e, de)
}

/// `(k, dk/d alpha)` with `k = 1 / E - 1`, so that a lobe of Fresnel `F`
/// is weighted `F (1 + F k)`.
#[inline(always)]
pub fn excess(cos_v: f64, alpha: f64) -> (f64, f64) {
    let (e, de) = albedo(cos_v, alpha);
    if e <= ALBEDO_MIN {
        return (1.0 / ALBEDO_MIN - 1.0, 0.0);
    }
    (1.0 / e - 1.0, -de / (e * e))
}

/// [`excess`] where the model carries the compensation (`on`), `(0, 0)`
/// where it does not: the one switch of the lobes' and the films' kernels.
#[inline(always)]
pub fn excess_if(on: bool, cos_v: f64, alpha: f64) -> (f64, f64) {
    if on { excess(cos_v, alpha) } else { (0.0, 0.0) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derivative_matches_central_differences() {
        for &x in &[0.05, 0.3, 0.7, 1.0] {
            for &a in &[0.01, 0.1, 0.4, 0.9] {
                let h = 1e-6;
                let fd = (albedo(x, a + h).0 - albedo(x, a - h).0) / (2.0 * h);
                let (_, d) = albedo(x, a);
                assert!(
                    (d - fd).abs() < 1e-6 * (1.0 + fd.abs()),
                    "{x} {a}: {d} vs {fd}"
                );
            }
        }
    }

    #[test]
    fn a_narrow_lobe_loses_nothing_and_a_wide_one_does() {
        // A mirror-like lobe reflects all it receives away from grazing.
        let (e, _) = albedo(1.0, 0.002);
        assert!((e - 1.0).abs() < 0.01, "{e}");
        let (e, _) = albedo(0.5, 1.0);
        assert!(e > 0.3 && e < 0.9, "{e}");
        let (k, _) = excess(0.5, 1.0);
        assert!(k > 0.1, "{k}");
    }
}
