//! Thin film: a Lambert term and one GGX lobe whose Fresnel is the Airy
//! reflectance of a thin film over a dielectric base, plus an optional white
//! dielectric coat lobe. Interference paints (the colour-shifting films of
//! the RGL database) turn hue with the angle of incidence on their flakes,
//! `theta_d`, as such a film does; Blender's Cycles (Thin Film Thickness and
//! IOR, since 4.2; on the Metallic BSDF in 5.0), MaterialX
//! (`thinfilm_thickness`, `thinfilm_ior`) and OpenPBR (`thin_film_*`) offer
//! it as parameters an artist can edit.
//!
//! ## Formula
//!
//! With `mu = cos theta_d = V.H` and `S(alpha) = D G2 / (4 cos_i cos_o)`
//! (GGX with height-correlated masking, [`crate::coloured_lobes::geometry`]):
//!
//! `f_c = kd_c / pi + w A_c(mu; d, n2, n3) S(alpha) + F_diel(mu; coat_ior) S(coat_alpha)`,
//!
//! `A_c` the film's reflectance in channel `c`: the unpolarised Airy
//! reflectance of ambient (index 1) | film (index `n2`, thickness `d`) |
//! base (index `n3`), integrated over 380-780 nm against the CIE 1931
//! colour-matching functions under the equal-energy illuminant (as Cycles
//! integrates its film) and mapped to linear sRGB (luminance
//! for one channel), clamped to `[0, 1]` ([`airy`]), interpolated
//! between 257 nodes of `mu` ([`table`]). A film of zero
//! thickness, or of the base's index, leaves the base's Fresnel in every
//! channel. The coat is as the coloured lobes' ([`crate::coloured_lobes`]).
//!
//! ## Parameters
//!
//! | parameter | meaning | box | default | linear |
//! | --- | --- | --- | --- | --- |
//! | `kd_c` | diffuse albedo | `[0, 1]` | 0.3 | yes |
//! | `w` | weight of the film lobe | `[0, 1]` | 1 | yes |
//! | `alpha` | GGX width of the film lobe | `[0.002, 1]` | 0.1 | no |
//! | `film_d` | film thickness, nm | `[0, 1500]` | 250 | no |
//! | `film_ior` | film index `n2` | `[1.05, 5]` | 1.6 | no |
//! | `base_ior` | base index `n3` | `[1.05, 5]` | 1.5 | no |
//! | `coat_ior` (coat) | coat index | `[1.2, 2]` | 1.5 | no |
//! | `coat_alpha` (coat) | coat GGX width | `[0.002, 1]` | 0.05 | no |
//!
//! `alpha` is the distribution's width (Cycles' Roughness is
//! `sqrt(alpha)`). The indices reach 5, beyond common dielectrics (a base
//! of index 5 reflects 0.44 at normal incidence, as a metal might): the
//! colour-shifting paints' flakes reflect more than glass, and on
//! cc_ibiza_sunset a fit at the earlier limit of 3 sat on it (studio FLIP
//! 0.132 there, 0.115 with the base at 4.0). Indices start at 1.05: at 1 the film's refraction
//! cosine vanishes at grazing incidence, and so would the derivatives'
//! denominators.
//!
//! ## Properties
//!
//! - Reciprocal (`V.H = L.H`; `D`, `G2` and `cos_i cos_o` are symmetric),
//!   except the `-materialx` forms (their compensation depends on the
//!   first direction).
//! - Non-negative and finite inside the box; 0 below the horizon.
//! - Energy: `A_c`, `F_diel` lie in `[0, 1]` and each `S` has directional
//!   albedo at most 1, so the albedo is at most `kd_c + w + 1` (coat).
//! - Analytic derivatives in every parameter ([`airy`] for the film's).
//! - Fit starts: [`scan::screened_starts`] scans the thickness, whose
//!   fringes (about 150 nm apart) are each a local optimum.
//!
//! ## Renderers
//!
//! Cycles sums the terms exactly (Add Shader): a Diffuse BSDF, a Metallic
//! BSDF (physical conductor, IOR `n3`, Extinction 0, the thin film, plain
//! `GGX`) scaled by `w` (a Mix Shader), and the coat. Cycles integrates the
//! film with its own table of sensitivities and three orders of Airy's
//! series rather than this module's quadrature; its mirror sphere renders
//! within 1e-3 of [`airy`] up to 70 degrees.
//!
//! MaterialX evaluates its own film: the `film*-materialx` models take
//! `A_c` from its two-order series with fitted sensitivities
//! ([`materialx_airy`]) and carry its GGX energy compensation on the film
//! lobe and the coat (each term's Fresnel `F` becomes `F (1 + F k)`, `k =
//! 1/E - 1` by [`crate::coloured_lobes::compensation`], the first
//! direction the viewer's; so those two are not reciprocal). MaterialX
//! sums with `add`: an `oren_nayar_diffuse_bsdf` of roughness 0, a
//! `dielectric_bsdf` (reflection, IOR `n3`, weight `w`, `thinfilm_thickness`
//! `d`, `thinfilm_ior` `n2`) and the coat's `dielectric_bsdf`.
//!
//! ```
//! use brdf_core::{Brdf, Parametric};
//! use brdf_models::thin_film::ThinFilm;
//! use nalgebra::Vector3;
//! // One channel, no film thickness: Lambert plus a dielectric GGX lobe.
//! let m = ThinFilm::new("film-cycles", 1, false)?
//!     .with_params(&[0.2, 1.0, 0.1, 0.0, 1.6, 1.5])?;
//! let mut f = [0.0];
//! m.eval(&Vector3::z(), &Vector3::z(), &mut f);
//! // At the pole D = 1/(pi alpha^2), G = 1, and F = ((n - 1)/(n + 1))^2.
//! let pi = std::f64::consts::PI;
//! let expect = 0.2 / pi + 0.04 / (4.0 * pi * 0.01);
//! assert!((f[0] - expect).abs() < 1e-12 * expect);
//! # Ok::<(), brdf_core::ParamError>(())
//! ```
//!
//! Papers: Belcour & Barla 2017, "A practical extension to microfacet
//! theory for the modeling of varying iridescence", ACM TOG 36(4):65 (the
//! film's reflectance in a microfacet model); Born & Wolf, "Principles of
//! Optics", section 7.6 (Airy's summation); Walter et al. 2007 (GGX);
//! Heitz 2014 (height-correlated masking).

