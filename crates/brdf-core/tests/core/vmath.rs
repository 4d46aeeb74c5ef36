//! `vmath::exp` against the C library's correctly rounded (to within
//! 1 ulp) `f64::exp`, in ulps, over its whole range and at its edges.

use brdf_core::vmath::exp;

fn ulps(a: f64, b: f64) -> u64 {
    (a.to_bits() as i64 - b.to_bits() as i64).unsigned_abs()
}

#[test]
fn within_two_ulp_over_the_range() {
    // A deterministic sweep: 2 million points over [-708, 709], plus a
    // fine sweep around 0 where the polynomial alone is used.
    let mut worst = (0u64, 0.0);
    let n = 2_000_000;
    for i in 0..=n {
        let x = -708.0 + 1417.0 * (i as f64) / (n as f64);
        let u = ulps(exp(x), x.exp());
        if u > worst.0 {
            worst = (u, x);
        }
    }
    for i in 0..=200_000 {
        let x = -0.5 + (i as f64) / 200_000.0;
        let u = ulps(exp(x), x.exp());
        if u > worst.0 {
            worst = (u, x);
        }
    }
    assert!(worst.0 <= 2, "{} ulp at x = {}", worst.0, worst.1);
}

#[test]
fn edges_and_special_values() {
    assert_eq!(exp(0.0), 1.0);
    assert_eq!(exp(-708.5), 0.0);
    assert_eq!(exp(f64::NEG_INFINITY), 0.0);
    assert_eq!(exp(710.0), f64::INFINITY);
    assert_eq!(exp(f64::INFINITY), f64::INFINITY);
    assert!(exp(f64::NAN).is_nan());
    assert!(ulps(exp(709.0), 709f64.exp()) <= 2);
    assert!(ulps(exp(-708.0), (-708f64).exp()) <= 2);
    assert!(ulps(exp(1.0), std::f64::consts::E) <= 1);
}
