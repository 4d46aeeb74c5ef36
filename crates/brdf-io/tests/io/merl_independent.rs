//! MERL `.binary` against a table described independently of the library:
//! `tests/fixtures/merl/known_bins.py` lists a background value per channel,
//! planted bins (one invalid) and direction pairs inside them with their
//! flat index (sqrt(theta_h) mapping) and expected values in 1/sr (the
//! published scale factors, planar R, G, B). The file is assembled here from
//! the documented byte layout, not by the library's writer, then read.

use brdf_io::merl::{self, BINS};
use nalgebra::Vector3;

/// `(L, V, flat index, expected RGB or None when invalid)`.
type Query = (Vector3<f64>, Vector3<f64>, usize, Option<[f64; 3]>);

struct Known {
    background: [f64; 3],
    bins: Vec<(usize, [f64; 3])>,
    queries: Vec<Query>,
}

fn nums(f: &[&str]) -> Vec<f64> {
    f.iter().map(|s| s.parse().unwrap()).collect()
}

fn known() -> Known {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/merl/known_bins.txt"
    ))
    .unwrap();
    let mut k = Known {
        background: [0.0; 3],
        bins: Vec::new(),
        queries: Vec::new(),
    };
    for line in text.lines() {
        let f: Vec<&str> = line.split_whitespace().collect();
        match f[0] {
            "#" => {
                let b = nums(&f[2..5]);
                k.background = [b[0], b[1], b[2]];
            }
            "bin" => {
                let i = nums(&f[1..7]);
                let flat = i[0] as usize * 90 * 180 + i[1] as usize * 180 + i[2] as usize;
                k.bins.push((flat, [i[3], i[4], i[5]]));
            }
            "query" => {
                let d = nums(&f[1..7]);
                let flat: usize = f[7].parse().unwrap();
                let value = (f[8] != "invalid").then(|| {
                    let v = nums(&f[8..11]);
                    [v[0], v[1], v[2]]
                });
                k.queries.push((
                    Vector3::new(d[0], d[1], d[2]),
                    Vector3::new(d[3], d[4], d[5]),
                    flat,
                    value,
                ));
            }
            _ => panic!("unknown fixture line {line}"),
        }
    }
    k
}

/// The file bytes: three little-endian i32 `90, 90, 180`, then the stored
/// (unscaled) values as little-endian f64, all R, then all G, then all B.
fn file_bytes(k: &Known) -> Vec<u8> {
    let mut stored = vec![0.0; 3 * BINS];
    for c in 0..3 {
        stored[c * BINS..(c + 1) * BINS].fill(k.background[c]);
    }
    for (flat, s) in &k.bins {
        for c in 0..3 {
            stored[c * BINS + flat] = s[c];
        }
    }
    let mut b = Vec::with_capacity(12 + 8 * stored.len());
    for d in [90i32, 90, 180] {
        b.extend_from_slice(&d.to_le_bytes());
    }
    for x in stored {
        b.extend_from_slice(&x.to_le_bytes());
    }
    b
}

#[test]
fn merl_reads_an_independently_described_file() {
    let k = known();
    assert_eq!(k.bins.len(), 10);
    assert!(k.queries.len() >= 15);
    let bytes = file_bytes(&k);
    let path =
        std::env::temp_dir().join(format!("brdf-io-merl-known-{}.binary", std::process::id()));
    std::fs::write(&path, &bytes).unwrap();
    let m = merl::read(&path).unwrap();
    std::fs::remove_file(&path).unwrap();
    for (l, v, flat, want) in &k.queries {
        assert_eq!(merl::bin_of(l, v), Some(*flat), "bin of {l:?} {v:?}");
        let got = m.lookup(l, v);
        match (got, want) {
            (Some(g), Some(w)) => {
                for c in 0..3 {
                    assert!(
                        (g[c] - w[c]).abs() <= 1e-15 * w[c],
                        "channel {c} at bin {flat}: {} vs {}",
                        g[c],
                        w[c]
                    );
                }
            }
            (None, None) => {}
            _ => panic!("bin {flat}: {got:?} vs expected {want:?}"),
        }
    }
    assert_eq!(m.invalid_count(), 3, "one invalid bin, three channels");
    // The library's writer gives back the same layout (values within the
    // rounding of scaling and unscaling).
    let out = std::env::temp_dir().join(format!(
        "brdf-io-merl-known-out-{}.binary",
        std::process::id()
    ));
    merl::write(&out, &m).unwrap();
    let written = std::fs::read(&out).unwrap();
    std::fs::remove_file(&out).unwrap();
    assert_eq!(written.len(), bytes.len());
    assert_eq!(written[..12], bytes[..12]);
    for (a, b) in written[12..]
        .chunks_exact(8)
        .zip(bytes[12..].chunks_exact(8))
    {
        let (a, b) = (
            f64::from_le_bytes(a.try_into().unwrap()),
            f64::from_le_bytes(b.try_into().unwrap()),
        );
        assert!((a - b).abs() <= 1e-12 * b.abs(), "written {a} vs {b}");
    }
}
