//! Energy conservation on each model's documented plausible domain:
//! directional albedo plus its quadrature error estimate at most 1, over
//! incident angles from the pole to near grazing; and a point just outside
//! the domain where the albedo exceeds 1, so the domain is not arbitrary.

use brdf_core::{AlbedoFrame, Brdf, QuadratureOptions, directional_albedo, spherical_to_cartesian};
use brdf_models::{BlinnPhong, Phong};

fn max_albedo(m: &dyn Brdf, frame: AlbedoFrame) -> (f64, f64) {
    let opts = QuadratureOptions {
        rel_tol: 1e-7,
        abs_tol: 1e-9,
        max_intervals: 400,
    };
    let mut worst = (f64::NEG_INFINITY, 0.0);
    for deg in [0.0f64, 20.0, 45.0, 70.0, 85.0, 89.9] {
        let l = spherical_to_cartesian(deg.to_radians(), 0.3);
        let a = directional_albedo(m, &l, frame, &opts);
        if a.value[0] > worst.0 {
            worst = (a.value[0], a.error[0]);
        }
    }
    worst
}

#[test]
fn phong_conserves_energy_for_kd_plus_ks_at_most_one() {
    for n in [0.0, 1.0, 10.0, 100.0, 1e4] {
        // kd + ks = 0.9999: the lobe's albedo reaches exactly 1 at normal
        // incidence, so at kd + ks = 1 the quadrature can only show equality
        // (checked below), not a strict bound.
        for (kd, ks) in [(0.0, 0.9999), (0.5, 0.4999), (0.9999, 0.0)] {
            let m = Phong::new(&[kd], &[ks], &[n]).unwrap();
            let (a, e) = max_albedo(&m, AlbedoFrame::Mirror);
            assert!(a + e <= 1.0 + 1e-12, "n {n} kd {kd} ks {ks}: {a} + {e}");
        }
    }
    // The bound is tight: at normal incidence the lobe's albedo is 1 to
    // within the quadrature error, so kd + ks slightly above 1 exceeds 1.
    for n in [0.0, 10.0, 1e4] {
        let m = Phong::new(&[0.0], &[1.0], &[n]).unwrap();
        let a = directional_albedo(
            &m,
            &nalgebra::Vector3::z(),
            AlbedoFrame::Mirror,
            &QuadratureOptions::default(),
        );
        assert!(
            (a.value[0] - 1.0).abs() <= a.error[0] + 1e-12,
            "n {n}: {:?}",
            a
        );
    }
    let m = Phong::new(&[0.02], &[1.0], &[50.0]).unwrap();
    let (a, e) = max_albedo(&m, AlbedoFrame::Mirror);
    assert!(a - e > 1.0, "{a} {e}");
}

#[test]
fn blinn_phong_conserves_energy_for_kd_plus_4ks_at_most_one() {
    // Documented domain: kd + 4 ks <= 1 (the half-vector lobe's albedo tends
    // to 4 ks as n grows; see the model's doc).
    for n in [0.0, 1.0, 10.0, 100.0, 1e4] {
        for (kd, ks) in [(0.0, 0.25), (0.6, 0.1), (1.0, 0.0)] {
            let m = BlinnPhong::new(&[kd], &[ks], &[n]).unwrap();
            let (a, e) = max_albedo(&m, AlbedoFrame::Normal);
            assert!(a + e <= 1.0 + 1e-12, "n {n} kd {kd} ks {ks}: {a} + {e}");
        }
    }
    // Outside it: ks = 0.3 with a sharp lobe exceeds 1 at normal incidence.
    let m = BlinnPhong::new(&[0.0], &[0.3], &[1e4]).unwrap();
    let (a, e) = max_albedo(&m, AlbedoFrame::Normal);
    assert!(a - e > 1.0, "{a} {e}");
}

