//! Tables written by the study: CSV (machine-readable) and Markdown
//! (readable, with the thesis value beside the project's where there is
//! one), and the names and numbers they print.

// The tables live in brdf-fit (the batch summary and `brdf select` write
// them too); the study uses them under the names it always has.
pub use brdf_fit::table::{Cell, Table};
pub use brdf_render::fmt_sig;

pub use brdf_fit::data_name;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn significant_digits() {
        assert_eq!(fmt_sig(0.0190, 3), "0.0190");
        assert_eq!(fmt_sig(2.1987, 4), "2.199");
        assert_eq!(fmt_sig(1234.6, 3), "1235");
        assert_eq!(fmt_sig(1.5e-7, 2), "1.5e-7");
    }
}
