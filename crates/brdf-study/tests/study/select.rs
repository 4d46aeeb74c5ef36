//! `select` on data with a known answer: Lambertian reflectance with small
//! deterministic noise. Every candidate fits the noise at least as well as
//! Lambert, none much better, so
//! - with a generous tolerance the rule picks Lambert (1 stored number);
//! - with tolerance 0 it picks the candidate with the smallest error;
//! - Lambert's AIC and BIC equal the closed form: its Ngan fit is the
//!   weighted mean `kd/pi = sum c^2 y / sum c^2` (`c = cos_i`), so
//!   `SSR = sum c^2 (y - kd/pi)^2`, `AIC = n ln(SSR/n) + 2`,
//!   `BIC = n ln(SSR/n) + ln n`;
//! - BIC, whose penalty grows with `ln n`, is smallest for Lambert.

use brdf_core::SampleSet;
use brdf_fit::FitOptions;
use brdf_fit::select::select;
use brdf_study::synthetic::scattered_pairs;

const N: usize = 150;

fn noisy_lambert() -> SampleSet {
    let mut s = SampleSet::new("noisy lambert", "test", vec!["y".into()]);
    for (j, (l, v)) in scattered_pairs(N, 80f64.to_radians())
        .into_iter()
        .enumerate()
    {
        // Noise of 2%: a fixed irregular sequence, mean near 0.
        let noise = 0.02 * (12.9898 * j as f64 + 0.5).sin();
        s.push(&l, &v, &[0.5 / std::f64::consts::PI * (1.0 + noise)], 1.0)
            .unwrap();
    }
    s
}

#[test]
fn tolerance_rule_aic_and_bic_on_noisy_lambert() {
    let data = noisy_lambert();
    let opts = FitOptions {
        starts: 3,
        ..FitOptions::default()
    };
    let (rows, choice) = select(&data, 1.0, &opts).unwrap();
    assert_eq!(rows[choice].model, "lambert", "{:?}", rows[choice]);
    assert_eq!(rows[choice].stored_numbers, 1);
    // Every candidate was fitted (none failed or was dropped silently),
    // except Dupuy's, read off back-scattering samples these scattered
    // pairs do not have: its row says so.
    for r in &rows {
        if r.model == "dupuy" {
            assert!(
                r.error.is_nan() && r.termination.contains("back-scattering samples"),
                "{}: {}",
                r.label,
                r.termination
            );
            continue;
        }
        assert!(r.error.is_finite(), "{}: {}", r.label, r.termination);
    }
    // 150 samples are fewer than the coarse subsample: no coarse stage,
    // every row is of all samples.
    assert!(
        rows.iter()
            .all(|r| !r.screened_out && r.coarse_error.is_none() && r.samples == N)
    );
    assert!(rows.iter().any(|r| r.model == "dupuy"));
    assert!(rows.iter().any(|r| r.label == "lafortune (2 lobes)"));
    assert!(rows.iter().any(|r| r.label == "koenderink order 8"));

    // Lambert's row from the closed form.
    let y = data.channel(0);
    let c: Vec<f64> = data.pairs().lz.clone();
    let (s2, s2y): (f64, f64) = c.iter().zip(y).fold((0.0, 0.0), |(a, b), (ci, yi)| {
        (a + ci * ci, b + ci * ci * yi)
    });
    let m = s2y / s2;
    let ssr: f64 = c
        .iter()
        .zip(y)
        .map(|(ci, yi)| (ci * (yi - m)).powi(2))
        .sum();
    let n = N as f64;
    let lambert = &rows[choice];
    assert!(
        (lambert.ssr - ssr).abs() <= 1e-9 * ssr,
        "SSR {} vs {ssr}",
        lambert.ssr
    );
    let aic = n * (ssr / n).ln() + 2.0;
    let bic = n * (ssr / n).ln() + n.ln();
    assert!(
        (lambert.aic - aic).abs() <= 1e-7 * aic.abs(),
        "AIC {} vs {aic}",
        lambert.aic
    );
    assert!(
        (lambert.bic - bic).abs() <= 1e-7 * bic.abs(),
        "BIC {} vs {bic}",
        lambert.bic
    );
    let by_bic = rows.iter().min_by(|a, b| a.bic.total_cmp(&b.bic)).unwrap();
    assert_eq!(by_bic.model, "lambert", "BIC picks {}", by_bic.label);
    // AIC and BIC of every fitted row follow the stated formulas from its
    // SSR.
    for r in rows.iter().filter(|r| r.error.is_finite()) {
        let ll = n * (r.ssr / n).ln();
        let k = r.stored_numbers as f64;
        assert!(
            (r.aic - (ll + 2.0 * k)).abs() <= 1e-9 * r.aic.abs().max(1.0),
            "{}",
            r.label
        );
        assert!(
            (r.bic - (ll + k * n.ln())).abs() <= 1e-9 * r.bic.abs().max(1.0),
            "{}",
            r.label
        );
    }

    // Tolerance 0: the smallest error wins, whatever it costs.
    let (rows0, choice0) = select(&data, 0.0, &opts).unwrap();
    let best = rows0.iter().map(|r| r.error).fold(f64::INFINITY, f64::min);
    assert_eq!(rows0[choice0].error, best);
    assert!(rows0[choice0].stored_numbers > 1, "{:?}", rows0[choice0]);
    assert!(select(&data, -1.0, &opts).is_err());
}