/// Azimuths of incidence to check: two for an anisotropic model (they
/// differ there), one for an isotropic model (its albedo does not depend on
/// the azimuth: the second would repeat the first at the same cost).
fn azimuths(name: &str) -> &'static [f64] {
    if name.contains("aniso") {
        &[0.3, 1.2]
    } else {
        &[0.3]
    }
}

/// Worst albedo (value + its error) over incident angles up to `max_deg`
/// (the pole, 45 deg, the domain's limit and, for a full domain, 89.9 deg)
/// at the given azimuths.
fn worst(m: &dyn Brdf, frame: AlbedoFrame, max_deg: f64, phis: &[f64]) -> (f64, f64) {
    let opts = QuadratureOptions {
        rel_tol: 1e-6,
        abs_tol: 1e-9,
        max_intervals: 300,
    };
    let mut w = (f64::NEG_INFINITY, 0.0);
    let limit = if max_deg >= 90.0 { 89.9 } else { max_deg };
    for deg in [0.0f64, 45.0, 0.5 * (45.0 + limit), limit] {
        for &phi in phis {
            let l = spherical_to_cartesian(deg.to_radians(), phi);
            let a = directional_albedo(m, &l, frame, &opts);
            for c in 0..a.value.len() {
                if a.value[c] + a.error[c] > w.0 + w.1 {
                    w = (a.value[c], a.error[c]);
                }
            }
        }
    }
    w
}

fn model(name: &str, lobes: usize, p: &[f64]) -> Box<dyn brdf_core::Parametric> {
    let mut m = brdf_models::build(
        name,
        &brdf_models::ModelConfig {
            lobes,
            ..brdf_models::ModelConfig::default()
        },
    )
    .unwrap();
    m.set_params(p).unwrap();
    m
}

fn assert_within(name: &str, p: &[f64], lobes: usize, frame: AlbedoFrame, max_deg: f64) {
    let m = model(name, lobes, p);
    let (a, e) = worst(m.as_ref(), frame, max_deg, azimuths(name));
    assert!(
        a + e <= 1.0 + 1e-9,
        "{name} {p:?} up to {max_deg} deg: albedo {a} + {e}"
    );
}

fn assert_exceeds(name: &str, p: &[f64], lobes: usize, frame: AlbedoFrame, max_deg: f64) {
    let m = model(name, lobes, p);
    let (a, e) = worst(m.as_ref(), frame, max_deg, azimuths(name));
    assert!(
        a - e > 1.0,
        "{name} {p:?}: albedo {a} - {e} should exceed 1"
    );
}

/// Ward: `kd + ks <= 1` for incidence up to 85 deg (the `sqrt(cos_i cos_o)`
/// denominator lets a rough lobe's albedo grow without bound at grazing).
#[test]
fn ward_domain() {
    for a in [1e-3, 0.1, 0.5] {
        assert_within("ward", &[0.0, 1.0, a], 1, AlbedoFrame::Mirror, 85.0);
        assert_within(
            "ward-aniso",
            &[0.5, 0.5, a, 0.5 - 0.4 * a],
            1,
            AlbedoFrame::Mirror,
            85.0,
        );
    }
    assert_exceeds("ward", &[0.0, 1.0, 0.5], 1, AlbedoFrame::Mirror, 90.0);
}

/// Ward-Duer: `kd + ks <= 1` for incidence up to 70 deg (anisotropic lobes
/// exceed 1 at 80 deg).
#[test]
fn ward_duer_domain() {
    for a in [1e-3, 0.05, 0.5] {
        assert_within("ward-duer", &[0.0, 1.0, a], 1, AlbedoFrame::Mirror, 70.0);
        assert_within(
            "ward-duer-aniso",
            &[0.2, 0.8, a, 0.5 - 0.45 * a / 0.5],
            1,
            AlbedoFrame::Mirror,
            70.0,
        );
    }
    assert_exceeds(
        "ward-duer-aniso",
        &[0.2, 0.8, 0.05, 0.48],
        1,
        AlbedoFrame::Mirror,
        80.0,
    );
}

