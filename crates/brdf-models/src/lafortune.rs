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
//! and for any axis weights and exponents (tested in `tests/models/energy.rs`,
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
use brdf_core::{
    DirPairs, PairGeometry, ParamError, ParamSpec, Parametric, SharedBasis, impl_brdf_via_params,
};
use nalgebra::Vector3;

use crate::combinators::{lobes_coefficient_index, pow_clamped, start_lobes_basis};

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
            let (s, ds) = lobe(cs, p[base + nc + na], &feats[..na]);
            if s == 0.0 {
                continue;
            }
            for c in 0..nc {
                out[c] += p[base + c] * s;
            }
            if let Some(g) = grad.as_deref_mut() {
                for c in 0..nc {
                    let ks = p[base + c];
                    let row = &mut g[c * np..(c + 1) * np];
                    row[base + c] = s;
                    for i in 0..=na {
                        row[base + nc + i] = ks * ds[i];
                    }
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
    fn shared_basis(&self) -> Option<&dyn SharedBasis> {
        Some(self)
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

/// Basis `[1/pi, S_1, .., S_K]` (`S_k` the normalised lobe `k` with unit
/// strength): `x_{c,0} = kd_c`, `x_{c,k} = ks{k}_c`. The lobes share every
/// channel, so a colour fit factors one basis for all channels.
impl SharedBasis for Lafortune {
    fn basis_len(&self) -> usize {
        1 + self.lobes
    }

    fn coefficient_index(&self, channel: usize, t: usize) -> usize {
        lobes_coefficient_index(self.channels, self.per_lobe(), channel, t)
    }

    fn basis_batch(
        &self,
        p: &[f64],
        pairs: &DirPairs,
        geom: &PairGeometry,
        phi: &mut [f64],
        mut dphi: Option<&mut [f64]>,
    ) {
        let (n, nc) = (pairs.len(), self.channels);
        let na = if self.aniso { 3 } else { 2 };
        // Non-linear parameters per lobe (axes and exponent), in order.
        let nql = na + 1;
        let big_q = nql * self.lobes;
        start_lobes_basis(geom, self.lobes, big_q, phi, dphi.as_deref_mut());
        for k in 0..self.lobes {
            let base = nc + k * self.per_lobe() + nc;
            let (cs, e) = (&p[base..base + na], p[base + na]);
            let t = 1 + k;
            let col = &mut phi[t * n..(t + 1) * n];
            for j in 0..n {
                let feats = if self.aniso {
                    [
                        pairs.lx[j] * pairs.vx[j],
                        pairs.ly[j] * pairs.vy[j],
                        pairs.lz[j] * pairs.vz[j],
                    ]
                } else {
                    [
                        pairs.lx[j] * pairs.vx[j] + pairs.ly[j] * pairs.vy[j],
                        pairs.lz[j] * pairs.vz[j],
                        0.0,
                    ]
                };
                let (s, ds) = if geom.valid[j] {
                    lobe(cs, e, &feats[..na])
                } else {
                    (0.0, [0.0; 4])
                };
                col[j] = s;
                if let Some(d) = dphi.as_deref_mut() {
                    for (i, dsi) in ds[..nql].iter().enumerate() {
                        d[(t * big_q + k * nql + i) * n + j] = *dsi;
                    }
                }
            }
        }
    }
}

/// One normalised lobe `(n+2)/(2 pi) max(0, C.f / max|C|)^n` at the
/// features `f` and its derivatives with respect to the axis weights `C`
/// and the exponent `n` (`[d/dC_0, .., d/dC_{na-1}, d/dn]`).
fn lobe(cs: &[f64], n: f64, feats: &[f64]) -> (f64, [f64; 4]) {
    let na = cs.len();
    let mut d = [0.0; 4];
    let (imax, m) = (0..na).fold((0, 0.0f64), |(bi, bm), i| {
        if cs[i].abs() > bm {
            (i, cs[i].abs())
        } else {
            (bi, bm)
        }
    });
    if m == 0.0 {
        return (0.0, d);
    }
    let dot: f64 = (0..na).map(|i| cs[i] * feats[i]).sum();
    let r = dot / m;
    let (pw, dpw) = pow_clamped(r, n);
    if pw == 0.0 {
        return (0.0, d);
    }
    let norm = (n + 2.0) / (2.0 * PI);
    let ds_dr = norm * n * pw / r;
    for i in 0..na {
        let mut dr = feats[i] / m;
        if i == imax {
            dr -= dot / (m * m) * cs[i].signum();
        }
        d[i] = ds_dr * dr;
    }
    d[na] = pw / (2.0 * PI) + norm * dpw;
    (norm * pw, d)
}
