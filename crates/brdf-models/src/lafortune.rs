//! Lafortune et al. (1997, "Non-linear approximation of reflectance
//! functions", SIGGRAPH): a Lambertian term plus `K` generalised cosine lobes,
//! isotropic and anisotropic.
//!
//! isotropic lobe: `ks (n+2) / (2 pi max(|Cxy|,|Cz|)^n) * max(0, Cxy (ux vx + uy vy) + Cz uz vz)^n`
//!
//! anisotropic lobe: `Cx ux vx + Cy uy vy + Cz uz vz`, normaliser `max(|Cx|,|Cy|,|Cz|)^n`
//!
//! `f = kd/pi + sum_k lobe_k`. `-Cxy = Cz` gives a Phong lobe around the
//! mirror direction, `-Cxy > Cz > 0` off-specular peaks towards grazing, all
//! `C` positive retro-reflection.
//!
//! | parameter | meaning | default box | linear |
//! | --- | --- | --- | --- |
//! | `kd` (per channel) | diffuse albedo | `[0, 1]` | yes |
//! | `ks1`, `ks2`, ... (per channel) | lobe strength | `[0, 1]` | yes |
//! | `cxy1`, `cz1` (iso) / `cx1`, `cy1`, `cz1` (aniso), ... | lobe axis weights | `[-1, 1]` | no |
//! | `n1`, `n2`, ... | lobe exponents | `[0, 1e6]` | no |
//!
//! Properties: reciprocal (the lobe is symmetric in `u` and `v`);
//! non-negative. The normalised base `r = C.(u*v)/max|C|` satisfies
//! `r <= |ux vx + uy vy| + |uz vz| <= 1` (Cauchy-Schwarz), so powers never
//! overflow. Energy: the normalised lobe is a cosine power of `u` against a
//! vector of length at most 1, so it is bounded by a Phong lobe and the
//! albedo stays at most 1 for `kd + sum_k ks_k <= 1` at every incidence
//! and for any axis weights and exponents (tested in `tests/energy.rs`,
//! including retro-reflective and off-specular lobes; the bound is reached
//! at normal incidence by `-Cxy = Cz`).
//!
//! ```
//! use brdf_core::Brdf;
//! use brdf_models::Lafortune;
//! use nalgebra::Vector3;
//! // One Phong-like lobe (-Cxy = Cz = 1, n = 2) at normal incidence, kd = 0.
//! let m = Lafortune::new(false, 1, 1).unwrap();
//! let mut m = m;
//! brdf_core::Parametric::set_params(&mut m, &[0.0, 1.0, -1.0, 1.0, 2.0]).unwrap();
//! let mut f = [0.0];
//! m.eval(&Vector3::z(), &Vector3::z(), &mut f);
//! assert!((f[0] - 4.0 / (2.0 * std::f64::consts::PI)).abs() < 1e-15);
//! ```

use std::f64::consts::{FRAC_1_PI, PI};

use brdf_core::params::per_channel_specs;
use brdf_core::{ParamError, ParamSpec, Parametric, impl_brdf_via_params};
use nalgebra::Vector3;

use crate::combinators::pow_clamped;

/// Lafortune's model with `K` lobes (isotropic or anisotropic).
#[derive(Clone, Debug, PartialEq)]
pub struct Lafortune {
    channels: usize,
    lobes: usize,
    aniso: bool,
    specs: Vec<ParamSpec>,
    params: Vec<f64>,
}

impl Lafortune {
    /// Name in the catalogue (isotropic).
    pub const NAME: &'static str = "lafortune";
    /// Name in the catalogue (anisotropic).
    pub const NAME_ANISO: &'static str = "lafortune-aniso";

