//! `brdf fit --for RENDERER`: among the models a renderer renders exactly,
//! the one whose render is closest to the data, fitted for appearance and
//! written as that renderer's material, in one step.
//!
//! The candidates are the catalogue's renderer models that the target's
//! exporter writes exactly, neither converted nor mapped ([`exact_models`],
//! the same judgement as `brdf export --list`), so the list cannot drift
//! from what is written. Each
//! candidate is fitted for appearance as `brdf fit` fits it and judged at
//! the report size by selection by image error
//! ([`brdf_fit::SelectRequest`]); the least mean FLIP wins.

use brdf_fit::judged::COLOUR_PLANE_NOTE;
use brdf_fit::select_by_image::{ImageChoice, ModelSpec};
use brdf_fit::{FitReport, Material, SelectOutcome, SelectRequest};
use brdf_models::{RendererForm, catalogue};

use crate::convert::{Conversion, DELTA_E_WARN, FLIP_WARN};
use crate::table::{Support, support};
use crate::{ExportError, FrontEnd, Target, WriteOptions, export_with};

/// What [`fit_for`] gives.
pub struct ForRenderer {
    /// Every candidate's fit for appearance and image errors.
    pub rows: Vec<ImageChoice>,
    /// Index of the choice in `rows`.
    pub choice: usize,
    /// The chosen model's fit.
    pub report: FitReport,
    /// The material file's text, exact for `target`.
    pub text: String,
}

/// Why [`fit_for`] failed.
#[derive(Debug, thiserror::Error)]
pub enum ForRendererError {
    /// The target renders no catalogue renderer model exactly.
    #[error(
        "--for {target}: no model of the catalogue renders exactly in it; export a fit with `brdf export --to {target}` instead (a conversion, its image error printed)"
    )]
    NoExactModel {
        /// the target's name
        target: String,
    },
    /// Fitting or judging failed.
    #[error(transparent)]
    Fit(#[from] brdf_fit::FitError),
    /// Writing the material failed.
    #[error(transparent)]
    Export(#[from] ExportError),
}

/// The catalogue's renderer models that `target` renders exactly: those its
/// exporter writes neither converted nor mapped onto a material of its own
/// ([`Support::Exact`], as `brdf export --list` says).
pub fn exact_models(target: Target) -> Vec<&'static str> {
    catalogue()
        .iter()
        .filter(|e| e.renderer && support(e.name, target) == Support::Exact)
        .map(|e| e.name)
        .collect()
}

/// What [`select_for`] gives: the choice among the models a renderer
/// renders exactly, before anything is written.
pub struct ForSelection {
    /// Every candidate's fit for appearance and image errors.
    pub rows: Vec<ImageChoice>,
    /// Index of the choice in `rows`.
    pub choice: usize,
    /// The chosen model's fit.
    pub report: FitReport,
}

/// The candidates of [`select_for`] on `material`: [`exact_models`], less
/// the anisotropic forms when the data are isotropic (as a fit for
/// appearance does not try anisotropy there: an anisotropic twin can only
/// tie, at the price of a fit; on cc_iris_purple_gem the three took 14 s
/// of the 88 s of processor time of `--for mitsuba` and rendered within
/// 0.001 of their isotropic twins).
///
/// glTF's thin film (`gltf-iridescence`) is a candidate only where the
/// data's colours leave every plane of white and one colour (beyond
/// [`COLOUR_PLANE_NOTE`], as the colour-plane note says): there a film
/// can follow the hue the single-colour materials cannot, elsewhere it can
/// only tie with `gltf-ext` at many times its fit's cost (its formula is
/// evaluated over dual numbers: 54 s on cc_iris_purple_gem against 25 s
/// for `gltf-ext`, in one `--for gltf` run).
///
/// Where the data's colours leave every colour plane by more than
/// [`TWO_LOBES_OUTSIDE`], the coloured-lobe model with a conductor lobe is
/// also tried with a second, plain lobe ([`TWO_LOBES`]).
pub fn candidates_for(material: &Material, target: Target) -> Vec<ModelSpec> {
    let isotropic = material
        .dense()
        .is_some_and(brdf_fit::isotropy::is_isotropic);
    // How far the data's colours leave the nearest plane of white and one
    // colour (0 where they cannot be rendered); asked only where a
    // candidate depends on it.
    let outside = || {
        material
            .judge()
            .ok()
            .flatten()
            .and_then(|j| j.data_colour_plane())
            .map_or(0.0, |c| c.outside)
    };
    let off_plane = || outside() > COLOUR_PLANE_NOTE;
    let names: Vec<&str> = exact_models(target)
        .into_iter()
        .filter(|name| {
            let Some(e) = catalogue::entry(name) else {
                return true;
            };
            !(isotropic && e.form.is_anisotropic())
                && (e.form != RendererForm::GltfIridescence || off_plane())
        })
        .collect();
    let two_lobes: Vec<ModelSpec> = names
        .iter()
        .filter(|n| {
            TWO_LOBES
                .iter()
                .any(|t| n.starts_with(t) && !n.contains("coat"))
        })
        .map(|n| ModelSpec {
            name: n.to_string(),
            lobes: 2,
        })
        .collect();
    let mut specs: Vec<ModelSpec> = names.iter().map(|n| ModelSpec::named(n)).collect();
    if !two_lobes.is_empty() && outside() > TWO_LOBES_OUTSIDE {
        specs.extend(two_lobes);
    }
    specs
}

