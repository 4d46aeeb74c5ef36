//! AIC and BIC of `brdf select` do not depend on the data's unit: the same
//! data times `1e-300` are fitted to the same parameters up to the scale
//! (values are divided internally), so every candidate's log-likelihood
//! moves by the same `2 n ln(1e-300)` and their differences, the criteria's
//! only meaning, stay. Before, the errors of such data (near `1e-302`) were
//! floored at the smallest normal number inside the logarithm: every
//! candidate got the same log-likelihood and AIC ranked by the parameter
//! count alone.

use brdf_core::{Direction, SampleSet};
use brdf_fit::FitOptions;
use brdf_fit::select::{Among, Search, SelectRow, select_with};

/// Ward's model (`kd = 0.2`, `ks = 0.5`, `alpha = 0.15`, grey) at 300 pairs
/// within 75 degrees, times `scale`, with a fixed irregular 2% noise.
fn data(scale: f64) -> SampleSet {
    let model = brdf_models::build("ward", &brdf_models::ModelConfig::default()).expect("model");
    let mut s = SampleSet::new("synthetic ward", "test", vec!["grey".into()]);
    let limit = 75f64.to_radians();
    let mut out = [0.0];
    let mut j = 0;
    for i in 0..5 {
        let l = Direction::from_spherical(limit * (i as f64 + 0.5) / 5.0, 0.0).expect("dir");
        for t in 0..6 {
            for q in 0..10 {
                let theta = limit * (t as f64 + 0.5) / 6.0;
                let phi = std::f64::consts::TAU * q as f64 / 10.0;
                let v = Direction::from_spherical(theta, phi).expect("dir");
                model.eval_at(&[0.2, 0.5, 0.15], l.vector(), v.vector(), &mut out);
                let noise = 1.0 + 0.02 * (12.9898 * j as f64).sin();
                s.push(&l, &v, &[out[0] * noise * scale], 1.0)
                    .expect("sample");
                j += 1;
            }
        }
    }
    s
}

fn rows(scale: f64) -> Vec<SelectRow> {
    let among = Among {
        models: ["lambert", "ward", "blinn-phong"]
            .map(String::from)
            .to_vec(),
        max_parameters: None,
    };
    let opts = FitOptions {
        starts: 4,
        ..FitOptions::default()
    };
    select_with(&data(scale), 0.1, &opts, &among, Search::Exhaustive)
        .expect("select")
        .0
}

#[test]
fn aic_and_bic_differences_do_not_depend_on_the_unit() {
    let unit = rows(1.0);
    let tiny = rows(1e-300);
    assert_eq!(unit.len(), tiny.len());
    assert!(unit.len() >= 3);
    let n = 300.0;
    for (u, t) in unit.iter().zip(&tiny).skip(1) {
        assert_eq!(u.label, t.label);
        for (du, dt) in [
            (u.aic - unit[0].aic, t.aic - tiny[0].aic),
            (u.bic - unit[0].bic, t.bic - tiny[0].bic),
        ] {
            // Against the unit data's difference; 1e-6 of n is far below
            // one unit of AIC (and far above the fits' rounding).
            assert!(
                (du - dt).abs() <= 1e-6 * n,
                "{}: difference {du} on unit data, {dt} on data of 1e-300",
                u.label
            );
        }
    }
    // The generating model fits best, and by far: not a parameter count.
    let best = |r: &[SelectRow]| {
        r.iter()
            .min_by(|a, b| a.aic.total_cmp(&b.aic))
            .map(|r| r.label.clone())
    };
    assert_eq!(best(&tiny), best(&unit));
    assert_eq!(best(&unit).as_deref(), Some("ward"));
}
