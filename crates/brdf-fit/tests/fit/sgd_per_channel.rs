//! Quality of the per-channel SGD fit: Bagher's SGD with its
//! own parameters in every channel, fitted by the default pipeline (its
//! suggested starts, channel by channel, the channel's one-channel batch
//! model, the shadowing parameters on a log scale, the starts ranked on a
//! subsample), recovers every parameter of noise-free synthetic data.
//! The reference is the generating parameter vector itself, evaluated by
//! the RGB model's per-pair formula.

use brdf_core::{Direction, Parametric, SampleSet};
use brdf_fit::FitOptions;
use brdf_fit::pipeline::fit;
use brdf_models::Sgd;
use brdf_models::channel_slice::{ChannelSlice, channel_blocks};

/// `kd, ks, alpha, p, f0, f1, lambda, c, k, theta0`, every parameter per
/// channel (RGB, layout of [`Sgd`]): widths and shifts differing by
/// channel, a shadowing term that darkens the grazing pairs (`G1` 0.92 at
/// 0.8 rad, 0.25 at 1.2 rad: every shadowing parameter shapes the data)
/// and a Fresnel term whose grazing rise the data see.
const TRUTH: [[f64; 10]; 3] = [
    [0.2, 0.5, 0.05, 0.4, 0.2, 0.05, 1.5, 0.8, 3.0, 0.4],
    [0.3, 1.0, 0.1, 0.8, 0.3, 0.1, 1.2, 0.6, 2.5, 0.35],
    [0.4, 2.0, 0.2, 1.2, 0.4, 0.02, 1.8, 1.0, 3.5, 0.45],
];

/// The RGB parameter vector of [`TRUTH`] (each parameter for every channel
/// in turn).
fn truth() -> Vec<f64> {
    (0..10)
        .flat_map(|k| (0..3).map(move |c| TRUTH[c][k]))
        .collect()
}

/// A direction on the hemisphere.
fn dir(theta: f64, phi: f64) -> Direction {
    Direction::from_spherical(theta, phi).unwrap()
}

/// The model's values on a grid of pairs within 80 degrees: incidence at
/// `ni` polar angles in the plane `phi = 0`, outgoing directions on a
/// `nt x np` grid (offset by `shift` of a cell, so a second grid holds
/// pairs the first does not).
fn synth(model: &Sgd, p: &[f64], (ni, nt, np): (usize, usize, usize), shift: f64) -> SampleSet {
    let names = ["r", "g", "b"].map(String::from).to_vec();
    let mut s = SampleSet::new("synthetic sgd", "test", names);
    let limit = 80f64.to_radians();
    let mut out = [0.0; 3];
    for i in 0..ni {
        let l = dir(limit * (i as f64 + 0.5 * shift + 0.25) / ni as f64, 0.0);
        for t in 0..nt {
            for q in 0..np {
                let theta = limit * (t as f64 + shift + 0.5) / (nt as f64 + 1.0);
                let phi = std::f64::consts::TAU * (q as f64 + shift) / np as f64;
                let v = dir(theta, phi);
                model.eval_at(p, &l, &v, &mut out);
                s.push(&l, &v, &out, 1.0).unwrap();
            }
        }
    }
    s
}

/// The fit of `rep` went channel by channel and ended at the truth `p`:
/// every parameter within 1e-4 of it (relative, or absolute below 0.1).
fn assert_per_channel_at_truth(rep: &brdf_fit::FitSummary, p: &[f64], what: &str) {
    assert!(
        rep.solver.starts_with("per channel"),
        "{what}: the per-channel path, not {}",
        rep.solver
    );
    for (k, fp) in rep.parameters.iter().enumerate() {
        let tol = 1e-4 * p[k].abs().max(0.1);
        assert!(
            (fp.value - p[k]).abs() <= tol,
            "{what}: {} = {} vs truth {} (Ngan L2 {})",
            fp.name,
            fp.value,
            p[k],
            rep.ngan_l2
        );
    }
}

