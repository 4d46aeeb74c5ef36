//! Robust weight functions against hand-computed values and their limits.

use brdf_solve::robust_weights::RobustWeight;

#[test]
fn values_by_hand() {
    use RobustWeight::*;
    let cases = [
        (Andrews, 0.5, 0.5f64.sin() / 0.5),
        (Andrews, 3.2, 0.0),
        (Bisquare, 0.5, 0.5625),
        (Bisquare, 1.0, 0.0),
        (Cauchy, 2.0, 0.2),
        (Fair, -3.0, 0.25),
        (Huber, 0.5, 1.0),
        (Huber, -4.0, 0.25),
        (Logistic, 1.0, 1f64.tanh()),
        (Talwar, 0.99, 1.0),
        (Talwar, 1.0, 0.0),
        (Welsch, 1.0, (-1f64).exp()),
    ];
    for (w, u, expect) in cases {
        assert!(
            (w.weight(u) - expect).abs() < 1e-15,
            "{w:?}({u}) = {} vs {expect}",
            w.weight(u)
        );
    }
}

#[test]
fn every_weight_is_one_at_zero_symmetric_bounded_and_nan_safe() {
    for w in RobustWeight::ALL {
        assert_eq!(w.weight(0.0), 1.0, "{w:?}");
        for u in [1e-9, 0.3, 0.9, 2.5, 10.0] {
            let a = w.weight(u);
            assert_eq!(a, w.weight(-u), "{w:?} symmetric at {u}");
            assert!((0.0..=1.0).contains(&a), "{w:?}({u}) = {a}");
        }
        assert_eq!(w.weight(f64::NAN), 0.0);
        assert_eq!(w.name().parse::<RobustWeight>().unwrap(), w);
    }
    assert!("nope".parse::<RobustWeight>().is_err());
    assert_eq!(RobustWeight::default(), RobustWeight::Bisquare);
    assert_eq!(RobustWeight::Bisquare.default_tune(), 4.685);
    assert_eq!(RobustWeight::Welsch.default_tune(), 2.985);
}