    /// A model with `lobes >= 1` lobes at default parameters (a Phong-like
    /// lobe `-Cxy = Cz`).
    pub fn new(aniso: bool, lobes: usize, channels: usize) -> Result<Self, ParamError> {
        let name = if aniso { Self::NAME_ANISO } else { Self::NAME };
        if channels == 0 || lobes == 0 {
            return Err(ParamError::Config {
                model: name.into(),
                reason: "a model needs at least one channel and one lobe".into(),
            });
        }
        let mut specs = per_channel_specs("kd", "diffuse albedo", channels, 0.0, 1.0, 0.3);
        for k in 1..=lobes {
            specs.extend(per_channel_specs(
                &format!("ks{k}"),
                &format!("strength of lobe {k}"),
                channels,
                0.0,
                1.0,
                0.2,
            ));
            let axes: &[(&str, f64)] = if aniso {
                &[("cx", -0.7), ("cy", -0.7), ("cz", 0.7)]
            } else {
                &[("cxy", -0.7), ("cz", 0.7)]
            };
            for (a, d) in axes {
                specs.push(ParamSpec::new(
                    format!("{a}{k}"),
                    format!("axis weight {a} of lobe {k}"),
                    -1.0,
                    1.0,
                    *d,
                    false,
                ));
            }
            specs.push(ParamSpec::new(
                format!("n{k}"),
                format!("exponent of lobe {k}"),
                0.0,
                1e6,
                10.0,
                false,
            ));
        }
        let params = specs.iter().map(|s| s.default).collect();
        Ok(Lafortune {
            channels,
            lobes,
            aniso,
            specs,
            params,
        })
    }

    fn per_lobe(&self) -> usize {
        self.channels + if self.aniso { 4 } else { 3 }
    }

    fn value_grad(
        &self,
        p: &[f64],
        l: &Vector3<f64>,
        v: &Vector3<f64>,
        out: &mut [f64],
        mut grad: Option<&mut [f64]>,
    ) {
        let nc = self.channels;
        let np = self.specs.len();
        if let Some(g) = grad.as_deref_mut() {
            g[..nc * np].iter_mut().for_each(|x| *x = 0.0);
        }
        if !(l.z > 0.0 && v.z > 0.0) {
            out[..nc].iter_mut().for_each(|x| *x = 0.0);
            return;
        }
        for c in 0..nc {
            out[c] = p[c] * FRAC_1_PI;
            if let Some(g) = grad.as_deref_mut() {
                g[c * np + c] = FRAC_1_PI;
            }
        }
        let na = if self.aniso { 3 } else { 2 };
        let feats: [f64; 3] = if self.aniso {
            [l.x * v.x, l.y * v.y, l.z * v.z]
        } else {
            [l.x * v.x + l.y * v.y, l.z * v.z, 0.0]
        };
        for k in 0..self.lobes {
            let base = nc + k * self.per_lobe();
            let cs = &p[base + nc..base + nc + na];
            let n = p[base + nc + na];
            let (imax, m) = (0..na).fold((0, 0.0f64), |(bi, bm), i| {
                if cs[i].abs() > bm {
                    (i, cs[i].abs())
                } else {
                    (bi, bm)
                }
            });
            if m == 0.0 {
                continue;
            }
            let d: f64 = (0..na).map(|i| cs[i] * feats[i]).sum();
            let r = d / m;
            let (pw, dpw) = pow_clamped(r, n);
            if pw == 0.0 {
                continue;
            }
            let norm = (n + 2.0) / (2.0 * PI);
            let s = norm * pw;
            for c in 0..nc {
                out[c] += p[base + c] * s;
            }
            if let Some(g) = grad.as_deref_mut() {
                // dS/dr = norm n r^(n-1) = norm n pw / r (r > 0 here).
                let ds_dr = norm * n * pw / r;
                let ds_dn = pw / (2.0 * PI) + norm * dpw;
                for c in 0..nc {
                    let ks = p[base + c];
                    let row = &mut g[c * np..(c + 1) * np];
                    row[base + c] = s;
                    for i in 0..na {
                        // r = d/m: dr/dC_i = f_i/m - d/m^2 dm/dC_i, dm/dC_i = sign(C_i) for the max.
                        let mut dr = feats[i] / m;
                        if i == imax {
                            dr -= d / (m * m) * cs[i].signum();
                        }
                        row[base + nc + i] = ks * ds_dr * dr;
                    }
                    row[base + nc + na] = ks * ds_dn;
                }
            }
        }
    }
}

impl Parametric for Lafortune {
    brdf_core::param_accessors!();
    fn name(&self) -> &str {
        if self.aniso {
            Self::NAME_ANISO
        } else {
            Self::NAME
        }
    }
    fn eval_at(&self, p: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        self.value_grad(p, l, v, out, None);
    }
    fn eval_grad_at(
        &self,
        p: &[f64],
        l: &Vector3<f64>,
        v: &Vector3<f64>,
        out: &mut [f64],
        grad: &mut [f64],
    ) {
        self.value_grad(p, l, v, out, Some(grad));
    }
}

impl_brdf_via_params!(Lafortune);
