//! Start points for fitting a coloured-lobe model. The lobes of one model
//! differ only in width until the fit separates them, and a fit started
//! with two lobes of one width keeps them equal (their derivatives agree),
//! so every start spreads the widths over a decade or more: narrow, medium
//! and broad sets, the coat's width with them.

use brdf_core::Parametric;

/// Width sets `alpha1, alpha2, alpha3` (each ascending, so lobe 1 is the
/// sharpest) and the coat width of each start.
const WIDTHS: [([f64; 3], f64); 4] = [
    ([0.01, 0.06, 0.3], 0.01),
    ([0.03, 0.15, 0.6], 0.03),
    ([0.08, 0.3, 0.9], 0.1),
    ([0.005, 0.03, 0.15], 0.005),
];

/// Full parameter vectors (defaults elsewhere), one per width set:
/// `alpha1..3` = (0.01, 0.06, 0.3), (0.03, 0.15, 0.6), (0.08, 0.3, 0.9),
/// (0.005, 0.03, 0.15), coat 0.01, 0.03, 0.1, 0.005; none for a model
/// without `alpha1` (not a coloured-lobe layout).
pub fn suggested_starts(model: &dyn Parametric) -> Vec<Vec<f64>> {
    let specs = model.param_specs();
    if !specs.iter().any(|s| s.name == "alpha1") {
        return Vec::new();
    }
    WIDTHS
        .iter()
        .map(|(alphas, coat)| {
            specs
                .iter()
                .map(|s| {
                    let width = match s.name.as_str() {
                        "coat_alpha" => Some(*coat),
                        n => n
                            .strip_prefix("alpha")
                            .and_then(|k| k.parse::<usize>().ok())
                            .and_then(|k| alphas.get(k.wrapping_sub(1)).copied()),
                    };
                    width.unwrap_or(s.default).clamp(s.lower, s.upper)
                })
                .collect()
        })
        .collect()
}