pub mod airy;
pub mod materialx_airy;
pub mod model;
pub mod scan;
pub mod spectral;
pub mod table;

pub use model::{FilmRenderer, THICKNESS_MAX, ThinFilm};

use brdf_core::{ParamError, Parametric};

use crate::model_entry::{ModelConfig, ModelEntry};

/// A catalogue constructor.
type Build = fn(&ModelConfig) -> Result<Box<dyn Parametric>, ParamError>;

const PAPER: &str = "Belcour & Barla 2017, ACM TOG 36(4):65 (thin film in a microfacet model); \
     Walter et al. 2007 (GGX); Heitz 2014, JCGT 3(2) (masking)";

fn entry(name: &'static str, summary: &'static str, build: Build) -> ModelEntry {
    ModelEntry {
        name,
        family: "renderer",
        summary,
        paper: PAPER,
        has_lobes: false,
        build,
        build_for_data: None,
        from_samples: None,
        starts: Some(scan::screened_starts),
        polish_factor: 1,
        channel_model: None,
        renderer: true,
        by_image_rank: None,
        colour: crate::ColourStructure::PerLobe,
        optional_lobes: &[],
        linear_solver: crate::LinearSolver::Direct,
        nonlinear_search: crate::NonlinearSearch::Projected,
        form: crate::RendererForm::ThinFilm,
    }
}

/// The film as MaterialX evaluates it.
fn materialx(name: &'static str, channels: usize, coat: bool) -> Result<ThinFilm, ParamError> {
    ThinFilm::new(name, channels, coat).map(|m| m.for_renderer(FilmRenderer::MaterialX))
}

/// The catalogue entries: the film alone and under a coat, in Cycles' and
/// in MaterialX's form.
pub fn entries() -> Vec<ModelEntry> {
    vec![
        entry(
            "film-cycles",
            "kd/pi + w A(V.H; d, n_film, n_base) D G2 / (4 N.L N.V): a GGX lobe with a thin film's Airy colour (Cycles)",
            |c| Ok(Box::new(ThinFilm::new("film-cycles", c.channels, false)?)),
        ),
        entry(
            "film-coat-cycles",
            "film-cycles plus a white GGX coat lobe with exact dielectric Fresnel",
            |c| {
                Ok(Box::new(ThinFilm::new(
                    "film-coat-cycles",
                    c.channels,
                    true,
                )?))
            },
        ),
        entry(
            "film-materialx",
            "kd/pi + w A (1 + A k) D G2 / (4 N.L N.V): the film lobe as MaterialX renders it (two-order Airy series, energy compensation k)",
            |c| Ok(Box::new(materialx("film-materialx", c.channels, false)?)),
        ),
        entry(
            "film-coat-materialx",
            "film-materialx plus a white compensated GGX coat lobe with exact dielectric Fresnel",
            |c| {
                Ok(Box::new(materialx(
                    "film-coat-materialx",
                    c.channels,
                    true,
                )?))
            },
        ),
    ]
}
