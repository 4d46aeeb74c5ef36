//! The catalogue's configurations of the coloured-lobe model: each name
//! fixes the masking (the target renderer's GGX), the Fresnel law of the
//! first lobe (further lobes, from `ModelConfig::lobes`, have none) and
//! whether the coat lobe is present, so a fitted model exports exactly.

use brdf_core::{ParamError, Parametric};

use super::model::{ColouredLobes, LobeFresnel, MAX_LOBES};
use crate::ggx::Masking;
use crate::model_entry::{ModelConfig, ModelEntry};

/// One named configuration.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Variant {
    /// Catalogue name.
    pub name: &'static str,
    /// Masking of every lobe.
    pub masking: Masking,
    /// Fresnel law of lobe 1.
    pub first: LobeFresnel,
    /// Whether the white dielectric coat lobe is added.
    pub coat: bool,
    /// Whether every lobe carries MaterialX's energy compensation
    /// ([`super::compensation`]).
    pub compensated: bool,
    /// One-line summary for the catalogue.
    pub summary: &'static str,
}

use LobeFresnel::{Conductor, F82Tint, None as Plain};
use Masking::{HeightCorrelated as Hc, Separable as Sep};

const fn variant(
    name: &'static str,
    masking: Masking,
    first: LobeFresnel,
    coat: bool,
    summary: &'static str,
) -> Variant {
    Variant {
        name,
        masking,
        first,
        coat,
        compensated: false,
        summary,
    }
}

/// A configuration as MaterialX evaluates it: height-correlated masking
/// and its energy compensation.
const fn materialx(
    name: &'static str,
    first: LobeFresnel,
    coat: bool,
    summary: &'static str,
) -> Variant {
    Variant {
        name,
        masking: Masking::HeightCorrelated,
        first,
        coat,
        compensated: true,
        summary,
    }
}

/// Every configuration in the catalogue. `-mitsuba`: separable Smith
/// masking (Mitsuba 3 `roughconductor` with `distribution = "ggx"`);
/// `-cycles`: height-correlated (Cycles' Glossy and Metallic BSDFs with the
/// plain `GGX` distribution); `-materialx`: height-correlated with
/// MaterialX's energy compensation (its `generalized_schlick_bsdf`,
/// `conductor_bsdf` and `dielectric_bsdf`). F82 tint has no Mitsuba
/// counterpart, so it comes in the Cycles and MaterialX forms only.
///
/// Export notes: Cycles sums the terms exactly with Add Shader nodes
/// (Roughness is `sqrt(alpha)`; a coat is a Metallic BSDF, physical
/// conductor, with IOR `coat_ior` and Extinction 0). Mitsuba has no sum
/// but `blendbsdf`'s convex weights, so nesting reproduces the model
/// exactly only when the weights can absorb the amplitudes:
/// `max_c kd_c + sum_k max_c ks{k}_c (+ 1 per Fresnel-coloured lobe or
/// coat) <= 1`, the terms then scaled back by their weights. MaterialX
/// sums BSDFs exactly with `add_bsdf`.
pub const VARIANTS: [Variant; 16] = [
    variant(
        "lobes-mitsuba",
        Sep,
        Plain,
        false,
        "kd/pi + sum_k ks_k D G1 G1 / (4 N.L N.V): K coloured GGX lobes, separable masking (Mitsuba 3)",
    ),
    variant(
        "lobes-cycles",
        Hc,
        Plain,
        false,
        "kd/pi + sum_k ks_k D G2 / (4 N.L N.V): K coloured GGX lobes, height-correlated masking (Cycles)",
    ),
    variant(
        "lobes-coat-mitsuba",
        Sep,
        Plain,
        true,
        "lobes-mitsuba plus a white GGX coat lobe with exact dielectric Fresnel",
    ),
    variant(
        "lobes-coat-cycles",
        Hc,
        Plain,
        true,
        "lobes-cycles plus a white GGX coat lobe with exact dielectric Fresnel",
    ),
    variant(
        "lobes-conductor-mitsuba",
        Sep,
        Conductor,
        false,
        "lobes-mitsuba with an exact per-channel conductor Fresnel (eta, kappa) on lobe 1",
    ),
    variant(
        "lobes-conductor-cycles",
        Hc,
        Conductor,
        false,
        "lobes-cycles with an exact per-channel conductor Fresnel (eta, kappa) on lobe 1",
    ),
    variant(
        "lobes-conductor-coat-mitsuba",
        Sep,
        Conductor,
        true,
        "lobes-conductor-mitsuba plus a white dielectric GGX coat lobe",
    ),
    variant(
        "lobes-conductor-coat-cycles",
        Hc,
        Conductor,
        true,
        "lobes-conductor-cycles plus a white dielectric GGX coat lobe",
    ),
    variant(
        "lobes-f82-cycles",
        Hc,
        F82Tint,
        false,
        "lobes-cycles with an F82-tint Fresnel (colours f0, tint) on lobe 1 (Blender Metallic BSDF F82)",
    ),
    variant(
        "lobes-f82-coat-cycles",
        Hc,
        F82Tint,
        true,
        "lobes-f82-cycles plus a white dielectric GGX coat lobe",
    ),
    materialx(
        "lobes-materialx",
        Plain,
        false,
        "kd/pi + sum_k ks_k (1 + ks_k k) D G2 / (4 N.L N.V): K coloured GGX lobes with MaterialX's energy compensation k = 1/E(N.V) - 1",
    ),
    materialx(
        "lobes-coat-materialx",
        Plain,
        true,
        "lobes-materialx plus a white compensated GGX coat lobe with exact dielectric Fresnel",
    ),
    materialx(
        "lobes-conductor-materialx",
        Conductor,
        false,
        "lobes-materialx with an exact per-channel conductor Fresnel (eta, kappa) on lobe 1 (MaterialX conductor_bsdf)",
    ),
    materialx(
        "lobes-conductor-coat-materialx",
        Conductor,
        true,
        "lobes-conductor-materialx plus a white compensated dielectric GGX coat lobe",
    ),
    materialx(
        "lobes-f82-materialx",
        F82Tint,
        false,
        "lobes-materialx with an F82-tint Fresnel (colours f0, tint) on lobe 1 (MaterialX generalized_schlick_bsdf with color82)",
    ),
    materialx(
        "lobes-f82-coat-materialx",
        F82Tint,
        true,
        "lobes-f82-materialx plus a white compensated dielectric GGX coat lobe",
    ),
];

