//! The verdict in plain words: what, if anything, is wrong with a fit —
//! visible colour difference, FLIP above threshold, parameters on their
//! bounds, a solver that did not converge — and what only looks wrong:
//! optional lobes switched off (at 0 on their lower bound by design,
//! `brdf_models::ModelEntry::optional_lobes`), and a refinement in the image
//! objective that stopped at its iteration cap (it is kept only because it
//! renders closer to the data, and the verdict judges the render).

use brdf_fit::judged::colour_plane_note;
use brdf_fit::{Objective, Termination};
use brdf_models::saved_model::SavedModel;
use brdf_render::ImageError;
use serde::Serialize;

/// The verdict: a headline and the reasons.
#[derive(Clone, Debug, Serialize)]
pub struct Verdict {
    /// whether nothing was found wrong
    pub good: bool,
    /// one sentence
    pub headline: String,
    /// each problem, in words
    pub reasons: Vec<String>,
    /// what looks like a problem and is not, in words
    pub notes: Vec<String>,
}

/// The verdict on `saved`, its image errors (`None`: scattered data) and
/// how the solver ended (`None`: not recorded).
pub fn verdict(
    saved: &SavedModel,
    image: Option<&ImageError>,
    termination: Option<&Termination>,
) -> Verdict {
    let mut reasons = image.map(ImageError::warnings).unwrap_or_default();
    // What no fit of this model can mend: colours off its one colour plane.
    reasons.extend(image.and_then(|e| colour_plane_note(&saved.model, e)));
    let mut notes = Vec::new();
    let off = lobes_off(saved);
    if !off.is_empty() {
        notes.push(format!(
            "optional lobes off (at 0; the data did not need them): {}",
            off.join(", ")
        ));
    }
    let on_bound: Vec<String> = saved
        .parameters
        .iter()
        .filter(|p| !off.iter().any(|l| p.name.starts_with(l.as_str())))
        .filter_map(|p| p.at_bound.as_ref().map(|b| format!("{} ({b})", p.name)))
        .collect();
    if !on_bound.is_empty() {
        reasons.push(format!(
            "parameters on their bounds: {}; the model may be too simple for this material or the bound too tight",
            on_bound.join(", ")
        ));
    }
    if let Some(t) = termination.filter(|t| !t.is_converged()) {
        if image.is_some() && saved.provenance.objective == Objective::Image.name() {
            notes.push(format!(
                "the kept solve, a refinement of the render (in the image objective, or the search on its FLIP of --polish), ended without meeting its convergence test ({t}); it was kept because it renders closer to the data, and this verdict judges the render"
            ));
        } else {
            reasons.push(format!(
                "the solver did not converge ({t}); try more --starts or another --solver"
            ));
        }
    }
    let good = reasons.is_empty();
    let headline = match (good, image.is_some()) {
        (true, true) => "The fit looks like the data: no visible colour difference, FLIP below threshold, no parameter on a bound.".into(),
        (true, false) => "No problem found in the parameters; the data are scattered, so no image error could be formed.".into(),
        (false, _) => format!("The fit misses in {} way{}:", reasons.len(), if reasons.len() == 1 { "" } else { "s" }),
    };
    Verdict {
        good,
        headline,
        reasons,
        notes,
    }
}

