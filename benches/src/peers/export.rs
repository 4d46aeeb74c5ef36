//! A peer problem and the Rust solvers' results written to a folder
//! `DIR/NAME/` for `benches/peers/peers.py`:
//!
//! | file | contents |
//! | --- | --- |
//! | `L.npy`, `V.npy` | `n x 3` directions |
//! | `values.npy` | `channels x n` measured values |
//! | `scales.npy` | `n` row scales `sqrt(w_j) cos_i_j` |
//! | `model_at_start.npy` | `channels x n` model values at the start (Rust) |
//! | `jacobian_at_start.npy` | `(channels n) x params` residual Jacobian at the start (Rust; up to 1M rows) |
//! | `meta.json` | names, model, start, box, counts |
//! | `rust_results.json` | one entry per Rust solver: final parameters, time, passes |

use std::path::{Path, PathBuf};

use brdf_solve::LeastSquaresProblem;
use serde_json::json;

use super::npy::write_f64;
use super::{Outcome, PeerError, PeerProblem, ours};

/// Rows up to which the start Jacobian is exported.
const JACOBIAN_ROWS: usize = 1_000_000;

fn write_text(path: &Path, text: &str) -> Result<(), PeerError> {
    std::fs::write(path, text).map_err(|source| PeerError::Io {
        path: path.display().to_string(),
        source,
    })
}

/// The folder of `prob` under `dir` (created).
pub fn folder(dir: &Path, prob: &PeerProblem) -> Result<PathBuf, PeerError> {
    let d = dir.join(&prob.name);
    std::fs::create_dir_all(&d).map_err(|source| PeerError::Io {
        path: d.display().to_string(),
        source,
    })?;
    Ok(d)
}

/// Write the problem's samples, rows, start, box and the Rust model at the
/// start.
pub fn problem(dir: &Path, prob: &PeerProblem) -> Result<(), PeerError> {
    let d = folder(dir, prob)?;
    let (n, nc, np) = (prob.len(), prob.channels(), prob.model.n_params());
    let p = &prob.pairs;
    let l: Vec<f64> = (0..n).flat_map(|j| [p.lx[j], p.ly[j], p.lz[j]]).collect();
    let v: Vec<f64> = (0..n).flat_map(|j| [p.vx[j], p.vy[j], p.vz[j]]).collect();
    write_f64(&d.join("L.npy"), &[n, 3], &l)?;
    write_f64(&d.join("V.npy"), &[n, 3], &v)?;
    write_f64(&d.join("values.npy"), &[nc, n], &prob.values)?;
    write_f64(&d.join("scales.npy"), &[n], &prob.scales)?;
    let mut m = vec![0.0; nc * n];
    prob.model.eval_batch_at(&prob.start, p, &mut m);
    write_f64(&d.join("model_at_start.npy"), &[nc, n], &m)?;
    if nc * n <= JACOBIAN_ROWS {
        let mp = prob.model_problem()?;
        let mut jac = vec![0.0; nc * n * np];
        mp.jacobian(&prob.start, &mut jac);
        write_f64(&d.join("jacobian_at_start.npy"), &[nc * n, np], &jac)?;
    }
    let meta = json!({
        "name": prob.name,
        "source": prob.source,
        "model": prob.model_name,
        "channels": nc,
        "samples_present": prob.samples_present,
        "samples": n,
        "limit_deg": super::problem::LIMIT_DEG,
        "param_names": prob.param_names(),
        "start": prob.start,
        "lower": prob.lower,
        "upper": prob.upper,
        "rust_cost_at_start": ours::cost(prob, &prob.start)?,
    });
    write_text(&d.join("meta.json"), &format!("{meta:#}"))
}

/// Write the Rust solvers' outcomes.
pub fn results(dir: &Path, prob: &PeerProblem, outcomes: &[Outcome]) -> Result<(), PeerError> {
    let d = folder(dir, prob)?;
    let list: Vec<_> = outcomes
        .iter()
        .map(|o| {
            json!({
                "solver": o.solver,
                "params": o.params,
                "seconds": o.seconds,
                "cpu_seconds": o.cpu_seconds,
                "repeats": o.repeats,
                "residual_evals": o.residual_evals,
                "jacobian_evals": o.jacobian_evals,
                "passes": o.passes,
                "termination": o.termination,
                "inside_box": o.inside_box,
                "own_cost": o.own_cost,
            })
        })
        .collect();
    write_text(
        &d.join("rust_results.json"),
        &format!("{:#}", serde_json::Value::Array(list)),
    )
}
