//! The verdict in plain words: what, if anything, is wrong with a fit —
//! visible colour difference, FLIP above threshold, parameters on their
//! bounds, a solver that did not converge.

use brdf_fit::appearance::ImageError;
use brdf_models::saved_model::SavedModel;
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
}

/// Whether a termination text means the solver did not converge.
pub fn not_converged(termination: &str) -> bool {
    let t = termination.to_ascii_lowercase();
    t.contains("not converged") || t.contains("max") && t.contains("iteration")
}

/// The verdict on `saved`, its image errors (`None`: scattered data) and
/// how the solver ended (`None`: not recorded).
pub fn verdict(
    saved: &SavedModel,
    image: Option<&ImageError>,
    termination: Option<&str>,
) -> Verdict {
    let mut reasons = image.map(ImageError::warnings).unwrap_or_default();
    let on_bound: Vec<String> = saved
        .parameters
        .iter()
        .filter_map(|p| p.at_bound.as_ref().map(|b| format!("{} ({b})", p.name)))
        .collect();
    if !on_bound.is_empty() {
        reasons.push(format!(
            "parameters on their bounds: {}; the model may be too simple for this material or the bound too tight",
            on_bound.join(", ")
        ));
    }
    if let Some(t) = termination.filter(|t| not_converged(t)) {
        reasons.push(format!(
            "the solver did not converge ({t}); try more --starts or another --solver"
        ));
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
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounds_and_non_convergence_are_named() {
        let text = r#"{ "schema": "brdf-fit/saved-model", "version": 1,
          "model": "blinn-phong", "structure": { "channels": 1 },
          "parameters": [ { "name": "kd", "value": 0.5, "at_bound": "lower" },
                          { "name": "ks", "value": 0.0 }, { "name": "n", "value": 10.0 } ] }"#;
        let saved = SavedModel::from_json(text, "inline").expect("valid");
        let v = verdict(&saved, None, Some("NOT converged: iteration limit"));
        assert!(!v.good);
        assert_eq!(v.reasons.len(), 2, "{:?}", v.reasons);
        assert!(v.reasons[0].contains("kd (lower)"));
        let ok = verdict(&saved, None, Some("converged: gradient"));
        assert_eq!(ok.reasons.len(), 1);
    }
}
