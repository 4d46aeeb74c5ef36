//! The Fresnel laws a coloured lobe can carry besides none (`F = 1`): the
//! F82-tint law of Blender's Metallic BSDF, OpenPBR's metal and MaterialX's
//! `generalized_schlick_bsdf` with `color82`, and the exact conductor
//! reflectance (per channel, from [`brdf_core::fresnel_conductor`]).
//!
//! F82 tint (Hoffman 2019; Kutz, Hasan & Edmondson 2021): with `mu = cos
//! theta_d`, Schlick's `S(mu) = F0 + (1 - F0)(1 - mu)^5` and
//! `q(mu) = mu (1 - mu)^6`, `F(mu) = S(mu) - a q(mu)`. The value at the
//! reference cosine `mu_b = 1/7` (about 81.8 deg, where `q` is largest:
//! `q' = (1 - mu)^5 (1 - 7 mu)`) is asked to be `tint` times Schlick's:
//! `S(mu_b) - a q(mu_b) = tint S(mu_b)`, so
//! `a = S(mu_b) (1 - tint) / q(mu_b)`, `q(mu_b) = 6^6 / 7^7`.
//!
//! Derivatives: `dF/dF0 = (1 - (1 - mu)^5) - (1 - (1 - mu_b)^5)(1 - tint) r`
//! and `dF/d tint = S(mu_b) r`, with `r = q(mu) / q(mu_b)` in `[0, 1]`.
//!
//! Range: `F <= S <= 1` for `tint <= 1`. `F` is linear in `F0`, so its
//! minimum over `F0 in [0, 1]` is at an end: at `F0 = 1` it is
//! `1 - (1 - tint) r >= 0`; at `F0 = 0` it is
//! `(1 - mu)^5 (1 - (1 - tint) (49/6) mu (1 - mu))`, whose bracket is least
//! at `mu = 1/2`: `F >= 0` everywhere for every `F0` exactly when
//! `tint >= 25/49` ([`F82_TINT_MIN`], the lower end of the tint box).

/// The F82 law's reference cosine `mu_b = 1/7` (`theta` about 81.8 deg).
pub const F82_COS: f64 = 1.0 / 7.0;

/// The least tint for which the F82 law is non-negative for every `F0` in
/// `[0, 1]` at every angle: `25/49`.
pub const F82_TINT_MIN: f64 = 25.0 / 49.0;

/// `(F, dF/dF0, dF/d tint)` of the F82-tint law at `mu = cos theta_d`.
#[inline]
pub fn f82_tint(f0: f64, tint: f64, mu: f64) -> (f64, f64, f64) {
    let m = 1.0 - mu;
    let m5 = m * m * m * m * m;
    // (1 - mu_b) = 6/7: (6/7)^5 and q(mu_b) = (1/7)(6/7)^6.
    let mb = 1.0 - F82_COS;
    let mb5 = mb * mb * mb * mb * mb;
    let qb = F82_COS * mb5 * mb;
    let r = mu * m5 * m / qb;
    let s = f0 + (1.0 - f0) * m5;
    let sb = f0 + (1.0 - f0) * mb5;
    let f = s - sb * (1.0 - tint) * r;
    let df0 = (1.0 - m5) - (1.0 - mb5) * (1.0 - tint) * r;
    (f, df0, sb * r)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn f82_meets_its_defining_values() {
        for (f0, t) in [(0.0, 0.6), (0.5, 1.0), (0.9, 0.7), (1.0, F82_TINT_MIN)] {
            let schlick = |mu: f64| f0 + (1.0 - f0) * (1.0 - mu).powi(5);
            // Normal incidence: F0; grazing: 1; at mu_b: tint times Schlick.
            assert!((f82_tint(f0, t, 1.0).0 - f0).abs() < 1e-15);
            assert!((f82_tint(f0, t, 0.0).0 - 1.0).abs() < 1e-15);
            let fb = f82_tint(f0, t, F82_COS).0;
            assert!((fb - t * schlick(F82_COS)).abs() < 1e-14, "{fb}");
        }
        // q(mu_b) = 6^6 / 7^7 as stated.
        let qb = F82_COS * (1.0 - F82_COS).powi(6);
        assert!((qb - 46656.0 / 823543.0).abs() < 1e-16);
    }

    #[test]
    fn f82_is_non_negative_exactly_from_its_tint_bound() {
        // At F0 = 0, mu = 1/2 the bound is tight: F = 0 at the bound,
        // negative just below it.
        let (f, _, _) = f82_tint(0.0, F82_TINT_MIN, 0.5);
        assert!(f.abs() < 1e-15, "{f}");
        assert!(f82_tint(0.0, F82_TINT_MIN - 1e-3, 0.5).0 < 0.0);
        for i in 0..=200 {
            let mu = i as f64 / 200.0;
            for f0 in [0.0, 0.3, 1.0] {
                let f = f82_tint(f0, F82_TINT_MIN, mu).0;
                assert!((-1e-15..=1.0 + 1e-15).contains(&f), "{f0} {mu}: {f}");
            }
        }
    }

    #[test]
    fn f82_derivatives_match_finite_differences() {
        let h = 1e-6;
        for mu in [0.05, F82_COS, 0.4, 0.9] {
            for (f0, t) in [(0.2, 0.6), (0.8, 0.95)] {
                let (_, d0, dt) = f82_tint(f0, t, mu);
                let n0 = (f82_tint(f0 + h, t, mu).0 - f82_tint(f0 - h, t, mu).0) / (2.0 * h);
                let nt = (f82_tint(f0, t + h, mu).0 - f82_tint(f0, t - h, mu).0) / (2.0 * h);
                assert!((d0 - n0).abs() < 1e-9, "{mu} dF0 {d0} vs {n0}");
                assert!((dt - nt).abs() < 1e-9, "{mu} dtint {dt} vs {nt}");
            }
        }
    }
}