/// The configuration named `name`.
pub fn variant_named(name: &str) -> Option<&'static Variant> {
    VARIANTS.iter().find(|v| v.name == name)
}

impl ColouredLobes {
    /// Configuration `variant` with `lobes` GGX lobes (1 to 3) and
    /// `channels` colour channels, at its default parameters.
    pub fn new(variant: &Variant, lobes: usize, channels: usize) -> Result<Self, ParamError> {
        let mut fresnels = [LobeFresnel::None; MAX_LOBES];
        fresnels[0] = variant.first;
        let k = lobes.clamp(1, MAX_LOBES);
        if k != lobes {
            return Err(ParamError::Config {
                model: variant.name.to_string(),
                reason: format!("takes 1 to {MAX_LOBES} GGX lobes, not {lobes}"),
            });
        }
        let m = ColouredLobes::custom(
            variant.name,
            variant.masking,
            &fresnels[..k],
            variant.coat,
            channels,
        )?;
        Ok(if variant.compensated {
            m.compensated()
        } else {
            m
        })
    }
}

/// Build the configuration named `name` for `config` (its `channels` and
/// `lobes`); `None` for a name that is not one of [`VARIANTS`].
pub fn build(name: &str, config: &ModelConfig) -> Option<Result<Box<dyn Parametric>, ParamError>> {
    let v = variant_named(name)?;
    Some(
        ColouredLobes::new(v, config.lobes, config.channels)
            .map(|m| Box::new(m) as Box<dyn Parametric>),
    )
}

fn build_index(i: usize, config: &ModelConfig) -> Result<Box<dyn Parametric>, ParamError> {
    let m = ColouredLobes::new(&VARIANTS[i], config.lobes, config.channels)?;
    Ok(Box::new(m))
}

/// A catalogue constructor.
type Build = fn(&ModelConfig) -> Result<Box<dyn Parametric>, ParamError>;

const PAPER: &str = "Walter, Marschner, Li & Torrance 2007 (GGX); Heitz 2014, JCGT 3(2) (masking); \
     Hoffman 2019 and Kutz, Hasan & Edmondson 2021 (F82 tint)";

/// The catalogue entries of every configuration, in [`VARIANTS`] order.
pub fn entries() -> Vec<ModelEntry> {
    // A catalogue constructor is a plain `fn`: one non-capturing closure per
    // configuration, each naming its index.
    let builds: [Build; 16] = [
        |c| build_index(0, c),
        |c| build_index(1, c),
        |c| build_index(2, c),
        |c| build_index(3, c),
        |c| build_index(4, c),
        |c| build_index(5, c),
        |c| build_index(6, c),
        |c| build_index(7, c),
        |c| build_index(8, c),
        |c| build_index(9, c),
        |c| build_index(10, c),
        |c| build_index(11, c),
        |c| build_index(12, c),
        |c| build_index(13, c),
        |c| build_index(14, c),
        |c| build_index(15, c),
    ];
    VARIANTS
        .iter()
        .zip(builds)
        .map(|(v, build)| ModelEntry {
            name: v.name,
            family: "renderer",
            summary: v.summary,
            paper: PAPER,
            has_lobes: true,
            build,
            build_for_data: None,
            from_samples: None,
            starts: Some(|m, _| super::starts::suggested_starts(m)),
            polish_factor: 1,
            channel_model: None,
            // Renderers evaluate every lobe exactly: fitted for appearance
            // by default, each lobe of its own colour.
            renderer: true,
            by_image_rank: None,
            colour: crate::ColourStructure::PerLobe,
            optional_lobes: &[],
            linear_solver: crate::LinearSolver::Direct,
            // A compensated plain lobe's colour is not linear.
            nonlinear_search: if v.first == Plain && !v.compensated {
                crate::NonlinearSearch::Projected
            } else {
                crate::NonlinearSearch::AllParameters
            },
            form: crate::RendererForm::ColouredLobes,
        })
        .collect()
}
