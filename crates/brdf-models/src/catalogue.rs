//! The catalogue: every model by name, with a constructor from a
//! [`ModelConfig`], so the command line, the study and the tests can build
//! any model without naming its type. Models whose structure depends on
//! the data are built for them: Kurt's polynomial for the direction pairs
//! (`build_for_data`), Dupuy's tabulated microfacet model for the samples
//! (`from_samples`: its normal distribution is extracted from their
//! back-scattering values before the fit solves its free parameters).

use std::sync::OnceLock;

use brdf_core::{DirPairs, ParamError, Parametric, SampleSet};

use crate::Lambert;
use crate::entry_facts::{
    ColourStructure, LinearSolver, NonlinearSearch, OptionalLobe, RendererForm,
};
#[cfg(feature = "renderer")]
use crate::entry_facts::{GgxForm, GgxFresnel};
pub use crate::model_entry::{
    BuildForData, BuildFromSamples, ChannelModel, ModelConfig, ModelEntry, SuggestStarts,
};

/// The polish iteration factor of model `model` (its catalogue entry's
/// [`ModelEntry::polish_factor`]; 1 for a model not in the catalogue).
pub fn polish_factor(model: &dyn Parametric) -> usize {
    entry(model.name()).map_or(1, |e| e.polish_factor.max(1))
}

/// The one-channel model of one channel of `model` (its catalogue entry's
/// [`ModelEntry::channel_model`]); `None` for a model without, or not in
/// the catalogue, or when it cannot be built.
pub fn channel_model(model: &dyn Parametric) -> Option<Box<dyn Parametric>> {
    entry(model.name())
        .and_then(|e| e.channel_model)
        .and_then(|f| f().ok())
}

/// The start points model `model` suggests (its catalogue entry's
/// [`ModelEntry::starts`]); none for a model without, or not in the
/// catalogue.
pub fn suggested_starts(model: &dyn Parametric, data: &SampleSet) -> Vec<Vec<f64>> {
    match entry(model.name()).and_then(|e| e.starts) {
        Some(f) => f(model, data),
        None => Vec::new(),
    }
}

/// Principled's optional lobes, in the order a fit tries them.
#[cfg(feature = "renderer")]
const PRINCIPLED_LOBES: &[OptionalLobe] = &[
    OptionalLobe {
        name: "sheen",
        companions: &["sheen_tint"],
    },
    OptionalLobe {
        name: "clearcoat",
        companions: &["clearcoat_gloss"],
    },
    OptionalLobe {
        name: "anisotropic",
        companions: &[],
    },
];

/// The extended glTF model's optional lobe.
#[cfg(feature = "renderer")]
const GLTF_EXT_LOBES: &[OptionalLobe] = &[OptionalLobe {
    name: "clearcoat",
    companions: &["clearcoat_roughness"],
}];

/// Every model compiled into this build, in a stable order: the table is
/// built once and every lookup reads it.
pub fn catalogue() -> &'static [ModelEntry] {
    static CATALOGUE: OnceLock<Vec<ModelEntry>> = OnceLock::new();
    CATALOGUE.get_or_init(entries)
}

/// The catalogue's entries ([`catalogue`] keeps them).
/// The form of a one-lobe GGX model (unnumbered parameters).
#[cfg(feature = "renderer")]
const fn single_ggx(fresnel: GgxFresnel, anisotropic: bool, separable: bool) -> RendererForm {
    RendererForm::Ggx(GgxForm {
        fresnel,
        anisotropic,
        separable,
        numbered: false,
    })
}