/// The optional lobes of `saved`'s model that are off: the lobe's own
/// parameter (named as the lobe) is 0.
fn lobes_off(saved: &SavedModel) -> Vec<String> {
    brdf_models::optional_lobes(&saved.model)
        .iter()
        .map(|l| l.name)
        .filter(|l| {
            saved
                .parameters
                .iter()
                .any(|p| p.name == **l && p.value == 0.0)
        })
        .map(|l| l.to_string())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use brdf_solve::Termination as SolverEnd;

    #[test]
    fn bounds_and_non_convergence_are_named() {
        let text = r#"{ "schema": "brdf-fit/saved-model", "version": 1,
          "model": "blinn-phong", "structure": { "channels": 1 },
          "parameters": [ { "name": "kd", "value": 0.5, "at_bound": "lower" },
                          { "name": "ks", "value": 0.0 }, { "name": "n", "value": 10.0 } ] }"#;
        let saved = SavedModel::from_json(text, "inline").expect("valid");
        let v = verdict(
            &saved,
            None,
            Some(&Termination::Solver(SolverEnd::MaxIterations)),
        );
        assert!(!v.good);
        assert_eq!(v.reasons.len(), 2, "{:?}", v.reasons);
        assert!(v.reasons[0].contains("kd (lower)"));
        let ok = verdict(
            &saved,
            None,
            Some(&Termination::Solver(SolverEnd::SmallGradient)),
        );
        assert_eq!(ok.reasons.len(), 1);
    }

    /// A principled fit with its sheen and clear coat off and metallic on
    /// its upper bound, refined in the image objective to its cap.
    fn principled(objective: &str) -> SavedModel {
        let text = format!(
            r#"{{ "schema": "brdf-fit/saved-model", "version": 1,
          "model": "principled", "structure": {{ "channels": 1 }},
          "parameters": [
            {{ "name": "base_color", "value": 0.3 }},
            {{ "name": "metallic", "value": 1.0, "at_bound": "upper" }},
            {{ "name": "specular", "value": 0.5 }}, {{ "name": "spec_tint", "value": 0.2 }},
            {{ "name": "roughness", "value": 0.3 }},
            {{ "name": "anisotropic", "value": 0.2 }},
            {{ "name": "sheen", "value": 0.0, "at_bound": "lower" }},
            {{ "name": "sheen_tint", "value": 0.0, "at_bound": "lower" }},
            {{ "name": "clearcoat", "value": 0.0, "at_bound": "lower" }},
            {{ "name": "clearcoat_gloss", "value": 1.0, "at_bound": "upper" }} ],
          "provenance": {{ "data": "inline", "samples_used": 10, "samples_present": 10,
            "objective": "{objective}", "limit_deg": 80.0, "error": 0.1,
            "solver": "test", "software": "test" }} }}"#
        );
        SavedModel::from_json(&text, "inline").expect("valid")
    }

    fn looks_right() -> ImageError {
        let light = |name: &str| brdf_render::LightError {
            light: name.into(),
            flip: 0.05,
            psnr: 35.0,
            delta_e: 0.5,
            mean_colour_data: [0.2; 3],
            mean_colour_fit: [0.2; 3],
            exposure: 1.0,
        };
        ImageError {
            size: 128,
            lights: vec![light("sky"), light("studio")],
            colour_plane: None,
        }
    }

    #[test]
    fn lobes_switched_off_are_not_parameters_on_bounds() {
        let v = verdict(
            &principled("ngan"),
            None,
            Some(&Termination::Solver(SolverEnd::SmallGradient)),
        );
        assert_eq!(v.reasons.len(), 1, "{:?}", v.reasons);
        assert!(v.reasons[0].contains("metallic (upper)"));
        assert!(!v.reasons[0].contains("sheen") && !v.reasons[0].contains("clearcoat"));
        assert_eq!(
            v.notes,
            ["optional lobes off (at 0; the data did not need them): sheen, clearcoat"]
        );
    }

    /// A principled fit of data whose colours lie off every plane of white
    /// and one colour is told so, as a reason; the same figure below the
    /// note's threshold, or no figure, adds none.
    #[test]
    fn colours_off_the_single_colour_plane_are_a_reason() {
        use brdf_fit::judged::COLOUR_PLANE_NOTE;
        use brdf_render::image_error::DataColourPlane;
        let with = |outside: f64| ImageError {
            colour_plane: Some(DataColourPlane {
                light: "studio".into(),
                colour: [1.0, 0.2, 0.0],
                outside,
            }),
            ..looks_right()
        };
        let named = |image: &ImageError| {
            verdict(&principled("image"), Some(image), None)
                .reasons
                .iter()
                .any(|r| r.contains("every plane of white and one colour"))
        };
        assert!(named(&with(2.0 * COLOUR_PLANE_NOTE)));
        assert!(!named(&with(0.5 * COLOUR_PLANE_NOTE)));
        assert!(!named(&looks_right()));
    }

    #[test]
    fn an_image_refinement_at_its_cap_is_judged_by_its_render() {
        let image = looks_right();
        let capped = Some(&Termination::Solver(SolverEnd::MaxIterations));
        let v = verdict(&principled("image"), Some(&image), capped);
        assert!(
            v.reasons.iter().all(|r| !r.contains("did not converge")),
            "{:?}",
            v.reasons
        );
        assert!(
            v.notes
                .iter()
                .any(|n| n.contains("(NOT converged: iteration cap)"))
        );
        // Not so for a BRDF-space fit, nor without image errors.
        for (objective, image) in [("ngan", Some(&image)), ("image", None)] {
            let v = verdict(&principled(objective), image, capped);
            assert!(v.reasons.iter().any(|r| r.contains("did not converge")));
        }
    }

    /// The FLIP search of `--polish` (recorded with the image objective)
    /// stopped at its budget is named as not converged: a note beside
    /// image errors, a reason without them; converged, nothing.
    #[test]
    fn a_polish_at_its_budget_is_named() {
        let image = looks_right();
        use brdf_solve::compass::CompassTermination;
        // As brdf_fit::flip_polish ends its search.
        let end = |end: CompassTermination| Termination::FlipSearch {
            end,
            mean_flip: 0.2510,
            from: 0.2600,
        };
        let (budget, done) = (
            end(CompassTermination::EvaluationBudget),
            end(CompassTermination::StepBelowTolerance),
        );
        let (budget, done) = (Some(&budget), Some(&done));
        let v = verdict(&principled("image"), Some(&image), budget);
        assert!(
            v.notes
                .iter()
                .any(|n| n.contains("search on its FLIP") && n.contains("evaluation budget")),
            "{:?}",
            v.notes
        );
        assert!(v.reasons.iter().all(|r| !r.contains("did not converge")));
        let v = verdict(&principled("image"), None, budget);
        assert!(v.reasons.iter().any(|r| r.contains("did not converge")));
        let v = verdict(&principled("image"), Some(&image), done);
        assert!(v.notes.iter().all(|n| !n.contains("convergence test")));
        assert!(v.reasons.iter().all(|r| !r.contains("did not converge")));
    }
}
