//! Python source text the Blender writers emit.

/// A Python string literal (Rust's debug quoting is valid Python for the
/// names and values written).
pub(crate) fn py_str(s: &str) -> String {
    format!("{s:?}")
}