fn entries() -> Vec<ModelEntry> {
    #[allow(unused_mut)]
    let mut v = vec![ModelEntry {
        name: Lambert::NAME,
        family: "lambert",
        summary: "ideal diffuse reflector, f = kd / pi",
        paper: "Lambert 1760, Photometria",
        has_lobes: false,
        build: |c| Ok(Box::new(Lambert::with_channels(c.channels)?)),
        build_for_data: None,
        from_samples: None,
        starts: None,
        polish_factor: 1,
        channel_model: None,
        renderer: false,
        by_image_rank: None,
        colour: ColourStructure::PerLobe,
        optional_lobes: &[],
        linear_solver: LinearSolver::Direct,
        nonlinear_search: NonlinearSearch::Projected,
        form: RendererForm::Diffuse,
    }];
    // Only the lobe families use it; a build without them has no use for it.
    #[cfg(any(feature = "phong", feature = "ward", feature = "microfacet"))]
    macro_rules! lobe_model {
        ($t:ty, $family:literal, $summary:literal, $paper:literal) => {
            lobe_model!($t, $family, $summary, $paper, RendererForm::None)
        };
        ($t:ty, $family:literal, $summary:literal, $paper:literal, $form:expr) => {
            v.push(ModelEntry {
                name: <<$t as crate::combinators::HasLobe>::L as crate::combinators::Lobe>::NAME,
                family: $family,
                summary: $summary,
                paper: $paper,
                has_lobes: false,
                build: |c| Ok(Box::new(<$t>::with_channels(c.channels)?)),
                build_for_data: None,
                from_samples: None,
                starts: None,
                polish_factor: 1,
                channel_model: None,
                renderer: matches!($family, "renderer"),
                by_image_rank: None,
                colour: ColourStructure::PerLobe,
                optional_lobes: &[],
                linear_solver: LinearSolver::Direct,
                nonlinear_search: NonlinearSearch::Projected,
                form: $form,
            })
        };
    }
    #[cfg(feature = "phong")]
    {
        lobe_model!(
            crate::Phong,
            "phong",
            "kd/pi + ks (n+2)/(2 pi) cos^n(alpha_r)",
            "Phong 1975; Lafortune & Willems 1994"
        );
        lobe_model!(
            crate::BlinnPhong,
            "phong",
            "kd/pi + ks (n+2)/(2 pi) cos^n(delta)",
            "Blinn 1977"
        );
    }
    #[cfg(feature = "ward")]
    {
        lobe_model!(
            crate::Ward,
            "ward",
            "kd/pi + ks exp(-tan^2 delta/a^2)/(4 pi a^2 sqrt(cos_i cos_o))",
            "Ward 1992"
        );
        lobe_model!(
            crate::WardAniso,
            "ward",
            "Ward with roughness ax, ay along x, y",
            "Ward 1992"
        );
        lobe_model!(
            crate::WardDuer,
            "ward",
            "Ward with cos_i cos_o in the denominator",
            "Duer 2004"
        );
        lobe_model!(
            crate::WardDuerAniso,
            "ward",
            "Ward-Duer with roughness ax, ay",
            "Duer 2004"
        );
    }
    #[cfg(feature = "microfacet")]
    {
        lobe_model!(
            crate::AshikhminShirley,
            "microfacet",
            "kd/pi + ks (n+1)/(8 pi) (N.H)^n F(V.H) / ((V.H) max(N.L, N.V))",
            "Ashikhmin & Shirley 2000, Journal of Graphics Tools"
        );
        lobe_model!(
            crate::AshikhminShirleyAniso,
            "microfacet",
            "Ashikhmin-Shirley with exponents nu, nv (anisotropic)",
            "Ashikhmin & Shirley 2000, Journal of Graphics Tools"
        );
        lobe_model!(
            crate::AshikhminShirleyCoupled,
            "microfacet",
            "Ashikhmin-Shirley with the coupled diffuse term 28 kd/(23 pi)(1-F0)(...)",
            "Ashikhmin & Shirley 2000, Journal of Graphics Tools"
        );
        lobe_model!(
            crate::AshikhminShirleyCoupledAniso,
            "microfacet",
            "anisotropic Ashikhmin-Shirley with the coupled diffuse term",
            "Ashikhmin & Shirley 2000, Journal of Graphics Tools"
        );
        lobe_model!(
            crate::TorranceSparrow,
            "microfacet",
            "kd/pi + ks D G F / (N.L N.V), Gaussian D = exp(-(delta/m)^2)/(pi m^2)",
            "Torrance & Sparrow 1967, JOSA; normalisation of Ramamoorthi & Hanrahan 2001"
        );
        lobe_model!(
            crate::Std,
            "microfacet",
            "kd/pi + ks D G F / (4 N.L N.V): Student's t slopes (GGX at gamma 2, Beckmann as gamma grows), exact Smith, Schlick F",
            "Ribardière, Bringier, Meneveaux & Simonot 2017, Computer Graphics Forum 36(2)"
        );
        v.push(ModelEntry {
            name: <crate::cook_torrance::CtLobe as crate::combinators::Lobe>::NAME,
            family: "microfacet",
            summary: "kd/pi + sum_k ks_k/pi D_k G F_k / (N.L N.V), Beckmann D, K lobes",
            paper: "Cook & Torrance 1982, ACM TOG",
            has_lobes: true,
            build: |c| Ok(Box::new(crate::CookTorrance::new(c.lobes, c.channels)?)),
            build_for_data: None,
            from_samples: None,
            starts: None,
            polish_factor: 1,
            channel_model: None,
            renderer: false,
            by_image_rank: None,
            colour: ColourStructure::PerLobe,
            optional_lobes: &[],
            linear_solver: LinearSolver::Direct,
            nonlinear_search: NonlinearSearch::Projected,
            form: RendererForm::None,
        });
        v.push(ModelEntry {
            name: <crate::sgd::SgdShape as crate::fitted_lobes::FittedShape>::NAME,
            family: "microfacet",
            summary: "kd/pi + ks D G1 G1 F / (pi N.L N.V): shifted gamma D, fitted shadowing, F0/F1 Fresnel; every parameter per channel",
            paper: "Bagher, Soler & Holzschuch 2012, Computer Graphics Forum 31(4)",
            has_lobes: false,
            build: |c| Ok(Box::new(crate::Sgd::with_channels(c.channels)?)),
            build_for_data: None,
            from_samples: None,
            starts: Some(|m, _| crate::sgd::suggested_starts(m)),
            polish_factor: 10,
            channel_model: Some(|| Ok(Box::new(crate::sgd::channel::SgdChannel::with_defaults()?))),
            renderer: false,
            by_image_rank: None,
            colour: ColourStructure::PerLobe,
            optional_lobes: &[],
            linear_solver: LinearSolver::Direct,
            nonlinear_search: NonlinearSearch::Projected,
            form: RendererForm::None,
        });
        v.push(ModelEntry {
            name: <crate::low::LowAbcShape as crate::fitted_lobes::FittedShape>::NAME,
            family: "microfacet",
            summary: "kd/pi + A D G F(eta) / (pi N.L N.V), D = (1 + B (1 - N.H))^-C, V-groove G",
            paper: "Löw, Kronander, Ynnerman & Unger 2012, ACM TOG 31(1)",
            has_lobes: false,
            build: |c| Ok(Box::new(crate::LowAbc::with_channels(c.channels)?)),
            build_for_data: None,
            from_samples: None,
            starts: None,
            polish_factor: 1,
            channel_model: None,
            renderer: false,
            by_image_rank: None,
            colour: ColourStructure::PerLobe,
            optional_lobes: &[],
            linear_solver: LinearSolver::Direct,
            nonlinear_search: NonlinearSearch::Projected,
            form: RendererForm::None,
        });
        v.push(ModelEntry {
            name: <crate::low::LowSmoothShape as crate::fitted_lobes::FittedShape>::NAME,
            family: "microfacet",
            summary: "kd/pi + A F(eta) / (1 + B |Lp + Vp|^2)^C, smooth-surface model",
            paper: "Löw, Kronander, Ynnerman & Unger 2012, ACM TOG 31(1)",
            has_lobes: false,
            build: |c| Ok(Box::new(crate::LowSmooth::with_channels(c.channels)?)),
            build_for_data: None,
            from_samples: None,
            starts: None,
            polish_factor: 1,
            channel_model: None,
            renderer: false,
            by_image_rank: None,
            colour: ColourStructure::PerLobe,
            optional_lobes: &[],
            linear_solver: LinearSolver::Direct,
            nonlinear_search: NonlinearSearch::Projected,
            form: RendererForm::None,
        });
        v.push(ModelEntry {
            name: crate::dupuy::NAME,
            family: "microfacet",
            summary: "kd/pi + (F + S (1 - V.H)^5) D G / (4 N.L N.V): D tabulated from the data's back-scattering by power iteration, Smith G from it",
            paper: "Dupuy, Heitz, Iehl, Poulin & Ostromoukhov 2015, Computer Graphics Forum 34(4)",
            has_lobes: false,
            build: |c| Ok(Box::new(crate::Dupuy::with_channels(c.channels)?)),
            build_for_data: None,
            from_samples: Some(|c, s| Ok(Box::new(crate::Dupuy::from_samples(c.channels, s)?))),
            starts: None,
            polish_factor: 1,
            channel_model: None,
            renderer: false,
            by_image_rank: None,
            colour: ColourStructure::PerLobe,
            optional_lobes: &[],
            linear_solver: LinearSolver::Direct,
            nonlinear_search: NonlinearSearch::Projected,
            form: RendererForm::None,
        });
    }
    #[cfg(feature = "lafortune")]
    {
        v.push(ModelEntry {
            name: crate::Lafortune::NAME,
            family: "lafortune",
            summary: "kd/pi + K generalised cosine lobes Cxy (ux vx + uy vy) + Cz uz vz",
            paper: "Lafortune, Foo, Torrance & Greenberg 1997, SIGGRAPH",
            has_lobes: true,
            build: |c| Ok(Box::new(crate::Lafortune::new(false, c.lobes, c.channels)?)),
            build_for_data: None,
            from_samples: None,
            starts: None,
            polish_factor: 1,
            channel_model: None,
            renderer: false,
            by_image_rank: None,
            colour: ColourStructure::PerLobe,
            optional_lobes: &[],
            linear_solver: LinearSolver::Direct,
            nonlinear_search: NonlinearSearch::Projected,
            form: RendererForm::None,
        });
        v.push(ModelEntry {
            name: crate::Lafortune::NAME_ANISO,
            family: "lafortune",
            summary: "Lafortune with Cx, Cy, Cz per lobe",
            paper: "Lafortune, Foo, Torrance & Greenberg 1997, SIGGRAPH",
            has_lobes: true,
            build: |c| Ok(Box::new(crate::Lafortune::new(true, c.lobes, c.channels)?)),
            build_for_data: None,
            from_samples: None,
            starts: None,
            polish_factor: 1,
            channel_model: None,
            renderer: false,
            by_image_rank: None,
            colour: ColourStructure::PerLobe,
            optional_lobes: &[],
            linear_solver: LinearSolver::Direct,
            nonlinear_search: NonlinearSearch::Projected,
            form: RendererForm::None,
        });
    }
    #[cfg(feature = "oren-nayar")]
    v.push(ModelEntry {
        name: crate::OrenNayar::NAME,
        family: "oren-nayar",
        summary: "kd/pi (A + B max(0, cos dphi) sin alpha tan beta), rough diffuse",
        paper: "Oren & Nayar 1994, SIGGRAPH",
        has_lobes: false,
        build: |c| Ok(Box::new(crate::OrenNayar::with_channels(c.channels)?)),
        build_for_data: None,
        from_samples: None,
        starts: None,
        polish_factor: 1,
        channel_model: None,
        renderer: false,
        by_image_rank: None,
        colour: ColourStructure::PerLobe,
        optional_lobes: &[],
        linear_solver: LinearSolver::Direct,
        nonlinear_search: NonlinearSearch::Projected,
        form: RendererForm::None,
    });
    #[cfg(feature = "oren-nayar")]
    v.push(ModelEntry {
        name: crate::OrenNayarFull::NAME,
        family: "oren-nayar",
        summary: "full Oren-Nayar with the interreflection term (kd enters squared), clamped at 0",
        paper: "Oren & Nayar 1994, SIGGRAPH",
        has_lobes: false,
        build: |c| Ok(Box::new(crate::OrenNayarFull::with_channels(c.channels)?)),
        build_for_data: None,
        from_samples: None,
        starts: None,
        polish_factor: 1,
        channel_model: None,
        renderer: false,
        by_image_rank: None,
        colour: ColourStructure::PerLobe,
        optional_lobes: &[],
        linear_solver: LinearSolver::Direct,
        nonlinear_search: NonlinearSearch::Projected,
        form: RendererForm::None,
    });
    #[cfg(feature = "sopp")]
    {
        lobe_model!(
            crate::PhongFresnel,
            "sopp",
            "cd/pi + (ns+2)/(2 pi) cs (R.V)^ns (1 - Fr(theta_i; eta)), not reciprocal",
            "Sopp 2017, MSc thesis, THM Friedberg"
        );
        lobe_model!(
            crate::AsPaint,
            "sopp",
            "Ashikhmin-Shirley paint shader, fitted form cd/pi + cs (ns+1)/(8 pi) (N.H)^ns / ((H.V) max(N.L, N.V)); Rs by conversion",
            "Sopp 2017, MSc thesis, THM Friedberg"
        );
        v.push(ModelEntry {
            name: crate::ClearCoat::NAME,
            family: "sopp",
            summary: "clear coat (eta 1.5) over the AS paint shader: Fr(theta_i) + (1 - Fr) f_base, not reciprocal",
            paper: "Sopp 2017, MSc thesis, THM Friedberg",
            has_lobes: false,
            build: |c| {
                Ok(Box::new(crate::ClearCoat::new(
                    Box::new(crate::AsPaint::with_channels(c.channels)?),
                    1.5,
                )?))
            },
            build_for_data: None,
            from_samples: None,
            starts: None,
            polish_factor: 1,
            channel_model: None,
            renderer: false,
            by_image_rank: None,
            colour: ColourStructure::PerLobe,
            optional_lobes: &[],
            linear_solver: LinearSolver::Direct,
            nonlinear_search: NonlinearSearch::Projected,
            form: RendererForm::None,
        });
    }
    #[cfg(feature = "koenderink")]
    v.push(ModelEntry {
        name: crate::Koenderink::NAME,
        family: "koenderink",
        summary: "Zernike-product expansion of order N, linear in all coefficients (5, 14, 55 for N = 2, 4, 8)",
        paper: "Koenderink, van Doorn & Stavridis 1996, ECCV",
        has_lobes: false,
        build: |c| Ok(Box::new(crate::Koenderink::new(c.order, c.channels)?)),
        build_for_data: None,
        from_samples: None,
        starts: None,
        polish_factor: 1,
        channel_model: None,
        renderer: false,
        by_image_rank: None,
        colour: ColourStructure::PerLobe,
        optional_lobes: &[],
        linear_solver: LinearSolver::Direct,
        nonlinear_search: NonlinearSearch::Projected,
        form: RendererForm::None,
    });
    #[cfg(feature = "polynomial")]
    {
        use crate::kurt_polynomial::{KurtPolynomial, Pca, PolyVariant};
        v.push(ModelEntry {
            name: KurtPolynomial::NAME,
            family: "polynomial",
            summary: "Kurt's PCA response surface in W1 = ux vx + uy vy, W2 = uz vz; 2p+1 coefficients",
            paper: "Kurt 2007, MSc thesis, Ege University",
            has_lobes: false,
            build: |c| {
                Ok(Box::new(KurtPolynomial::new(
                    PolyVariant::Isotropic,
                    c.degree,
                    c.channels,
                    Pca::identity(2),
                )?))
            },
            build_for_data: Some(|c, pairs| {
                let pca = Pca::from_pairs(PolyVariant::Isotropic, pairs)?;
                Ok(Box::new(KurtPolynomial::new(PolyVariant::Isotropic, c.degree, c.channels, pca)?))
            }),
            from_samples: None,
            starts: None,
            polish_factor: 1,
            channel_model: None,
            renderer: false,
            by_image_rank: None,
            colour: ColourStructure::PerLobe,
            optional_lobes: &[],
            linear_solver: LinearSolver::RobustIrls,
            nonlinear_search: NonlinearSearch::Projected,
            form: RendererForm::None,
        });
        v.push(ModelEntry {
            name: KurtPolynomial::NAME_ANISO,
            family: "polynomial",
            summary: "Kurt's PCA response surface in X1 = ux vx, X2 = uy vy, X3 = uz vz; 3p+1 coefficients",
            paper: "Kurt 2007, MSc thesis, Ege University",
            has_lobes: false,
            build: |c| {
                Ok(Box::new(KurtPolynomial::new(
                    PolyVariant::Anisotropic,
                    c.degree,
                    c.channels,
                    Pca::identity(3),
                )?))
            },
            build_for_data: Some(|c, pairs| {
                let pca = Pca::from_pairs(PolyVariant::Anisotropic, pairs)?;
                Ok(Box::new(KurtPolynomial::new(PolyVariant::Anisotropic, c.degree, c.channels, pca)?))
            }),
            from_samples: None,
            starts: None,
            polish_factor: 1,
            channel_model: None,
            renderer: false,
            by_image_rank: None,
            colour: ColourStructure::PerLobe,
            optional_lobes: &[],
            linear_solver: LinearSolver::RobustIrls,
            nonlinear_search: NonlinearSearch::Projected,
            form: RendererForm::None,
        });
    }
    #[cfg(feature = "renderer")]
    {
        v.push(ModelEntry {
            name: <crate::ggx::GgxLobe as crate::combinators::Lobe>::NAME,
            family: "renderer",
            summary: "kd/pi + sum_k ks_k D G F / (4 N.L N.V): GGX, height-correlated Smith, Schlick F, K lobes",
            paper: "Walter, Marschner, Li & Torrance 2007, EGSR; Heitz 2014, JCGT 3(2)",
            has_lobes: true,
            build: |c| Ok(Box::new(crate::Ggx::new(c.lobes, c.channels)?)),
            build_for_data: None,
            from_samples: None,
            starts: None,
            polish_factor: 1,
            channel_model: None,
            renderer: true,
            by_image_rank: Some(3),
            colour: ColourStructure::PerLobe,
            optional_lobes: &[],
            linear_solver: LinearSolver::Direct,
            nonlinear_search: NonlinearSearch::Projected,
            form: RendererForm::Ggx(GgxForm { fresnel: GgxFresnel::Schlick, anisotropic: false, separable: false, numbered: true }),
        });
        v.push(ModelEntry {
            name: <crate::ggx::GgxSeparableLobe as crate::combinators::Lobe>::NAME,
            family: "renderer",
            summary: "GGX with the separable Smith G1(L) G1(V) (Mitsuba 3), Schlick F, K lobes",
            paper: "Walter, Marschner, Li & Torrance 2007, EGSR; Heitz 2014, JCGT 3(2)",
            has_lobes: true,
            build: |c| Ok(Box::new(crate::GgxSeparable::new(c.lobes, c.channels)?)),
            build_for_data: None,
            from_samples: None,
            starts: None,
            polish_factor: 1,
            channel_model: None,
            renderer: true,
            by_image_rank: None,
            colour: ColourStructure::PerLobe,
            optional_lobes: &[],
            linear_solver: LinearSolver::Direct,
            nonlinear_search: NonlinearSearch::Projected,
            form: RendererForm::Ggx(GgxForm {
                fresnel: GgxFresnel::Schlick,
                anisotropic: false,
                separable: true,
                numbered: true,
            }),
        });
        lobe_model!(
            crate::GgxAniso,
            "renderer",
            "kd/pi + ks D G F / (4 N.L N.V): anisotropic GGX (ax, ay), height-correlated Smith, Schlick F",
            "Walter, Marschner, Li & Torrance 2007, EGSR; Heitz 2014, JCGT 3(2)",
            single_ggx(GgxFresnel::Schlick, true, false)
        );
        lobe_model!(
            crate::GgxAnisoSeparable,
            "renderer",
            "anisotropic GGX, separable Smith, Schlick F",
            "Walter, Marschner, Li & Torrance 2007, EGSR; Heitz 2014, JCGT 3(2)",
            single_ggx(GgxFresnel::Schlick, true, true)
        );
        lobe_model!(
            crate::GgxDielectric,
            "renderer",
            "kd/pi + ks D G F_dielectric(eta) / (4 N.L N.V): GGX, height-correlated Smith",
            "Walter, Marschner, Li & Torrance 2007, EGSR; Heitz 2014, JCGT 3(2)",
            single_ggx(GgxFresnel::Dielectric, false, false)
        );
        lobe_model!(
            crate::GgxDielectricSeparable,
            "renderer",
            "GGX, separable Smith, exact dielectric F(eta)",
            "Walter, Marschner, Li & Torrance 2007, EGSR; Heitz 2014, JCGT 3(2)",
            single_ggx(GgxFresnel::Dielectric, false, true)
        );
        lobe_model!(
            crate::GgxDielectricAniso,
            "renderer",
            "anisotropic GGX, height-correlated Smith, exact dielectric F(eta)",
            "Walter, Marschner, Li & Torrance 2007, EGSR; Heitz 2014, JCGT 3(2)",
            single_ggx(GgxFresnel::Dielectric, true, false)
        );
        lobe_model!(
            crate::GgxDielectricAnisoSeparable,
            "renderer",
            "anisotropic GGX, separable Smith, exact dielectric F(eta)",
            "Walter, Marschner, Li & Torrance 2007, EGSR; Heitz 2014, JCGT 3(2)",
            single_ggx(GgxFresnel::Dielectric, true, true)
        );
        lobe_model!(
            crate::GgxConductor,
            "renderer",
            "kd/pi + ks D G F_conductor(eta, k) / (4 N.L N.V): GGX, height-correlated Smith",
            "Walter, Marschner, Li & Torrance 2007, EGSR; Heitz 2014, JCGT 3(2)",
            single_ggx(GgxFresnel::Conductor, false, false)
        );
        lobe_model!(
            crate::GgxConductorSeparable,
            "renderer",
            "GGX, separable Smith, exact conductor F(eta, k) (Mitsuba 3 roughconductor)",
            "Walter, Marschner, Li & Torrance 2007, EGSR; Heitz 2014, JCGT 3(2)",
            single_ggx(GgxFresnel::Conductor, false, true)
        );
        lobe_model!(
            crate::GgxConductorAniso,
            "renderer",
            "anisotropic GGX, height-correlated Smith, exact conductor F(eta, k)",
            "Walter, Marschner, Li & Torrance 2007, EGSR; Heitz 2014, JCGT 3(2)",
            single_ggx(GgxFresnel::Conductor, true, false)
        );
        lobe_model!(
            crate::GgxConductorAnisoSeparable,
            "renderer",
            "anisotropic GGX, separable Smith, exact conductor F(eta, k)",
            "Walter, Marschner, Li & Torrance 2007, EGSR; Heitz 2014, JCGT 3(2)",
            single_ggx(GgxFresnel::Conductor, true, true)
        );
        v.push(ModelEntry {
            name: <crate::principled::PrincipledFormula as crate::dual_model::DualFormula>::NAME,
            family: "renderer",
            summary: "Disney principled BRDF (reflection) as Mitsuba 3's principled: base_color, metallic, specular, spec_tint, roughness, anisotropic, sheen, sheen_tint, clearcoat, clearcoat_gloss",
            paper: "Burley 2012, SIGGRAPH course; Burley 2015; Mitsuba 3 principled",
            has_lobes: false,
            build: |c| Ok(Box::new(crate::Principled::with_channels(c.channels)?)),
            build_for_data: None,
            from_samples: None,
            starts: None,
            polish_factor: 1,
            channel_model: None,
            renderer: true,
            by_image_rank: Some(0),
            colour: ColourStructure::Single,
            optional_lobes: PRINCIPLED_LOBES,
            linear_solver: LinearSolver::Direct,
            nonlinear_search: NonlinearSearch::Projected,
            form: RendererForm::Principled,
        });
        v.push(ModelEntry {
            name: <crate::gltf_pbr::GltfFormula as crate::dual_model::DualFormula>::NAME,
            family: "renderer",
            summary: "glTF 2.0 metallic-roughness: Lambert + GGX (height-correlated), F0 = 0.04 mixed with base_color by metallic",
            paper: "Khronos glTF 2.0 specification, Appendix B",
            has_lobes: false,
            build: |c| Ok(Box::new(crate::GltfPbr::with_channels(c.channels)?)),
            build_for_data: None,
            from_samples: None,
            starts: None,
            polish_factor: 1,
            channel_model: None,
            renderer: true,
            by_image_rank: Some(1),
            colour: ColourStructure::Single,
            optional_lobes: &[],
            linear_solver: LinearSolver::Direct,
            nonlinear_search: NonlinearSearch::Projected,
            form: RendererForm::Gltf { extended: false },
        });
        v.push(ModelEntry {
            name: <crate::gltf_pbr::GltfExtFormula as crate::dual_model::DualFormula>::NAME,
            family: "renderer",
            summary: "glTF 2.0 with KHR_materials_ior, _specular and _clearcoat (coat Fresnel in N.V: not reciprocal)",
            paper: "Khronos glTF 2.0 specification, Appendix B; KHR_materials_ior/_specular/_clearcoat",
            has_lobes: false,
            build: |c| Ok(Box::new(crate::GltfPbrExt::with_channels(c.channels)?)),
            build_for_data: None,
            from_samples: None,
            starts: None,
            polish_factor: 1,
            channel_model: None,
            renderer: true,
            by_image_rank: Some(2),
            colour: ColourStructure::PerLobe,
            optional_lobes: GLTF_EXT_LOBES,
            linear_solver: LinearSolver::Direct,
            nonlinear_search: NonlinearSearch::Projected,
            form: RendererForm::Gltf { extended: true },
        });
        v.push(ModelEntry {
            name: <crate::gltf_pbr::iridescence::GltfIridescenceFormula as crate::dual_model::DualFormula>::NAME,
            family: "renderer",
            summary: "gltf-ext with KHR_materials_iridescence: its Fresnel mixed with a thin film's (Schlick interfaces, Fourier-domain spectral sum)",
            paper: "Khronos glTF 2.0 specification, Appendix B; KHR_materials_iridescence; Belcour & Barla 2017, ACM TOG 36(4):65",
            has_lobes: false,
            build: |c| Ok(Box::new(crate::GltfIridescence::with_channels(c.channels)?)),
            build_for_data: None,
            from_samples: None,
            starts: Some(crate::gltf_pbr::iridescence::screened_starts),
            polish_factor: 1,
            channel_model: None,
            renderer: true,
            by_image_rank: None,
            colour: ColourStructure::PerLobe,
            optional_lobes: &[],
            linear_solver: LinearSolver::Direct,
            nonlinear_search: NonlinearSearch::Projected,
            form: RendererForm::GltfIridescence,
        });
    }
    #[cfg(feature = "renderer")]
    v.extend(crate::coloured_lobes::entries());
    #[cfg(feature = "renderer")]
    v.extend(crate::thin_film::entries());
    v
}

