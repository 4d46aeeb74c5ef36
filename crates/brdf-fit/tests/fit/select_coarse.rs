//! `brdf select` coarse to fine against the exhaustive selection, on
//! synthetic data from a known model: a one-lobe RGB Lafortune
//! BRDF on a grid of 4800 pairs with 1% deterministic noise, among
//! candidates of which some cannot represent its lobe (Lambert, low
//! polynomial degrees, low Koenderink orders) and some can.
//!
//! The references are independent of the coarse path: the exhaustive
//! selection (every candidate fitted to all samples), and the coarse
//! subsample's size counted from its definition (every `k`-th sample,
//! `k = ceil(N / COARSE_SAMPLES)`).

use brdf_core::{Direction, SampleSet};
use brdf_fit::FitOptions;
use brdf_fit::select::{Among, COARSE_SAMPLES, Search, SelectRow, select_with};

use brdf_models::ModelConfig;

const TOLERANCE: f64 = 0.1;

/// `kd` (RGB), `ks1` (RGB), `cxy1`, `cz1`, `n1`: a glossy lobe with a
/// diffuse base differing by channel.
const TRUTH: [f64; 9] = [0.15, 0.25, 0.35, 0.6, 0.5, 0.4, -0.95, 0.9, 40.0];

/// The Lafortune values on a grid of pairs within 80 degrees (incidence
/// at 10 polar angles in the plane `phi = 0`, outgoing on a 20 x 24
/// grid), each channel times `1 + 0.01 sin(...)`: a fixed irregular noise.
fn data() -> SampleSet {
    let config = ModelConfig {
        lobes: 1,
        channels: 3,
        ..ModelConfig::default()
    };
    let model = brdf_models::build("lafortune", &config).unwrap();
    let names = ["r", "g", "b"].map(String::from).to_vec();
    let mut s = SampleSet::new("synthetic lafortune", "test", names);
    let limit = 80f64.to_radians();
    let (ni, nt, np) = (10, 20, 24);
    let mut out = [0.0; 3];
    let mut j = 0;
    for i in 0..ni {
        let l = Direction::from_spherical(limit * (i as f64 + 0.25) / ni as f64, 0.0).unwrap();
        for t in 0..nt {
            for q in 0..np {
                let theta = limit * (t as f64 + 0.5) / (nt as f64 + 1.0);
                let phi = std::f64::consts::TAU * q as f64 / np as f64;
                let v = Direction::from_spherical(theta, phi).unwrap();
                model.eval_at(&TRUTH, l.vector(), v.vector(), &mut out);
                for (c, x) in out.iter_mut().enumerate() {
                    *x *= 1.0 + 0.01 * (12.9898 * j as f64 + 3.1 * c as f64).sin();
                }
                s.push(&l, &v, &out, 1.0).unwrap();
                j += 1;
            }
        }
    }
    s
}

fn among() -> Among {
    Among {
        models: ["lambert", "lafortune", "koenderink", "polynomial", "ward"]
            .map(String::from)
            .to_vec(),
        max_parameters: None,
    }
}

fn run(data: &SampleSet, search: Search, threads: usize) -> (Vec<SelectRow>, usize) {
    // As `brdf select` runs (without it Koenderink's pivoted QR differs in
    // the last bits between 1 and 2 threads).
    brdf_fit::select::sequential_factorisations();
    let opts = FitOptions {
        starts: 6,
        ..FitOptions::default()
    };
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(|| select_with(data, TOLERANCE, &opts, &among(), search).unwrap())
}

/// Everything of a row but its time, bit for bit.
fn key(r: &SelectRow) -> String {
    format!(
        "{} {} {:x} {:x} {:x} {:x} {} {} {} {:?}",
        r.label,
        r.stored_numbers,
        r.error.to_bits(),
        r.ssr.to_bits(),
        r.aic.to_bits(),
        r.bic.to_bits(),
        r.termination,
        r.samples,
        r.screened_out,
        r.coarse_error.map(f64::to_bits)
    )
}

