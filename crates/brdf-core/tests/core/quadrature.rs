//! The adaptive quadrature and the directional albedo against exact values.

use std::f64::consts::PI;

use brdf_core::plausibility::{
    energy_scan, hemisphere_directions, nonnegativity_scan, reciprocity_deviation,
};
use brdf_core::quadrature::{integrate, integrate_around_peak, integrate_with_breaks};
use brdf_core::{AlbedoFrame, Brdf, QuadratureOptions, directional_albedo, spherical_to_cartesian};
use nalgebra::Vector3;

#[test]
fn gauss_kronrod_is_exact_for_polynomials_and_accurate_for_smooth_functions() {
    let opts = QuadratureOptions::default();
    // Kronrod-15 integrates degree <= 22 exactly: int_0^1 x^20 = 1/21.
    let r = integrate(|x, o| o[0] = x.powi(20), 0.0, 1.0, 1, &opts);
    assert!((r.value[0] - 1.0 / 21.0).abs() < 1e-15);
    // int_0^pi sin = 2, with an error estimate that covers the true error.
    let r = integrate(|x, o| o[0] = x.sin(), 0.0, PI, 1, &opts);
    assert!((r.value[0] - 2.0).abs() <= r.error[0].max(1e-15));
    // A kink: int_{-1}^{1.001} |x|. The Kronrod/Gauss comparison is an
    // estimate, valid where the integrand is smooth on each interval; a kink
    // must be a break point (as the albedo puts the horizon and the mirror
    // peak), and then the result is exact to rounding.
    let r = integrate_with_breaks(|x, o| o[0] = x.abs(), &[-1.0, 0.0, 1.001], 1, &opts);
    let exact = 0.5 + 0.5 * 1.001f64 * 1.001;
    assert!(
        (r.value[0] - exact).abs() <= r.error[0] + 1e-15,
        "{} vs {exact}",
        r.value[0]
    );
    assert!((r.value[0] - exact).abs() < 1e-14);
}

/// `f = kd/pi` with two channels.
struct TwoLambert([f64; 2]);
impl Brdf for TwoLambert {
    fn channels(&self) -> usize {
        2
    }
    fn eval(&self, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        let on = l.z > 0.0 && v.z > 0.0;
        for c in 0..2 {
            out[c] = if on { self.0[c] / PI } else { 0.0 };
        }
    }
}

/// A normalised Phong lobe `(n+1)/(2 pi) cos^n(alpha_r)` whose albedo at
/// normal incidence is exactly `1` times the part of the lobe above the
/// horizon, which for `L = N` is all of it: `a(N) = (n+1)/(n+2)`.
/// Derivation: with `L = N`, `R = N`, `alpha_r = theta_o`, and
/// `int_0^{2pi} int_0^1 (n+1)/(2pi) mu^n mu dmu dphi = (n+1)/(n+2)`.
struct PhongLobe(f64);
impl Brdf for PhongLobe {
    fn channels(&self) -> usize {
        1
    }
    fn eval(&self, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        let r = Vector3::new(-l.x, -l.y, l.z);
        let c = r.dot(v).max(0.0);
        out[0] = if l.z > 0.0 && v.z > 0.0 {
            (self.0 + 1.0) / (2.0 * PI) * c.powf(self.0)
        } else {
            0.0
        };
    }
}

#[test]
fn lambert_albedo_is_exactly_kd_at_every_incidence() {
    let m = TwoLambert([0.3, 1.0]);
    for theta in [0.0, 0.5, 1.2, PI / 2.0 - 1e-6] {
        let l = spherical_to_cartesian(theta, 0.7);
        for frame in [AlbedoFrame::Normal, AlbedoFrame::Mirror] {
            let a = directional_albedo(&m, &l, frame, &QuadratureOptions::default());
            for c in 0..2 {
                let err = (a.value[c] - m.0[c]).abs();
                assert!(
                    err <= a.error[c] + 1e-13,
                    "theta {theta} {frame:?}: {err} vs {}",
                    a.error[c]
                );
                assert!(a.error[c] < 1e-6, "error bound too loose: {}", a.error[c]);
            }
        }
    }
}

#[test]
fn sharp_lobe_albedo_in_the_mirror_frame() {
    for n in [1.0, 50.0, 1e4] {
        let a = directional_albedo(
            &PhongLobe(n),
            &Vector3::z(),
            AlbedoFrame::Mirror,
            &QuadratureOptions::default(),
        );
        let exact = (n + 1.0) / (n + 2.0);
        assert!(
            (a.value[0] - exact).abs() <= a.error[0] + 1e-12,
            "n {n}: {} vs {exact}",
            a.value[0]
        );
    }
}

