//! The data's side of the judge kept across processes.
//!
//! Rendering a measured file on the judge's film (RGL interpolation at
//! every direction pair of every pixel, both light sets) costs about as
//! much as a whole fit, and it does not depend on the fit: a `fit`, a
//! `select`, a `report` and a batch row of the same file need the same
//! renders. They are kept in a cache folder, one entry per file content
//! and judge:
//!
//! - the key digests the file's bytes, the loaded data's values at fixed
//!   direction pairs (a change of the reader shows there), and the
//!   judge's renders of a fixed analytic probe (a change of the light
//!   sets, the film or the renderer shows there), with the film size;
//! - an entry repeats its key and ends in a checksum of its bytes; an
//!   entry that does not read back whole, under its key, with finite
//!   non-negative radiance of the film's size is rebuilt and rewritten,
//!   never trusted;
//! - entries are written to a temporary file and renamed, so a reader in
//!   another process sees a whole entry or none.
//!
//! The folder is `BRDF_CACHE_DIR` when set, else the platform's cache
//! folder (`$XDG_CACHE_HOME` or `~/.cache` on Linux, `~/Library/Caches`
//! on macOS, `%LOCALAPPDATA%` on Windows) under `brdf-fit/judge`.
//! `BRDF_NO_CACHE=1` or [`set_enabled`]`(false)` (`brdf --no-cache`)
//! renders every time and touches no file.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};

use brdf_core::Brdf;
use brdf_core::direction::spherical_to_cartesian;
use brdf_core::nalgebra::Vector3;
use brdf_render::Image;
use brdf_render::judge::Judge;

use crate::FitError;

/// First bytes of an entry; a change of the layout changes it.
const MAGIC: &[u8] = b"brdf-fit judge renders 1\n";

static ENABLED: AtomicBool = AtomicBool::new(true);

/// Switch the cache on or off for this process (`brdf --no-cache`).
pub fn set_enabled(on: bool) {
    ENABLED.store(on, Ordering::Relaxed);
}

/// The cache folder in use: `None` when switched off or when the platform
/// names none.
pub fn folder() -> Option<PathBuf> {
    if !ENABLED.load(Ordering::Relaxed) || std::env::var_os("BRDF_NO_CACHE").is_some() {
        return None;
    }
    if let Some(dir) = std::env::var_os("BRDF_CACHE_DIR").filter(|d| !d.is_empty()) {
        return Some(PathBuf::from(dir));
    }
    platform_cache().map(|d| d.join("brdf-fit").join("judge"))
}

/// The platform's folder for caches.
fn platform_cache() -> Option<PathBuf> {
    let var = |name: &str| {
        std::env::var_os(name)
            .filter(|v| !v.is_empty())
            .map(PathBuf::from)
    };
    if cfg!(windows) {
        return var("LOCALAPPDATA");
    }
    if cfg!(target_os = "macos") {
        return var("HOME").map(|h| h.join("Library").join("Caches"));
    }
    var("XDG_CACHE_HOME").or_else(|| var("HOME").map(|h| h.join(".cache")))
}

/// `terms` (a judge without data) with the renders of `data`, loaded from
/// `file`: read from the cache when a whole entry is there, else rendered
/// and stored. Without a cache folder, rendered.
pub fn rendering(terms: &Judge, file: &Path, data: &dyn Brdf) -> Result<Judge, FitError> {
    let Some(dir) = folder() else {
        return Ok(terms.rendering(data)?);
    };
    let Some(key) = key(terms, file, data)? else {
        return Ok(terms.rendering(data)?);
    };
    let entry = dir.join(format!("{key:016x}.bin"));
    if let Some(judge) = read(&entry, key).and_then(|r| terms.rendering_from(r).ok()) {
        return Ok(judge);
    }
    let judge = terms.rendering(data)?;
    // A cache that cannot be written (read-only home, full disk) costs
    // the next run a render, nothing else.
    let _ = write(&dir, &entry, key, &judge.data_renders());
    Ok(judge)
}

/// The entry's key (see the module doc); `None` when the file cannot be
/// read again (then nothing is cached).
fn key(terms: &Judge, file: &Path, data: &dyn Brdf) -> Result<Option<u64>, FitError> {
    let Ok(bytes) = std::fs::read(file) else {
        return Ok(None);
    };
    let mut h = Fnv::default();
    h.bytes(MAGIC);
    h.u64(terms.size() as u64);
    h.u64(bytes.len() as u64);
    h.bytes(&bytes);
    let mut f = vec![0.0; data.channels()];
    for (l, v) in probe_pairs() {
        data.eval(&l, &v, &mut f);
        f.iter().for_each(|x| h.u64(x.to_bits()));
    }
    h.u64(judge_fingerprint(terms)?);
    Ok(Some(h.0))
}

/// The digest of `terms`' renders of [`Probe`], made once per process and
/// film size.
fn judge_fingerprint(terms: &Judge) -> Result<u64, FitError> {
    static KNOWN: Mutex<Vec<(usize, u64)>> = Mutex::new(Vec::new());
    let size = terms.size();
    let known = |k: &[(usize, u64)]| k.iter().find(|(s, _)| *s == size).map(|(_, d)| *d);
    if let Some(d) = KNOWN.lock().ok().and_then(|k| known(&k)) {
        return Ok(d);
    }
    let mut h = Fnv::default();
    for image in terms.rendering(&Probe)?.data_renders() {
        image.data.iter().for_each(|x| h.u64(x.to_bits()));
    }
    if let Ok(mut k) = KNOWN.lock() {
        k.push((size, h.0));
    }
    Ok(h.0)
}

