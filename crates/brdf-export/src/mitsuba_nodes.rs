//! The property elements every Mitsuba 3 BSDF writer uses: a named float
//! and a named RGB colour.

use crate::fitted::rgb_string;
use crate::xml::Node;

/// `<float name=.. value=..>`.
pub(crate) fn float(name: &str, v: f64) -> Node {
    Node::new("float").attr("name", name).attr("value", v)
}

/// `<rgb name=.. value="r, g, b">`.
pub(crate) fn rgb(name: &str, c: &[f64; 3]) -> Node {
    Node::new("rgb")
        .attr("name", name)
        .attr("value", rgb_string(c))
}
