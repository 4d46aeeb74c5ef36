//! The glTF 2.0 metallic-roughness BRDF (Khronos, glTF 2.0 specification,
//! Appendix B "BRDF implementation"), and the same material with the
//! `KHR_materials_ior`, `KHR_materials_specular` and `KHR_materials_clearcoat`
//! extensions (their README "Implementation" sections).
//!
//! With `alpha = roughness^2`, `S(alpha) = D G / (4 N.L N.V)` the isotropic
//! GGX lobe with height-correlated Smith `G` (the appendix's `V D`; see
//! [`crate::ggx`]), `w = (1 - |V.H|)^5`, `C` the base colour and `m` metallic:
//!
//! `f0 = min(((ior - 1)/(ior + 1))^2 specular_color, 1) specular`,
//! `F_d = f0 + (specular - f0) w` (per channel),
//! `dielectric = F_d S(alpha) + (1 - max_c F_d) C / pi`,
//! `metal = S(alpha) (C + (1 - C) w)`,
//! `material = (1 - m) dielectric + m metal`;
//! with the clear coat, `F_c = 0.04 + 0.96 (1 - N.V)^5` (`V` towards the
//! viewer: the first direction, as renderers evaluate a BRDF, see
//! `brdf_render::shading`) and
//! `f = (1 - clearcoat F_c) material + clearcoat F_c S(clearcoat_roughness^2)`.
//!
//! The core model (`gltf`) is the extension model at `ior = 1.5`,
//! `specular = 1`, `specular_color = 1`, `clearcoat = 0`: `F_d = 0.04 + 0.96 w`.
//!
//! | parameter | meaning | default box | default | linear |
//! | --- | --- | --- | --- | --- |
//! | `base_color` (per channel, linear sRGB) | `baseColorFactor` | `[0, 1]` | 0.5 | no |
//! | `metallic` | `metallicFactor` | `[0, 1]` | 0 | no |
//! | `roughness` | `roughnessFactor` (perceptual) | `(0, 1]` | 0.5 | no |
//! | `ior` (`gltf-ext`) | `KHR_materials_ior.ior` | `[1, 3]` | 1.5 | no |
//! | `specular` (`gltf-ext`) | `KHR_materials_specular.specularFactor` | `[0, 1]` | 1 | no |
//! | `specular_color` (`gltf-ext`, per channel) | `specularColorFactor` | `[0, 2]` | 1 | no |
//! | `clearcoat` (`gltf-ext`) | `KHR_materials_clearcoat.clearcoatFactor` | `[0, 1]` | 0 | no |
//! | `clearcoat_roughness` (`gltf-ext`) | `clearcoatRoughnessFactor` | `(0, 1]` | 0.1 | no |
//!
//! The glTF spec asks for `alpha > 0`; the open lower end of `roughness`
//! keeps it so. The colour is not a linear parameter (`C` multiplies
//! `1 - max F_d` and enters the metal's Fresnel). `KHR_materials_sheen` is
//! not included: its albedo scaling needs the tabulated directional albedo
//! of the Charlie lobe, which the extension leaves to the implementation.
//!
//! Properties: `gltf` is reciprocal; `gltf-ext` is not when `clearcoat > 0`
//! (the coat's Fresnel uses `N.V`, as the extension specifies), so it
//! declares itself non-reciprocal. Non-negative and finite above the
//! horizon. The appendix's mix is not energy conserving in general (its own
//! discussion); the albedo checks in `tests/models/renderer_models.rs` state the
//! domain found.
//!
//! ```
//! use brdf_core::Brdf;
//! use brdf_models::GltfPbr;
//! use nalgebra::Vector3;
//! // base_color, metallic, roughness
//! let m = GltfPbr::new(1, &[0.5, 0.0, 0.5]).unwrap();
//! let mut f = [0.0];
//! m.eval(&Vector3::z(), &Vector3::z(), &mut f);
//! // At the pole w = 0: F_d = 0.04, S = 1/(4 pi alpha^2), alpha = 0.25.
//! let s = 1.0 / (4.0 * std::f64::consts::PI * 0.0625);
//! let expect = 0.04 * s + 0.96 * 0.5 / std::f64::consts::PI;
//! assert!((f[0] - expect).abs() < 1e-12 * expect);
//! ```

mod ext_kernel;
pub mod iridescence;
mod kernel;

use std::f64::consts::FRAC_1_PI;

use brdf_core::params::per_channel_specs;
use brdf_core::{DirPairs, ParamSpec};
use nalgebra::Vector3;

use crate::dual::Dual;
use crate::dual_model::{DualFormula, DualModel};
use crate::ggx::Masking;
use crate::principled::{ggx_dual, schlick_weight};

fn core_specs(nc: usize) -> Vec<ParamSpec> {
    let mut s = per_channel_specs("base_color", "base colour (linear sRGB)", nc, 0.0, 1.0, 0.5);
    s.iter_mut().for_each(|p| p.linear = false);
    s.push(ParamSpec::new(
        "metallic",
        "metal weight",
        0.0,
        1.0,
        0.0,
        false,
    ));
    s.push(
        ParamSpec::new(
            "roughness",
            "perceptual roughness (alpha = roughness^2)",
            0.0,
            1.0,
            0.5,
            false,
        )
        .open_below(),
    );
    s
}