/// Ashikhmin-Shirley (both diffuse forms) and the paint shader:
/// `kd + ks <= 1` at every incidence.
#[test]
fn ashikhmin_shirley_domain() {
    for n in [0.0, 10.0, 1e4] {
        assert_within(
            "ashikhmin-shirley",
            &[0.0, 1.0, n, 0.999],
            1,
            AlbedoFrame::Mirror,
            90.0,
        );
        assert_within(
            "ashikhmin-shirley-coupled",
            &[0.5, 0.5, n, 0.5],
            1,
            AlbedoFrame::Mirror,
            90.0,
        );
        assert_within(
            "ashikhmin-shirley-coupled",
            &[1.0, 0.0, n, 0.0],
            1,
            AlbedoFrame::Mirror,
            90.0,
        );
        assert_within(
            "ashikhmin-shirley-aniso",
            &[0.3, 0.7, n, 10.0, 0.999],
            1,
            AlbedoFrame::Mirror,
            90.0,
        );
        assert_within("as-paint", &[0.3, 0.7, n], 1, AlbedoFrame::Mirror, 90.0);
    }
    assert_exceeds(
        "ashikhmin-shirley",
        &[0.5, 1.0, 1e4, 0.999],
        1,
        AlbedoFrame::Mirror,
        30.0,
    );
}

/// Torrance-Sparrow and Cook-Torrance: the lobe's albedo approaches 4 ks F0
/// for sharp lobes (the 1/(N.L N.V) with G and the normalisation of D), so
/// the domain is `kd + 4 ks <= 1` (all lobes summed).
#[test]
fn torrance_sparrow_and_cook_torrance_domain() {
    for m in [1e-3, 0.2, 0.999] {
        assert_within(
            "torrance-sparrow",
            &[0.0, 0.25, m, 0.999],
            1,
            AlbedoFrame::Mirror,
            90.0,
        );
        assert_within(
            "cook-torrance",
            &[0.2, 0.2, m, 0.999],
            1,
            AlbedoFrame::Mirror,
            90.0,
        );
        assert_within(
            "cook-torrance",
            &[0.0, 0.125, m, 0.999, 0.125, 0.5, 0.999],
            2,
            AlbedoFrame::Mirror,
            90.0,
        );
    }
    assert_exceeds(
        "torrance-sparrow",
        &[0.0, 0.3, 0.05, 0.999],
        1,
        AlbedoFrame::Mirror,
        30.0,
    );
    assert_exceeds(
        "cook-torrance",
        &[0.0, 0.3, 0.05, 0.999],
        1,
        AlbedoFrame::Mirror,
        30.0,
    );
}

/// Lafortune: with the `max|C|^n` normalisation each lobe is bounded by a
/// Phong lobe, so `kd + sum ks <= 1` at every incidence, for any axis
/// weights and exponents. As for Phong the bound is reached at normal
/// incidence, so the sum is taken as 0.9999 where the quadrature would
/// otherwise only show equality.
#[test]
fn lafortune_domain() {
    for n in [0.0, 10.0, 1e3] {
        for (cxy, cz) in [(-1.0, 1.0), (-0.5, 1.0), (0.3, -0.2)] {
            assert_within(
                "lafortune",
                &[0.0, 0.9999, cxy, cz, n],
                1,
                AlbedoFrame::Normal,
                90.0,
            );
        }
        assert_within(
            "lafortune",
            &[0.2, 0.4, -1.0, 0.5, n, 0.3999, -1.0, 1.0, 5.0],
            2,
            AlbedoFrame::Normal,
            90.0,
        );
        assert_within(
            "lafortune-aniso",
            &[0.1, 0.8999, -1.0, -0.5, 0.8, n],
            1,
            AlbedoFrame::Normal,
            90.0,
        );
    }
    assert_exceeds(
        "lafortune",
        &[0.3, 1.0, -1.0, 1.0, 50.0],
        1,
        AlbedoFrame::Mirror,
        30.0,
    );
}

