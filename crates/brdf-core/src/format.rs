//! Numbers as the workspace prints them in tables, labels and colour bars:
//! a fixed count of significant digits, plain notation in `1e-4 ..= 1e6`,
//! scientific outside. One formatter, so a number reads the same in every
//! report, table and figure (the committed results compare these strings).

/// `x` with `digits` significant digits: `number(0.019, 3)` is `0.0190`,
/// `number(1234.6, 3)` is `1235`, `number(1.5e-7, 2)` is `1.5e-7`; zero is
/// `0`, and NaN and the infinities print as Rust prints them.
pub fn number(x: f64, digits: usize) -> String {
    if !x.is_finite() {
        return format!("{x}");
    }
    if x == 0.0 {
        return "0".into();
    }
    let mag = x.abs().log10().floor() as i32;
    if !(-4..6).contains(&mag) {
        return format!("{:.*e}", digits.saturating_sub(1), x);
    }
    let decimals = (digits as i32 - 1 - mag).max(0) as usize;
    format!("{x:.decimals$}")
}

#[cfg(test)]
mod tests {
    use super::number;

    #[test]
    fn plain_numbers_keep_their_significant_digits() {
        assert_eq!(number(0.0190, 3), "0.0190");
        assert_eq!(number(2.1987, 4), "2.199");
        assert_eq!(number(1234.6, 3), "1235");
        assert_eq!(number(-0.5, 2), "-0.50");
        assert_eq!(number(0.0755, 3), "0.0755");
        assert_eq!(number(2.73, 3), "2.73");
        assert_eq!(number(999_999.0, 3), "999999");
        // Ten to the minus four is the smallest magnitude written plainly.
        assert_eq!(number(1e-4, 2), "0.00010");
        assert_eq!(number(0.2, 1), "0.2");
    }

    #[test]
    fn large_and_small_numbers_are_scientific() {
        assert_eq!(number(1.5e-7, 2), "1.5e-7");
        assert_eq!(number(1e6, 3), "1.00e6");
        assert_eq!(number(-2.5e-5, 2), "-2.5e-5");
        assert_eq!(number(6.02e23, 4), "6.020e23");
        assert_eq!(number(1.2e7, 0), "1e7");
    }

    #[test]
    fn zero_and_non_finite_values() {
        assert_eq!(number(0.0, 4), "0");
        assert_eq!(number(-0.0, 4), "0");
        assert_eq!(number(f64::NAN, 3), "NaN");
        assert_eq!(number(f64::INFINITY, 3), "inf");
        assert_eq!(number(f64::NEG_INFINITY, 3), "-inf");
    }
}
