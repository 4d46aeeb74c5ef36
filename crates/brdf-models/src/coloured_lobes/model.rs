//! The coloured-lobe model itself: its parameter layout and the per-pair
//! kernel shared by values and derivatives.

use std::f64::consts::FRAC_1_PI;

use brdf_core::fresnel::fresnel_dielectric_d_eta;
use brdf_core::fresnel_conductor::{fresnel_conductor, fresnel_conductor_grad};
use brdf_core::params::per_channel_specs;
use brdf_core::{DirPairs, ParamError, ParamSpec, Parametric};
use nalgebra::Vector3;

use super::batch::{Batch, View};
use super::compensation;
use super::fresnel_laws::{F82_TINT_MIN, f82_tint};
use super::geometry::LobeGeometry;
pub use super::layout::LobeFresnel;
use super::layout::{LobeLayout, weighted};
use crate::ggx::Masking;

/// Most GGX lobes a model may have.
pub const MAX_LOBES: usize = 3;

/// Lower end of every GGX width box: narrower lobes than this are below
/// what a measured BRDF resolves and make `D` at the pole `1/(pi alpha^2)`
/// dwarf every other sample.
pub const ALPHA_MIN: f64 = 0.002;

/// Lambert plus `K` coloured isotropic GGX lobes plus an optional white
/// dielectric coat lobe (see the module documentation of
/// [`crate::coloured_lobes`]).
#[derive(Clone, Debug, PartialEq)]
pub struct ColouredLobes {
    name: &'static str,
    pub(super) channels: usize,
    pub(super) masking: Masking,
    pub(super) lobes: Vec<LobeLayout>,
    /// Index of `coat_ior` (`coat_alpha` follows), if there is a coat.
    pub(super) coat: Option<usize>,
    /// Whether every lobe carries MaterialX's energy compensation
    /// ([`compensation`]).
    pub(super) compensated: bool,
    pub(super) specs: Vec<ParamSpec>,
    params: Vec<f64>,
}

fn alpha_spec(k: usize, default: f64) -> ParamSpec {
    ParamSpec::new(
        format!("alpha{k}"),
        format!("GGX width of lobe {k}"),
        ALPHA_MIN,
        1.0,
        default,
        false,
    )
}

/// The per-channel parameters of lobe `k` under its Fresnel law: its
/// colour `ks{k}` (none), `f0{k}` and `tint{k}` (F82 tint) or `eta{k}` and
/// `kappa{k}` (conductor).
fn fresnel_specs(k: usize, fresnel: LobeFresnel, nc: usize) -> Vec<ParamSpec> {
    let mut out = Vec::with_capacity(2 * nc);
    match fresnel {
        LobeFresnel::None => out.extend(per_channel_specs(
            &format!("ks{k}"),
            &format!("colour of lobe {k}"),
            nc,
            0.0,
            1.0,
            0.1,
        )),
        LobeFresnel::F82Tint => {
            out.extend(non_linear(per_channel_specs(
                &format!("f0{k}"),
                &format!("lobe {k} reflectance at normal incidence"),
                nc,
                0.0,
                1.0,
                0.9,
            )));
            out.extend(non_linear(per_channel_specs(
                &format!("tint{k}"),
                &format!("lobe {k} tint at 82 deg (times Schlick's value)"),
                nc,
                F82_TINT_MIN,
                1.0,
                1.0,
            )));
        }
        LobeFresnel::Conductor => {
            out.extend(non_linear(per_channel_specs(
                &format!("eta{k}"),
                &format!("lobe {k} real part of the complex index"),
                nc,
                0.01,
                5.0,
                0.2,
            )));
            out.extend(non_linear(per_channel_specs(
                &format!("kappa{k}"),
                &format!("lobe {k} extinction coefficient"),
                nc,
                0.0,
                10.0,
                3.0,
            )));
        }
    }
    out
}

fn non_linear(mut s: Vec<ParamSpec>) -> Vec<ParamSpec> {
    s.iter_mut().for_each(|p| p.linear = false);
    s
}

