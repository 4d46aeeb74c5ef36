//! Structurally valid RGL materials with arbitrary (small) table sizes and
//! arbitrary values, written by `TensorFile::to_bytes`: reading and
//! evaluating them (the inverse VNDF warp, interpolation, the forward map)
//! must not panic, whatever the tables hold.
#![no_main]

use std::path::Path;

use arbitrary::Arbitrary;
use brdf_core::Brdf;
use brdf_io::rgl::{Field, Rgl, TensorFile};
use libfuzzer_sys::fuzz_target;

#[path = "common.rs"]
mod common;

#[derive(Arbitrary, Debug)]
struct Tables {
    /// Sizes, each taken modulo 6: phi_i, theta_i, and the 2D grid sides.
    sizes: [u8; 4],
    /// Values cycled to fill every table (f32, may be negative, zero, huge).
    values: Vec<f32>,
    /// Where the forward map is probed.
    s: [f32; 2],
}

fn field(shape: &[usize], values: &[f32], start: &mut usize) -> Field {
    let n: usize = shape.iter().product();
    let mut bytes = Vec::with_capacity(4 * n);
    for k in 0..n {
        let x = if values.is_empty() {
            1.0
        } else {
            values[(*start + k) % values.len()]
        };
        bytes.extend_from_slice(&x.to_le_bytes());
    }
    *start += n;
    Field {
        dtype: 10,
        shape: shape.to_vec(),
        bytes,
    }
}

fuzz_target!(|t: Tables| {
    let [np, nt, nx, ny] = t.sizes.map(|s| (s % 6) as usize);
    let mut at = 0;
    let v = &t.values;
    let fields = vec![
        ("phi_i".to_string(), field(&[np], v, &mut at)),
        ("theta_i".to_string(), field(&[nt], v, &mut at)),
        ("ndf".to_string(), field(&[ny, nx], v, &mut at)),
        ("sigma".to_string(), field(&[ny, nx], v, &mut at)),
        ("vndf".to_string(), field(&[np, nt, ny, nx], v, &mut at)),
        ("rgb".to_string(), field(&[np, nt, 3, ny, nx], v, &mut at)),
    ];
    let Ok(bytes) = (TensorFile { fields }).to_bytes() else {
        return;
    };
    if let Ok(m) = Rgl::parse(Path::new("fuzz.bsdf"), &bytes) {
        let mut out = [0.0; 3];
        for (l, v) in common::probe_pairs() {
            m.eval(&l, &v, &mut out);
            let _ = m.direction_of_sample(&l, [t.s[0] as f64, t.s[1] as f64]);
        }
    }
});
