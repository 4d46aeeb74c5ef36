//! MERL `.binary`; a parsed table is looked up and sampled.
#![no_main]

use std::path::Path;

use brdf_io::merl;
use libfuzzer_sys::fuzz_target;

#[path = "common.rs"]
mod common;

fuzz_target!(|data: &[u8]| {
    if let Ok(m) = merl::parse(Path::new("fuzz.binary"), data) {
        for (l, v) in common::probe_pairs() {
            let _ = m.lookup(&l, &v);
        }
        let _ = m.to_samples("fuzz", 997);
    }
});
