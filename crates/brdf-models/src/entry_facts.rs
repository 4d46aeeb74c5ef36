//! Typed facts a catalogue entry ([`crate::ModelEntry`]) states about its
//! model beside its constructors: how it colours its lobes, which lobes it
//! may switch off, and how an all-linear model is solved by default. The
//! fitting front ends ask the entry instead of matching model names.

/// How a model colours its lobes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ColourStructure {
    /// Every lobe is white or the one base colour (`principled`: diffuse,
    /// sheen, tinted and metallic Fresnel, clear coat; `gltf`: diffuse,
    /// dielectric and metal Fresnel): under white light all its renders lie
    /// in one plane of white and one colour.
    Single,
    /// Lobes have colours of their own (a diffuse and a specular colour
    /// per channel, or a second colour such as `gltf-ext`'s specular).
    PerLobe,
}

/// A lobe a model may switch off: the parameter that is its strength
/// (held at 0, its lower bound, to switch it off) and its companions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OptionalLobe {
    /// The lobe's strength parameter (its name is the lobe's).
    pub name: &'static str,
    /// The parameters of the lobe besides its strength: they act only
    /// through the lobe, so while it is off they are held at their
    /// defaults. Left free, such a parameter has no influence at all: the
    /// solver then stops on a plateau with a singular Jacobian, and a saved
    /// model carries whatever value a random start gave it.
    pub companions: &'static [&'static str],
}

/// How the non-linear parameters of a model with some are searched when
/// no solver is asked for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NonlinearSearch {
    /// The linear parameters projected out (variable projection), the
    /// search on the non-linear ones alone.
    Projected,
    /// Levenberg-Marquardt on every parameter at once. For models whose
    /// few linear parameters share their rows with a Fresnel law (a
    /// coloured lobe's complex index or F82 tint): there the projected
    /// search ends in false minima with the lobes' widths swapped, even
    /// from starts near the truth, where the full search does not.
    AllParameters,
}

/// How an all-linear model is solved when no solver is asked for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LinearSolver {
    /// Direct least squares (NNLS where the box starts at 0).
    Direct,
    /// Robust IRLS with the bisquare weight (Kurt's procedure for his
    /// polynomial).
    RobustIrls,
}

/// The renderer material a model's formula is, when one is: what its
/// exporters write it as, reading its parameters by their names here.
/// Models without one are converted (fitted again as a renderer model)
/// by every exporter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RendererForm {
    /// No renderer material has the model's formula.
    None,
    /// Lambert's `kd / pi`: every renderer's diffuse material.
    Diffuse,
    /// Burley's principled BRDF as Mitsuba 3's `principled` evaluates it.
    Principled,
    /// glTF 2.0's metallic-roughness material (`base_color`, `metallic`,
    /// `roughness`); `extended`: with `KHR_materials_specular`, `_ior` and
    /// `_clearcoat` (`ior`, `specular`, `specular_color`, `clearcoat`,
    /// `clearcoat_roughness`).
    Gltf {
        /// Whether the KHR extensions' parameters are present.
        extended: bool,
    },
    /// glTF's material with `KHR_materials_iridescence` as well as the
    /// extended form's parameters (`iridescence`, `iridescence_ior`,
    /// `iridescence_thickness`).
    GltfIridescence,
    /// A Lambert base (`kd`) under GGX lobes.
    Ggx(GgxForm),
    /// Lobes with colours of their own, one renderer's formula each
    /// ([`crate::coloured_lobes`]): their exporters read the variant.
    ColouredLobes,
    /// A GGX lobe with a thin film's Fresnel over a dielectric base
    /// ([`crate::thin_film`]): Cycles' thin film on a Metallic BSDF.
    ThinFilm,
}

impl RendererForm {
    /// Whether the form always has two widths (`ax`, `ay`), so that on
    /// isotropic data it can only match its isotropic twin with one more
    /// parameter. Principled's anisotropy is an optional lobe, not this.
    pub fn is_anisotropic(&self) -> bool {
        matches!(self, RendererForm::Ggx(g) if g.anisotropic)
    }
}

/// The GGX lobes of a [`RendererForm::Ggx`] model.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GgxForm {
    /// Each lobe's Fresnel term.
    pub fresnel: GgxFresnel,
    /// Two widths `ax`, `ay` instead of one `alpha`.
    pub anisotropic: bool,
    /// Smith's separable masking `G1(L) G1(V)` (Mitsuba 3's), not the
    /// height-correlated one.
    pub separable: bool,
    /// Any number of lobes, numbered (`ks1`, `alpha1`, `f0_1`, ...); else
    /// one lobe with unnumbered parameters.
    pub numbered: bool,
}

/// The Fresnel term of a GGX lobe.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GgxFresnel {
    /// Schlick's approximation from `f0`.
    Schlick,
    /// A dielectric's exact Fresnel from its index `eta`.
    Dielectric,
    /// A conductor's exact Fresnel from its complex index `eta + i k`.
    Conductor,
}
