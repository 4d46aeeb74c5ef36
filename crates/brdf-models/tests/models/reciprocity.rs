//! Reciprocity at random parameter points (proptest over the whole box,
//! exponents up to `1e6`, unbounded coefficients in `[-1, 1]`) and random
//! direction pairs, for every catalogue model that declares itself
//! reciprocal, with 1 and 3 channels and 1 and 2 lobes; the models declared
//! non-reciprocal (Phong with Fresnel, the clear coat: both weight by a
//! Fresnel term of the incident angle only; the `-materialx` forms, whose
//! energy compensation depends on the first direction) are shown to be so.

use crate::strategies;

use brdf_core::Parametric;
use brdf_models::{ModelConfig, catalogue};
use nalgebra::Vector3;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed, TestRunner};

fn point(model: &dyn Parametric, u: &[f64]) -> Vec<f64> {
    model
        .param_specs()
        .iter()
        .zip(u)
        .map(|(s, t)| {
            let lo = if s.lower.is_finite() { s.lower } else { -1.0 };
            let hi = if s.upper.is_finite() { s.upper } else { 1.0 };
            // Exponents: log-uniform over [1, 1e6] so large ones occur.
            if hi >= 1e3 {
                10f64.powf(6.0 * t)
            } else if s.lower_open {
                lo + (hi - lo) * (0.001 + 0.999 * t)
            } else {
                lo + (hi - lo) * t
            }
        })
        .collect()
}

#[test]
fn reciprocal_at_random_parameter_points() {
    for (channels, lobes) in [(1, 1), (3, 1), (1, 2)] {
        let config = ModelConfig {
            channels,
            lobes,
            order: 4,
            degree: 3,
        };
        for entry in catalogue() {
            let model = (entry.build)(&config).expect("catalogue models build");
            let declared = model.is_reciprocal();
            assert_eq!(
                declared,
                !(matches!(
                    entry.name,
                    "phong-fresnel" | "clear-coat" | "gltf-ext" | "gltf-iridescence"
                ) || entry.name.ends_with("-materialx")),
                "{} declares reciprocal = {declared}",
                entry.name
            );
            let np = model.n_params();
            let nc = model.channels();
            // A fixed seed: the same 32 points on every run. With random
            // seeds about one run in 300 drew no point where phong-fresnel's
            // asymmetry exceeds 1e-6 (seed 235 of PROPTEST_RNG_SEED), and the
            // check below failed by chance, not by a change.
            let mut runner = TestRunner::new(Config {
                cases: 32,
                rng_seed: RngSeed::Fixed(1),
                ..Config::default()
            });
            let strategy = (
                strategies::pair_above_horizon(),
                proptest::collection::vec(0.0..1.0f64, np),
            );
            let asymmetric = std::cell::Cell::new(0usize);
            let result = runner.run(&strategy, |((l, v), u)| {
                let p = point(model.as_ref(), &u);
                let (mut a, mut b) = (vec![0.0; nc], vec![0.0; nc]);
                model.eval_at(&p, &l, &v, &mut a);
                model.eval_at(&p, &v, &l, &mut b);
                for c in 0..nc {
                    let d = (a[c] - b[c]).abs();
                    if declared {
                        prop_assert!(
                            d <= 1e-9 * a[c].abs().max(b[c].abs()) + 1e-300,
                            "{} ch {c}: f(L,V) {} vs f(V,L) {} at p {:?}, l {:?}, v {:?}",
                            entry.name,
                            a[c],
                            b[c],
                            p,
                            l,
                            v
                        );
                    } else if d > 1e-6 * a[c].abs().max(b[c].abs()) {
                        asymmetric.set(asymmetric.get() + 1);
                    }
                }
                Ok(())
            });
            if let Err(e) = result {
                panic!("{} ({channels} ch, {lobes} lobes): {e}", entry.name);
            }
            if !declared {
                assert!(
                    asymmetric.get() > 0,
                    "{} is declared non-reciprocal but was symmetric",
                    entry.name
                );
            }
        }
    }
    // The documented asymmetry at a pair: Phong with Fresnel at 10 and 70 deg.
    let mut m = brdf_models::build("phong-fresnel", &ModelConfig::default()).unwrap();
    m.set_params(&[0.0, 1.0, 1.0, 1.5]).unwrap();
    let l = Vector3::new(10f64.to_radians().sin(), 0.0, 10f64.to_radians().cos());
    let v = Vector3::new(-(70f64.to_radians().sin()), 0.0, 70f64.to_radians().cos());
    let (mut a, mut b) = ([0.0], [0.0]);
    m.eval(&l, &v, &mut a);
    m.eval(&v, &l, &mut b);
    // Same lobe, weighted by 1 - Fr(10 deg) = 0.96 and 1 - Fr(70 deg) = 0.83.
    let fr = |deg: f64| brdf_core::fresnel::fresnel_dielectric(deg.to_radians().cos(), 1.5);
    assert!(((a[0] / b[0]) - (1.0 - fr(10.0)) / (1.0 - fr(70.0))).abs() < 1e-12);
}
