//! The FLIP polish of an appearance fit (`Fit::polish_on_flip`): it starts
//! at the fit chosen without it, so it never renders worse; it moves only
//! free parameters (a lobe switched off stays off); its candidate is
//! listed as `flip` and its report names the search.

use brdf_fit::appearance::fit_for_appearance;
use brdf_render::judge::{FIT_SIZE, Judge};

use crate::common;
use common::{rgb_fit, rgb_model, rgb_samples};

#[test]
fn the_polish_starts_at_the_choice_and_moves_only_free_parameters() {
    // Data the principled model cannot match exactly: a grey GGX lobe
    // (height-correlated Smith, Schlick Fresnel) over a dark blue diffuse
    // base.
    let mut data = rgb_model("ggx");
    let specs = data.param_specs().to_vec();
    let mut p = data.params().to_vec();
    for (k, s) in specs.iter().enumerate() {
        p[k] = match s.name.as_str() {
            "kd_r" => 0.02,
            "kd_g" => 0.05,
            "kd_b" => 0.08,
            n if n.starts_with("ks") => 0.3,
            n if n.starts_with("alpha") => 0.25,
            _ => p[k],
        };
    }
    data.set_params(&p).expect("in the box");
    let s = rgb_samples(data.as_ref(), 2000);
    let fit = rgb_fit("principled");
    let (plain, plain_candidates) = fit_for_appearance(&fit, &s, data.as_ref()).expect("fit");
    let (polished, candidates) =
        fit_for_appearance(&fit.clone().polish_on_flip(true), &s, data.as_ref()).expect("fit");
    // Everything before the polish is the same deterministic pipeline.
    assert_eq!(candidates.len(), plain_candidates.len() + 1);
    let last = candidates.last().expect("the polish's candidate");
    assert_eq!(last.objective, "flip");
    let judge = Judge::with_data(FIT_SIZE, data.as_ref()).expect("judge");
    let before = judge
        .fit_errors(plain.model.as_ref())
        .expect("errors")
        .mean_flip();
    let after = judge
        .fit_errors(polished.model.as_ref())
        .expect("errors")
        .mean_flip();
    assert!(after <= before, "{after} > {before}");
    assert!(
        last.image.mean_flip() < before,
        "the search found no lower FLIP"
    );
    // Held parameters (box of one value) did not move.
    let (held, moved): (Vec<_>, Vec<_>) = polished
        .model
        .param_specs()
        .iter()
        .enumerate()
        .partition(|(_, s)| s.lower == s.upper);
    assert!(!held.is_empty());
    for (k, s) in held {
        assert_eq!(polished.model.params()[k], s.lower, "{}", s.name);
    }
    assert!(!moved.is_empty());
    if last.chosen {
        assert!(polished.summary.solver.contains("compass search"));
        assert!(
            polished
                .summary
                .termination
                .to_string()
                .contains("mean FLIP")
        );
    }
}