/// The models selection by image error chooses among, in the order of its
/// rows ([`ModelEntry::by_image_rank`]).
pub fn by_image_models() -> Vec<&'static str> {
    let mut ranked: Vec<(u8, &'static str)> = catalogue()
        .iter()
        .filter_map(|e| e.by_image_rank.map(|r| (r, e.name)))
        .collect();
    ranked.sort_unstable();
    ranked.into_iter().map(|(_, name)| name).collect()
}

/// The optional lobes of catalogue model `name` ([`ModelEntry::optional_lobes`];
/// none for a model not in the catalogue).
pub fn optional_lobes(name: &str) -> &'static [OptionalLobe] {
    entry(name).map_or(&[], |e| e.optional_lobes)
}

/// Build a model by name for the samples it will be fitted to
/// ([`ModelEntry::build_from`]).
pub fn build_from(
    name: &str,
    config: &ModelConfig,
    samples: &SampleSet,
) -> Result<Box<dyn Parametric>, ParamError> {
    entry_or_error(name).and_then(|e| e.build_from(config, samples))
}

/// Look up a model by name.
pub fn entry(name: &str) -> Option<ModelEntry> {
    catalogue().iter().find(|e| e.name == name).copied()
}

/// Build a model by name at its default parameters.
pub fn build(name: &str, config: &ModelConfig) -> Result<Box<dyn Parametric>, ParamError> {
    entry_or_error(name).and_then(|e| (e.build)(config))
}

