//! `gltf-iridescence` (glTF with `KHR_materials_iridescence`) against
//! `tests/reference/gltf_iridescence.py`, an independent NumPy
//! transcription of the extension's formulas (its GLSL of the film, the
//! appendix's GGX in slope form), whose output `gltf_iridescence.json` is
//! committed beside it: one and three channels, six parameter sets each
//! across the box, seven direction pairs among them the pole, a grazing
//! pair and one below the horizon. Derivatives, finiteness and the
//! declared non-reciprocity are the catalogue-wide tests'
//! (`tests/models/properties.rs`, `tests/models/reciprocity.rs`).

use brdf_models::{ModelConfig, build};
use nalgebra::Vector3;

#[derive(serde::Deserialize)]
struct Case {
    channels: usize,
    params: Vec<f64>,
    wi: [f64; 3],
    wo: [f64; 3],
    values: Vec<f64>,
}

#[test]
fn values_match_the_independent_numpy_script() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/reference/gltf_iridescence.json"
    ))
    .expect("reference file");
    let cases: Vec<Case> = serde_json::from_str(&text).expect("reference JSON");
    assert_eq!(cases.len(), 84);
    let mut worst: f64 = 0.0;
    for c in &cases {
        let config = ModelConfig {
            channels: c.channels,
            ..ModelConfig::default()
        };
        let mut m = build("gltf-iridescence", &config).expect("a catalogue model");
        m.set_params(&c.params).expect("in the box");
        let mut f = vec![f64::NAN; c.channels];
        m.eval(&Vector3::from(c.wi), &Vector3::from(c.wo), &mut f);
        for (&a, &b) in f.iter().zip(&c.values) {
            let dev = (a - b).abs() / b.abs().max(1e-12);
            worst = worst.max(dev);
            assert!(
                (a - b).abs() <= 1e-10 * b.abs() + 1e-15,
                "at wi {:?} wo {:?}: {a} vs reference {b} (params {:?})",
                c.wi,
                c.wo,
                c.params
            );
        }
    }
    eprintln!("largest relative deviation {worst:.2e}");
}

/// Batches (fits, renders) read the film from a Catmull-Rom table over
/// `V.H` built once per parameter vector; single points evaluate it
/// exactly. On the reference's parameter sets and pairs, and on a dense
/// fan of pairs, the batch's values lie within [`TABLE_REL`] of the exact
/// ones (largest gap printed), and the batch's Jacobian is the derivative
/// of the batch's own values (central differences, within [`FD_REL`] of
/// the row's scale). Not the exact gradient: the extension clamps
/// `R12 R23` at `1e-5`, a kink in `V.H` that the interpolant rounds off, so
/// at such a pair one slope differs (a 1164 nm film: 30% in the film
/// index, while the value differs by 1e-4 of the film).
#[test]
fn batches_read_the_film_from_a_table_within_its_bound() {
    const TABLE_REL: f64 = 1e-4;
    const FD_REL: f64 = 1e-5;
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/reference/gltf_iridescence.json"
    ))
    .expect("reference file");
    let cases: Vec<Case> = serde_json::from_str(&text).expect("reference JSON");
    let mut pairs = brdf_core::DirPairs::with_capacity(64);
    for c in cases.iter().take(7) {
        pairs.push(&Vector3::from(c.wi), &Vector3::from(c.wo));
    }
    for k in 0..40 {
        let t = 0.035 * k as f64;
        let l = Vector3::new(t.sin(), 0.0, t.cos());
        let v = Vector3::new(-(0.5 * t).sin(), 0.1, (0.5 * t).cos()).normalize();
        pairs.push(&l, &v);
    }
    let n = pairs.len();
    let (mut worst, mut worst_fd): (f64, f64) = (0.0, 0.0);
    for c in cases.iter().step_by(7) {
        let nc = c.channels;
        let config = ModelConfig {
            channels: nc,
            ..ModelConfig::default()
        };
        let m = build("gltf-iridescence", &config).expect("a catalogue model");
        let np = m.n_params();
        let (mut out, mut jac) = (vec![0.0; nc * n], vec![0.0; nc * n * np]);
        m.eval_grad_batch_at(&c.params, &pairs, &mut out, &mut jac);
        let mut values = vec![0.0; nc * n];
        m.eval_batch_at(&c.params, &pairs, &mut values);
        assert_eq!(values, out, "values with and without the Jacobian");
        for j in 0..n {
            let mut f = vec![0.0; nc];
            m.eval_at(&c.params, &pairs.l(j), &pairs.v(j), &mut f);
            for ch in 0..nc {
                let gap = (out[ch * n + j] - f[ch]).abs() / f[ch].abs().max(1e-6);
                worst = worst.max(gap);
                assert!(
                    gap <= TABLE_REL,
                    "pair {j} ch {ch}: {} vs {}",
                    out[ch * n + j],
                    f[ch]
                );
            }
        }
        let (mut up, mut down) = (vec![0.0; nc * n], vec![0.0; nc * n]);
        for k in 0..np {
            let h = 1e-6 * c.params[k].abs().max(1.0);
            let (mut pu, mut pd) = (c.params.clone(), c.params.clone());
            pu[k] += h;
            pd[k] -= h;
            m.eval_batch_at(&pu, &pairs, &mut up);
            m.eval_batch_at(&pd, &pairs, &mut down);
            for r in 0..nc * n {
                let fd = (up[r] - down[r]) / (2.0 * h);
                let row = &jac[r * np..(r + 1) * np];
                let scale = row
                    .iter()
                    .fold(out[r].abs(), |s, x| s.max(x.abs()))
                    .max(1e-6);
                worst_fd = worst_fd.max((row[k] - fd).abs() / scale);
                assert!(
                    (row[k] - fd).abs() <= FD_REL * scale,
                    "row {r} d/dp{k}: {} vs {fd} at {:?}",
                    row[k],
                    c.params
                );
            }
        }
    }
    eprintln!("largest gap of the table {worst:.2e}; Jacobian against differences {worst_fd:.2e}");
}
