//! Every catalogue model, its value and its analytic
//! derivatives stay finite at the extremes of its box and of the
//! directions. Parameters: the defaults, every exponent-like parameter
//! (box reaching 1e3 or more) at its upper end (1e6 for the exponents) and
//! at its lower end (0 where the box allows it), every roughness-like
//! parameter (box open at 0) at 1e-6, and all of these together.
//! Directions: the pole (`L = V = N`), `L = V` off the pole, the mirror
//! configuration, directions 1e-9 rad from the horizon (incident, outgoing
//! and both, in the mirror and the retro-reflection plane), the pole
//! against a grazing direction, and a grazing pair at right angles.
//!
//! The check is finiteness (no NaN, no infinity) and, for the value,
//! non-negativity where the model is a BRDF with non-negative linear
//! parameters (all defaults are); the exact values at these points are
//! tested elsewhere (`extremes.rs`, `reference.rs`).

use brdf_core::Parametric;
use brdf_models::{ModelConfig, catalogue};
use nalgebra::Vector3;

const GRAZE: f64 = 1e-9;

fn dir(theta: f64, phi: f64) -> Vector3<f64> {
    Vector3::new(
        theta.sin() * phi.cos(),
        theta.sin() * phi.sin(),
        theta.cos(),
    )
}

fn mirror(l: &Vector3<f64>) -> Vector3<f64> {
    Vector3::new(-l.x, -l.y, l.z)
}

/// `(label, L, V)` of every extreme configuration.
fn configurations() -> Vec<(&'static str, Vector3<f64>, Vector3<f64>)> {
    use std::f64::consts::FRAC_PI_2;
    let pole = Vector3::z();
    let l40 = dir(40f64.to_radians(), 0.3);
    let grazing_l = dir(FRAC_PI_2 - GRAZE, 0.3);
    vec![
        ("pole L = V = N", pole, pole),
        ("L = V at 40 deg", l40, l40),
        ("mirror at 40 deg", l40, mirror(&l40)),
        (
            "L 1e-9 from the horizon, V at 30 deg",
            grazing_l,
            dir(0.5, 2.0),
        ),
        (
            "V 1e-9 from the horizon, L at 30 deg",
            dir(0.5, 2.0),
            grazing_l,
        ),
        ("both grazing, mirror", grazing_l, mirror(&grazing_l)),
        ("both grazing, L = V (retro)", grazing_l, grazing_l),
        (
            "both grazing, at right angles",
            grazing_l,
            dir(FRAC_PI_2 - GRAZE, 0.3 + FRAC_PI_2),
        ),
        ("pole L, grazing V", pole, grazing_l),
        ("grazing L, pole V", grazing_l, pole),
    ]
}

/// Parameter vectors at the extremes of `model`'s box, with a label.
fn extreme_points(model: &dyn Parametric) -> Vec<(String, Vec<f64>)> {
    let specs = model.param_specs();
    let default: Vec<f64> = specs.iter().map(|s| s.default).collect();
    let mut out = vec![("defaults".to_string(), default.clone())];
    let mut all_extreme_high = default.clone();
    let mut all_extreme_low = default.clone();
    for (k, s) in specs.iter().enumerate() {
        if s.linear {
            continue;
        }
        if s.upper >= 1e3 {
            let hi = s.upper.min(1e6);
            let lo = if s.lower_open {
                s.lower + 1e-9
            } else {
                s.lower.max(0.0).min(hi)
            };
            for (tag, v) in [("upper", hi), ("lower", lo)] {
                let mut p = default.clone();
                p[k] = v;
                out.push((format!("{} = {v:e} ({tag} end)", s.name), p));
            }
            all_extreme_high[k] = hi;
            all_extreme_low[k] = lo;
        } else if s.lower_open && s.lower == 0.0 {
            let v = 1e-6f64.min(s.upper);
            let mut p = default.clone();
            p[k] = v;
            out.push((format!("{} = {v:e} (roughness near 0)", s.name), p));
            all_extreme_high[k] = v;
            all_extreme_low[k] = v;
        }
    }
    out.push(("every extreme, exponents high".into(), all_extreme_high));
    out.push(("every extreme, exponents low".into(), all_extreme_low));
    out
}

#[test]
fn every_model_and_its_derivatives_are_finite_at_the_extremes() {
    let mut checked = 0usize;
    let mut failures = Vec::new();
    for entry in catalogue() {
        for lobes in [1usize, 2] {
            if lobes == 2 && !entry.has_lobes {
                continue;
            }
            let config = ModelConfig {
                lobes,
                order: 8,
                degree: 7,
                channels: 1,
            };
            let mut model = (entry.build)(&config)
                .unwrap_or_else(|e| panic!("{} ({lobes} lobes) builds: {e}", entry.name));
            let np = model.param_specs().len();
            for (label, p) in extreme_points(model.as_ref()) {
                // Every point is inside the model's own box.
                model
                    .set_params(&p)
                    .unwrap_or_else(|e| panic!("{} {label}: inside the box: {e}", entry.name));
                for (where_, l, v) in configurations() {
                    let mut out = vec![0.0; model.channels()];
                    let mut grad = vec![0.0; model.channels() * np];
                    model.eval_at(&p, &l, &v, &mut out);
                    let value_ok = out.iter().all(|x| x.is_finite());
                    let mut out2 = vec![0.0; model.channels()];
                    model.eval_grad_at(&p, &l, &v, &mut out2, &mut grad);
                    let grad_ok =
                        grad.iter().all(|x| x.is_finite()) && out2.iter().all(|x| x.is_finite());
                    checked += 1;
                    if !(value_ok && grad_ok) {
                        failures.push(format!(
                            "{} ({lobes} lobes), {label}, {where_}: value {out:?}, grad {grad:?}",
                            entry.name
                        ));
                    }
                }
            }
        }
    }
    assert!(checked > 500, "only {checked} evaluations");
    assert!(
        failures.is_empty(),
        "{} non-finite of {checked}:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
