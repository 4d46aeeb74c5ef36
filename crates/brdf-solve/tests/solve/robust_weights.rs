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

/// `rho(u) = int_0^u t w(t) dt` by composite Simpson quadrature of the
/// weight function (independent of `rho`'s closed forms), and
/// `rho'(u) = u w(u)` by central differences.
#[test]
fn rho_is_the_integral_of_psi() {
    for w in RobustWeight::ALL {
        for u in [1e-3_f64, 0.2, 0.7, 0.999, 1.5, 2.9, 3.3, 6.0, -2.0] {
            let f = |t: f64| t * w.weight(t);
            // Pieces end at the kinks (|t| = 1, pi), where Simpson's rule
            // would lose its accuracy.
            let mut ends: Vec<f64> = [1.0, std::f64::consts::PI]
                .into_iter()
                .filter(|k| *k < u.abs())
                .map(|k| k * u.signum())
                .collect();
            ends.push(u);
            let (mut a, mut simpson) = (0.0, 0.0);
            for &b in &ends {
                let n = 10_000;
                let h = (b - a) / n as f64;
                simpson += (0..n)
                    .map(|k| {
                        let t = a + k as f64 * h;
                        // Endpoints just inside the piece: one-sided limits at a jump.
                        h / 6.0 * (f(t + 1e-9 * h) + 4.0 * f(t + 0.5 * h) + f(t + (1.0 - 1e-9) * h))
                    })
                    .sum::<f64>();
                a = b;
            }
            let r = w.rho(u);
            assert!(
                (r - simpson).abs() < 1e-10 * simpson.abs().max(1e-6),
                "{w:?} rho({u}) = {r} vs {simpson}"
            );
            let d = 1e-6 * u.abs().max(1e-3);
            let near_kink =
                (u.abs() - 1.0).abs() < 2.0 * d || (u.abs() - std::f64::consts::PI).abs() < 2.0 * d;
            if !near_kink {
                let fd = (w.rho(u + d) - w.rho(u - d)) / (2.0 * d);
                assert!(
                    (fd - f(u)).abs() < 1e-6 * f(u).abs().max(1e-3),
                    "{w:?} rho'({u}) = {fd} vs {}",
                    f(u)
                );
            }
        }
        assert_eq!(w.rho(0.0), 0.0);
        assert!(w.rho(f64::NAN) >= w.rho(1e3), "{w:?}");
    }
    // Small-|u| forms keep relative accuracy (rho = u^2 / 2 + O(|u|^3)).
    for w in RobustWeight::ALL {
        let u = 1e-6;
        assert!((w.rho(u) / (0.5 * u * u) - 1.0).abs() < 1e-5, "{w:?}");
    }
}
