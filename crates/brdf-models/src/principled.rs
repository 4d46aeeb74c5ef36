//! The Disney principled BRDF (Burley 2012, "Physically-based shading at
//! Disney", SIGGRAPH course notes; Burley 2015, "Extending the Disney BRDF to
//! a BSDF with integrated subsurface scattering"), reflection part, exactly
//! as Mitsuba 3's `principled` BSDF evaluates it (`src/bsdfs/principled.cpp`,
//! `principledhelpers.h`) with `spec_trans = 0` and `flatness = 0`.
//!
//! With `H = (L + V)/|L + V|`, `w(c) = (1 - c)^5`, `cos_d = V.H`, `m` =
//! metallic, `st` = spec_tint, `lum` the luminance of the base colour `C`
//! (`0.212671 r + 0.715160 g + 0.072169 b`; the grey value for one channel),
//! `C_tint = C / lum` (1 if `lum = 0`):
//!
//! - specular: `eta = 2 / (1 - sqrt(0.08 specular)) - 1`, `R0 = 0.08 specular`;
//!   `ax = max(0.001, r^2 / a)`, `ay = max(0.001, r^2 a)`, `a = sqrt(1 - 0.9 anisotropic)`;
//!   `F = (1 - m)(1 - st) F_dielectric(cos_d; eta) + m Schlick(C; cos_d)
//!   + (1 - m) st Schlick(C_tint R0; cos_d)`; `f_s = F D G / (4 N.L N.V)` with
//!   GGX `D` and the separable Smith `G` ([`crate::ggx`]); 0 when
//!   `F_dielectric = 0` (Mitsuba's `F_spec_dielectric > 0` mask);
//! - diffuse: `(1 - m) C/pi [(1 - w_L/2)(1 - w_V/2) + R_R (w_L + w_V + w_L w_V (R_R - 1))]`,
//!   `R_R = 2 roughness cos_d^2`, `w_L = w(N.L)`, `w_V = w(N.V)`;
//! - sheen: `sheen (1 - m) w(cos_d) (1 + sheen_tint (C_tint - 1))`;
//! - clearcoat: `clearcoat / 4 * Schlick(0.04; cos_d) D_GTR1(H; a_c) G1(L) G1(V)`,
//!   `a_c = 0.1 + (0.001 - 0.1) clearcoat_gloss`,
//!   `D_GTR1 = (a_c^2 - 1) / (pi ln(a_c^2) (1 + (a_c^2 - 1) (N.H)^2))`, `G1`
//!   separable GGX Smith with `alpha = 0.25`.
//!
//! Where Mitsuba differs from Burley's 2012 notes (and this model follows
//! Mitsuba): the untinted dielectric part of `F` is the exact dielectric
//! Fresnel for `eta(specular)`, not Schlick with `F0 = 0.08 specular`; the
//! main lobe's `G` uses the same `alpha` as `D` (Burley 2012 remapped it to
//! `(0.5 + roughness/2)^2`); the clearcoat lobe has no `1 / (4 N.L N.V)`
//! factor (Mitsuba's value is `clearcoat/4 F D G cos_o`), and its `G` uses
//! GGX Smith with `alpha = 0.25` as Burley's code does; the diffuse lobe is
//! Burley 2015's form (algebraically Burley 2012's `F_D90` product).
//!
//! | parameter | meaning | default box | default | linear |
//! | --- | --- | --- | --- | --- |
//! | `base_color` (per channel, linear sRGB) | base colour `C` | `[0, 1]` | 0.5 | no |
//! | `metallic` | metal weight | `[0, 1]` | 0 | no |
//! | `specular` | dielectric reflectance (0.5 = 4 %) | `(0, 1]` | 0.5 | no |
//! | `spec_tint` | tint of the dielectric lobe towards `C` | `[0, 1]` | 0 | no |
//! | `roughness` | perceptual roughness (`alpha = roughness^2`) | `[0, 1]` | 0.5 | no |
//! | `anisotropic` | anisotropy | `[0, 1]` | 0 | no |
//! | `sheen` | sheen strength | `[0, 1]` | 0 | no |
//! | `sheen_tint` | tint of the sheen towards `C` | `[0, 1]` | 0 | no |
//! | `clearcoat` | clear-coat strength | `[0, 1]` | 0 | no |
//! | `clearcoat_gloss` | clear-coat glossiness | `[0, 1]` | 0 | no |
//!
//! No parameter is flagged linear: the colour enters through `C / lum` and
//! `sheen`, `clearcoat` are added to a non-zero base. Derivatives are exact
//! (forward-mode duals, [`crate::dual`], at single points; the batch kernel
//! the fits call has the same derivatives written out, with the
//! parameter-only factors computed once per batch); they are 0 where
//! `max(0.001, .)` clamps the widths (`roughness < 0.032`).
//!
//! Properties: reciprocal; non-negative; finite above the horizon. Not
//! energy conserving on the whole box: the retro-reflective diffuse term
//! exceeds albedo 1 at grazing incidence for bright rough bases; the domain
//! found by `tests/models/renderer_models.rs` is stated there.
//!
//! ```
//! use brdf_core::Brdf;
//! use brdf_models::Principled;
//! use nalgebra::Vector3;
//! // base_color, metallic, specular, spec_tint, roughness, anisotropic,
//! // sheen, sheen_tint, clearcoat, clearcoat_gloss
//! let m = Principled::new(1, &[0.8, 1.0, 0.5, 0.0, 0.5, 0.0, 0.0, 0.0, 0.0, 0.0]).unwrap();
//! let mut f = [0.0];
//! m.eval(&Vector3::z(), &Vector3::z(), &mut f);
//! // A metal at the pole: F = C, D = 1/(pi alpha^2), G = 1, alpha = 0.25.
//! let expect = 0.8 / (4.0 * std::f64::consts::PI * 0.0625);
//! assert!((f[0] - expect).abs() < 1e-10 * expect);
//! ```