/// The coloured-lobe models tried with a second lobe on data whose
/// colours leave every colour plane (the films: a highlight of one hue
/// over a body of another). Measured with brdf-render's judge (128 px,
/// sky / studio HDR-FLIP), `lobes-conductor-mitsuba` with one lobe and two:
/// cc_ibiza_sunset 0.297 / 0.170 and 0.261 / 0.142, cc_iris_purple_gem
/// 0.307 / 0.210 and 0.304 / 0.183, vch_golden_yellow 0.191 / 0.138 and
/// 0.172 / 0.119; `lobes-f82-cycles` on cc_ibiza_sunset gained
/// nothing (0.302 / 0.207 and 0.274 / 0.212).
pub const TWO_LOBES: [&str; 1] = ["lobes-conductor-"];

/// How far the data's colours must leave every colour plane (the judge's
/// `outside`, under white light) for [`TWO_LOBES`] to be tried: the three
/// films of the RGL files lie 0.010-0.036 outside, the two paints
/// 0.0005-0.0016 (`results/colour_planes.md`).
pub const TWO_LOBES_OUTSIDE: f64 = 0.005;

/// Fit every model `target` renders exactly to the request's material for
/// appearance and keep the one of least image error (`brdf select
/// --for`). The request gives the angle limit, the polish and the
/// progress; the models and the way of choosing are the target's (a
/// request naming models is refused, as are the options of a selection by
/// L2).
pub fn select_for(
    request: &SelectRequest<'_>,
    target: Target,
) -> Result<ForSelection, ForRendererError> {
    let material = request.material;
    if !request.among.models.is_empty() {
        return Err(brdf_fit::FitError::InvalidOption {
            option: "models",
            value: request.among.models.join(","),
            expected: "none with --for: it chooses among the models the renderer renders exactly",
        }
        .into());
    }
    let models = candidates_for(material, target);
    if models.is_empty() {
        return Err(ForRendererError::NoExactModel {
            target: target.to_string(),
        });
    }
    let SelectOutcome::Image {
        rows,
        choice,
        chosen,
        ..
    } = request.by_image_among(&models)?
    else {
        // A selection by image always answers with image rows.
        return Err(brdf_fit::FitError::NoModelToFit.into());
    };
    Ok(ForSelection {
        rows,
        choice,
        report: *chosen,
    })
}

/// [`select_for`], the choice written as `target`'s material (`brdf fit
/// --for`).
pub fn fit_for(
    request: &SelectRequest<'_>,
    target: Target,
    write: &WriteOptions,
) -> Result<ForRenderer, ForRendererError> {
    let s = select_for(request, target)?;
    let text = export_with(s.report.model.as_ref(), target, None, write)?;
    Ok(ForRenderer {
        rows: s.rows,
        choice: s.choice,
        report: s.report,
        text,
    })
}

