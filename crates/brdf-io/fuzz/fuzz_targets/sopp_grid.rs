//! Sopp's goniometric grid as CSV; a parsed grid is turned into samples.
#![no_main]

use std::path::Path;

use brdf_io::sopp_grid;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    if let Ok(g) = sopp_grid::parse(Path::new("fuzz.csv"), &text) {
        let _ = g.to_samples("fuzz", 80.0, true);
    }
});
