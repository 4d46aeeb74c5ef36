//! Minimal NumPy `.npy` (format 1.0) writer for little-endian `f64` arrays,
//! so the Python side reads the exported problem bit for bit with
//! `numpy.load`.

use std::io::Write;
use std::path::Path;

use super::PeerError;

/// Write `data` (row-major, C order) with `shape` to `path`.
pub fn write_f64(path: &Path, shape: &[usize], data: &[f64]) -> Result<(), PeerError> {
    let count: usize = shape.iter().product();
    if count != data.len() {
        return Err(PeerError::Usage(format!(
            "{}: shape {shape:?} holds {count} values, got {}",
            path.display(),
            data.len()
        )));
    }
    let dims: Vec<String> = shape.iter().map(|d| d.to_string()).collect();
    let tuple = if dims.len() == 1 {
        format!("({},)", dims[0])
    } else {
        format!("({})", dims.join(", "))
    };
    let mut header = format!("{{'descr': '<f8', 'fortran_order': False, 'shape': {tuple}, }}");
    // Magic (6) + version (2) + header length (2) + header, padded with
    // spaces to a multiple of 64 and ended by a newline.
    let unpadded = 10 + header.len() + 1;
    header.push_str(&" ".repeat((64 - unpadded % 64) % 64));
    header.push('\n');
    let mut bytes = Vec::with_capacity(10 + header.len() + 8 * data.len());
    bytes.extend_from_slice(b"\x93NUMPY\x01\x00");
    bytes.extend_from_slice(&(header.len() as u16).to_le_bytes());
    bytes.extend_from_slice(header.as_bytes());
    for x in data {
        bytes.extend_from_slice(&x.to_le_bytes());
    }
    let io = |source| PeerError::Io {
        path: path.display().to_string(),
        source,
    };
    let mut f = std::fs::File::create(path).map_err(io)?;
    f.write_all(&bytes).map_err(io)
}