/// Oren-Nayar: at `kd = 1` both forms exceed 1 near grazing incidence (the
/// `tan(beta)` term; the full form also by its `kd^2` interreflection), so
/// the domain of both is `kd <= 0.95`.
#[test]
fn oren_nayar_domain() {
    for sigma in [0.0, 0.2, 0.5, 0.999] {
        assert_within("oren-nayar", &[0.95, sigma], 1, AlbedoFrame::Normal, 90.0);
        assert_within(
            "oren-nayar-full",
            &[0.95, sigma],
            1,
            AlbedoFrame::Normal,
            90.0,
        );
    }
    assert_exceeds("oren-nayar", &[1.0, 0.2], 1, AlbedoFrame::Normal, 90.0);
    assert_exceeds("oren-nayar-full", &[1.0, 0.5], 1, AlbedoFrame::Normal, 90.0);
}

/// Sopp's variants: Phong with Fresnel as Phong (`cd + cs <= 1`); the clear
/// coat over a base of albedo `a <= 0.5` while `Fr(theta_i) <= (1 - a)/(pi - a)`
/// (up to 70 deg for eta = 1.5), and above 1 at grazing.
#[test]
fn sopp_variants_domain() {
    for n in [0.0, 1e4] {
        for eta in [1.0, 3.0] {
            assert_within(
                "phong-fresnel",
                &[0.3, 0.6999, n, eta],
                1,
                AlbedoFrame::Mirror,
                90.0,
            );
        }
    }
    // Fr(70 deg; 1.5) = 0.171 < (1 - 0.5)/(pi - 0.5) = 0.189.
    let bound = 0.5 / (std::f64::consts::PI - 0.5);
    assert!(brdf_core::fresnel::fresnel_dielectric(70f64.to_radians().cos(), 1.5) < bound);
    assert_within(
        "clear-coat",
        &[0.25, 0.25, 20.0],
        1,
        AlbedoFrame::Normal,
        70.0,
    );
    assert_exceeds(
        "clear-coat",
        &[0.25, 0.25, 20.0],
        1,
        AlbedoFrame::Normal,
        90.0,
    );
}

/// Lambert: the albedo is `kd` at every incidence (1 at `kd = 1`, to the
/// quadrature's error), above 1 beyond.
#[test]
fn lambert_domain() {
    assert_within("lambert", &[1.0], 1, AlbedoFrame::Normal, 90.0);
    let m = model("lambert", 1, &[1.0]);
    let a = directional_albedo(
        m.as_ref(),
        &spherical_to_cartesian(1.2, 0.3),
        AlbedoFrame::Normal,
        &QuadratureOptions::default(),
    );
    assert!((a.value[0] - 1.0).abs() <= a.error[0] + 1e-12, "{a:?}");
}

/// The anisotropic coupled Ashikhmin-Shirley, as the isotropic one.
#[test]
fn ashikhmin_shirley_coupled_aniso_domain() {
    for (nu, nv) in [(0.0, 0.0), (10.0, 1e4), (1e4, 100.0)] {
        for p in [
            [0.5, 0.5, nu, nv, 0.5],
            [1.0, 0.0, nu, nv, 0.0],
            [0.0, 1.0, nu, nv, 0.999],
        ] {
            assert_within(
                "ashikhmin-shirley-coupled-aniso",
                &p,
                1,
                AlbedoFrame::Mirror,
                90.0,
            );
        }
    }
}