#[test]
fn coarse_to_fine_agrees_with_exhaustive() {
    let data = data();
    let n = data.len();
    assert!(n > COARSE_SAMPLES, "the data must have a coarse stage");
    let (full, full_choice) = run(&data, Search::Exhaustive, 2);
    let (rows, choice) = run(&data, Search::CoarseToFine, 2);
    assert_eq!(rows.len(), full.len());

    // (a) the same choice; the generating model is it.
    assert_eq!(
        rows[choice].label, full[full_choice].label,
        "coarse to fine chose {}, exhaustive {}",
        rows[choice].label, full[full_choice].label
    );
    assert_eq!(full[full_choice].label, "lafortune (1 lobe)");

    // (c) the coarse subsample's size from its definition.
    let k = n.div_ceil(COARSE_SAMPLES);
    let coarse_n = (0..n).filter(|j| j % k == 0).count();
    let screened: Vec<&SelectRow> = rows.iter().filter(|r| r.screened_out).collect();
    assert!(!screened.is_empty(), "nothing screened out");
    assert!(screened.len() < rows.len());
    for r in &screened {
        assert_eq!(r.samples, coarse_n, "{}", r.label);
        assert!(
            r.termination.starts_with(&format!(
                "screened out on the coarse subsample ({coarse_n} of {n} samples)"
            )),
            "{}: {}",
            r.label,
            r.termination
        );
        assert_eq!(r.coarse_error, Some(r.error), "{}", r.label);
        assert!(r.aic.is_nan() && r.bic.is_nan(), "{}", r.label);
    }
    // Every screened-out row is in fact worse on all samples than the
    // chosen one (the race dropped nothing that mattered).
    for r in &screened {
        let e = full.iter().find(|f| f.label == r.label).unwrap();
        assert!(
            e.error > (1.0 + TOLERANCE) * full[full_choice].error,
            "{}",
            r.label
        );
    }

    // (b) every row fitted to all samples equals or beats its exhaustive
    // error.
    for (r, e) in rows.iter().zip(&full) {
        assert_eq!(r.label, e.label);
        if r.screened_out {
            continue;
        }
        assert_eq!(r.samples, n, "{}", r.label);
        assert!(r.coarse_error.is_some(), "{}", r.label);
        assert!(
            r.error <= e.error * (1.0 + 1e-9),
            "{}: {} after the coarse stage, {} exhaustive ({})",
            r.label,
            r.error,
            e.error,
            r.termination
        );
    }
    // The exhaustive rows are all fitted to all samples.
    assert!(full.iter().all(|r| !r.screened_out && r.samples == n));

    // (d) the same rows on one thread as on two.
    let (one, one_choice) = run(&data, Search::CoarseToFine, 1);
    assert_eq!(one_choice, choice);
    let a: Vec<String> = one.iter().map(key).collect();
    let b: Vec<String> = rows.iter().map(key).collect();
    assert_eq!(a, b);
}

/// Data of at most [`COARSE_SAMPLES`] samples have no coarse stage: the
/// rows are the exhaustive ones.
#[test]
fn small_data_is_fitted_exhaustively() {
    let data = data();
    let keep: Vec<bool> = (0..data.len()).map(|j| j % 4 == 0).collect();
    let small = data.select(&keep);
    assert!(small.len() <= COARSE_SAMPLES);
    let opts = FitOptions {
        starts: 3,
        ..FitOptions::default()
    };
    let among = Among {
        models: vec!["lambert".into(), "lafortune".into()],
        max_parameters: None,
    };
    let (a, ca) = select_with(&small, TOLERANCE, &opts, &among, Search::CoarseToFine).unwrap();
    let (b, cb) = select_with(&small, TOLERANCE, &opts, &among, Search::Exhaustive).unwrap();
    assert_eq!(ca, cb);
    assert_eq!(
        a.iter().map(key).collect::<Vec<_>>(),
        b.iter().map(key).collect::<Vec<_>>()
    );
    assert!(
        a.iter()
            .all(|r| !r.screened_out && r.coarse_error.is_none())
    );
}