/// Fixed direction pairs spread over the hemisphere pairs.
fn probe_pairs() -> Vec<(Vector3<f64>, Vector3<f64>)> {
    let mut pairs = Vec::new();
    for i in 0..4 {
        for j in 0..4 {
            let (ti, to) = (0.1 + 0.35 * i as f64, 0.05 + 0.37 * j as f64);
            let phi = 0.4 + 0.9 * (i * 4 + j) as f64;
            pairs.push((
                spherical_to_cartesian(ti, 0.0),
                spherical_to_cartesian(to, phi),
            ));
        }
    }
    pairs
}

/// A fixed analytic reflectance with a diffuse part and a sharp,
/// coloured highlight: its renders fingerprint the judge.
struct Probe;

impl Brdf for Probe {
    fn channels(&self) -> usize {
        3
    }

    fn eval(&self, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        let h = (l + v).normalize();
        let lobe = h.z.max(0.0).powi(40);
        for (c, o) in out.iter_mut().enumerate() {
            *o = (0.2 + 0.1 * c as f64) / std::f64::consts::PI + (0.5 + 0.2 * c as f64) * lobe;
        }
    }
}

/// The renders of the entry at `path` when it is whole and under `key`.
fn read(path: &Path, key: u64) -> Option<Vec<Image>> {
    let bytes = std::fs::read(path).ok()?;
    let (body, sum) = bytes.split_at_checked(bytes.len().checked_sub(8)?)?;
    let mut h = Fnv::default();
    h.bytes(body);
    if h.0.to_le_bytes() != sum {
        return None;
    }
    let mut r = Reader(body.strip_prefix(MAGIC)?);
    if r.u64()? != key {
        return None;
    }
    let count = r.u64()?;
    let mut images = Vec::new();
    for _ in 0..count.min(16) {
        let (width, height, channels) = (r.u64()? as usize, r.u64()? as usize, r.u64()? as usize);
        let n = width.checked_mul(height)?.checked_mul(channels)?;
        let data = (0..n)
            .map(|_| r.u64().map(f64::from_bits))
            .collect::<Option<Vec<_>>>()?;
        images.push(Image {
            width,
            height,
            channels,
            data,
        });
    }
    (images.len() as u64 == count && r.0.is_empty()).then_some(images)
}

/// Write the entry for `key` holding `renders` (a temporary file renamed).
fn write(dir: &Path, path: &Path, key: u64, renders: &[&Image]) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    let mut body = MAGIC.to_vec();
    body.extend(key.to_le_bytes());
    body.extend((renders.len() as u64).to_le_bytes());
    for image in renders {
        for n in [image.width, image.height, image.channels] {
            body.extend((n as u64).to_le_bytes());
        }
        image
            .data
            .iter()
            .for_each(|x| body.extend(x.to_bits().to_le_bytes()));
    }
    let mut h = Fnv::default();
    h.bytes(&body);
    body.extend(h.0.to_le_bytes());
    // One temporary file per writer, threads of one process included, so a rename never moves a file another
    // writer is still filling.
    static WRITER: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let writer = WRITER.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let tmp = dir.join(format!("{key:016x}.{}-{writer}.tmp", std::process::id()));
    let mut f = std::fs::File::create(&tmp)?;
    f.write_all(&body)?;
    f.sync_all()?;
    std::fs::rename(&tmp, path).inspect_err(|_| {
        let _ = std::fs::remove_file(&tmp);
    })
}

/// Reads little-endian `u64`s off the front of a byte slice.
struct Reader<'a>(&'a [u8]);

impl Reader<'_> {
    fn u64(&mut self) -> Option<u64> {
        let (head, rest) = self.0.split_first_chunk::<8>()?;
        self.0 = rest;
        Some(u64::from_le_bytes(*head))
    }
}

/// FNV-1a, 64 bits: a digest stable across platforms and Rust releases
/// (the standard library's hasher promises neither).
struct Fnv(u64);

impl Default for Fnv {
    fn default() -> Self {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
}

impl Fnv {
    fn bytes(&mut self, bytes: &[u8]) {
        for b in bytes {
            self.0 = (self.0 ^ u64::from(*b)).wrapping_mul(0x0000_0100_0000_01b3);
        }
    }

    fn u64(&mut self, x: u64) {
        self.bytes(&x.to_le_bytes());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fnv_matches_the_published_test_vectors() {
        // FNV-1a 64 of "" and "a" (Fowler, Noll & Vo's reference values).
        let mut h = Fnv::default();
        h.bytes(b"");
        assert_eq!(h.0, 0xcbf2_9ce4_8422_2325);
        h.bytes(b"a");
        assert_eq!(h.0, 0xaf63_dc4c_8601_ec8c);
    }

    #[test]
    fn an_entry_reads_back_and_a_damaged_one_does_not() {
        let dir = std::env::temp_dir().join(format!("brdf-cache-test-{}", std::process::id()));
        let path = dir.join("e.bin");
        let image = Image {
            width: 2,
            height: 1,
            channels: 3,
            data: vec![0.0, 0.5, 1.0, 2.0, 0.25, 3.0],
        };
        write(&dir, &path, 7, &[&image, &image]).unwrap();
        let back = read(&path, 7).unwrap();
        assert_eq!(back.len(), 2);
        assert_eq!(back[1].data, image.data);
        assert!(read(&path, 8).is_none(), "another key");
        let mut bytes = std::fs::read(&path).unwrap();
        let k = bytes.len() / 2;
        bytes[k] ^= 1;
        std::fs::write(&path, &bytes).unwrap();
        assert!(read(&path, 7).is_none(), "a flipped bit");
        std::fs::write(&path, &bytes[..bytes.len() - 3]).unwrap();
        assert!(read(&path, 7).is_none(), "a cut entry");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