/// Samples of a plausible BRDF (Oren-Nayar, `kd = 0.8`, `sigma = 0.3`,
/// plus a broad Phong lobe `ks = 0.15`, `n = 8`: albedo below 0.95) at
/// scattered pairs up to 80 deg.
fn plausible_samples() -> (brdf_core::DirPairs, Vec<f64>) {
    let on = model("oren-nayar", 1, &[0.8, 0.3]);
    let ph = model("phong", 1, &[0.0, 0.15, 8.0]);
    let mut pairs = brdf_core::DirPairs::with_capacity(900);
    let mut y = Vec::new();
    let (mut a, mut b) = ([0.0], [0.0]);
    for i in 0..30 {
        for j in 0..30 {
            // A Fibonacci-like lattice over (theta_i, phi_i, theta_o, phi_o).
            let u = [
                (i as f64 + 0.5) / 30.0,
                (0.618 * (i * 30 + j) as f64).fract(),
            ];
            let w = [
                (j as f64 + 0.5) / 30.0,
                (0.414 * (i * 30 + j) as f64).fract(),
            ];
            let l = spherical_to_cartesian(
                u[0].sqrt() * 80f64.to_radians(),
                std::f64::consts::TAU * u[1],
            );
            let v = spherical_to_cartesian(
                w[0].sqrt() * 80f64.to_radians(),
                std::f64::consts::TAU * w[1],
            );
            on.eval(&l, &v, &mut a);
            ph.eval(&l, &v, &mut b);
            pairs.push(&l, &v);
            y.push(a[0] + b[0]);
        }
    }
    (pairs, y)
}

/// Least squares fit of a linear model's coefficients (its unclamped basis
/// rows, from `basis`) to `y`, by nalgebra's SVD.
fn fit_linear(
    pairs: &brdf_core::DirPairs,
    y: &[f64],
    per: usize,
    basis: impl Fn(&nalgebra::Vector3<f64>, &nalgebra::Vector3<f64>, &mut [f64]),
) -> Vec<f64> {
    let mut a = nalgebra::DMatrix::zeros(pairs.len(), per);
    let mut row = vec![0.0; per];
    for j in 0..pairs.len() {
        basis(&pairs.l(j), &pairs.v(j), &mut row);
        for k in 0..per {
            a[(j, k)] = row[k];
        }
    }
    let b = nalgebra::DVector::from_column_slice(y);
    let x = a.svd(true, true).solve(&b, 1e-12).unwrap();
    x.iter().copied().collect()
}

/// Fitted Kurt polynomials (degrees 1, 3, 7, both variants) and Koenderink
/// expansions (orders 2, 4, 8) of a plausible BRDF conserve energy up to
/// the fitted range (80 deg): their albedo stays below 1, within a few
/// percent of the source's. The clamp at 0 does not rescue them: the
/// unclamped fit is what is integrated (through the model's evaluation).
#[test]
fn fitted_linear_models_conserve_energy() {
    use brdf_models::kurt_polynomial::{KurtPolynomial, Pca, PolyVariant};
    let (pairs, y) = plausible_samples();
    let source_albedo = {
        let on = model("oren-nayar", 1, &[0.8, 0.3]);
        let ph = model("phong", 1, &[0.0, 0.15, 8.0]);
        worst(on.as_ref(), AlbedoFrame::Normal, 80.0, &[0.3]).0
            + worst(ph.as_ref(), AlbedoFrame::Mirror, 80.0, &[0.3]).0
    };
    assert!(source_albedo < 0.95, "{source_albedo}");
    let mut fitted: Vec<(String, Box<dyn brdf_core::Parametric>)> = Vec::new();
    for variant in [PolyVariant::Isotropic, PolyVariant::Anisotropic] {
        for degree in [1, 3, 7] {
            let pca = Pca::from_pairs(variant, &pairs).unwrap();
            let mut m = KurtPolynomial::new(variant, degree, 1, pca).unwrap();
            let c = fit_linear(&pairs, &y, m.coefficients_per_channel(), |l, v, r| {
                m.design_row(l, v, r)
            });
            brdf_core::Parametric::set_params(&mut m, &c).unwrap();
            fitted.push((
                format!("{variant:?} polynomial degree {degree}"),
                Box::new(m),
            ));
        }
    }
    for order in [2, 4, 8] {
        let mut m = brdf_models::Koenderink::new(order, 1).unwrap();
        let c = fit_linear(&pairs, &y, m.basis_len(), |l, v, r| m.basis(l, v, r));
        brdf_core::Parametric::set_params(&mut m, &c).unwrap();
        fitted.push((format!("koenderink order {order}"), Box::new(m)));
    }
    for (label, m) in &fitted {
        let (a, e) = worst(m.as_ref(), AlbedoFrame::Normal, 80.0, &[0.3, 1.2]);
        assert!(a + e <= 1.0, "{label}: albedo {a} + {e}");
        assert!(a > 0.5, "{label}: albedo {a} (a failed fit?)");
    }
}

