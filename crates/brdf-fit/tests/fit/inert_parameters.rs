//! Parameters without influence: a lobe switched off holds the parameters
//! only it uses at their defaults, and a fit where bounds switch a term off
//! says so instead of "NOT converged". Before, 4 of the 5 RGL files'
//! default principled fits ended "NOT converged: stopped on a plateau with
//! a singular Jacobian" because `sheen_tint` or `clearcoat_gloss` stayed
//! free with their lobe at 0 (or `specular` at `metallic = 1`).

use brdf_fit::appearance::fit_for_appearance;
use brdf_fit::{Fit, Objective};

use crate::common;
use common::{principled_at, rgb_fit, rgb_model, rgb_samples};

/// A matte dielectric without sheen or clear coat: the appearance fit keeps
/// the lobes off, holds their companions at the defaults (0), and its kept
/// solve converges.
#[test]
fn lobes_off_hold_their_companions_and_the_fit_converges() {
    let truth = [0.6, 0.3, 0.1, 0.0, 0.5, 0.0, 0.6, 0.0, 0.0, 0.0, 0.0, 0.0];
    let data = principled_at(&truth);
    let s = rgb_samples(data.as_ref(), 2000);
    let fit = rgb_fit("principled");
    let (report, _) = fit_for_appearance(&fit, &s, data.as_ref()).expect("fit");
    let specs = report.model.param_specs();
    let p = report.model.params();
    let value = |name: &str| {
        let k = specs.iter().position(|s| s.name == name).expect(name);
        p[k]
    };
    let mut held = 0;
    for lobe in brdf_models::optional_lobes("principled") {
        let (lobe, companions) = (lobe.name, lobe.companions);
        if value(lobe) != 0.0 {
            continue;
        }
        for name in companions {
            let default = specs.iter().find(|s| s.name == *name).expect(name).default;
            assert_eq!(value(name), default, "{name} with {lobe} off");
            let note = format!("`{name}` = ");
            assert!(
                report
                    .notes
                    .iter()
                    .any(|n| n.starts_with(&note) && n.contains("is held there")),
                "{:?}",
                report.notes
            );
            held += 1;
        }
    }
    assert!(held >= 1, "no lobe with companions was off: {p:?}");
    let t = &report.summary.termination.to_string();
    assert!(!t.contains("NOT converged"), "{t}");
}

/// glTF with KHR clear coat at its defaults (no clear coat): the lobe stays
/// off and `clearcoat_roughness`, whose box `(0, 1]` is open below, is held
/// at its default 0.1 (narrowing it to `[0.1, 0.1]` once made the empty
/// box `(0.1, 0.1]`, and every `gltf-ext` appearance fit failed).
#[test]
fn an_open_boxed_companion_is_held_too() {
    let data = rgb_model("gltf-ext");
    let s = rgb_samples(data.as_ref(), 2000);
    let fit = Fit::model("gltf-ext").expect("model");
    let (report, _) = fit_for_appearance(&fit, &s, data.as_ref()).expect("fit");
    let specs = report.model.param_specs();
    let p = report.model.params();
    let k = |name: &str| specs.iter().position(|s| s.name == name).expect(name);
    assert_eq!(p[k("clearcoat")], 0.0);
    let rough = &specs[k("clearcoat_roughness")];
    assert_eq!(p[k("clearcoat_roughness")], rough.default);
    assert_eq!(
        brdf_models::optional_lobes("gltf-ext")[0].companions,
        ["clearcoat_roughness"]
    );
}

/// Principled with `metallic` held at 1 on data with a dielectric part:
/// `specular` and `spec_tint` act only in the dielectric lobe, which
/// `metallic = 1` switches off. The fit is degenerate, not a failure, and
/// the termination names them.
#[test]
fn a_term_switched_off_by_a_bound_is_named() {
    let truth = [0.5, 0.4, 0.3, 0.3, 0.5, 0.2, 0.4, 0.0, 0.0, 0.0, 0.0, 0.0];
    let data = principled_at(&truth);
    let s = rgb_samples(data.as_ref(), 2000);
    let report = Fit::model("principled")
        .expect("model")
        .objective(Objective::Ngan)
        .narrow("metallic", 1.0, 1.0)
        .starts(2)
        .run(&s)
        .expect("fit");
    let t = &report.summary.termination.to_string();
    assert!(t.starts_with("converged to a degenerate fit"), "{t}");
    assert!(t.contains("specular") && t.contains("spec_tint"), "{t}");
}

/// Ashikhmin-Shirley with its lobe held off (`ks = 0`) on Lambert data:
/// the lobe's exponent and Fresnel are undetermined, except that the
/// coupled diffuse term still depends on `f0`, which therefore stays
/// determined there. Read off the fitted model's Jacobian, not its name.
#[test]
fn a_shape_the_diffuse_term_shares_stays_determined() {
    let data = rgb_model("lambert");
    let s = rgb_samples(data.as_ref(), 500);
    let fit = |name: &str| {
        rgb_fit(name)
            .objective(Objective::Ngan)
            .narrow("ks", 0.0, 0.0)
            .starts(1)
            .run(&s)
            .expect("fit")
    };
    let plain = fit("ashikhmin-shirley");
    assert_eq!(
        brdf_fit::report_text::undetermined(&plain.summary),
        ["n", "f0"]
    );
    let coupled = fit("ashikhmin-shirley-coupled");
    assert_eq!(coupled.summary.inert, ["n"]);
    assert_eq!(brdf_fit::report_text::undetermined(&coupled.summary), ["n"]);
}