/// Build a model by name for the direction pairs it will be fitted at
/// ([`ModelEntry::build_for`]).
pub fn build_for(
    name: &str,
    config: &ModelConfig,
    pairs: &DirPairs,
) -> Result<Box<dyn Parametric>, ParamError> {
    entry_or_error(name).and_then(|e| e.build_for(config, pairs))
}

fn entry_or_error(name: &str) -> Result<ModelEntry, ParamError> {
    match entry(name) {
        Some(e) => Ok(e),
        None => Err(ParamError::Config {
            model: name.to_string(),
            reason: format!(
                "no such model; available: {}",
                catalogue()
                    .iter()
                    .map(|e| e.name)
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every optional lobe and companion an entry names is a parameter of
    /// its model, the lobe with a lower bound of 0 (held there to switch
    /// it off); only renderer models have optional lobes.
    #[test]
    fn optional_lobes_name_parameters_of_their_models() {
        for e in catalogue().iter().filter(|e| !e.optional_lobes.is_empty()) {
            assert!(e.renderer, "{}", e.name);
            let m = (e.build)(&ModelConfig::default()).expect("model");
            let specs = m.param_specs();
            let spec = |n: &str| specs.iter().find(|s| s.name == n);
            for lobe in e.optional_lobes {
                let s = spec(lobe.name).unwrap_or_else(|| panic!("{}: no `{}`", e.name, lobe.name));
                assert_eq!(s.lower, 0.0, "{}: {}", e.name, lobe.name);
                for c in lobe.companions {
                    assert!(spec(c).is_some(), "{}: no `{c}`", e.name);
                }
            }
        }
        assert!(optional_lobes("lambert").is_empty());
    }

    /// Selection by image error compares one model of each renderer kind,
    /// in a fixed order.
    #[cfg(feature = "renderer")]
    #[test]
    fn by_image_models_keep_their_order() {
        assert_eq!(by_image_models(), ["principled", "gltf", "gltf-ext", "ggx"]);
    }
}
