//! pbrt-v4 material statements.
//!
//! - `lambert` is `Material "diffuse"`.
//! - The height-correlated GGX models with a conductor or dielectric lobe
//!   (`ggx-conductor[-aniso]`, `ggx-dielectric[-aniso]`): pbrt-v4's
//!   `conductor` is `D G F / (4 cos cos)` with the Trowbridge-Reitz `D`, the
//!   height-correlated Smith `G` and the exact `FrComplex(eta + i k)`
//!   (`k = 0` gives the dielectric reflectance); `remaproughness false` makes
//!   `roughness` (or `uroughness`, `vroughness`) the width `alpha`. `kd/pi +
//!   ks S` is a `mix` of a `diffuse` with reflectance `kd / (1 - ks)` and the
//!   conductor with `amount = ks`; pbrt-v4's `mix` picks one of the two per
//!   shading point with probability `amount`, so the image equals the blend
//!   in expectation. It needs a grey `ks` and `kd / (1 - ks) <= 1`.
//!
//! No exact equivalent (an error): Schlick lobes (pbrt-v4 has no Schlick
//! conductor), the separable Smith, several lobes, principled and glTF
//! (pbrt-v4 has neither), and the other catalogue models.

use brdf_models::RendererForm;

use crate::fitted::{Fitted, LobeFresnel};
use crate::{ExportError, Target};

const T: Target = Target::Pbrt;

fn rgb(c: &[f64; 3]) -> String {
    format!("[ {} {} {} ]", c[0], c[1], c[2])
}

/// A constant spectrum over pbrt's visible range.
fn constant(v: f64) -> String {
    format!("[ 360 {v} 830 {v} ]")
}

/// The pbrt-v4 statements for `fit` (named materials and `NamedMaterial
/// "fitted"`, or a single `Material` statement), after `note` as a comment.
pub fn write(fit: &Fitted, note: Option<&str>) -> Result<String, ExportError> {
    let head = note
        .map(|n| format!("# {}\n", n.replace('\n', " ")))
        .unwrap_or_default();
    Ok(head + &statements(fit)?)
}

fn statements(fit: &Fitted) -> Result<String, ExportError> {
    if fit.form == RendererForm::Diffuse {
        return Ok(format!(
            "Material \"diffuse\" \"rgb reflectance\" {}\n",
            rgb(&fit.colour("kd")?)
        ));
    }
    let Some(g) = fit.ggx()? else {
        return Err(fit.no_equivalent(T, "pbrt-v4 has no material with this formula"));
    };
    if g.separable {
        return Err(fit.no_equivalent(
            T,
            "pbrt-v4's Trowbridge-Reitz G is height-correlated, not separable",
        ));
    }
    let [lobe] = g.lobes.as_slice() else {
        return Err(fit.no_equivalent(
            T,
            "a pbrt-v4 mix of several conductors needs weights summing to 1; export one lobe",
        ));
    };
    let LobeFresnel::Complex { eta, k } = lobe.fresnel else {
        return Err(fit.no_equivalent(
            T,
            "pbrt-v4 has no Schlick-Fresnel conductor; fit ggx-conductor or ggx-dielectric",
        ));
    };
    let ks = lobe.ks[0];
    if lobe.ks.iter().any(|&x| x != ks) {
        return Err(fit.no_equivalent(T, "the conductor cannot be tinted: ks must be grey"));
    }
    let widths = if lobe.ax == lobe.ay {
        format!("\"float roughness\" {}", lobe.ax)
    } else {
        format!(
            "\"float uroughness\" {} \"float vroughness\" {}",
            lobe.ax, lobe.ay
        )
    };
    let conductor = format!(
        "\"string type\" \"conductor\" \"spectrum eta\" {} \"spectrum k\" {} {widths} \"bool remaproughness\" false",
        constant(eta),
        constant(k)
    );
    if ks == 1.0 && g.kd.iter().all(|&x| x == 0.0) {
        return Ok(format!(
            "MakeNamedMaterial \"fitted\" {conductor}\nNamedMaterial \"fitted\"\n"
        ));
    }
    if ks >= 1.0 {
        return Err(fit.no_equivalent(T, "ks = 1 leaves no mix weight for the diffuse term"));
    }
    let diffuse = g.kd.map(|x| x / (1.0 - ks));
    if diffuse.iter().any(|&x| x > 1.0) {
        return Err(fit.no_equivalent(
            T,
            "kd / (1 - ks) > 1: pbrt-v4 clamps diffuse reflectance at 1",
        ));
    }
    Ok(format!(
        "MakeNamedMaterial \"fitted_diffuse\" \"string type\" \"diffuse\" \"rgb reflectance\" {}\n\
         MakeNamedMaterial \"fitted_specular\" {conductor}\n\
         MakeNamedMaterial \"fitted\" \"string type\" \"mix\" \"string materials\" [ \"fitted_diffuse\" \"fitted_specular\" ] \"float amount\" {ks}\n\
         NamedMaterial \"fitted\"\n",
        rgb(&diffuse)
    ))
}
