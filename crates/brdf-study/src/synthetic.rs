//! Built-in synthetic data, used by `brdf reproduce` when no measured data is
//! present (and saying so): sample sets generated from known models at known
//! parameters, with a deterministic multiplicative perturbation standing in
//! for measurement noise, on a CUReT-like scattered geometry (205 direction
//! pairs) or a dense grid.
//!
//! Every set records in its provenance the model and parameters it came from,
//! so fits on it can be checked against the truth.

use brdf_core::params::channel_param_name;
use brdf_core::{Direction, Parametric, SampleSet, spherical_to_cartesian};
use brdf_models::{ModelConfig, build};

use crate::StudyError;

/// A synthetic material: the model and parameters it is generated from.
#[derive(Clone, Debug)]
pub struct SyntheticMaterial {
    /// name (as the measured material it stands in for)
    pub name: &'static str,
    /// catalogue model name
    pub model: &'static str,
    /// parameters as `(name, value)`; others take their defaults
    pub params: &'static [(&'static str, f64)],
    /// relative amplitude of the deterministic perturbation
    pub noise: f64,
}

/// Stand-ins for Kurt's five Table 9.2 materials and the two Cornell paints,
/// generated from models of the catalogue at known parameters.
pub const MATERIALS: &[SyntheticMaterial] = &[
    SyntheticMaterial {
        name: "felt (synthetic)",
        model: "ward-duer",
        params: &[("kd", 0.45), ("ks", 0.05), ("a", 0.45)],
        noise: 0.03,
    },
    SyntheticMaterial {
        name: "orange peel (synthetic)",
        model: "blinn-phong",
        params: &[("kd", 0.35), ("ks", 0.08), ("n", 29.0)],
        noise: 0.03,
    },
    SyntheticMaterial {
        name: "quarry tile (synthetic)",
        model: "ward",
        params: &[("kd", 0.3), ("ks", 0.05), ("a", 0.43)],
        noise: 0.03,
    },
    SyntheticMaterial {
        name: "slate a (synthetic)",
        model: "phong",
        params: &[("kd", 0.2), ("ks", 0.05), ("n", 5.0)],
        noise: 0.03,
    },
    SyntheticMaterial {
        name: "slate b (synthetic)",
        model: "blinn-phong",
        params: &[("kd", 0.2), ("ks", 0.06), ("n", 22.0)],
        noise: 0.03,
    },
    SyntheticMaterial {
        name: "cayman (synthetic)",
        model: "ward",
        params: &[("kd", 0.05), ("ks", 0.2), ("a", 0.08)],
        noise: 0.02,
    },
    SyntheticMaterial {
        name: "mystique (synthetic)",
        model: "ward-duer",
        params: &[("kd", 0.1), ("ks", 0.3), ("a", 0.15)],
        noise: 0.02,
    },
];

/// A deterministic value in `[-1, 1]` for index `i` (a fixed integer hash; no
/// random generator, so the data are the same on every machine).
pub fn perturbation(i: u64) -> f64 {
    let mut x = i.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ 0xD1B5_4A32_D192_ED03;
    x ^= x >> 31;
    x = x.wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x ^= x >> 27;
    (x >> 11) as f64 / (1u64 << 52) as f64 - 1.0
}

/// `n` scattered direction pairs with polar angles up to `max_theta`
/// (a fixed low-discrepancy sequence, as a stand-in for CUReT's 205
/// configurations).
pub fn scattered_pairs(n: usize, max_theta: f64) -> Vec<(Direction, Direction)> {
    let g = [
        0.754_877_666_246_692_7,
        0.569_840_290_998_053_3,
        0.430_159_709_001_946_7,
        0.245_122_333_753_307_3,
    ];
    (0..n)
        .map(|i| {
            let u: Vec<f64> = g
                .iter()
                .map(|a| (0.5 + a * (i + 1) as f64).fract())
                .collect();
            let c0 = max_theta.cos();
            let ti = (1.0 - u[0] * (1.0 - c0)).acos();
            let to = (1.0 - u[2] * (1.0 - c0)).acos();
            let l = spherical_to_cartesian(ti, u[1] * std::f64::consts::TAU);
            let v = spherical_to_cartesian(to, u[3] * std::f64::consts::TAU);
            (Direction::new_unchecked(l), Direction::new_unchecked(v))
        })
        .collect()
}

