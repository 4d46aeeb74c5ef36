//! Sample sets: storage, filters and their reports, parameter validation.

use brdf_core::params::{assign_by_name, validate};
use brdf_core::{Direction, ParamError, ParamSpec, SampleSet};

fn set() -> SampleSet {
    let mut s = SampleSet::new("t", "hand-made", vec!["r".into(), "g".into()]);
    let d = |t: f64| Direction::from_spherical(t.to_radians(), 0.0).unwrap();
    s.push(&d(10.0), &d(20.0), &[1.0, 2.0], 1.0).unwrap();
    s.push(&d(85.0), &d(20.0), &[3.0, 4.0], 1.0).unwrap();
    s.push(&d(10.0), &d(30.0), &[-0.01, 4.0], 2.0).unwrap();
    s.push(&d(10.0), &d(40.0), &[f64::NAN, 4.0], 1.0).unwrap();
    s
}

#[test]
fn storage_is_channel_major() {
    let s = set();
    assert_eq!(s.len(), 4);
    assert_eq!(s.channels(), 2);
    assert_eq!(s.channel(1), &[2.0, 4.0, 4.0, 4.0]);
    let v = s.values_channel_major();
    assert_eq!(v[4], 2.0);
    assert_eq!(s.count_negative(), 1);
    assert_eq!(s.count_non_finite(), 1);
    let m = s.mean_channel();
    assert_eq!(m.channels(), 1);
    assert_eq!(m.channel(0)[0], 1.5);
}

#[test]
fn bad_samples_are_rejected_with_their_index() {
    let mut s = set();
    let d = Direction::from_spherical(0.1, 0.0).unwrap();
    let e = s.push(&d, &d, &[1.0], 1.0).unwrap_err();
    assert!(
        e.to_string()
            .contains("sample 4 has 1 channel values, expected 2"),
        "{e}"
    );
    assert!(s.push(&d, &d, &[1.0, 1.0], -1.0).is_err());
    assert!(s.push(&d, &d, &[1.0, 1.0], f64::NAN).is_err());
    assert!(s.set_weights(vec![1.0; 3]).is_err());
    assert!(s.set_weights(vec![1.0, 1.0, f64::INFINITY, 1.0]).is_err());
}

#[test]
fn filters_report_what_they_drop() {
    let s = set();
    let (a, r) = s.filter_angle_limit(80f64.to_radians());
    assert_eq!((r.kept, r.dropped_angle), (3, 1));
    assert_eq!(a.len(), 3);
    let (b, r) = s.filter_invalid(false);
    assert_eq!(
        (r.kept, r.dropped_non_finite, r.dropped_negative),
        (3, 1, 0)
    );
    // Negative values are data unless asked otherwise.
    assert_eq!(b.count_negative(), 1);
    let (c, r) = s.filter_invalid(true);
    assert_eq!(
        (r.kept, r.dropped_non_finite, r.dropped_negative),
        (2, 1, 1)
    );
    assert_eq!(c.weights(), &[1.0, 1.0]);
    assert_eq!(r.dropped(), 2);
}

#[test]
fn parameters_are_validated_by_name_and_box() {
    let specs = vec![
        ParamSpec::new("kd", "diffuse", 0.0, 1.0, 0.5, true),
        ParamSpec::new("a", "roughness", 0.0, 0.5, 0.1, false).open_below(),
    ];
    assert!(validate("ward", &specs, &[0.5, 0.2]).is_ok());
    let e = validate("ward", &specs, &[0.5, 0.0]).unwrap_err();
    assert_eq!(
        e,
        ParamError::OutOfBounds {
            name: "a".into(),
            value: 0.0,
            bounds: "(0, 0.5]".into()
        }
    );
    assert!(
        e.to_string()
            .contains("`a` = 0 is outside its box (0, 0.5]")
    );
    assert!(matches!(
        validate("ward", &specs, &[f64::NAN, 0.2]),
        Err(ParamError::NotFinite { .. })
    ));
    assert!(matches!(
        validate("ward", &specs, &[0.5]),
        Err(ParamError::WrongCount {
            expected: 2,
            got: 1,
            ..
        })
    ));
    let v = assign_by_name("ward", &specs, &[("a".into(), 0.3)]).unwrap();
    assert_eq!(v, vec![0.5, 0.3]);
    let e = assign_by_name("ward", &specs, &[("b".into(), 0.3)]).unwrap_err();
    assert!(
        e.to_string()
            .contains("has no parameter `b` (it has: kd, a)")
    );
}
