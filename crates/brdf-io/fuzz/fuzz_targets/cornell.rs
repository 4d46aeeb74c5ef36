//! Cornell `.brdf` text, converted to RGB and to luminance.
#![no_main]

use std::path::Path;

use brdf_io::cornell::{self, CornellColour};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let p = Path::new("fuzz.brdf");
    let _ = cornell::parse(p, &text, CornellColour::Rgb);
    let _ = cornell::parse(p, &text, CornellColour::Luminance);
});
