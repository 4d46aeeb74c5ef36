//! Lambert: exact values, exact albedo, validation.

use std::f64::consts::PI;

use brdf_core::{
    AlbedoFrame, Brdf, Parametric, QuadratureOptions, directional_albedo, spherical_to_cartesian,
};
use brdf_models::Lambert;
use nalgebra::Vector3;

#[test]
fn value_and_albedo_are_exact() {
    let m = Lambert::new(&[0.25, 0.5, 1.0]).unwrap();
    let mut f = [0.0; 3];
    m.eval(
        &spherical_to_cartesian(1.5, 0.1),
        &spherical_to_cartesian(0.0, 0.0),
        &mut f,
    );
    assert_eq!(f, [0.25 / PI, 0.5 / PI, 1.0 / PI]);
    m.eval(&spherical_to_cartesian(1.6, 0.1), &Vector3::z(), &mut f);
    assert_eq!(f, [0.0; 3]);
    for theta in [0.0, 0.7, PI / 2.0 - 1e-6] {
        let a = directional_albedo(
            &m,
            &spherical_to_cartesian(theta, 2.0),
            AlbedoFrame::Normal,
            &QuadratureOptions::default(),
        );
        for c in 0..3 {
            assert!((a.value[c] - m.params()[c]).abs() <= a.error[c] + 1e-14);
        }
    }
}

#[test]
fn construction_is_validated() {
    let e = Lambert::new(&[1.5]).unwrap_err();
    assert!(
        e.to_string()
            .contains("`kd` = 1.5 is outside its box [0, 1]"),
        "{e}"
    );
    assert!(Lambert::new(&[]).is_err());
    let e = Lambert::new(&[0.2, -0.1, 0.3]).unwrap_err();
    assert!(e.to_string().contains("kd_g"), "{e}");
}
