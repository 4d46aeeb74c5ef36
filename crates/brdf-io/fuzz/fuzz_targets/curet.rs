//! CUReT `table.txt` and channel files (`abrdf.dat` layout). The input is
//! split at its first NUL byte: the table before, the values after.
#![no_main]

use std::path::Path;

use brdf_io::curet;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let cut = data.iter().position(|b| *b == 0).unwrap_or(data.len());
    let table = String::from_utf8_lossy(&data[..cut]);
    let values = String::from_utf8_lossy(data.get(cut + 1..).unwrap_or(&[]));
    let _ = curet::parse_table(Path::new("table.txt"), &table);
    let _ = curet::parse_values(Path::new("abrdf.dat"), &values);
});
