//! `brdf batch`: two shards merged give the same fits as one run; a rerun
//! skips what is done (resumable); a truncated last line from a killed run
//! is refitted; bad shard specs and unknown models are errors naming them.

mod common;

use common::{brdf, data_file};

fn rows(dir: &std::path::Path) -> Vec<String> {
    // Drop the seconds column: measured, not reproducible.
    std::fs::read_to_string(dir.join("summary.csv"))
        .expect("summary written")
        .lines()
        .map(|l| {
            l.rsplit_once(',')
                .map(|(a, _)| a.to_string())
                .unwrap_or_default()
        })
        .collect()
}

#[test]
fn shards_merge_to_one_run_and_reruns_resume() {
    let (Some(curet), Some(rgl)) = (data_file("curet/abrdf.dat"), data_file("rgl")) else {
        return;
    };
    let tmp = std::env::temp_dir().join(format!("brdf-batch-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&tmp);
    let (c, r) = (curet.display().to_string(), rgl.display().to_string());
    let dir = |n: &str| tmp.join(n).display().to_string();
    let base = [
        "batch",
        "--data",
        &c,
        &r,
        "--models",
        "Lambert,blinn_phong",
        "--channels",
        "grey",
        "--starts",
        "3",
        "--out",
    ];
    let run = |out: &str, extra: &[&str]| {
        let mut a: Vec<&str> = base.to_vec();
        a.push(out);
        a.extend_from_slice(extra);
        let (ok, _, err) = brdf(&a);
        assert!(ok, "{err}");
        err
    };
    run(&dir("all"), &[]);
    run(&dir("s1"), &["--shard", "1/2"]);
    run(&dir("s2"), &["--shard", "2/2"]);
    let (ok, _, err) = brdf(&[
        "batch",
        "--merge",
        &dir("s1"),
        &dir("s2"),
        "--out",
        &dir("m"),
    ]);
    assert!(ok, "{err}");
    let all = rows(&tmp.join("all"));
    // 61 CUReT samples + 5 RGL files, 2 models, plus the header.
    assert_eq!(all.len(), 1 + 66 * 2);
    assert_eq!(all, rows(&tmp.join("m")));
    // Resume: nothing to do; then lose the last line half-written.
    assert!(run(&dir("all"), &[]).contains("132 already"));
    let fits = tmp.join("all").join("fits.jsonl");
    let text = std::fs::read_to_string(&fits).unwrap();
    let cut = text.trim_end().rfind('\n').unwrap() + 20;
    std::fs::write(&fits, &text[..cut]).unwrap();
    assert!(run(&dir("all"), &[]).contains("1 to run"));
    assert_eq!(all, rows(&tmp.join("all")));
    let _ = std::fs::remove_dir_all(&tmp);
}

#[test]
fn bad_requests_name_what_is_wrong() {
    let tmp = std::env::temp_dir().join(format!("brdf-batch-bad-{}", std::process::id()));
    let out = tmp.display().to_string();
    let (ok, _, err) = brdf(&[
        "batch", "--data", "x.csv", "--models", "lambert", "--out", &out, "--shard", "3/2",
    ]);
    assert!(!ok && err.contains("--shard 3/2"), "{err}");
    let (ok, _, err) = brdf(&[
        "batch",
        "--data",
        "x.csv",
        "--models",
        "blin-phong",
        "--out",
        &out,
    ]);
    assert!(!ok && err.contains("did you mean `blinn-phong`"), "{err}");
    let _ = std::fs::remove_dir_all(&tmp);
}
