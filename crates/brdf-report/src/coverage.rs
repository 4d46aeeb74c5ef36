//! The data's coverage of the hemisphere: incident and outgoing sample
//! directions projected onto the unit disk (`x = sin θ cos φ`,
//! `y = sin θ sin φ`), at most [`MAX_POINTS`] of each.

use brdf_core::SampleSet;
use brdf_render::plot::{Plot, Series};

use crate::ReportError;

/// Points drawn per series (evenly strided subset beyond this).
pub const MAX_POINTS: usize = 2500;

/// The coverage plot as inline SVG.
pub fn svg(data: &SampleSet) -> Result<String, ReportError> {
    let pairs = data.pairs();
    let stride = data.len().div_ceil(MAX_POINTS).max(1);
    let (mut inc, mut out) = (Vec::new(), Vec::new());
    for j in (0..data.len()).step_by(stride) {
        let (l, v) = (pairs.l(j), pairs.v(j));
        inc.push((l.x, l.y));
        out.push((v.x, v.y));
    }
    let mut series = vec![
        Series::points("outgoing", 1, out),
        Series::points("incident", 0, inc),
    ];
    for s in &mut series {
        s.marker = 2;
        s.alpha = 0.6;
    }
    let plot = Plot {
        title: format!(
            "{} samples ({} drawn)",
            data.len(),
            data.len().div_ceil(stride)
        ),
        x_label: "sin θ cos φ".into(),
        y_label: "sin θ sin φ".into(),
        series,
        ..Plot::default()
    };
    Ok(brdf_render::plot::svg(&plot, (640, 420))?)
}
