//! Conversion by fitting: the sampled pairs, and a source the target can
//! represent exactly is recovered (the conversion error is then ~0).

use brdf_core::Parametric;
use brdf_export::convert::{ConvertOptions, convert, sample_source};
use brdf_export::{Target, export};

fn model(name: &str, p: &[f64]) -> Box<dyn Parametric> {
    let mut m = brdf_models::build(name, &Default::default()).unwrap();
    m.set_params(p).unwrap();
    m
}

#[test]
fn sampled_pairs_lie_inside_the_limit_and_are_deterministic() {
    let m = model("blinn-phong", &[0.5, 0.2, 30.0]);
    let opts = ConvertOptions {
        pairs: 500,
        limit_deg: 60.0,
        ..Default::default()
    };
    let a = sample_source(m.as_ref(), &opts).unwrap();
    assert_eq!(a.len(), 500);
    let c = 60f64.to_radians().cos();
    for j in 0..a.len() {
        let (l, v) = (a.pairs().l(j), a.pairs().v(j));
        assert!(l.z >= c && v.z >= c);
        assert!(((l.norm() - 1.0).abs() < 1e-12) && ((v.norm() - 1.0).abs() < 1e-12));
    }
    // Half of the pairs near the mirror direction (theta_h < 22.5 deg), as
    // the warp theta_h = pi/2 u^2 intends.
    let near = (0..a.len())
        .filter(|&j| (a.pairs().l(j) + a.pairs().v(j)).normalize().z > 22.5f64.to_radians().cos())
        .count();
    assert!(near > 200, "{near}");
    assert_eq!(sample_source(m.as_ref(), &opts).unwrap(), a);
}

/// A Lambert + GGX dielectric lobe with a grey `ks` and `kd <= 1 - ks` is a
/// pbrt-v4 mix: fitting the mix to it recovers it.
#[test]
fn a_representable_source_is_recovered() {
    // kd, ks, alpha, eta
    let src = model("ggx-dielectric", &[0.4, 0.3, 0.2, 1.6]);
    let opts = ConvertOptions {
        pairs: 400,
        starts: 4,
        ..Default::default()
    };
    let c = convert(src.as_ref(), Target::Pbrt, &opts).unwrap();
    assert_eq!(c.model.name(), "ggx-dielectric");
    assert!(c.error.relative_l2 < 1e-6, "{:?}", c.error);
    for (a, b) in c.model.params().iter().zip(src.params()) {
        assert!(
            (a - b).abs() < 1e-4,
            "{:?} vs {:?}",
            c.model.params(),
            src.params()
        );
    }
    // The converted model is written exactly.
    assert!(export(c.model.as_ref(), Target::Pbrt).is_ok());
}
