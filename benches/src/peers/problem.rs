//! The peer problems, built from the measured data exactly as
//! `brdf fit` would see it but without a stride: RGL `paper_white` resampled
//! onto the full MERL grid (`brdf resample --to merl`), written and read
//! back as a MERL file, EVERY valid bin kept, Ngan's L2 rows
//! `sqrt(w_j) cos_i_j (M_j - R_j)` with the bins' solid-angle weights; and
//! CUReT sample 25 (unit weights). Both at the 80-degree limit.

use std::path::Path;

use brdf_core::{DirPairs, Parametric, SampleSet};
use brdf_models::{ModelConfig, build};
use brdf_solve::{Constraints, ModelProblem, StartBox, VarPro};

use super::PeerError;

/// The angle limit of Ngan and Kurt (degrees).
pub const LIMIT_DEG: f64 = 80.0;

/// One fitting problem, shared by every solver of the comparison.
pub struct PeerProblem {
    /// Short name (`paper_white_grey`, ...), also the export folder's name.
    pub name: String,
    /// Where the samples come from (relative to `BRDF_DATA`).
    pub source: String,
    /// Catalogue name of the model.
    pub model_name: String,
    /// The model (its channel count matches the data).
    pub model: Box<dyn Parametric>,
    /// Direction pairs.
    pub pairs: DirPairs,
    /// Measured values, channel-major (`values[c * n + j]`).
    pub values: Vec<f64>,
    /// Row scales `sqrt(w_j) cos_i_j`.
    pub scales: Vec<f64>,
    /// Samples before the angle limit (valid bins / table rows).
    pub samples_present: usize,
    /// The start of every solver (full parameter vector).
    pub start: Vec<f64>,
    /// Box lower ends.
    pub lower: Vec<f64>,
    /// Box upper ends.
    pub upper: Vec<f64>,
}

impl PeerProblem {
    /// Number of samples (rows per channel).
    pub fn len(&self) -> usize {
        self.pairs.len()
    }

    /// True without samples (never for a built problem).
    pub fn is_empty(&self) -> bool {
        self.pairs.is_empty()
    }

    /// Channels of the model and the data.
    pub fn channels(&self) -> usize {
        self.model.channels()
    }

    /// The least-squares problem over every parameter.
    pub fn model_problem(&self) -> Result<ModelProblem<'_>, PeerError> {
        Ok(ModelProblem::new(
            self.model.as_ref(),
            &self.pairs,
            &self.values,
            &self.scales,
        )?)
    }

    /// The box of every parameter.
    pub fn constraints(&self) -> Result<Constraints, PeerError> {
        Ok(Constraints::boxed(self.lower.clone(), self.upper.clone())?)
    }

    /// Whether `p` lies in the box (within 1e-12 of its width).
    pub fn inside_box(&self, p: &[f64]) -> bool {
        p.iter().enumerate().all(|(k, x)| {
            let tol = 1e-12 * (self.upper[k] - self.lower[k]).abs().max(1.0);
            x.is_finite() && *x >= self.lower[k] - tol && *x <= self.upper[k] + tol
        })
    }

    /// Parameter names in vector order.
    pub fn param_names(&self) -> Vec<String> {
        self.model
            .param_specs()
            .iter()
            .map(|s| s.name.clone())
            .collect()
    }
}

/// `paper_white` on the full MERL grid, grey (`channels = 1`, the mean of
/// R, G, B) or RGB (`channels = 3`). The MERL table is written to
/// `scratch/paper_white.binary` and read back, as `brdf resample` and
/// `brdf fit --data X.binary#1` would.
pub fn paper_white(
    data: &Path,
    scratch: &Path,
    channels: usize,
    model_name: &str,
) -> Result<PeerProblem, PeerError> {
    let rel = "rgl/paper_white_rgb.bsdf";
    let merl_path = scratch.join("paper_white.binary");
    if !merl_path.exists() {
        let rgl = brdf_io::rgl::Rgl::read(&data.join(rel))?;
        brdf_io::merl::write(&merl_path, &brdf_io::merl::Merl::resample(&rgl))?;
    }
    let merl = brdf_io::merl::read(&merl_path)?;
    let (set, _invalid) = merl.to_samples("merl#paper_white", 1);
    let set = if channels == 1 {
        set.mean_channel()
    } else {
        set
    };
    let kind = if channels == 1 { "grey" } else { "rgb" };
    let source =
        format!("$BRDF_DATA/{rel} resampled onto the full MERL grid (every valid bin), {kind}");
    assemble(
        &format!("paper_white_{kind}_{}", short(model_name)),
        source,
        set,
        model_name,
    )
}

