//! Every model against independently computed values: `tests/reference/models.py`
//! writes each formula of spec/models.md again in plain Python (angles, no
//! shared code) and evaluates it at fixed pairs, among them the pole, pairs
//! within 1e-6 rad of the horizon and pairs on or below it; `models.json`
//! holds its output. Besides the one-channel cases it covers two-lobe
//! Lafortune and Cook-Torrance, three-channel models, `F0 = 0.999`,
//! Koenderink's basis of orders 2, 4 and 8 at pairs with `phi_i != 0`, and
//! Kurt's polynomial (features, PCA, scores, design rows, values) for degrees
//! 1, 3 and 7.

use brdf_core::{DirPairs, Parametric};
use brdf_models::kurt_polynomial::{KurtPolynomial, Pca, PolyVariant};
use brdf_models::{Koenderink, ModelConfig, build, build_for};
use nalgebra::Vector3;

#[derive(serde::Deserialize)]
struct Case {
    model: String,
    channels: usize,
    lobes: usize,
    params: Vec<f64>,
    wi: [f64; 3],
    wo: [f64; 3],
    value: Vec<f64>,
}

#[derive(serde::Deserialize)]
struct KoenderinkCase {
    order: usize,
    wi: [f64; 3],
    wo: [f64; 3],
    basis: Vec<f64>,
    coef: Vec<f64>,
    value: f64,
}

#[derive(serde::Deserialize)]
struct Pair {
    wi: [f64; 3],
    wo: [f64; 3],
}

#[derive(serde::Deserialize)]
struct PcaRef {
    mean: Vec<f64>,
    axes: Vec<f64>,
    variances: Vec<f64>,
}

#[derive(serde::Deserialize)]
struct PolyCase {
    model: String,
    degree: usize,
    channels: usize,
    params: Vec<f64>,
    wi: [f64; 3],
    wo: [f64; 3],
    features: Vec<f64>,
    scores: Vec<f64>,
    row: Vec<f64>,
    value: Vec<f64>,
}

#[derive(serde::Deserialize)]
struct Polynomial {
    train: Vec<Pair>,
    polynomial: PcaRef,
    #[serde(rename = "polynomial-aniso")]
    polynomial_aniso: PcaRef,
    cases: Vec<PolyCase>,
}

#[derive(serde::Deserialize)]
struct Reference {
    cases: Vec<Case>,
    koenderink: Vec<KoenderinkCase>,
    polynomial: Polynomial,
}

fn reference() -> Reference {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/reference/models.json"
    ))
    .unwrap();
    serde_json::from_str(&text).unwrap()
}

/// Relative 1e-9 (the script uses angles, acos/atan2 and pow where the
/// models use vector forms); absolute 1e-12 for values near 0.
fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * b.abs() + 1e-12
}

#[test]
fn models_match_the_independent_script() {
    let r = reference();
    assert_eq!(r.cases.len(), 564);
    let mut seen = std::collections::BTreeSet::new();
    for c in &r.cases {
        let config = ModelConfig {
            channels: c.channels,
            lobes: c.lobes,
            ..ModelConfig::default()
        };
        let mut m: Box<dyn Parametric> = build(&c.model, &config).unwrap();
        m.set_params(&c.params).unwrap();
        let (l, v) = (Vector3::from(c.wi), Vector3::from(c.wo));
        let mut f = vec![f64::NAN; c.channels];
        m.eval(&l, &v, &mut f);
        for (ch, (&got, &want)) in f.iter().zip(&c.value).enumerate() {
            assert!(
                close(got, want) && got.is_finite(),
                "{} ({} channels, {} lobes) channel {ch} at wi {:?} wo {:?}: {got} vs reference {want}",
                c.model,
                c.channels,
                c.lobes,
                c.wi,
                c.wo,
            );
        }
        seen.insert((c.model.clone(), c.channels, c.lobes));
    }
    // Every catalogue model except the linear expansions (compared below) is
    // covered with one channel; the lobe models with two lobes. The renderer
    // family has its own independent reference (renderer_models.rs, which
    // asserts the same coverage for it).
    for e in brdf_models::catalogue() {
        // SGD, ABC, smooth ABC and STD have their own script (new_models.rs);
        // Dupuy's is read off data, and its table is checked against the
        // GGX and Beckmann closed forms it must reproduce (tests/models/dupuy.rs).
        let own_script = ["sgd", "abc", "abc-smooth", "std", "dupuy"].contains(&e.name);
        if e.name == "koenderink"
            || e.name.starts_with("polynomial")
            || e.family == "renderer"
            || own_script
        {
            continue;
        }
        assert!(
            seen.contains(&(e.name.to_string(), 1, 1)),
            "no reference values for {}",
            e.name
        );
        if e.has_lobes {
            assert!(
                seen.contains(&(e.name.to_string(), 1, 2)),
                "no two-lobe values for {}",
                e.name
            );
        }
    }
    assert!(seen.iter().filter(|s| s.1 == 3).count() >= 14);
}

