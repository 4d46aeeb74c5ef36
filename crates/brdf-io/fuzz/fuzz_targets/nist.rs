//! NIST StRD `.dat` files.
#![no_main]

use std::path::Path;

use brdf_io::nist;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = nist::parse(Path::new("fuzz.dat"), &String::from_utf8_lossy(data));
});