/// The warning written with a conversion `c` to `target` beyond
/// [`FLIP_WARN`] or [`DELTA_E_WARN`]: its image error and the route that
/// renders the data exactly (`--for`, where the target has models it
/// renders exactly; the target's own model otherwise), in `front`'s words.
pub fn conversion_warning(c: &Conversion, target: Target, front: FrontEnd) -> Option<String> {
    let (flip, delta_e) = (c.image.max_flip(), c.image.max_delta_e());
    if flip <= FLIP_WARN && delta_e <= DELTA_E_WARN {
        return None;
    }
    let route = if exact_models(target).is_empty() {
        format!(
            "fit {} to the data directly for a closer material",
            front.fit_hint(c.model.name())
        )
    } else {
        format!(
            "fit the data for {target} instead: {} renders exactly what it fits",
            front.for_hint(target)
        )
    };
    Some(format!(
        "`{}` has no exact {target} equivalent; the `{}` written renders differently (HDR-FLIP {flip:.3} under one light set, CIEDE2000 {delta_e:.2}; warned above {FLIP_WARN} or {DELTA_E_WARN}): {route}",
        c.source,
        c.model.name(),
    ))
}

#[cfg(test)]
mod tests {
    use brdf_core::SampleSet;
    use brdf_fit::select::Among;
    use brdf_models::{ModelConfig, build};

    use super::*;

    /// A material whose dense data is the catalogue model `name` at `p`.
    fn material(name: &str, p: &[f64]) -> Material {
        let mut m = build(name, &ModelConfig::default()).expect("model");
        m.set_params(p).expect("in the box");
        let samples = SampleSet::new("synthetic", "test", vec!["grey".into()]);
        Material::new(name, samples, Some(m))
    }

    fn names(specs: &[ModelSpec]) -> Vec<&str> {
        specs.iter().map(|s| s.name.as_str()).collect()
    }

    #[test]
    fn anisotropic_forms_are_candidates_on_anisotropic_data_only() {
        let iso = candidates_for(&material("lambert", &[0.5]), Target::Mitsuba);
        let iso = names(&iso);
        assert!(iso.contains(&"ggx-separable"), "{iso:?}");
        assert!(!iso.contains(&"ggx-aniso-separable"), "{iso:?}");
        // kd, ks, ax, ay, f0: widths 0.05 and 0.4.
        let aniso = material("ggx-aniso-separable", &[0.2, 0.5, 0.05, 0.4, 0.04]);
        let all = candidates_for(&aniso, Target::Mitsuba);
        assert_eq!(names(&all), exact_models(Target::Mitsuba));
        assert!(all.iter().all(|s| s.lobes == 1), "{all:?}");
    }

    /// An orange body under a magenta highlight leaves every colour plane:
    /// there the conductor lobe is tried with a second lobe too; a grey
    /// material keeps every model at one lobe.
    #[test]
    fn a_second_lobe_is_tried_where_the_colours_leave_every_plane() {
        let config = ModelConfig {
            channels: 3,
            ..ModelConfig::default()
        };
        let mut m = build("lobes-cycles", &config).expect("model");
        // kd (rgb), ks1 (rgb), alpha1.
        m.set_params(&[0.6, 0.3, 0.05, 0.5, 0.0, 0.5, 0.05])
            .expect("in the box");
        let samples = SampleSet::new("two hues", "test", vec!["r".into(), "g".into(), "b".into()]);
        let two_hues = Material::new("two hues", samples, Some(m));
        let specs = candidates_for(&two_hues, Target::Blender);
        let two: Vec<&str> = specs
            .iter()
            .filter(|s| s.lobes == 2)
            .map(|s| s.name.as_str())
            .collect();
        assert_eq!(two, ["lobes-conductor-cycles"], "{specs:?}");
        let grey = candidates_for(&material("lambert", &[0.5]), Target::Blender);
        assert!(grey.iter().all(|s| s.lobes == 1), "{grey:?}");
    }

    #[test]
    fn options_a_choice_by_image_cannot_use_are_refused_not_ignored() {
        let m = material("lambert", &[0.5]);
        let named = SelectRequest {
            among: Among {
                models: vec!["ggx".into()],
                max_parameters: None,
            },
            ..SelectRequest::new(&m)
        };
        let e = select_for(&named, Target::Mitsuba).err().expect("refused");
        let e = e.to_string();
        assert!(e.contains("models ggx") && e.contains("--for"), "{e}");
        let grey = SelectRequest {
            grey: true,
            ..SelectRequest::new(&m)
        };
        let e = select_for(&grey, Target::Mitsuba).err().expect("refused");
        let e = e.to_string();
        assert!(e.starts_with("grey on") && e.contains("--by-l2"), "{e}");
    }
}