/// Dupuy (the catalogue's table before data, a GGX `D` with `alpha` 0.3):
/// `kd + F + S <= 1` over the whole hemisphere of incidence. With `G <=
/// G1(L) = cos_i / sigma(L)` the lobe's albedo is at most
/// `integral D (L.H)+ / cos_i dH G1(L) = 1` times the largest Fresnel factor
/// `F + S`. The bound is not tight (at normal incidence the lobe alone
/// reflects 0.88 with `F = 1`: shadowing and the horizon take the rest),
/// but outside it the albedo can exceed 1 (`kd` 0.2 over `F = 1`). The table
/// is piecewise linear, so the adaptive quadrature runs at a looser
/// tolerance (its error estimate is still added to the albedo) at the
/// pole, 45, 85 and 89.9 deg.
#[test]
fn dupuy_domain() {
    let opts = QuadratureOptions {
        rel_tol: 1e-4,
        abs_tol: 1e-7,
        max_intervals: 100,
    };
    let albedo = |p: &[f64], deg: f64| {
        let m = model("dupuy", 1, p);
        let l = spherical_to_cartesian(f64::to_radians(deg), 0.3);
        let a = directional_albedo(m.as_ref(), &l, AlbedoFrame::Normal, &opts);
        (a.value[0], a.error[0])
    };
    for p in [[0.0, 0.999, 0.0], [0.3, 0.35, 0.349]] {
        for deg in [0.0, 45.0, 85.0, 89.9] {
            let (a, e) = albedo(&p, deg);
            assert!(a + e <= 1.0, "dupuy {p:?} at {deg} deg: {a} + {e}");
        }
    }
    let (a, e) = albedo(&[0.2, 1.0, 0.0], 0.0);
    assert!(a - e > 1.0, "dupuy just outside: {a} - {e}");
}

/// Every catalogue model has an energy test in this file (a new model
/// must get one).
#[test]
fn every_model_has_an_energy_test() {
    let covered = [
        "lambert",
        "phong",
        "blinn-phong",
        "ward",
        "ward-aniso",
        "ward-duer",
        "ward-duer-aniso",
        "ashikhmin-shirley",
        "ashikhmin-shirley-aniso",
        "ashikhmin-shirley-coupled",
        "ashikhmin-shirley-coupled-aniso",
        "torrance-sparrow",
        "cook-torrance",
        "lafortune",
        "lafortune-aniso",
        "oren-nayar",
        "oren-nayar-full",
        "phong-fresnel",
        "as-paint",
        "clear-coat",
        "koenderink",
        "polynomial",
        "polynomial-aniso",
        // SGD, ABC, STD and Dupuy: their domains are tested in new_models.rs.
        "sgd",
        "abc",
        "abc-smooth",
        "std",
        "dupuy",
    ];
    // The renderer family (GGX, principled, glTF) has its energy tests in
    // renderer_models.rs.
    for e in brdf_models::catalogue() {
        if e.family == "renderer" {
            continue;
        }
        assert!(covered.contains(&e.name), "{} has no energy test", e.name);
    }
}