/// The glTF material; `ext`: parameters after the core ones are
/// `ior, specular, specular_color (nc), clearcoat, clearcoat_roughness`.
fn gltf_eval<const N: usize>(
    p: &[Dual<N>],
    nc: usize,
    l: &Vector3<f64>,
    v: &Vector3<f64>,
    ext: bool,
    out: &mut [Dual<N>],
) {
    let base = &p[..nc];
    let (metallic, rough) = (p[nc], p[nc + 1]);
    let one = Dual::c(1.0);
    let (ior, specular, sc, cc, cc_rough) = if ext {
        let e = &p[nc + 2..];
        (e[0], e[1], &e[2..2 + nc], e[2 + nc], e[3 + nc])
    } else {
        (Dual::c(1.5), one, &[] as &[Dual<N>], Dual::c(0.0), one)
    };
    let h = (l + v).normalize();
    let w = schlick_weight(v.dot(&h).abs());
    let alpha = rough.sq();
    let spec = ggx_dual(l, v, alpha, alpha, Masking::HeightCorrelated);
    let f0_ior = ((ior - 1.0) / (ior + 1.0)).sq();
    let mut fd = [Dual::c(0.0); crate::dual_model::MAX_CHANNELS];
    let mut fmax = Dual::c(f64::NEG_INFINITY);
    for c in 0..nc {
        let colour = if ext { sc[c] } else { one };
        let f0 = (f0_ior * colour).min_c(1.0) * specular;
        fd[c] = f0 + (specular - f0) * w;
        fmax = fmax.max(fd[c]);
    }
    let coat = if ext {
        let a = cc_rough.sq();
        let fc = cc * (0.04 + 0.96 * schlick_weight(l.z));
        Some((fc, ggx_dual(l, v, a, a, Masking::HeightCorrelated)))
    } else {
        None
    };
    for c in 0..nc {
        let dielectric = fd[c] * spec + (1.0 - fmax) * base[c] * FRAC_1_PI;
        let metal = spec * (base[c] + (1.0 - base[c]) * w);
        let material = (1.0 - metallic) * dielectric + metallic * metal;
        out[c] = match coat {
            Some((fc, s)) => (1.0 - fc) * material + fc * s,
            None => material,
        };
    }
}

/// The core glTF 2.0 metallic-roughness formula.
#[derive(Clone, Debug, PartialEq)]
pub struct GltfFormula;

impl DualFormula for GltfFormula {
    const NAME: &'static str = "gltf";
    fn specs(channels: usize) -> Vec<ParamSpec> {
        core_specs(channels)
    }
    fn eval<const N: usize>(
        p: &[Dual<N>],
        nc: usize,
        l: &Vector3<f64>,
        v: &Vector3<f64>,
        out: &mut [Dual<N>],
    ) {
        gltf_eval(p, nc, l, v, false, out)
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

/// glTF 2.0 metallic-roughness with `KHR_materials_ior`, `_specular` and
/// `_clearcoat`.
#[derive(Clone, Debug, PartialEq)]
pub struct GltfExtFormula;

impl DualFormula for GltfExtFormula {
    const NAME: &'static str = "gltf-ext";
    fn specs(nc: usize) -> Vec<ParamSpec> {
        let mut s = core_specs(nc);
        s.push(ParamSpec::new(
            "ior",
            "index of refraction (KHR_materials_ior)",
            1.0,
            3.0,
            1.5,
            false,
        ));
        s.push(ParamSpec::new(
            "specular",
            "specularFactor (KHR_materials_specular)",
            0.0,
            1.0,
            1.0,
            false,
        ));
        let mut col = per_channel_specs("specular_color", "specularColorFactor", nc, 0.0, 2.0, 1.0);
        col.iter_mut().for_each(|p| p.linear = false);
        s.extend(col);
        s.push(ParamSpec::new(
            "clearcoat",
            "clearcoatFactor (KHR_materials_clearcoat)",
            0.0,
            1.0,
            0.0,
            false,
        ));
        s.push(
            ParamSpec::new(
                "clearcoat_roughness",
                "clearcoatRoughnessFactor",
                0.0,
                1.0,
                0.1,
                false,
            )
            .open_below(),
        );
        s
    }
    fn eval<const N: usize>(
        p: &[Dual<N>],
        nc: usize,
        l: &Vector3<f64>,
        v: &Vector3<f64>,
        out: &mut [Dual<N>],
    ) {
        gltf_eval(p, nc, l, v, true, out)
    }
    fn batch(
        p: &[f64],
        nc: usize,
        pairs: &DirPairs,
        out: &mut [f64],
        jac: Option<&mut [f64]>,
    ) -> bool {
        ext_kernel::batch(p, nc, pairs, out, jac);
        true
    }
    fn reciprocal() -> bool {
        false
    }
}

/// The glTF 2.0 metallic-roughness BRDF.
pub type GltfPbr = DualModel<GltfFormula>;
/// The glTF 2.0 BRDF with the ior, specular and clearcoat extensions.
pub type GltfPbrExt = DualModel<GltfExtFormula>;
