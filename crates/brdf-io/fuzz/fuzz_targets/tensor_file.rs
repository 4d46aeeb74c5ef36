//! Raw bytes as a tensor file and as an RGL material; a material that
//! parses is evaluated.
#![no_main]

use std::path::Path;

use brdf_core::Brdf;
use brdf_io::rgl::{Rgl, TensorFile};
use libfuzzer_sys::fuzz_target;

#[path = "common.rs"]
mod common;

fuzz_target!(|data: &[u8]| {
    let p = Path::new("fuzz.bsdf");
    if TensorFile::parse(p, data).is_ok() {
        if let Ok(m) = Rgl::parse(p, data) {
            let mut out = [0.0; 3];
            for (l, v) in common::probe_pairs() {
                m.eval(&l, &v, &mut out);
            }
        }
    }
});