impl ColouredLobes {
    /// A model named `name` (the name it reports and is saved under) with
    /// the given masking, one GGX lobe per entry of `fresnels` (1 to
    /// [`MAX_LOBES`]), a coat lobe if `coat`, and `channels` colour channels,
    /// at its default parameters.
    pub fn custom(
        name: &'static str,
        masking: Masking,
        fresnels: &[LobeFresnel],
        coat: bool,
        channels: usize,
    ) -> Result<Self, ParamError> {
        let config = |reason: String| ParamError::Config {
            model: name.to_string(),
            reason,
        };
        if channels == 0 {
            return Err(config("needs at least one colour channel".into()));
        }
        if fresnels.is_empty() || fresnels.len() > MAX_LOBES {
            return Err(config(format!(
                "takes 1 to {MAX_LOBES} GGX lobes, not {}",
                fresnels.len()
            )));
        }
        let nc = channels;
        let mut specs = per_channel_specs("kd", "diffuse albedo", nc, 0.0, 1.0, 0.3);
        let mut lobes = Vec::with_capacity(fresnels.len());
        // Distinct default widths, so lobes start apart rather than as
        // copies of one another (a fit from copies cannot separate them).
        let widths = [0.05, 0.2, 0.5];
        for (i, &fresnel) in fresnels.iter().enumerate() {
            let k = i + 1;
            let start = specs.len();
            specs.extend(fresnel_specs(k, fresnel, nc));
            let alpha = specs.len();
            specs.push(alpha_spec(k, widths[i]));
            lobes.push(LobeLayout {
                fresnel,
                start,
                alpha,
            });
        }
        let coat = coat.then(|| {
            let at = specs.len();
            specs.push(ParamSpec::new(
                "coat_ior",
                "index of refraction of the coat",
                1.2,
                2.0,
                1.5,
                false,
            ));
            specs.push(ParamSpec::new(
                "coat_alpha",
                "GGX width of the coat",
                ALPHA_MIN,
                1.0,
                0.05,
                false,
            ));
            at
        });
        let params = specs.iter().map(|s| s.default).collect();
        Ok(ColouredLobes {
            name,
            channels,
            masking,
            lobes,
            coat,
            compensated: false,
            specs,
            params,
        })
    }

    /// The model with MaterialX's GGX energy compensation on every lobe and
    /// the coat ([`compensation`]): each term's Fresnel `F` becomes
    /// `F (1 + F k)`, so plain lobes' colours are no longer linear.
    pub fn compensated(mut self) -> Self {
        self.compensated = true;
        for l in &self.lobes {
            if l.fresnel == LobeFresnel::None {
                for s in &mut self.specs[l.start..l.alpha] {
                    s.linear = false;
                }
            }
        }
        self
    }

    /// Whether the lobes carry MaterialX's energy compensation.
    pub fn is_compensated(&self) -> bool {
        self.compensated
    }

    /// The model with parameters `p` (checked against the box).
    pub fn with_params(mut self, p: &[f64]) -> Result<Self, ParamError> {
        self.set_params(p)?;
        Ok(self)
    }

    /// The masking form of every lobe (and the coat).
    pub fn masking(&self) -> Masking {
        self.masking
    }

    /// The Fresnel law of each GGX lobe, in order.
    pub fn fresnels(&self) -> Vec<LobeFresnel> {
        self.lobes.iter().map(|l| l.fresnel).collect()
    }