/// The model and parameters of a synthetic material, with `channels`
/// channels (per-channel parameters given without suffix apply to all).
pub fn truth(m: &SyntheticMaterial, channels: usize) -> Result<Box<dyn Parametric>, StudyError> {
    let config = ModelConfig {
        channels,
        ..ModelConfig::default()
    };
    let mut model = build(m.model, &config)?;
    let mut p: Vec<f64> = model.param_specs().iter().map(|s| s.default).collect();
    for (name, value) in m.params {
        let mut found = false;
        for (k, s) in model.param_specs().iter().enumerate() {
            let per_channel =
                (0..channels).any(|c| channel_param_name(name, c, channels) == s.name);
            if s.name == *name || per_channel {
                p[k] = *value;
                found = true;
            }
        }
        if !found {
            return Err(StudyError::Usage(format!(
                "synthetic material `{}`: model `{}` has no parameter `{name}`",
                m.name, m.model
            )));
        }
    }
    model.set_params(&p)?;
    Ok(model)
}

/// Sample a synthetic material at the given pairs, with its perturbation.
pub fn sample(
    m: &SyntheticMaterial,
    pairs: &[(Direction, Direction)],
    channels: usize,
) -> Result<SampleSet, StudyError> {
    let model = truth(m, channels)?;
    let names = if channels == 1 {
        vec!["grey".to_string()]
    } else {
        (0..channels).map(|c| format!("c{c}")).collect()
    };
    let params: Vec<String> = model
        .param_specs()
        .iter()
        .zip(model.params())
        .map(|(s, v)| format!("{}={v}", s.name))
        .collect();
    let mut set = SampleSet::new(
        m.name,
        format!(
            "synthetic: {} with {} and a deterministic multiplicative perturbation of +-{}",
            m.model,
            params.join(","),
            m.noise
        ),
        names,
    );
    let mut f = vec![0.0; channels];
    for (j, (l, v)) in pairs.iter().enumerate() {
        model.eval(l.vector(), v.vector(), &mut f);
        for (c, x) in f.iter_mut().enumerate() {
            *x *= 1.0 + m.noise * perturbation((j * channels + c) as u64);
        }
        set.push(l, v, &f, 1.0)?;
    }
    Ok(set)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn perturbation_is_deterministic_and_bounded() {
        let a: Vec<f64> = (0..1000).map(perturbation).collect();
        assert!(a.iter().all(|x| (-1.0..=1.0).contains(x)));
        let mean = a.iter().sum::<f64>() / 1000.0;
        assert!(mean.abs() < 0.1);
        assert_eq!(perturbation(17), perturbation(17));
    }

    #[test]
    fn every_material_samples_from_its_model() {
        let pairs = scattered_pairs(205, 80f64.to_radians());
        for m in MATERIALS {
            let s = sample(m, &pairs, 1).unwrap();
            assert_eq!(s.len(), 205);
            assert!(s.provenance.starts_with("synthetic"));
            assert!(s.channel(0).iter().all(|x| x.is_finite() && *x >= 0.0));
        }
    }

    #[test]
    fn scattered_pairs_respect_the_limit() {
        let p = scattered_pairs(205, 80f64.to_radians());
        assert_eq!(p.len(), 205);
        assert!(
            p.iter()
                .all(|(l, v)| l.theta() <= 80f64.to_radians() + 1e-12
                    && v.theta() <= 80f64.to_radians() + 1e-12)
        );
    }
}
