//! Start points for fitting a coloured-lobe model. The lobes of one model
//! differ only in width until the fit separates them, and a fit started
//! with two lobes of one width keeps them equal (their derivatives agree),
//! so every start spreads the widths over a decade or more: narrow, medium
//! and broad sets, the coat's width with them.
//!
//! A conductor lobe's complex index has basins of its own (a metal's small
//! `eta` and large `kappa`, a dielectric's `eta` above 1 and no `kappa`,
//! and the weak absorbers between), which a search from one class rarely
//! leaves; its starts cross every width set with one index per class.
//!
//! Only lobe 1 carries a Fresnel law (the further lobes are plain), so the
//! lobes are not interchangeable: the Fresnel lobe may be the sharpest or
//! the broadest, and a model with more than one lobe also starts from each
//! width set reversed.

use brdf_core::Parametric;

/// Width sets `alpha1, alpha2, alpha3` (each ascending, so lobe 1 is the
/// sharpest) and the coat width of each start.
const WIDTHS: [([f64; 3], f64); 4] = [
    ([0.01, 0.06, 0.3], 0.01),
    ([0.03, 0.15, 0.6], 0.03),
    ([0.08, 0.3, 0.9], 0.1),
    ([0.005, 0.03, 0.15], 0.005),
];

/// Complex indices `(eta, kappa)` of a conductor lobe's starts: a metal
/// (normal-incidence reflectance 0.92), a weak absorber (0.38) and a
/// dielectric (0.04).
pub const CONDUCTOR_INDICES: [(f64, f64); 3] = [(0.2, 3.0), (0.5, 1.0), (1.5, 0.0)];

/// Full parameter vectors (defaults elsewhere), one per width set:
/// `alpha1..3` = (0.01, 0.06, 0.3), (0.03, 0.15, 0.6), (0.08, 0.3, 0.9),
/// (0.005, 0.03, 0.15), coat 0.01, 0.03, 0.1, 0.005; for a model with
/// conductor lobes, each width set once per index of
/// [`CONDUCTOR_INDICES`] (every lobe and channel alike); with a Fresnel
/// lobe 1 and more lobes, each again with the widths reversed (lobe 1 the
/// broadest); none for a model without `alpha1` (not a coloured-lobe
/// layout).
pub fn suggested_starts(model: &dyn Parametric) -> Vec<Vec<f64>> {
    let specs = model.param_specs();
    if !specs.iter().any(|s| s.name == "alpha1") {
        return Vec::new();
    }
    let conductor = specs.iter().any(|s| s.name.starts_with("kappa"));
    let indices: &[(f64, f64)] = if conductor {
        &CONDUCTOR_INDICES
    } else {
        &[(f64::NAN, f64::NAN)]
    };
    let lobes = specs.iter().filter(|s| s.name.starts_with("alpha")).count();
    let fresnel = conductor || specs.iter().any(|s| s.name.starts_with("tint"));
    let mut widths: Vec<([f64; 3], f64)> = WIDTHS.to_vec();
    if fresnel && lobes > 1 {
        widths.extend(WIDTHS.iter().map(|(a, coat)| {
            let mut r = [0.0; 3];
            r[..lobes].copy_from_slice(&a[..lobes]);
            r[..lobes].reverse();
            (r, *coat)
        }));
    }
    let mut starts = Vec::with_capacity(widths.len() * indices.len());
    for &(eta, kappa) in indices {
        for (alphas, coat) in &widths {
            let start = specs.iter().map(|s| {
                let name = s.name.as_str();
                let value = if name == "coat_alpha" {
                    Some(*coat)
                } else if let Some(k) = name.strip_prefix("alpha") {
                    k.parse::<usize>()
                        .ok()
                        .and_then(|k| alphas.get(k.wrapping_sub(1)).copied())
                } else if name.starts_with("eta") && conductor {
                    Some(eta)
                } else if name.starts_with("kappa") {
                    Some(kappa)
                } else {
                    None
                };
                value.unwrap_or(s.default).clamp(s.lower, s.upper)
            });
            starts.push(start.collect());
        }
    }
    starts
}
