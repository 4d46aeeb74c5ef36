//! Shared by the integration tests: RGB samples of a model at fixed
//! quasi-random direction pairs.

use std::f64::consts::TAU;

use brdf_core::{Brdf, Direction, SampleSet};
use nalgebra::Vector3;

/// A direction of polar angle `1.45 a` (below 83 deg) and azimuth `b`.
pub fn dir(a: f64, b: f64) -> Vector3<f64> {
    let th = a * 1.45;
    Vector3::new(th.sin() * b.cos(), th.sin() * b.sin(), th.cos())
}

/// `model` (3 channels) at `n` quasi-random pairs (golden-ratio and
/// square-root sequences), weight 1.
pub fn rgb_samples(model: &dyn Brdf, n: usize) -> SampleSet {
    let mut s = SampleSet::new(
        "synthetic",
        "test",
        vec!["r".into(), "g".into(), "b".into()],
    );
    let mut f = [0.0; 3];
    for j in 0..n {
        let x = j as f64;
        let l = dir(
            (x * 0.618_033_988_75).fract(),
            TAU * (x * 0.414_213_562_37).fract(),
        );
        let v = dir(
            (x * 0.732_050_807_57).fract(),
            TAU * (x * 0.236_067_977_5).fract(),
        );
        model.eval(&l, &v, &mut f);
        s.push(
            &Direction::try_new(l).expect("unit"),
            &Direction::try_new(v).expect("unit"),
            &f,
            1.0,
        )
        .expect("push");
    }
    s
}
