//! pbrt-v4's `mix` of a `diffuse` and a `conductor` material as a model to
//! fit, for conversions to pbrt:
//!
//! `f_c = (1 - a) R_c / pi + a S(L, V)`,
//!
//! `R_c` the diffuse reflectance per channel (`[0, 1]`, pbrt clamps it
//! there), `a` the mix amount (`[0, 1]`, one for all channels), `S` the
//! height-correlated GGX conductor lobe of `ggx-conductor` /
//! `ggx-dielectric` with `kd = 0`, `ks = 1` (its widths, `eta` and `k` keep
//! their catalogue boxes). The catalogue model `kd/pi + ks S` needs
//! `kd <= 1 - ks` with a grey `ks` to be such a mix; this model has exactly
//! the mixes pbrt can write, so a fit of it is written without loss:
//! [`PbrtMix::catalogue`] turns it into the catalogue model (`kd = (1 - a)
//! R`, `ks = a`) that [`crate::pbrt`] writes.
//!
//! | parameter | meaning | box | linear |
//! | --- | --- | --- | --- |
//! | `reflectance` (per channel) | diffuse reflectance `R` | `[0, 1]` | no |
//! | `amount` | mix amount `a` | `[0, 1]` | no |
//! | the lobe's `alpha` (or `ax`, `ay`), `eta` (, `k`) | as in [`brdf_models::ggx`] | theirs | no |
//!
//! Derivatives: central differences (the default of
//! [`brdf_core::Parametric`]).

use brdf_core::params::per_channel_specs;
use brdf_core::{ParamError, ParamSpec, Parametric};
use nalgebra::Vector3;

/// The mix model (see the module doc).
#[derive(Clone)]
pub struct PbrtMix {
    lobe: Box<dyn Parametric>,
    /// Index of the lobe's first non-linear parameter (after `kd`, `ks`).
    first: usize,
    channels: usize,
    specs: Vec<ParamSpec>,
    params: Vec<f64>,
}

impl PbrtMix {
    /// The mix with the lobe of catalogue model `lobe` (`ggx-conductor`,
    /// `ggx-dielectric` or their `-aniso` forms) and `channels` channels.
    pub fn new(lobe: &str, channels: usize) -> Result<Self, ParamError> {
        let config = brdf_models::ModelConfig {
            channels,
            ..brdf_models::ModelConfig::default()
        };
        let lobe = brdf_models::build(lobe, &config)?;
        let first = 2 * channels;
        let mut specs = per_channel_specs(
            "reflectance",
            "diffuse reflectance",
            channels,
            0.0,
            1.0,
            0.5,
        );
        specs.push(ParamSpec::new("amount", "mix amount", 0.0, 1.0, 0.5, false));
        specs.extend(lobe.param_specs()[first..].iter().cloned());
        for s in &mut specs {
            s.linear = false;
        }
        let params = specs.iter().map(|s| s.default).collect();
        Ok(PbrtMix {
            lobe,
            first,
            channels,
            specs,
            params,
        })
    }

    /// The catalogue model equal to this mix: `kd = (1 - a) R`, `ks = a`.
    pub fn catalogue(&self) -> Result<Box<dyn Parametric>, ParamError> {
        let mut m = self.lobe.clone_box();
        m.set_params(&self.lobe_params(&self.params, true))?;
        Ok(m)
    }

    /// The lobe's parameter vector: the mix's `kd`, `ks` when `mixed`, else
    /// `kd = 0`, `ks = 1` (the lobe `S` alone).
    fn lobe_params(&self, p: &[f64], mixed: bool) -> Vec<f64> {
        let nc = self.channels;
        let a = p[nc];
        let mut q = Vec::with_capacity(self.lobe.n_params());
        q.extend((0..nc).map(|c| if mixed { (1.0 - a) * p[c] } else { 0.0 }));
        q.extend((0..nc).map(|_| if mixed { a } else { 1.0 }));
        q.extend_from_slice(&p[nc + 1..]);
        debug_assert_eq!(q.len(), self.first + p.len() - nc - 1);
        q
    }
}

brdf_core::impl_brdf_via_params!(PbrtMix);

impl Parametric for PbrtMix {
    fn name(&self) -> &str {
        "pbrt-mix"
    }

    brdf_core::param_accessors!();

    fn eval_at(&self, p: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        let nc = self.channels;
        let a = p[nc];
        self.lobe.eval_at(&self.lobe_params(p, false), l, v, out);
        let above = l.z > 0.0 && v.z > 0.0;
        for c in 0..nc {
            let diffuse = if above {
                (1.0 - a) * p[c] * std::f64::consts::FRAC_1_PI
            } else {
                0.0
            };
            out[c] = diffuse + a * out[c];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use brdf_core::Brdf;

    /// The mix equals its catalogue model (`kd = (1 - a) R`, `ks = a`) at
    /// random-ish pairs.
    #[test]
    fn mix_equals_its_catalogue_model() {
        let mut m = PbrtMix::new("ggx-conductor", 3).unwrap();
        // R (3), amount, alpha, eta, k
        m.set_params(&[0.8, 0.5, 0.2, 0.3, 0.25, 1.4, 2.0]).unwrap();
        let c = m.catalogue().unwrap();
        let names: Vec<&str> = c.param_specs().iter().map(|s| s.name.as_str()).collect();
        assert_eq!(names[..6], ["kd_r", "kd_g", "kd_b", "ks_r", "ks_g", "ks_b"]);
        assert!((c.params()[0] - 0.7 * 0.8).abs() < 1e-15);
        assert!((c.params()[4] - 0.3).abs() < 1e-15);
        let (mut f, mut g) = ([0.0; 3], [0.0; 3]);
        for t in 0..20 {
            let a = t as f64 * 0.07;
            let l = Vector3::new(a.sin() * 0.6, 0.3, 1.0);
            let v = Vector3::new(-0.2, (2.0 * a).cos() * 0.5, 1.0);
            let (l, v) = (l.normalize(), v.normalize());
            m.eval(&l, &v, &mut f);
            c.eval(&l, &v, &mut g);
            for k in 0..3 {
                assert!(
                    (f[k] - g[k]).abs() <= 1e-14 * g[k].abs().max(1.0),
                    "{f:?} {g:?}"
                );
            }
        }
    }
}
