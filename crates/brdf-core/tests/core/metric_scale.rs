//! The error metrics at the ends of the `f64` range: the same data times
//! 1e-300, 2^-1000 or 1e300 give the unit data's error times that factor
//! (their squared residuals underflow to 0 or overflow to infinity, so a
//! textbook root-mean-square gave 0 or infinity), and ordinary data give
//! the textbook value bit for bit.

use brdf_core::metrics::{lafortune_l2, ngan_l2, relative_rms, rms, sopp_error};

/// Deterministic data: 3 channels x 40 samples, residuals of 1e-3 to 0.3.
struct Data {
    measured: Vec<f64>,
    model: Vec<f64>,
    cos_i: Vec<f64>,
    cos_o: Vec<f64>,
    weights: Vec<f64>,
}

fn data() -> Data {
    let n = 40;
    let cos_i: Vec<f64> = (0..n)
        .map(|j| 0.1 + 0.9 * ((j * 7) % n) as f64 / n as f64)
        .collect();
    let cos_o: Vec<f64> = (0..n)
        .map(|j| 0.2 + 0.8 * ((j * 11) % n) as f64 / n as f64)
        .collect();
    let weights: Vec<f64> = (0..n).map(|j| 0.5 + (j % 5) as f64 * 0.25).collect();
    let measured: Vec<f64> = (0..3 * n)
        .map(|k| 0.05 + 0.9 * ((k * 13) % 97) as f64 / 97.0)
        .collect();
    let model: Vec<f64> = measured
        .iter()
        .enumerate()
        .map(|(k, m)| m + (((k * 17) % 31) as f64 - 15.0) * 0.01 + 1e-3)
        .collect();
    Data {
        measured,
        model,
        cos_i,
        cos_o,
        weights,
    }
}

fn scaled(v: &[f64], s: f64) -> Vec<f64> {
    v.iter().map(|x| x * s).collect()
}

/// Every scale-proportional metric of `(measured, model)` with `weights`:
/// Ngan, Lafortune, Sopp weighted and not (totals and channels), RMS.
fn metrics(d: &Data, measured: &[f64], model: &[f64], weights: &[f64]) -> Vec<f64> {
    let mut out = Vec::new();
    for m in [
        ngan_l2(measured, model, &d.cos_i, weights).unwrap(),
        lafortune_l2(measured, model, &d.cos_i, &d.cos_o, weights).unwrap(),
        sopp_error(measured, model, &d.cos_i, weights, true).unwrap(),
        sopp_error(measured, model, &d.cos_i, weights, false).unwrap(),
    ] {
        out.push(m.total);
        out.extend(m.per_channel);
    }
    out.push(rms(measured, model).unwrap());
    out
}

#[test]
fn metrics_scale_with_the_data_across_the_f64_range() {
    let d = data();
    let unit = metrics(&d, &d.measured, &d.model, &d.weights);
    assert!(unit.iter().all(|e| *e > 1e-4 && e.is_finite()), "{unit:?}");
    for s in [1e-300, 2f64.powi(-1000), 1e300, 1e-150, 1e150] {
        let (m, f) = (scaled(&d.measured, s), scaled(&d.model, s));
        let got = metrics(&d, &m, &f, &d.weights);
        for (k, (g, u)) in got.iter().zip(&unit).enumerate() {
            let rel = (g / s - u).abs() / u;
            assert!(
                rel < 1e-13,
                "scale {s:e}, metric {k}: {g:e} / {s:e} against {u:e}"
            );
        }
        // The relative RMS does not depend on the scale at all.
        let r = relative_rms(&f, &m).unwrap();
        let r1 = relative_rms(&d.model, &d.measured).unwrap();
        assert!(
            (r - r1).abs() < 1e-13 * r1,
            "scale {s:e}: relative RMS {r} against {r1}"
        );
    }
}

#[test]
fn huge_weights_with_huge_data_stay_finite() {
    // Weights of 1e300 on data of 1e300: each w r^2 overflows.
    let d = data();
    let unit = metrics(&d, &d.measured, &d.model, &d.weights);
    let w = scaled(&d.weights, 1e300);
    let got = metrics(
        &d,
        &scaled(&d.measured, 1e300),
        &scaled(&d.model, 1e300),
        &w,
    );
    for (k, (g, u)) in got.iter().zip(&unit).enumerate() {
        assert!(
            (g / 1e300 - u).abs() < 1e-13 * u,
            "metric {k}: {g:e} against {u:e} x 1e300"
        );
    }
}

#[test]
fn ordinary_data_give_the_textbook_value_bit_for_bit() {
    // The Ngan L2 of channel 0 and the RMS written out as their formulas.
    let d = data();
    let n = d.cos_i.len();
    let wsum: f64 = d.weights.iter().sum();
    let s: f64 = (0..n)
        .map(|j| {
            let t = d.cos_i[j] * (d.measured[j] - d.model[j]);
            d.weights[j] * t * t
        })
        .sum();
    let ngan = ngan_l2(&d.measured, &d.model, &d.cos_i, &d.weights).unwrap();
    assert_eq!(ngan.per_channel[0], (s / wsum).sqrt());
    let total = (ngan.per_channel.iter().map(|e| e * e).sum::<f64>() / 3.0).sqrt();
    assert_eq!(ngan.total, total);
    let r: f64 = d
        .measured
        .iter()
        .zip(&d.model)
        .map(|(a, b)| (a - b) * (a - b))
        .sum();
    assert_eq!(
        rms(&d.measured, &d.model).unwrap(),
        (r / d.measured.len() as f64).sqrt()
    );
}

#[test]
fn exact_fits_and_nan_keep_their_meaning() {
    let d = data();
    let zero = ngan_l2(&d.measured, &d.measured, &d.cos_i, &d.weights).unwrap();
    assert_eq!(zero.total, 0.0);
    let mut bad = d.model.clone();
    bad[3] = f64::NAN;
    let nan = ngan_l2(&d.measured, &bad, &d.cos_i, &d.weights).unwrap();
    assert!(nan.per_channel[0].is_nan() && nan.total.is_nan());
}