#[test]
fn koenderink_basis_matches_the_independent_script() {
    let r = reference();
    assert_eq!(r.koenderink.len(), 18);
    for c in &r.koenderink {
        let (l, v) = (Vector3::from(c.wi), Vector3::from(c.wo));
        assert!(
            l.y.abs() > 0.05,
            "phi_i = 0 cannot tell phi_i - phi_o from phi_i + phi_o"
        );
        let k = Koenderink::new(c.order, 1).unwrap();
        let want_len = match c.order {
            2 => 5,
            4 => 14,
            8 => 55,
            _ => unreachable!(),
        };
        assert_eq!(k.basis_len(), want_len);
        assert_eq!(c.basis.len(), want_len);
        let mut b = vec![0.0; want_len];
        k.basis(&l, &v, &mut b);
        for (i, (&got, &want)) in b.iter().zip(&c.basis).enumerate() {
            // The basis functions are O(1): an absolute 1e-11.
            assert!(
                (got - want).abs() <= 1e-11,
                "order {} function {i} {:?} at wi {:?} wo {:?}: {got} vs {want}",
                c.order,
                Koenderink::basis_indices(c.order)[i],
                c.wi,
                c.wo
            );
        }
        // Evaluation: one channel, and three channels with the coefficients
        // scaled by 1, 2, 3.
        let mut m = build(
            "koenderink",
            &ModelConfig {
                order: c.order,
                ..ModelConfig::default()
            },
        )
        .unwrap();
        m.set_params(&c.coef).unwrap();
        let mut f = [0.0];
        m.eval(&l, &v, &mut f);
        assert!(
            (f[0] - c.value).abs() <= 1e-11,
            "order {}: {} vs {}",
            c.order,
            f[0],
            c.value
        );
        let config = ModelConfig {
            order: c.order,
            channels: 3,
            ..ModelConfig::default()
        };
        let mut m3 = build("koenderink", &config).unwrap();
        let p3: Vec<f64> = (1..=3)
            .flat_map(|s| c.coef.iter().map(move |x| s as f64 * x))
            .collect();
        m3.set_params(&p3).unwrap();
        let mut f3 = [0.0; 3];
        m3.eval(&l, &v, &mut f3);
        for (s, got) in f3.iter().enumerate() {
            assert!(
                (got - (s + 1) as f64 * c.value).abs() <= 1e-10,
                "order {} channel {s}",
                c.order
            );
        }
    }
}

fn check_pca(got: &Pca, want: &PcaRef, what: &str) {
    for (a, b) in got.mean.iter().zip(&want.mean) {
        assert!(
            (a - b).abs() <= 1e-13,
            "{what} mean {:?} vs {:?}",
            got.mean,
            want.mean
        );
    }
    for (a, b) in got.axes.iter().zip(&want.axes) {
        assert!(
            (a - b).abs() <= 1e-10,
            "{what} axes {:?} vs {:?}",
            got.axes,
            want.axes
        );
    }
    for (a, b) in got.variances.iter().zip(&want.variances) {
        assert!(
            close(*a, *b),
            "{what} variances {:?} vs {:?}",
            got.variances,
            want.variances
        );
    }
}

#[test]
fn kurt_polynomial_matches_the_independent_script() {
    let r = reference().polynomial;
    let mut train = DirPairs::with_capacity(r.train.len());
    for p in &r.train {
        train.push(&Vector3::from(p.wi), &Vector3::from(p.wo));
    }
    let iso = Pca::from_pairs(PolyVariant::Isotropic, &train).unwrap();
    let aniso = Pca::from_pairs(PolyVariant::Anisotropic, &train).unwrap();
    check_pca(&iso, &r.polynomial, "isotropic");
    check_pca(&aniso, &r.polynomial_aniso, "anisotropic");
    assert_eq!(r.cases.len(), 72);
    for c in &r.cases {
        let (variant, pca) = match c.model.as_str() {
            "polynomial" => (PolyVariant::Isotropic, &iso),
            _ => (PolyVariant::Anisotropic, &aniso),
        };
        let (l, v) = (Vector3::from(c.wi), Vector3::from(c.wo));
        let w = variant.features(&l, &v);
        for (a, b) in w.iter().zip(&c.features) {
            assert!(
                (a - b).abs() <= 1e-15,
                "{} features {w:?} vs {:?}",
                c.model,
                c.features
            );
        }
        let z = pca.scores(variant, &l, &v);
        for (a, b) in z.iter().zip(&c.scores) {
            assert!(
                (a - b).abs() <= 1e-10,
                "{} scores {z:?} vs {:?}",
                c.model,
                c.scores
            );
        }
        let m = KurtPolynomial::new(variant, c.degree, c.channels, pca.clone()).unwrap();
        let mut row = vec![0.0; m.coefficients_per_channel()];
        assert_eq!(row.len(), c.row.len());
        m.design_row(&l, &v, &mut row);
        for (a, b) in row.iter().zip(&c.row) {
            assert!(
                (a - b).abs() <= 1e-10,
                "{} degree {} row {row:?} vs {:?}",
                c.model,
                c.degree,
                c.row
            );
        }
        // Through the catalogue, with the PCA fitted to the training pairs.
        let config = ModelConfig {
            degree: c.degree,
            channels: c.channels,
            ..ModelConfig::default()
        };
        let mut fitted = build_for(&c.model, &config, &train).unwrap();
        fitted.set_params(&c.params).unwrap();
        let mut f = vec![0.0; c.channels];
        fitted.eval(&l, &v, &mut f);
        for (ch, (a, b)) in f.iter().zip(&c.value).enumerate() {
            assert!(
                (a - b).abs() <= 1e-10,
                "{} degree {} channel {ch} at wi {:?} wo {:?}: {a} vs {b}",
                c.model,
                c.degree,
                c.wi,
                c.wo
            );
        }
    }
}
