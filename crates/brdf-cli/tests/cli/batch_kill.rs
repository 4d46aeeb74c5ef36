//! `brdf batch` killed with SIGKILL at random points and resumed each time
//! ends with the same (material, model) fits as an uninterrupted run, with
//! no torn and no repeated lines in `fits.jsonl`.

use crate::common;

use std::collections::BTreeSet;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

use common::data_file;

/// A pseudo-random number in `0..n` (xorshift seeded by the clock).
fn random(state: &mut u64, n: u64) -> u64 {
    *state ^= *state << 13;
    *state ^= *state >> 7;
    *state ^= *state << 17;
    *state % n.max(1)
}

fn batch(curet: &Path, out: &Path) -> Command {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_brdf"));
    cmd.arg("batch").arg("--data");
    for s in 1..=6 {
        cmd.arg(format!("{}#{s}", curet.display()));
    }
    cmd.args(["--models", "lambert,blinn-phong", "--channels", "grey"])
        .args(["--starts", "4", "--out"])
        .arg(out)
        .stdout(Stdio::null())
        .stderr(Stdio::null());
    cmd
}

/// The (material, model) keys of `fits.jsonl`; every line must be whole
/// JSON and no key may repeat.
fn keys(dir: &Path) -> BTreeSet<(String, String)> {
    let text = std::fs::read_to_string(dir.join("fits.jsonl")).expect("fits.jsonl");
    assert!(text.is_empty() || text.ends_with('\n'), "torn last line");
    let mut out = BTreeSet::new();
    for line in text.lines() {
        let v: serde_json::Value = serde_json::from_str(line).expect("a whole JSON line");
        let key = (v["data"].to_string(), v["model"].to_string());
        assert!(out.insert(key.clone()), "repeated line {key:?}");
    }
    out
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn killed_and_resumed_batches_equal_one_run() {
    let curet = data_file("curet/abrdf.dat");
    let tmp = std::env::temp_dir().join(format!("brdf-batch-kill-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&tmp);
    let whole = tmp.join("whole");
    let t0 = Instant::now();
    assert!(batch(&curet, &whole).status().expect("runs").success());
    let span = t0.elapsed().as_micros() as u64;
    let expected = keys(&whole);
    assert_eq!(expected.len(), 12);
    let mut seed = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(88172645463325252, |d| d.as_nanos() as u64 | 1);
    let killed = tmp.join("killed");
    for _ in 0..8 {
        let mut child = batch(&curet, &killed).spawn().expect("spawns");
        std::thread::sleep(Duration::from_micros(random(&mut seed, span + span / 4)));
        let _ = child.kill();
        let _ = child.wait();
    }
    assert!(batch(&curet, &killed).status().expect("runs").success());
    assert_eq!(keys(&killed), expected);
    let _ = std::fs::remove_dir_all(&tmp);
}
