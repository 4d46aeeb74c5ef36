//! The data's renders kept across processes: a second fit of the same
//! file reads them from the cache and prints the same image errors to the
//! last bit; a damaged entry is rebuilt, never trusted; `--no-cache`
//! writes nothing.

use crate::common;

use std::path::{Path, PathBuf};
use std::process::Command;

/// `brdf fit` of the Lambert model on `data` with the cache in `cache`:
/// its JSON report.
fn fit(data: &Path, cache: &Path, extra: &[&str]) -> serde_json::Value {
    let out = Command::new(env!("CARGO_BIN_EXE_brdf"))
        .args(["fit", "--model", "lambert", "--metric", "ngan", "--json"])
        .arg("--data")
        .arg(data)
        .args(extra)
        .env("BRDF_CACHE_DIR", cache)
        .env_remove("BRDF_NO_CACHE")
        .output()
        .expect("the brdf binary runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("JSON on stdout")
}

fn entries(cache: &Path) -> Vec<PathBuf> {
    std::fs::read_dir(cache)
        .map(|d| d.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default()
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn a_second_fit_reads_the_renders_and_a_damaged_entry_is_rebuilt() {
    let data = common::data_file("rgl/paper_white_rgb.bsdf");
    let cache = std::env::temp_dir().join(format!("brdf-render-cache-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&cache);

    let uncached = fit(&data, &cache, &["--no-cache"]);
    assert!(
        entries(&cache).is_empty(),
        "--no-cache wrote {:?}",
        entries(&cache)
    );

    let first = fit(&data, &cache, &[]);
    let written = entries(&cache);
    assert_eq!(written.len(), 1, "one entry per file: {written:?}");
    let bytes = std::fs::read(&written[0]).expect("the entry");
    let second = fit(&data, &cache, &[]);
    assert_eq!(
        std::fs::read(&written[0]).expect("the entry"),
        bytes,
        "a whole entry is read, not rewritten"
    );
    let image = |v: &serde_json::Value| v["image_errors"].to_string();
    assert!(image(&uncached).contains("flip"), "{uncached}");
    assert_eq!(image(&first), image(&uncached));
    assert_eq!(image(&second), image(&uncached));

    // A flipped bit in the middle of a render: the checksum fails, the
    // renders are made again and the entry is rewritten whole.
    let mut damaged = bytes.clone();
    let k = damaged.len() / 2;
    damaged[k] ^= 0x40;
    std::fs::write(&written[0], &damaged).expect("damage the entry");
    let third = fit(&data, &cache, &[]);
    assert_eq!(image(&third), image(&uncached));
    assert_eq!(std::fs::read(&written[0]).expect("the entry"), bytes);

    // A cut entry likewise.
    std::fs::write(&written[0], &bytes[..bytes.len() / 3]).expect("cut the entry");
    assert_eq!(image(&fit(&data, &cache, &[])), image(&uncached));
    assert_eq!(std::fs::read(&written[0]).expect("the entry"), bytes);
    std::fs::remove_dir_all(&cache).expect("remove the test's cache");
}
