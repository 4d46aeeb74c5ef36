//! The linear fitting pipeline: exact recovery of known coefficients from
//! synthetic data (the `brdf fit` command on the real CUReT data is
//! tested in `crates/brdf-cli/tests/cli/fit_command.rs`).

use brdf_core::SampleSet;
use brdf_fit::pipeline::fit;
use brdf_fit::{FitOptions, Solver};
use brdf_models::{ModelConfig, entry};
use brdf_study::synthetic::scattered_pairs;

/// Direct linear least squares on Ngan's objective.
fn ols() -> FitOptions {
    FitOptions {
        solver: Solver::Ols,
        ..FitOptions::default()
    }
}

#[test]
fn known_coefficients_are_recovered_exactly() {
    let pairs = scattered_pairs(205, 80f64.to_radians());
    for (name, config) in [
        (
            "koenderink",
            ModelConfig {
                channels: 3,
                order: 4,
                ..ModelConfig::default()
            },
        ),
        (
            "lambert",
            ModelConfig {
                channels: 3,
                ..ModelConfig::default()
            },
        ),
    ] {
        let e = entry(name).unwrap();
        let mut truth = (e.build)(&config).unwrap();
        let np = truth.n_params();
        // Coefficients chosen so the model stays positive (no clamp active).
        let per = np / 3;
        let p: Vec<f64> = (0..np)
            .map(|k| {
                if k % per == 0 {
                    0.5 + 0.1 * (k / per) as f64
                } else {
                    0.005 * ((k * 7) % 5) as f64 - 0.01
                }
            })
            .collect();
        truth.set_params(&p).unwrap();
        let mut set = SampleSet::new(
            "synthetic",
            "test",
            vec!["r".into(), "g".into(), "b".into()],
        );
        let mut f = vec![0.0; 3];
        for (l, v) in &pairs {
            truth.eval(l.vector(), v.vector(), &mut f);
            assert!(
                f.iter().all(|x| *x > 0.0),
                "choose coefficients without clamping"
            );
            set.push(l, v, &f, 1.0).unwrap();
        }
        let mut model = (e.build)(&config).unwrap();
        let r = fit(model.as_mut(), &set, &ols()).unwrap();
        assert!(r.ngan_l2 < 1e-12, "{name}: {}", r.ngan_l2);
        for (k, q) in r.parameters.iter().enumerate() {
            let v = q.value;
            assert!((v - p[k]).abs() < 1e-9, "{name} param {k}: {v} vs {}", p[k]);
        }
    }
}

#[test]
fn non_linear_models_are_refused_with_a_message() {
    let pairs = scattered_pairs(50, 1.2);
    let mut set = SampleSet::new("s", "test", vec!["grey".into()]);
    for (l, v) in &pairs {
        set.push(l, v, &[0.1], 1.0).unwrap();
    }
    let mut m = (entry("ward").unwrap().build)(&ModelConfig::default()).unwrap();
    let e = fit(m.as_mut(), &set, &ols()).unwrap_err();
    assert!(e.to_string().contains("non-linear parameter `a`"), "{e}");
}