/// The slices of an RGB SGD model are evaluated by its one-channel batch
/// model (the catalogue's), which gives the channel's values.
#[test]
fn sgd_channels_are_sliced_to_the_one_channel_model() {
    let model = Sgd::new(3, &truth()).unwrap();
    let blocks = channel_blocks(&model).expect("SGD's channels share nothing");
    for (c, block) in blocks.into_iter().enumerate() {
        let slice = ChannelSlice::new(&model, c, block).unwrap();
        assert!(slice.is_fast(), "channel {c} sliced without its model");
        assert!(slice.shared_basis().is_some());
    }
}

/// Noise-free data of [`TRUTH`] on 20,736 pairs (above the size from which
/// the starts are ranked on a subsample): the default fit ends at the
/// truth, every parameter of every channel within 1e-4 of it (relative,
/// or absolute below 0.1), and the fitted function matches the truth at
/// pairs the fit has not seen.
#[test]
fn sgd_per_channel_fit_recovers_the_parameters() {
    let p = truth();
    let mut model = Sgd::with_channels(3).unwrap();
    let data = synth(&model, &p, (16, 36, 36), 0.0);
    assert!(data.len() > 20_000);
    let rep = fit(&mut model, &data, &FitOptions::default()).unwrap();
    assert_per_channel_at_truth(&rep, &p, "Ngan");
    let held_out = synth(&model, &p, (7, 11, 13), 0.37);
    let (n, fitted) = (held_out.len(), model.params().to_vec());
    let mut got = vec![0.0; 3 * n];
    model.eval_batch_at(&fitted, held_out.pairs(), &mut got);
    for c in 0..3 {
        let want = held_out.channel(c);
        let peak = want.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        for j in 0..n {
            assert!(
                (got[c * n + j] - want[j]).abs() <= 1e-6 * peak,
                "channel {c} pair {j}: {} vs {}",
                got[c * n + j],
                want[j]
            );
        }
    }
}

/// The transformed objectives (log, cube root) are sums over channels of
/// each channel's rows too, so they are fitted channel by channel, and on
/// noise-free data end at the truth (every parameter within 1e-4).
#[test]
fn sgd_transformed_objectives_are_fitted_per_channel_to_the_truth() {
    use brdf_fit::Objective;
    let p = truth();
    let data = synth(&Sgd::with_channels(3).unwrap(), &p, (16, 36, 36), 0.0);
    for objective in [Objective::Log, Objective::CubeRoot] {
        let mut model = Sgd::with_channels(3).unwrap();
        let opts = FitOptions {
            objective,
            ..FitOptions::default()
        };
        let rep = fit(&mut model, &data, &opts).unwrap();
        assert_per_channel_at_truth(&rep, &p, &format!("{objective:?}"));
    }
}

/// A fit made only as the start of another (`Fit::as_start`, the
/// appearance pipeline's candidates of a fitted-data model) stops at the
/// search's tolerance: on noisy data of [`TRUTH`], where the polish to
/// the full tolerances takes iterations, it takes fewer, and ends in the
/// polished fit's basin (Ngan's L2 within 1% of it).
#[test]
fn a_fit_as_a_start_is_not_polished() {
    let p = truth();
    let clean = synth(&Sgd::with_channels(3).unwrap(), &p, (16, 36, 36), 0.0);
    // Deterministic multiplicative noise of up to 1%, so the polish has
    // digits to chase.
    let mut data = SampleSet::new("noisy sgd", "test", clean.channel_names.clone());
    for j in 0..clean.len() {
        let noisy: Vec<f64> = (0..3)
            .map(|c| {
                let u = ((j * 7919 + c * 104_729) % 1000) as f64 / 1000.0;
                clean.channel(c)[j] * (1.0 + 0.02 * u - 0.01)
            })
            .collect();
        let l = Direction::try_new(clean.pairs().l(j)).unwrap();
        let v = Direction::try_new(clean.pairs().v(j)).unwrap();
        data.push(&l, &v, &noisy, 1.0).unwrap();
    }
    let fit = brdf_fit::Fit::model("sgd").unwrap();
    let full = fit.run(&data).unwrap();
    let start = fit.clone().as_start().run(&data).unwrap();
    assert!(
        start.summary.iterations < full.summary.iterations,
        "as a start {} iterations, polished {}",
        start.summary.iterations,
        full.summary.iterations
    );
    let ratio = start.summary.ngan_l2 / full.summary.ngan_l2;
    assert!((0.99..=1.01).contains(&ratio), "Ngan L2 ratio {ratio}");
}
