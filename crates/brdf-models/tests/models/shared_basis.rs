//! The batch kernels behind fitting ([`SharedBasis::basis_batch`]) against
//! the per-pair evaluation of the same model, for every catalogue model
//! that declares a channel-shared basis, with 1 and 3 channels and 1 and 2
//! lobes: `f_c = sum_t x_{c,t} phi_t` to rounding, and the basis
//! derivatives equal the model's own parameter derivatives
//! (`d f_c / d q_u = sum_t x_{c,t} d phi_t / d q_u`,
//! `d f_c / d x_{c,t} = phi_t`). Directions include the pole, near-grazing
//! pairs, the mirror configuration, `L = V` and pairs below the horizon
//! (where every entry must be 0).

use brdf_core::plausibility::hemisphere_directions;
use brdf_core::{DirPairs, PairGeometry};
use brdf_models::{ModelConfig, catalogue};
use nalgebra::Vector3;

fn pairs() -> DirPairs {
    let dirs = hemisphere_directions(5, 6, 1e-6);
    let mut p = DirPairs::default();
    for l in &dirs {
        for v in &dirs {
            p.push(l, v);
        }
        // The mirror direction and one below the horizon.
        p.push(l, &Vector3::new(-l.x, -l.y, l.z));
        p.push(l, &Vector3::new(0.3, 0.1, -0.5).normalize());
    }
    p
}

/// Parameters spread through the box (exponents moderate so values are
/// not all 0 and the comparison is meaningful).
fn params(model: &dyn brdf_core::Parametric) -> Vec<f64> {
    model
        .param_specs()
        .iter()
        .enumerate()
        .map(|(k, s)| {
            let t = 0.2 + 0.6 * ((k as f64 * 0.618_034) % 1.0);
            let hi = s.upper.min(60.0);
            let lo = if s.lower_open {
                s.lower + 0.05 * (hi - s.lower)
            } else {
                s.lower.max(-1.0)
            };
            lo + (hi - lo) * t
        })
        .collect()
}

#[test]
fn shared_basis_equals_per_pair_evaluation() {
    let pairs = pairs();
    let geom = PairGeometry::new(&pairs);
    let n = pairs.len();
    let mut checked = 0;
    for (channels, lobes) in [(1, 1), (3, 1), (3, 2)] {
        let config = ModelConfig {
            channels,
            lobes,
            order: 4,
            degree: 3,
        };
        for entry in catalogue() {
            let model = (entry.build)(&config).expect("catalogue models build");
            let Some(basis) = model.shared_basis() else {
                continue;
            };
            checked += 1;
            let p = params(model.as_ref());
            let (np, nc, l) = (p.len(), model.channels(), basis.basis_len());
            let nonlinear: Vec<usize> = (0..np)
                .filter(|k| !model.param_specs()[*k].linear)
                .collect();
            let nq = nonlinear.len();
            let mut phi = vec![f64::NAN; l * n];
            let mut dphi = vec![f64::NAN; l * nq * n];
            basis.basis_batch(&p, &pairs, &geom, &mut phi, Some(&mut dphi));
            let mut phi_only = vec![f64::NAN; l * n];
            basis.basis_batch(&p, &pairs, &geom, &mut phi_only, None);
            assert_eq!(phi, phi_only, "{}: value-only basis differs", entry.name);
            let mut out = vec![0.0; nc];
            let mut grad = vec![0.0; nc * np];
            for j in 0..n {
                model.eval_grad_at(&p, &pairs.l(j), &pairs.v(j), &mut out, &mut grad);
                for c in 0..nc {
                    let f: f64 = (0..l)
                        .map(|t| p[basis.coefficient_index(c, t)] * phi[t * n + j])
                        .sum();
                    let tol = 1e-12 * (1.0 + out[c].abs());
                    assert!(
                        (f - out[c]).abs() <= tol,
                        "{} ({channels} ch, {lobes} lobes) pair {j} ch {c}: basis {f} vs eval {}",
                        entry.name,
                        out[c]
                    );
                    for t in 0..l {
                        let k = basis.coefficient_index(c, t);
                        let g = grad[c * np + k];
                        assert!(
                            (phi[t * n + j] - g).abs() <= 1e-12 * (1.0 + g.abs()),
                            "{}: phi_{t} vs d f/d {}",
                            entry.name,
                            model.param_specs()[k].name
                        );
                    }
                    for (u, &k) in nonlinear.iter().enumerate() {
                        let d: f64 = (0..l)
                            .map(|t| p[basis.coefficient_index(c, t)] * dphi[(t * nq + u) * n + j])
                            .sum();
                        let g = grad[c * np + k];
                        assert!(
                            (d - g).abs() <= 1e-10 * (1.0 + g.abs()),
                            "{} pair {j} ch {c}: basis d/d{} = {d} vs model {g}",
                            entry.name,
                            model.param_specs()[k].name
                        );
                    }
                }
            }
        }
    }
    assert!(
        checked >= 20,
        "only {checked} model configurations have a shared basis"
    );
}
