//! # brdf-models
//!
//! Every analytic reflectance model of the study, one per file, each with its
//! formula, parameter table, properties and paper in its doc comment, validated
//! construction and analytic parameter derivatives. All implement
//! [`brdf_core::Parametric`], so any solver fits any of them.
//!
//! ## Catalogue by family
//!
//! | family (feature) | models |
//! | --- | --- |
//! | always | [`Lambert`] |
//! | `phong` | [`Phong`] (modified), [`BlinnPhong`] |
//! | `ward` | [`Ward`], [`WardAniso`], [`WardDuer`], [`WardDuerAniso`] |
//! | `lafortune` | [`Lafortune`] (isotropic and anisotropic, K lobes) |
//! | `microfacet` | [`AshikhminShirley`] (+ anisotropic, coupled diffuse), [`TorranceSparrow`], [`CookTorrance`] (K lobes) |
//! | `microfacet` (fitted-data models) | [`Sgd`] (Bagher 2012), [`LowSmooth`] and [`LowAbc`] (Löw 2012), [`Std`] (Ribardière 2017), [`Dupuy`] and its [`TabulatedMicrofacet`] (Dupuy 2015, normal distribution extracted from the data) |
//! | `oren-nayar` | [`OrenNayar`] (qualitative), [`OrenNayarFull`] (with interreflection) |
//! | `sopp` | [`PhongFresnel`], [`AsPaint`] / [`PaintShader`] (with the `Rs` conversion), [`ClearCoat`] over any base |
//! | `koenderink` | [`Koenderink`] (Zernike expansion of any order) |
//! | `polynomial` | [`KurtPolynomial`] (isotropic and anisotropic) |
//! | `renderer` | [`Ggx`] (K lobes) and the [`ggx`] family (anisotropic; separable Smith; dielectric and conductor Fresnel), [`Principled`] (Disney, as Mitsuba 3), [`GltfPbr`], [`GltfPbrExt`], [`GltfIridescence`], [`ColouredLobes`] (a colour and width per GGX lobe, a dielectric coat) |
//!
//! [`catalogue()`] lists the models compiled into this build; [`build`]
//! constructs one by name. Each entry also states facts about its model
//! ([`entry_facts`]: renderer model, colour structure, optional lobes,
//! default linear solver) that fitting front ends ask instead of matching
//! names.
//!
//! ## Crate features
//!
//! Features only subtract: the default build has every family. A renderer
//! that needs only some families turns the default off and names them.

pub mod aliases;
#[cfg(feature = "microfacet")]
pub mod ashikhmin_shirley;
#[cfg(feature = "phong")]
pub mod blinn_phong;
pub mod catalogue;
pub mod channel_slice;
#[cfg(feature = "sopp")]
pub mod clear_coat;
#[cfg(feature = "renderer")]
pub mod coloured_lobes;
pub mod combinators;
#[cfg(feature = "microfacet")]
pub mod cook_torrance;
#[cfg(feature = "renderer")]
pub mod dual;
#[cfg(feature = "renderer")]
pub mod dual_model;
#[cfg(feature = "microfacet")]
pub mod dupuy;
pub mod entry_facts;
#[cfg(feature = "microfacet")]
pub mod fitted_lobes;
#[cfg(feature = "renderer")]
pub mod ggx;
#[cfg(feature = "renderer")]
pub mod gltf_pbr;
#[cfg(feature = "koenderink")]
pub mod koenderink;
#[cfg(feature = "polynomial")]
pub mod kurt_polynomial;
#[cfg(feature = "lafortune")]
pub mod lafortune;
pub mod lambert;
#[cfg(feature = "microfacet")]
pub mod low;
#[cfg(feature = "microfacet")]
pub mod microfacet;
pub mod model_entry;
#[cfg(feature = "oren-nayar")]
pub mod oren_nayar;
#[cfg(feature = "sopp")]
pub mod paint_shader;
#[cfg(feature = "phong")]
pub mod phong;
#[cfg(feature = "sopp")]
pub mod phong_fresnel;
#[cfg(feature = "renderer")]
pub mod principled;
#[cfg(feature = "serde")]
pub mod saved_model;
#[cfg(feature = "microfacet")]
pub mod sgd;
#[cfg(feature = "microfacet")]
pub mod student_t;
#[cfg(feature = "renderer")]
pub mod thin_film;
#[cfg(feature = "microfacet")]
pub mod torrance_sparrow;
#[cfg(feature = "ward")]
pub mod ward;

#[cfg(feature = "microfacet")]
pub use ashikhmin_shirley::{
    AshikhminShirley, AshikhminShirleyAniso, AshikhminShirleyCoupled, AshikhminShirleyCoupledAniso,
};
#[cfg(feature = "phong")]
pub use blinn_phong::BlinnPhong;
pub use catalogue::{
    ModelConfig, ModelEntry, build, build_for, build_from, by_image_models, catalogue, entry,
    optional_lobes, polish_factor, suggested_starts,
};
#[cfg(feature = "sopp")]
pub use clear_coat::ClearCoat;
#[cfg(feature = "renderer")]
pub use coloured_lobes::ColouredLobes;
#[cfg(feature = "microfacet")]
pub use cook_torrance::CookTorrance;
#[cfg(feature = "microfacet")]
pub use dupuy::{Dupuy, TabulatedMicrofacet, TabulatedNdf};
#[cfg(feature = "microfacet")]
pub use entry_facts::{
    ColourStructure, GgxForm, GgxFresnel, LinearSolver, NonlinearSearch, OptionalLobe, RendererForm,
};
#[cfg(feature = "microfacet")]
pub use fitted_lobes::FittedLobe;
#[cfg(feature = "renderer")]
pub use ggx::{
    Ggx, GgxAniso, GgxAnisoSeparable, GgxConductor, GgxConductorAniso, GgxConductorAnisoSeparable,
    GgxConductorSeparable, GgxDielectric, GgxDielectricAniso, GgxDielectricAnisoSeparable,
    GgxDielectricSeparable, GgxSeparable,
};
#[cfg(feature = "renderer")]
pub use gltf_pbr::iridescence::GltfIridescence;
#[cfg(feature = "renderer")]
pub use gltf_pbr::{GltfPbr, GltfPbrExt};
#[cfg(feature = "koenderink")]
pub use koenderink::Koenderink;
#[cfg(feature = "polynomial")]
pub use kurt_polynomial::{KurtPolynomial, Pca, PolyVariant};
#[cfg(feature = "lafortune")]
pub use lafortune::Lafortune;
pub use lambert::Lambert;
#[cfg(feature = "microfacet")]
pub use low::{LowAbc, LowSmooth};
#[cfg(feature = "oren-nayar")]
pub use oren_nayar::{OrenNayar, OrenNayarFull};
#[cfg(feature = "sopp")]
pub use paint_shader::{AsPaint, PaintShader};
#[cfg(feature = "phong")]
pub use phong::Phong;
#[cfg(feature = "sopp")]
pub use phong_fresnel::PhongFresnel;
#[cfg(feature = "renderer")]
pub use principled::Principled;
#[cfg(feature = "microfacet")]
pub use sgd::Sgd;
#[cfg(feature = "microfacet")]
pub use student_t::Std;
#[cfg(feature = "microfacet")]
pub use torrance_sparrow::TorranceSparrow;
#[cfg(feature = "ward")]
pub use ward::{Ward, WardAniso, WardDuer, WardDuerAniso};