/// CUReT material `sample` (grey, unit weights).
pub fn curet(data: &Path, sample: u32, model_name: &str) -> Result<PeerProblem, PeerError> {
    let dir = data.join("curet");
    let sets = brdf_io::curet::read_grey(&dir.join("abrdf.dat"), &dir.join("table.txt"))?;
    let prefix = format!("curet#{sample} ");
    let set = sets
        .into_iter()
        .find(|s| s.name.starts_with(&prefix))
        .ok_or_else(|| PeerError::Missing(format!("CUReT sample {sample} in curet/abrdf.dat")))?;
    assemble(
        &format!("curet{sample}_{}", short(model_name)),
        format!("$BRDF_DATA/curet/abrdf.dat sample {sample} (grey, unit weights)"),
        set,
        model_name,
    )
}

fn short(model_name: &str) -> String {
    match model_name {
        "ashikhmin-shirley" => "as".into(),
        "cook-torrance" => "ct".into(),
        other => other.replace('-', "_"),
    }
}

/// Limit, rows, model, box and start for a sample set.
fn assemble(
    name: &str,
    source: String,
    set: SampleSet,
    model_name: &str,
) -> Result<PeerProblem, PeerError> {
    let samples_present = set.len();
    let (set, _) = set.filter_invalid(false);
    let (set, _) = set.filter_angle_limit(LIMIT_DEG.to_radians());
    let model = build(
        model_name,
        &ModelConfig {
            channels: set.channels(),
            ..ModelConfig::default()
        },
    )?;
    let p = set.pairs();
    let w = set.weights();
    let scales: Vec<f64> = (0..set.len()).map(|j| w[j].sqrt() * p.lz[j]).collect();
    let specs = model.param_specs();
    let lower: Vec<f64> = specs
        .iter()
        .map(|s| {
            if s.lower_open {
                s.lower + 1e-9 * (s.upper - s.lower).min(1.0)
            } else {
                s.lower
            }
        })
        .collect();
    let upper: Vec<f64> = specs.iter().map(|s| s.upper).collect();
    let mut prob = PeerProblem {
        name: name.into(),
        source,
        model_name: model_name.into(),
        model,
        pairs: p.clone(),
        values: set.values_channel_major(),
        scales,
        samples_present,
        start: Vec::new(),
        lower,
        upper,
    };
    prob.start = first_start(&prob)?;
    Ok(prob)
}

/// The start `brdf fit --starts 1` uses: the first Halton point of the
/// pipeline's start box for the non-linear parameters (exponents on a log
/// scale over `[1, 1e4]`, open-below parameters on a log scale over
/// `[1e-3 upper, upper]`, the rest linearly over the box), the linear ones
/// projected by NNLS, then clamped into the box.
fn first_start(prob: &PeerProblem) -> Result<Vec<f64>, PeerError> {
    let mp = prob.model_problem()?;
    let specs = prob.model.param_specs();
    let mut sb = StartBox {
        lower: Vec::new(),
        upper: Vec::new(),
        log_scale: Vec::new(),
    };
    for k in mp.nonlinear_indices() {
        let s = &specs[*k];
        let (lo, hi, log) = if s.upper >= 1e3 {
            (s.lower.max(1.0), s.upper.min(1e4), true)
        } else if s.lower_open && s.lower == 0.0 {
            (1e-3 * s.upper, s.upper, true)
        } else {
            let lo = if s.lower.is_finite() { s.lower } else { -1.0 };
            let hi = if s.upper.is_finite() {
                s.upper
            } else {
                lo + 2.0
            };
            let lo = if s.lower_open {
                lo + 1e-3 * (hi - lo)
            } else {
                lo
            };
            (lo, hi, false)
        };
        sb.lower.push(lo);
        sb.upper.push(hi);
        sb.log_scale.push(log);
    }
    let a = sb.starts(1)?.remove(0);
    let c = VarPro::new(&mp, true).linear_coefficients(&a)?;
    let mut p = mp.assemble(&a, &c);
    prob.constraints()?.clamp(&mut p);
    Ok(p)
}