#[test]
fn plausibility_scans_on_known_brdfs() {
    let dirs = hemisphere_directions(6, 8, 1e-6);
    let m = TwoLambert([0.3, 0.9]);
    let r = reciprocity_deviation(&m, &dirs);
    assert_eq!(r.max_abs, 0.0);
    let nn = nonnegativity_scan(&m, &dirs);
    assert_eq!(nn.negative, 0);
    assert!((nn.min_value - 0.3 / PI).abs() < 1e-15);
    let e = energy_scan(
        &m,
        &dirs[..5],
        AlbedoFrame::Normal,
        &QuadratureOptions::default(),
    );
    assert!(e.conserves_energy());
    assert!((e.max_albedo[1] - 0.9).abs() < 1e-9);
    // A non-reciprocal BRDF is caught: f = cos_i.
    struct CosI;
    impl Brdf for CosI {
        fn channels(&self) -> usize {
            1
        }
        fn eval(&self, l: &Vector3<f64>, _v: &Vector3<f64>, out: &mut [f64]) {
            out[0] = l.z.max(0.0);
        }
    }
    let r = reciprocity_deviation(&CosI, &dirs);
    assert!(r.max_abs > 0.5);
}

/// The error estimate bounds the true error for a sharp lobe at oblique
/// incidence, in both frames, at the default and at coarse tolerances.
/// Exact value: around `R` the lobe integrates `cos theta_o = cos alpha
/// cos theta_i + sin alpha cos beta (...)`; the `cos beta` part vanishes over
/// the azimuth, leaving `(n+1)/(n+2) cos theta_i`, as long as the lobe is
/// negligible at the horizon (`cos^n(90 deg - theta_i)` below 1e-15, which
/// the choice of `n` and `theta_i` below ensures).
fn check_sharp_oblique_lobe(frames: &[AlbedoFrame]) {
    let coarse = QuadratureOptions {
        abs_tol: 1e-6,
        rel_tol: 1e-3,
        max_intervals: 20,
    };
    for (n, thetas) in [
        (1e3, &[40.0, 60.0, 75.0][..]),
        (1e4, &[60.0, 85.0][..]),
        (1e6, &[70.0, 88.0][..]),
    ] {
        for &deg in thetas {
            let t = f64::to_radians(deg);
            assert!((90.0 - deg).to_radians().cos().powf(n) < 1e-15);
            let l = Vector3::new(t.sin() * 0.3f64.cos(), t.sin() * 0.3f64.sin(), t.cos());
            let exact = (n + 1.0) / (n + 2.0) * t.cos();
            for &frame in frames {
                for opts in [QuadratureOptions::default(), coarse] {
                    let a = directional_albedo(&PhongLobe(n), &l, frame, &opts);
                    assert!(
                        (a.value[0] - exact).abs() <= a.error[0] + 1e-12,
                        "n {n} at {deg} deg, {frame:?}, {opts:?}: {} vs exact {exact}, estimate {}",
                        a.value[0],
                        a.error[0]
                    );
                }
            }
        }
    }
}

#[test]
fn error_estimate_bounds_the_error_for_a_sharp_oblique_lobe_mirror_frame() {
    check_sharp_oblique_lobe(&[AlbedoFrame::Mirror]);
}

#[test]
fn error_estimate_bounds_the_error_for_a_sharp_oblique_lobe_normal_frame() {
    check_sharp_oblique_lobe(&[AlbedoFrame::Normal]);
}

/// A Gaussian of width `sigma` centred at `c` on `[c - pi, c + pi]`:
/// `int exp(-(x - c)^2 / (2 sigma^2)) dx = sqrt(2 pi) sigma` (the tails
/// beyond `pi` are below `exp(-4e8)`). The peak lies on the middle node of
/// the first pass; bisection would put it on interval ends.
#[test]
fn integrate_around_peak_catches_a_narrow_peak_within_its_estimate() {
    let opts = QuadratureOptions::default();
    for sigma in [1e-1, 1e-3, 1e-5, 1e-6] {
        let c = 0.3;
        let g = |x: f64, o: &mut [f64]| o[0] = (-(x - c).powi(2) / (2.0 * sigma * sigma)).exp();
        let r = integrate_around_peak(g, c, PI, 1, &opts);
        let exact = (2.0 * PI).sqrt() * sigma;
        assert!(
            (r.value[0] - exact).abs() <= r.error[0] + 1e-15,
            "sigma {sigma}: {} vs {exact}, estimate {}",
            r.value[0],
            r.error[0]
        );
        // And it converged: the estimate meets the tolerance.
        assert!(
            r.error[0] <= opts.abs_tol.max(opts.rel_tol * r.value[0].abs()),
            "sigma {sigma}: estimate {}",
            r.error[0]
        );
    }
}
