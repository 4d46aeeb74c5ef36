//! The documented exceptions: the non-reciprocal Sopp variants behave as
//! documented, the paint shader's `Rs` conversion round-trips, and the full
//! Oren-Nayar model's published formula is negative exactly where its
//! documentation says (and clamped there).

use brdf_core::fresnel::fresnel_dielectric;
use brdf_core::plausibility::hemisphere_directions;
use brdf_core::{Brdf, Parametric, spherical_to_cartesian};
use brdf_models::{AsPaint, ClearCoat, OrenNayarFull, PaintShader, PhongFresnel, Ward};
use nalgebra::Vector3;

fn dirs() -> Vec<Vector3<f64>> {
    hemisphere_directions(6, 5, 1e-6)
}

#[test]
fn phong_fresnel_is_reciprocal_after_removing_the_transmission() {
    let m = PhongFresnel::new(&[0.2], &[0.6], &[15.0, 1.6]).unwrap();
    let mut asym = 0.0f64;
    for l in dirs() {
        for v in dirs() {
            let (mut a, mut b) = ([0.0], [0.0]);
            m.eval(&l, &v, &mut a);
            m.eval(&v, &l, &mut b);
            let lobe_lv =
                (a[0] - 0.2 / std::f64::consts::PI) / (1.0 - fresnel_dielectric(l.z, 1.6));
            let lobe_vl =
                (b[0] - 0.2 / std::f64::consts::PI) / (1.0 - fresnel_dielectric(v.z, 1.6));
            // Removing cd/pi and dividing by 1 - Fr (small near grazing)
            // costs digits: compare to 1e-9, relative and absolute.
            assert!(
                (lobe_lv - lobe_vl).abs() <= 1e-9 * lobe_lv.abs() + 1e-9,
                "{lobe_lv} vs {lobe_vl} at l {l:?} v {v:?}"
            );
            asym = asym.max((a[0] - b[0]).abs());
        }
    }
    assert!(!m.is_reciprocal());
    assert!(asym > 1e-3, "the published model is not reciprocal: {asym}");
}

#[test]
fn clear_coat_adds_fresnel_and_transmits_the_base() {
    let base = Ward::new(&[0.3], &[0.2], &[0.2]).unwrap();
    let m = ClearCoat::new(Box::new(base.clone()), 1.5).unwrap();
    for l in dirs() {
        for v in dirs() {
            let (mut f, mut fb) = ([0.0], [0.0]);
            m.eval(&l, &v, &mut f);
            base.eval(&l, &v, &mut fb);
            let fr = fresnel_dielectric(l.z, 1.5);
            assert!((f[0] - (fr + (1.0 - fr) * fb[0])).abs() <= 1e-12 * f[0].max(1.0));
        }
    }
    assert!(!m.is_reciprocal());
    assert!(ClearCoat::new(Box::new(base), 0.5).is_err());
    // Fr(0) = ((eta-1)/(eta+1))^2.
    assert!((fresnel_dielectric(1.0, 1.5) - 0.04).abs() < 1e-15);
}

#[test]
fn paint_shader_conversion_round_trips_and_keeps_values() {
    let fitted = AsPaint::new(&[0.3, 0.2, 0.1], &[0.2, 0.4, 0.1], &[50.0]).unwrap();
    let paint = PaintShader::from_fit(&fitted).unwrap();
    assert_eq!(paint.rs, 0.4);
    let back = paint.to_fit().unwrap();
    for (a, b) in fitted.params().iter().zip(back.params()) {
        assert!((a - b).abs() < 1e-15);
    }
    // Sopp's form evaluated by hand equals the fitted form.
    let l = spherical_to_cartesian(0.5, 0.0);
    let v = spherical_to_cartesian(0.4, 3.0);
    let mut f = [0.0; 3];
    fitted.eval(&l, &v, &mut f);
    let h = (l + v).normalize();
    let lobe = 51.0 / (8.0 * std::f64::consts::PI) * h.z.powf(50.0) / (h.dot(&v) * l.z.max(v.z));
    for c in 0..3 {
        let sopp =
            paint.cd[c] / std::f64::consts::PI * (1.0 - paint.rs) + paint.rs * paint.cs[c] * lobe;
        assert!((f[c] - sopp).abs() < 1e-12 * f[c], "channel {c}");
    }
    // No specular part: Rs = 0 cannot be converted.
    let flat = AsPaint::new(&[0.3], &[0.0], &[5.0]).unwrap();
    assert!(PaintShader::from_fit(&flat).is_err());
}

#[test]
fn full_oren_nayar_negativity_is_where_documented() {
    let t = 89f64.to_radians();
    let l = spherical_to_cartesian(t, 0.0);
    let v = spherical_to_cartesian(t, std::f64::consts::PI);
    let (raw, _, _) = OrenNayarFull::unclamped(0.3, 0.999, &l, &v);
    assert!(raw < 0.0, "published value at the documented point: {raw}");
    let m = OrenNayarFull::new(&[0.3], 0.999).unwrap();
    let mut f = [1.0];
    m.eval(&l, &v, &mut f);
    assert_eq!(f[0], 0.0);
    // Elsewhere (forward scattering, moderate angles) the clamp is inactive
    // and sigma = 0 is Lambert.
    let v2 = spherical_to_cartesian(0.7, 0.3);
    let (raw, _, _) = OrenNayarFull::unclamped(0.3, 0.999, &l, &v2);
    m.eval(&l, &v2, &mut f);
    assert!(raw > 0.0 && (f[0] - raw).abs() < 1e-15);
    let lam = OrenNayarFull::new(&[0.8], 0.0).unwrap();
    lam.eval(&l, &v, &mut f);
    assert!((f[0] - 0.8 / std::f64::consts::PI).abs() < 1e-15);
}
