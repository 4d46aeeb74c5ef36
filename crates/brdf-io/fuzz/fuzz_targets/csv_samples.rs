//! Generic CSV samples.
#![no_main]

use std::path::Path;

use brdf_io::csv_samples;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = csv_samples::parse(Path::new("fuzz.csv"), &String::from_utf8_lossy(data));
});
