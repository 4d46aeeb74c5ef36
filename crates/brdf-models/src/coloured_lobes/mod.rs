//! Coloured lobes: a Lambert term and up to three GGX lobes, each with its
//! own colour and width, plus an optional white dielectric coat lobe, every
//! term of which a renderer evaluates exactly, so that hue shifting with
//! angle (highlights and rims of other hues than the body, as on films and
//! glossy paints) can be fitted and exported without approximation.
//!
//! ## Formula
//!
//! With `cos_i = N.L`, `cos_o = N.V`, `H` the unit half vector,
//! `mu = cos theta_d = V.H` and, per lobe of width `alpha`,
//! `S(alpha) = D(alpha) G(alpha) / (4 cos_i cos_o)`:
//!
//! `f_c = kd_c / pi + sum_k C_k,c(mu) S(alpha_k) + F_diel(mu; coat_ior) S(coat_alpha)`,
//!
//! `D = alpha^2 / (pi ((N.H)^2 (alpha^2 - 1) + 1)^2)` (GGX, Walter et al.
//! 2007), `Lambda(W) = (sqrt(1 + alpha^2 tan^2 theta_W) - 1) / 2`, and
//! `G` either separable, `1 / ((1 + Lambda(L)) (1 + Lambda(V)))`
//! ([`Masking::Separable`], Mitsuba 3's `roughconductor`), or
//! height-correlated, `1 / (1 + Lambda(L) + Lambda(V))`
//! ([`Masking::HeightCorrelated`], Heitz 2014; Cycles' Glossy and
//! Metallic BSDFs with the plain `GGX` distribution). The lobe's colour
//! `C_k,c(mu)` follows its [`LobeFresnel`]:
//!
//! - none: `C = ks{k}_c` (linear);
//! - F82 tint: `C = S_c(mu) - a_c mu (1 - mu)^6`, `S_c` Schlick's law from
//!   `f0{k}_c`, `a_c` chosen so the value at `mu = 1/7` is `tint{k}_c`
//!   times Schlick's (derived in [`fresnel_laws`]);
//! - conductor: the exact unpolarised reflectance of index
//!   `eta{k}_c + i kappa{k}_c` ([`brdf_core::fresnel_conductor`]).
//!
//! The coat is `F_diel S`, white, weight 1, `F_diel` the exact dielectric
//! reflectance of `coat_ior`: a plain sum with no energy coupling, which is
//! what an Add Shader (Cycles) or a sum of BSDFs shows exactly. In Mitsuba
//! and Cycles a dielectric reflection lobe is a conductor lobe with
//! `k = 0`.
//!
//! ## Parameters
//!
//! In this order; `_c` stands for the channel suffix (none for one channel,
//! `_r`, `_g`, `_b` for three):
//!
//! | parameter | meaning | box | default | linear |
//! | --- | --- | --- | --- | --- |
//! | `kd_c` | diffuse albedo | `[0, 1]` | 0.3 | yes |
//! | `ks{k}_c` (law none) | colour of lobe `k` | `[0, 1]` | 0.1 | yes (no in `-materialx`) |
//! | `f0{k}_c` (F82 tint) | reflectance at normal incidence | `[0, 1]` | 0.9 | no |
//! | `tint{k}_c` (F82 tint) | value at 82 deg over Schlick's | `[25/49, 1]` | 1 | no |
//! | `eta{k}_c` (conductor) | real part of the complex index | `[0.01, 5]` | 0.2 | no |
//! | `kappa{k}_c` (conductor) | extinction coefficient | `[0, 10]` | 3 | no |
//! | `alpha{k}` | GGX width of lobe `k` (after its colours) | `[0.002, 1]` | 0.05, 0.2, 0.5 | no |
//! | `coat_ior` (coat) | coat index of refraction | `[1.2, 2]` | 1.5 | no |
//! | `coat_alpha` (coat) | coat GGX width | `[0.002, 1]` | 0.05 | no |
//!
//! `alpha` is the distribution's own width (Mitsuba's `alpha`; Cycles'
//! Roughness is `sqrt(alpha)`). The tint's lower end `25/49` is where the
//! F82 law stops being non-negative for some `F0` ([`fresnel_laws`]).
//!
//! ## Properties
//!
//! - Reciprocal: `V.H = L.H`, and `D`, both forms of `G` and `cos_i cos_o`
//!   are symmetric in `L`, `V` (not the `-materialx` forms: their
//!   compensation depends on the first direction).
//! - Non-negative inside the box (every Fresnel law is in `[0, 1]` there);
//!   0 when either direction is on or below the horizon.
//! - Finite above the horizon: `G / cos` stays bounded near the horizon
//!   (`Lambda` grows like `1 / cos`), and `alpha >= 0.002` bounds `D`.
//! - Energy: each lobe's `S` has directional albedo at most 1 (`G` is at
//!   most `min(G1(L), G1(V))` in both forms and `D` is normalised for the
//!   projected area), so the model's albedo is at most
//!   `kd_c + sum_k max C_k,c + max F_diel`; with Fresnel law none on every
//!   lobe and no coat it conserves energy for `kd_c + sum_k ks{k}_c <= 1`.
//! - Analytic derivatives in every parameter; values and derivatives share
//!   one per-pair kernel that computes each lobe's `D` and `G` once and
//!   allocates nothing.
//! - Fit starts: [`suggested_starts`] spreads the lobes' widths apart (lobes
//!   started at one width stay equal).
//!
//! ```
//! use brdf_core::{Brdf, Parametric};
//! use brdf_models::coloured_lobes::{ColouredLobes, variant_named};
//! use nalgebra::Vector3;
//! let v = variant_named("lobes-cycles").expect("a catalogue configuration");
//! // One channel, one lobe: kd, ks1, alpha1.
//! let m = ColouredLobes::new(v, 1, 1)?.with_params(&[0.2, 0.5, 0.1])?;
//! let mut f = [0.0];
//! m.eval(&Vector3::z(), &Vector3::z(), &mut f);
//! // At the pole D = 1/(pi alpha^2), G = 1: S = 1 / (4 pi alpha^2).
//! let pi = std::f64::consts::PI;
//! let expect = 0.2 / pi + 0.5 / (4.0 * pi * 0.01);
//! assert!((f[0] - expect).abs() < 1e-12 * expect);
//! # Ok::<(), brdf_core::ParamError>(())
//! ```
//!
//! Papers: Walter, Marschner, Li & Torrance 2007, "Microfacet models for
//! refraction through rough surfaces", EGSR (GGX, separable Smith); Heitz
//! 2014, "Understanding the masking-shadowing function in microfacet-based
//! BRDFs", JCGT 3(2) (height-correlated Smith); Hoffman 2019, "Fresnel
//! equations considered harmful", EGSR workshop on material appearance
//! modeling, and Kutz, Hasan & Edmondson 2021, "Novel aspects of the Adobe
//! Standard Material" (F82 tint).
//!
//! The `-materialx` configurations multiply every term (lobes and coat)
//! by MaterialX's GGX energy compensation `1 + C (1 - E) / E`, `E` the
//! directional albedo of a white lobe seen from the first direction, by
//! MaterialX's rational fit ([`compensation`]): `C` becomes
//! `C (1 + C k)`, `k = 1/E - 1`, so a plain lobe's `ks` is not linear there,
//! and the model is not reciprocal (the first direction is the viewer's).
//! Turquin 2019, "Practical multiple scattering compensation for microfacet
//! models" (the factor).

mod batch;
pub mod compensation;
pub mod fresnel_laws;
pub mod geometry;
mod layout;
pub mod model;
pub mod starts;
pub mod variants;

pub use crate::ggx::Masking;
pub use model::{ALPHA_MIN, ColouredLobes, LobeFresnel, MAX_LOBES};
pub use starts::{CONDUCTOR_INDICES, suggested_starts};
pub use variants::{VARIANTS, Variant, build, entries, variant_named};
