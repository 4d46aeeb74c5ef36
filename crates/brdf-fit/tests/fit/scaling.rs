//! Scale invariance: data of magnitude 1e-300 fit like
//! unit data — the same parameters up to the scale, the same iterations —
//! bit for bit when the scale is a power of two; weights of 1e300 like
//! unit weights; ordinary data are not touched.

use brdf_core::{Direction, SampleSet, spherical_to_cartesian};
use brdf_fit::{Fit, FitReport};
use brdf_models::{ModelConfig, build};

/// Cook-Torrance at 205 deterministic pairs, divided by the largest value
/// (so the largest is exactly 1), times `scale`, weights `w`.
fn data(scale: f64, w: f64) -> SampleSet {
    let mut m = build("cook-torrance", &ModelConfig::default()).unwrap();
    m.set_params(&[0.3, 0.4, 0.15, 0.04]).unwrap();
    let frac = |x: f64| x - x.floor();
    let mut pairs = Vec::new();
    let mut vals = Vec::new();
    for j in 0..205 {
        let j = j as f64;
        let l = spherical_to_cartesian(1.3 * frac(0.5 + 0.618 * j), 6.0 * frac(0.3 + 0.754 * j));
        let v = spherical_to_cartesian(1.3 * frac(0.25 + 0.382 * j), 6.0 * frac(0.7 + 0.57 * j));
        let mut out = [0.0];
        m.eval(&l, &v, &mut out);
        pairs.push((l, v));
        vals.push(out[0]);
    }
    let top = vals.iter().fold(0.0f64, |a, b| a.max(*b));
    let mut s = SampleSet::new("ct", "test", vec!["y".into()]);
    for ((l, v), x) in pairs.iter().zip(&vals) {
        s.push(
            &Direction::new_unchecked(*l),
            &Direction::new_unchecked(*v),
            &[x / top * scale],
            w,
        )
        .unwrap();
    }
    s
}

fn fit(s: &SampleSet) -> FitReport {
    Fit::model("cook-torrance").unwrap().run(s).unwrap()
}

fn values(r: &FitReport) -> Vec<f64> {
    r.summary.parameters.iter().map(|p| p.value).collect()
}

#[test]
fn power_of_two_scales_fit_bit_for_bit_like_unit_data() {
    let unit = fit(&data(1.0, 1.0));
    assert!(
        unit.notes.iter().all(|n| !n.contains("divided")),
        "{:?}",
        unit.notes
    );
    // Scales below 1 only: above, kd and ks <= 1 would have to grow with
    // the data and sit on their bound instead.
    for k in [-1000, -100, -20] {
        let s = 2f64.powi(k);
        let r = fit(&data(s, 1.0));
        assert_eq!(r.summary.iterations, unit.summary.iterations, "2^{k}");
        for ((a, b), spec) in values(&unit)
            .iter()
            .zip(values(&r))
            .zip(&unit.summary.parameters)
        {
            let want = if spec.name.starts_with('k') {
                a * s
            } else {
                *a
            };
            assert_eq!(b, want, "2^{k}: {}", spec.name);
        }
        assert_eq!(r.summary.ngan_l2, unit.summary.ngan_l2 * s, "2^{k}");
        assert_eq!(r.summary.termination, unit.summary.termination);
    }
}

#[test]
fn data_of_1e_minus_300_and_weights_of_1e300_fit_like_unit_data() {
    let unit = fit(&data(1.0, 1.0));
    for (scale, w) in [(1e-300, 1.0), (1.0, 1e300), (1e-300, 1e300), (1e-5, 1e-250)] {
        let r = fit(&data(scale, w));
        let what = format!("values x {scale:e}, weights {w:e}");
        // Scaling by a non-power of two leaves the data within one
        // rounding of the unit data; the solver's path can still branch
        // on that (1e-5 takes 15 iterations to the unit data's 11), the
        // parameters cannot.
        if scale != 1e-5 {
            assert_eq!(r.summary.iterations, unit.summary.iterations, "{what}");
        }
        for (a, b) in unit.summary.parameters.iter().zip(&r.summary.parameters) {
            let want = if a.name.starts_with('k') {
                a.value * scale
            } else {
                a.value
            };
            assert!(
                (b.value - want).abs() <= 1e-10 * want.abs(),
                "{what}: {} = {} vs {want}",
                a.name,
                b.value
            );
            assert_eq!(a.at_bound, b.at_bound, "{what}: {}", a.name);
        }
        assert!(r.notes.iter().any(|n| n.contains("divided")), "{what}");
    }
}
