//! Proptest strategies for directions, shared by the property tests of this
//! folder (`mod strategies;`).

use nalgebra::Vector3;
use proptest::prelude::*;

use brdf_core::spherical_to_cartesian;

/// A direction strictly above the horizon, uniform in `cos theta` in
/// `[1e-6, 1]` with extra weight on the pole and the last `1e-6` before the
/// horizon.
pub fn above_horizon() -> impl Strategy<Value = Vector3<f64>> {
    let cos = prop_oneof![
        8 => 1e-6f64..=1.0,
        1 => Just(1.0),
        1 => 1e-6f64..=2e-6,
    ];
    (cos, 0.0..(2.0 * std::f64::consts::PI)).prop_map(|(c, phi)| {
        let theta = c.acos();
        spherical_to_cartesian(theta, phi)
    })
}

/// A pair `(L, V)` of directions above the horizon.
pub fn pair_above_horizon() -> impl Strategy<Value = (Vector3<f64>, Vector3<f64>)> {
    (above_horizon(), above_horizon())
}
