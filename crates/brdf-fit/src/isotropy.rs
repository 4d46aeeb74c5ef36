//! Whether measured data are isotropic: the appearance fit does not try an
//! anisotropic lobe on data that cannot need one.

use brdf_core::Brdf;

/// Whether `data` is isotropic: its values do not change when both
/// directions of a pair turn about the normal (64 fixed pairs, each turned by
/// a fixed angle, relative agreement `1e-6`). Anisotropy is a lobe such data
/// cannot need, so [`fit_for_appearance`](crate::appearance::fit_for_appearance) does not try it there.
pub fn is_isotropic(data: &dyn Brdf) -> bool {
    let nc = data.channels().max(1);
    let (mut a, mut b) = (vec![0.0; nc], vec![0.0; nc]);
    // A fixed low-discrepancy set of pairs in the upper hemisphere.
    let dir = |u: f64, w: f64| {
        let z = 0.05 + 0.95 * u;
        let r = (1.0 - z * z).sqrt();
        let phi = 2.0 * std::f64::consts::PI * w;
        brdf_core::nalgebra::Vector3::new(r * phi.cos(), r * phi.sin(), z)
    };
    let frac = |x: f64| x - x.floor();
    (0..64).all(|i| {
        let t = i as f64;
        let l = dir(frac(0.5 + t * 0.618_033_988_7), frac(t * 0.754_877_666_2));
        let v = dir(frac(t * 0.569_840_290_9), frac(0.3 + t * 0.414_213_562_4));
        let turn = brdf_core::nalgebra::Rotation3::from_axis_angle(
            &brdf_core::nalgebra::Vector3::z_axis(),
            0.7 + 2.1 * frac(t * 0.324_717_957_2),
        );
        data.eval(&l, &v, &mut a);
        data.eval(&(turn * l), &(turn * v), &mut b);
        a.iter()
            .zip(&b)
            .all(|(x, y)| (x - y).abs() <= 1e-6 * x.abs().max(y.abs()) + 1e-12)
    })
}