    /// What the batch kernel reads of the model.
    fn view(&self) -> View<'_> {
        View {
            channels: self.channels,
            np: self.specs.len(),
            masking: self.masking,
            lobes: &self.lobes,
            coat: self.coat,
            compensated: self.compensated,
        }
    }

    /// Whether the model has the dielectric coat lobe.
    pub fn has_coat(&self) -> bool {
        self.coat.is_some()
    }

    /// The per-pair kernel: channel `c`'s value into `out[c * os]` and,
    /// with `grad = Some((g, gs))`, its gradient into `g[c * gs..c * gs + np]`
    /// (strides let the batch write straight into its channel-major
    /// layout). 0 (and a zero gradient) below the horizon.
    #[inline]
    fn kernel(
        &self,
        p: &[f64],
        l: &Vector3<f64>,
        v: &Vector3<f64>,
        (out, os): (&mut [f64], usize),
        mut grad: Option<(&mut [f64], usize)>,
    ) {
        let (nc, np) = (self.channels, self.specs.len());
        if let Some((g, gs)) = grad.as_mut() {
            for c in 0..nc {
                g[c * *gs..c * *gs + np].fill(0.0);
            }
        }
        let Some(geo) = LobeGeometry::new(l, v) else {
            for c in 0..nc {
                out[c * os] = 0.0;
            }
            return;
        };
        for c in 0..nc {
            out[c * os] = p[c] * FRAC_1_PI;
            if let Some((g, gs)) = grad.as_mut() {
                g[c * *gs + c] = FRAC_1_PI;
            }
        }
        let mu = geo.cos_d;
        let derivatives = grad.is_some();
        for lobe in &self.lobes {
            let alpha = p[lobe.alpha];
            let (s, ds) = geo.lobe(alpha, self.masking);
            let k = self.excess(&geo, alpha);
            let (a, b) = (lobe.start, lobe.start + nc);
            for c in 0..nc {
                // Value F s and the derivatives of F in its (up to two)
                // channel parameters.
                let (f, d1, d2) = match lobe.fresnel {
                    LobeFresnel::None => (p[a + c], 1.0, 0.0),
                    LobeFresnel::F82Tint => f82_tint(p[a + c], p[b + c], mu),
                    // Trial points and renders need the value alone.
                    LobeFresnel::Conductor if derivatives => {
                        fresnel_conductor_grad(mu, p[a + c], p[b + c])
                    }
                    LobeFresnel::Conductor => (fresnel_conductor(mu, p[a + c], p[b + c]), 0.0, 0.0),
                };
                let (w, dw_df, dw_da) = weighted(f, k);
                out[c * os] += w * s;
                if let Some((g, gs)) = grad.as_mut() {
                    let row = &mut g[c * *gs..c * *gs + np];
                    row[a + c] = d1 * dw_df * s;
                    if lobe.fresnel != LobeFresnel::None {
                        row[b + c] = d2 * dw_df * s;
                    }
                    row[lobe.alpha] = w * ds + dw_da * s;
                }
            }
        }
        if let Some(at) = self.coat {
            let alpha = p[at + 1];
            let (s, ds) = geo.lobe(alpha, self.masking);
            let (f, df) = fresnel_dielectric_d_eta(mu, p[at]);
            let (w, dw_df, dw_da) = weighted(f, self.excess(&geo, alpha));
            for c in 0..nc {
                out[c * os] += w * s;
                if let Some((g, gs)) = grad.as_mut() {
                    g[c * *gs + at] = df * dw_df * s;
                    g[c * *gs + at + 1] = w * ds + dw_da * s;
                }
            }
        }
    }

    /// MaterialX's `(k, dk/d alpha)` for a lobe of width `alpha` at this
    /// pair, `(0, 0)` without compensation.
    #[inline]
    fn excess(&self, geo: &LobeGeometry, alpha: f64) -> (f64, f64) {
        compensation::excess_if(self.compensated, geo.cos_first, alpha)
    }
}

brdf_core::impl_brdf_via_params!(ColouredLobes);

impl Parametric for ColouredLobes {
    fn name(&self) -> &str {
        self.name
    }

    brdf_core::param_accessors!();

    fn is_reciprocal(&self) -> bool {
        // The compensation depends on the first direction alone.
        !self.compensated
    }

    fn eval_at(&self, p: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        self.kernel(p, l, v, (out, 1), None);
    }

    fn eval_grad_at(
        &self,
        p: &[f64],
        l: &Vector3<f64>,
        v: &Vector3<f64>,
        out: &mut [f64],
        grad: &mut [f64],
    ) {
        let np = self.specs.len();
        self.kernel(p, l, v, (out, 1), Some((grad, np)));
    }

    fn eval_batch_at(&self, p: &[f64], pairs: &DirPairs, out: &mut [f64]) {
        pulp::Arch::new().dispatch(Batch {
            view: self.view(),
            p,
            pairs,
            out,
            jac: None,
        });
    }

    fn eval_grad_batch_at(&self, p: &[f64], pairs: &DirPairs, out: &mut [f64], jac: &mut [f64]) {
        // Layout: out[c * n + j], jac[(c * n + j) * np + k].
        pulp::Arch::new().dispatch(Batch {
            view: self.view(),
            p,
            pairs,
            out,
            jac: Some(jac),
        });
    }
}