pub(crate) mod kernel;

use std::f64::consts::{FRAC_1_PI, PI};

use brdf_core::fresnel::fresnel_dielectric_d_eta;
use brdf_core::params::per_channel_specs;
use brdf_core::{DirPairs, ParamSpec};
use nalgebra::Vector3;

use crate::dual::Dual;
use crate::dual_model::{DualFormula, DualModel};
use crate::ggx::{Masking, ggx_specular, smith_lambda};

/// `(1 - c)^5` with `c` clipped to `[0, 1]` (Mitsuba's `schlick_weight`).
#[inline(always)]
pub(crate) fn schlick_weight(c: f64) -> f64 {
    let m = (1.0 - c).clamp(0.0, 1.0);
    let m2 = m * m;
    m2 * m2 * m
}

/// Luminance of a colour: Rec. 709 weights for three channels, the value
/// itself for one, the mean otherwise.
pub(crate) fn luminance<const N: usize>(c: &[Dual<N>]) -> Dual<N> {
    match c.len() {
        1 => c[0],
        3 => c[0] * 0.212671 + c[1] * 0.715160 + c[2] * 0.072169,
        n => c.iter().fold(Dual::c(0.0), |a, &b| a + b) / n as f64,
    }
}

/// The GGX lobe `D G / (4 N.L N.V)` at dual widths.
pub(crate) fn ggx_dual<const N: usize>(
    l: &Vector3<f64>,
    v: &Vector3<f64>,
    ax: Dual<N>,
    ay: Dual<N>,
    m: Masking,
) -> Dual<N> {
    match ggx_specular(l, v, ax.v, ay.v, m) {
        Some(s) => ax.chain2(&ay, s.value, s.d_ax, s.d_ay),
        None => Dual::c(0.0),
    }
}

/// Mitsuba's GTR1 clear-coat distribution at `N.H` for width `a`.
fn gtr1<const N: usize>(nh: f64, a: Dual<N>) -> Dual<N> {
    let a2 = a.sq();
    (a2 - 1.0) / (PI * a2.ln() * (1.0 + (a2 - 1.0) * (nh * nh)))
}

/// The principled formula.
#[derive(Clone, Debug, PartialEq)]
pub struct PrincipledFormula;

/// Parameter names after the per-channel `base_color`.
pub const PRINCIPLED_SCALARS: [&str; 9] = [
    "metallic",
    "specular",
    "spec_tint",
    "roughness",
    "anisotropic",
    "sheen",
    "sheen_tint",
    "clearcoat",
    "clearcoat_gloss",
];

