//! The residual of a transformed objective (log, cube root) as the row
//! transform of a least-squares problem over all parameters, so the model
//! problem forms it in its fused blocked pass (see
//! [`crate::objective::Objective::is_transformed`]).

use brdf_core::SampleSet;
use brdf_solve::RowTransform;

use crate::objective::{Objective, cube_root_offset};

/// A residual transform `T`: the objective's residual is `T(M cos_i) -
/// T(R cos_i)`.
#[derive(Clone, Copy)]
enum Transform {
    /// `ln(1 + x)` (Matusik's log; arguments clamped at `-1 + 1e-12`).
    Log,
    /// `sqrt(w_j) cbrt(x + d)` (Forés' cube root).
    CubeRoot(f64),
}

impl Transform {
    fn value(self, x: f64) -> f64 {
        match self {
            Transform::Log => x.max(-1.0 + 1e-12).ln_1p(),
            Transform::CubeRoot(d) => (x.max(0.0) + d).cbrt(),
        }
    }

    /// `T(x)` and `T'(x)`, the cube root taken once for both (it was
    /// 4% of a default appearance fit's profile when taken twice).
    fn value_and_derivative(self, x: f64) -> (f64, f64) {
        match self {
            Transform::Log => (self.value(x), 1.0 / (1.0 + x).max(1e-12)),
            Transform::CubeRoot(d) => {
                let t = (x.max(0.0) + d).cbrt();
                (t, 1.0 / (3.0 * t * t))
            }
        }
    }
}

/// A transformed objective (log, cube root) as the row transform of a
/// least-squares problem over all parameters: residual `s_j (T(M cos_i) -
/// T(R cos_i))` with `s_j = 1` (log) or `sqrt(w_j / mean w)` (cube root),
/// so the model problem forms it in its fused blocked pass.
pub(crate) struct TransformedRows {
    transform: Transform,
    /// `cos_i` of each sample (`n` of them; row `i` is sample `i % n`).
    cos_i: Vec<f64>,
    row: Vec<f64>,
    target: Vec<f64>,
    /// The measured values (channel-major).
    values: Vec<f64>,
}

impl TransformedRows {
    pub(crate) fn new(data: &SampleSet, objective: Objective) -> Self {
        let n = data.len();
        let values = data.values_channel_major();
        let cos_i = data.pairs().lz.clone();
        let (transform, row) = match objective {
            Objective::CubeRoot => {
                let w = data.weights();
                let mean = w.iter().sum::<f64>() / n as f64;
                let row = (0..values.len())
                    .map(|i| (w[i % n] / mean).sqrt())
                    .collect();
                (Transform::CubeRoot(cube_root_offset(data)), row)
            }
            _ => (Transform::Log, vec![1.0; values.len()]),
        };
        let target = values
            .iter()
            .enumerate()
            .map(|(i, r)| row[i] * transform.value(r * cos_i[i % n]))
            .collect();
        Self {
            transform,
            cos_i,
            row,
            target,
            values,
        }
    }
}

impl RowTransform for TransformedRows {
    fn apply(&self, i: usize, m: f64) -> (f64, f64) {
        let c = self.cos_i[i % self.cos_i.len()];
        // The model value as the unit-scale residual `M - R` plus `R`, as
        // the transformed objective has always formed it (at data near
        // 1e300 the difference is what the fit has seen).
        let v = self.values[i];
        let x = ((m - v) + v) * c;
        let (t, dt) = self.transform.value_and_derivative(x);
        (self.row[i] * t - self.target[i], self.row[i] * c * dt)
    }
}