impl DualFormula for PrincipledFormula {
    const NAME: &'static str = "principled";
    fn specs(channels: usize) -> Vec<ParamSpec> {
        let mut s = per_channel_specs(
            "base_color",
            "base colour (linear sRGB)",
            channels,
            0.0,
            1.0,
            0.5,
        );
        s.iter_mut().for_each(|p| p.linear = false);
        let meaning = [
            "metal weight",
            "dielectric reflectance (0.5 = 4 %)",
            "tint of the dielectric lobe towards the base colour",
            "perceptual roughness (alpha = roughness^2)",
            "anisotropy",
            "sheen strength",
            "tint of the sheen towards the base colour",
            "clear-coat strength",
            "clear-coat glossiness",
        ];
        for (k, (name, m)) in PRINCIPLED_SCALARS.iter().zip(meaning).enumerate() {
            let default = match k {
                1 | 3 => 0.5,
                _ => 0.0,
            };
            let p = ParamSpec::new(*name, m, 0.0, 1.0, default, false);
            s.push(if k == 1 { p.open_below() } else { p });
        }
        s
    }

    fn eval<const N: usize>(
        p: &[Dual<N>],
        nc: usize,
        l: &Vector3<f64>,
        v: &Vector3<f64>,
        out: &mut [Dual<N>],
    ) {
        let base = &p[..nc];
        let [
            metallic,
            specular,
            spec_tint,
            rough,
            aniso,
            sheen,
            sheen_tint,
            cc,
            cc_gloss,
        ] = std::array::from_fn(|k| p[nc + k]);
        let h = (l + v).normalize();
        let cos_d = v.dot(&h).clamp(0.0, 1.0);
        let w = schlick_weight(cos_d);
        let lum = luminance(base);
        let tint = |c: Dual<N>| if lum.v > 0.0 { c / lum } else { Dual::c(1.0) };
        // Keep sqrt away from 0, where d/dspecular of sqrt(0.08 s) is infinite
        // although the reflectance (~0.08 s) is smooth.
        let r = (specular.max_c(1e-12) * 0.08).sqrt();
        let eta = (1.0 + r) / (1.0 - r);
        let r0 = r.sq();
        let (fd, dfd) = fresnel_dielectric_d_eta(cos_d, eta.v);
        let f_diel = eta.chain(fd, dfd);
        let r2 = rough.sq();
        let aspect = (1.0 - aniso * 0.9).sqrt();
        let ax = (r2 / aspect).max_c(0.001);
        let ay = (r2 * aspect).max_c(0.001);
        let spec = if fd > 0.0 {
            ggx_dual(l, v, ax, ay, Masking::Separable)
        } else {
            Dual::c(0.0)
        };
        let (wl, wv) = (schlick_weight(l.z), schlick_weight(v.z));
        let f_diff = (1.0 - 0.5 * wl) * (1.0 - 0.5 * wv);
        let rr = rough * (2.0 * cos_d * cos_d);
        let diffuse =
            (1.0 - metallic) * FRAC_1_PI * (f_diff + rr * (wl + wv + wl * wv * (rr - 1.0)));
        let a_c = cc_gloss.lerp(Dual::c(0.1), Dual::c(0.001));
        let g_cc = separable_g1(l, 0.25) * separable_g1(v, 0.25);
        let coat = cc * 0.25 * (0.04 + 0.96 * w) * gtr1(h.z, a_c) * g_cc;
        let sheen_w = sheen * (1.0 - metallic) * w;
        for c in 0..nc {
            let ct = tint(base[c]);
            let f0_tint = ct * r0;
            let f = (1.0 - metallic) * (1.0 - spec_tint) * f_diel
                + metallic * (base[c] + (1.0 - base[c]) * w)
                + (1.0 - metallic) * spec_tint * (f0_tint + (1.0 - f0_tint) * w);
            let c_sheen = 1.0 + sheen_tint * (ct - 1.0);
            out[c] = f * spec + diffuse * base[c] + sheen_w * c_sheen + coat;
        }
    }

    fn batch(
        p: &[f64],
        nc: usize,
        pairs: &DirPairs,
        out: &mut [f64],
        jac: Option<&mut [f64]>,
    ) -> bool {
        kernel::batch(p, nc, pairs, out, jac);
        true
    }
}

/// `G1(w) = 1 / (1 + Lambda(w))` of isotropic GGX with a fixed width.
fn separable_g1(w: &Vector3<f64>, alpha: f64) -> f64 {
    1.0 / (1.0 + smith_lambda(w, alpha, alpha).0)
}

/// The Disney principled BRDF as Mitsuba 3 defines it.
pub type Principled = DualModel<PrincipledFormula>;
