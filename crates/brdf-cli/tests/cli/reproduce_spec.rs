//! `brdf reproduce --spec` on a reduced study: only the selection is
//! written, the README lists it, results are identical for 1 and 2
//! threads, and (with the measured data) a rerun gives the numbers
//! committed in `results/`.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use crate::common::{self, Data};

fn temp(name: &str) -> std::path::PathBuf {
    common::scratch("spec", name)
}

/// Run `brdf reproduce` with `args` into `out` on `data`; the folder the
/// files land in.
fn reproduce(out: &Path, args: &[&str], data: Data) -> PathBuf {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_brdf"));
    cmd.arg("reproduce").arg("--out").arg(out).args(args);
    match data {
        Data::Synthetic => {
            cmd.env_remove("BRDF_DATA");
        }
        Data::Measured => {
            let root = std::env::var_os("BRDF_DATA")
                .expect("BRDF_DATA is not set: this test reads the measured data");
            assert!(
                Path::new(&root).is_dir(),
                "BRDF_DATA={} is not a folder",
                Path::new(&root).display()
            );
        }
    }
    let o = cmd.output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    // Progress bars are silent when stderr is not a terminal.
    assert!(!err.contains("[=") && !err.contains("eta"), "{err}");
    match data {
        Data::Measured => out.to_path_buf(),
        Data::Synthetic => out.join("synthetic"),
    }
}

fn files(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// On the measured CUReT samples.
#[test]
#[ignore = "needs BRDF_DATA"]
fn a_reduced_spec_writes_only_its_selection_and_is_the_same_for_1_and_2_threads() {
    reduced_spec(Data::Measured, "threads");
}

/// On the built-in synthetic samples.
#[test]
fn a_reduced_spec_on_synthetic_data_writes_only_its_selection_and_is_the_same_for_1_and_2_threads()
{
    reduced_spec(Data::Synthetic, "threads-synthetic");
}

fn reduced_spec(data: Data, tag: &str) {
    let dir = temp(tag);
    let spec = dir.join("reduced.toml");
    std::fs::write(
        &spec,
        "tables = [\"kurt_9_1\", \"kurt_9_2\", \"lafortune_box\"]\nmaterials = [\"25\", \"1\", \"quarry\", \"felt (synthetic)\"]\nmodels = [\"ward\", \"lafortune\", \"polynomial\"]\ndegrees = [1, 2, 3]\n",
    )
    .unwrap();
    let spec_arg = spec.to_string_lossy().into_owned();
    let one = reproduce(
        &dir.join("t1"),
        &["--spec", &spec_arg, "--threads", "1"],
        data,
    );
    let two = reproduce(
        &dir.join("t2"),
        &["--spec", &spec_arg, "--threads", "2"],
        data,
    );
    let names = files(&one);
    for want in [
        "kurt_9_1.csv",
        "kurt_9_1.png",
        "kurt_9_2.csv",
        "kurt_9_2_parameters.csv",
        "lafortune_box.csv",
        "README.md",
    ] {
        assert!(names.iter().any(|n| n == want), "{want} missing: {names:?}");
    }
    for unwanted in [
        "kurt_9_4.csv",
        "kurt_9_5.csv",
        "kurt_9_4_times.csv",
        "nist.csv",
        "sopp_a8.csv",
    ] {
        assert!(
            !names.iter().any(|n| n == unwanted),
            "{unwanted} written outside the selection"
        );
    }
    assert_eq!(names, files(&two));
    for n in names
        .iter()
        .filter(|n| n.ends_with(".csv") || n.ends_with(".md"))
    {
        if n == "README.md" {
            continue;
        }
        let a = std::fs::read_to_string(one.join(n)).unwrap();
        let b = std::fs::read_to_string(two.join(n)).unwrap();
        assert_eq!(a, b, "{n} differs between 1 and 2 threads");
    }
    // Table 9.1: three degrees; Table 9.2: the three models, two materials.
    let t91 = std::fs::read_to_string(one.join("kurt_9_1.csv")).unwrap();
    assert_eq!(t91.lines().count(), 4, "{t91}");
    let t92 = std::fs::read_to_string(one.join("kurt_9_2.csv")).unwrap();
    assert_eq!(t92.lines().count(), 4, "{t92}");
    assert_eq!(
        t92.lines().next().unwrap().split(',').count(),
        1 + 2 * 2,
        "{t92}"
    );
    let readme = std::fs::read_to_string(one.join("README.md")).unwrap();
    assert!(readme.contains("`kurt_9_2.{csv,md}`") && readme.contains("`lafortune_box.{csv,md}`"));
    assert!(!readme.contains("| `kurt_9_4"), "{readme}");
    for n in &names {
        if n.ends_with(".md") || n.ends_with(".csv") {
            let text = std::fs::read_to_string(one.join(n)).unwrap();
            assert!(
                !text.contains(&*dir.to_string_lossy()),
                "{n} names an absolute path"
            );
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A spec names a model as `brdf fit --model` does: `blinn_phong` is
/// Blinn-Phong, and only it is fitted.
#[test]
fn a_spec_takes_the_model_names_brdf_fit_takes() {
    let dir = temp("names");
    let spec = dir.join("names.toml");
    std::fs::write(
        &spec,
        "tables = [\"kurt_9_2\"]\nmaterials = [\"25\", \"1\", \"quarry\", \"felt (synthetic)\"]\nmodels = [\"blinn_phong\"]\n",
    )
    .unwrap();
    let out = reproduce(
        &dir.join("out"),
        &["--spec", &spec.to_string_lossy()],
        Data::Synthetic,
    );
    let t92 = std::fs::read_to_string(out.join("kurt_9_2.csv")).unwrap();
    let models: Vec<&str> = t92
        .lines()
        .skip(1)
        .filter_map(|l| l.split(',').next())
        .collect();
    assert_eq!(models, ["Blinn-Phong"], "{t92}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_unknown_part_or_a_bad_spec_is_a_usage_error_naming_it() {
    let dir = temp("bad");
    let o = Command::new(env!("CARGO_BIN_EXE_brdf"))
        .args(["reproduce", "--only", "kurt_9_9", "--out"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(!o.status.success());
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(e.contains("kurt_9_9") && e.contains("kurt_9_1"), "{e}");
    let spec = dir.join("bad.toml");
    std::fs::write(&spec, "degrees = [0]\n").unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_brdf"))
        .args(["reproduce", "--spec"])
        .arg(&spec)
        .arg("--out")
        .arg(&dir)
        .output()
        .unwrap();
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && e.contains("bad.toml") && e.contains("degrees"),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// CSV as `row key -> column -> value`.
fn csv_map(text: &str) -> BTreeMap<String, BTreeMap<String, String>> {
    let mut lines = csv::Reader::from_reader(text.as_bytes());
    let header: Vec<String> = lines
        .headers()
        .unwrap()
        .iter()
        .map(str::to_string)
        .collect();
    lines
        .records()
        .map(|r| {
            let r = r.unwrap();
            let key = r[0].to_string();
            (
                key,
                header
                    .iter()
                    .cloned()
                    .zip(r.iter().map(str::to_string))
                    .collect(),
            )
        })
        .collect()
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn a_rerun_of_a_reduced_study_gives_the_committed_results() {
    let committed = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../results");
    let dir = temp("rerun");
    let spec = dir.join("rerun.toml");
    std::fs::write(
        &spec,
        "tables = [\"kurt_9_1\", \"kurt_9_2\"]\nmaterials = [\"25\", \"1\", \"55\"]\nmodels = [\"ward\", \"blinn-phong\", \"lafortune\", \"polynomial\"]\ndegrees = [1, 2, 3, 4]\n",
    )
    .unwrap();
    let out = reproduce(
        &dir.join("out"),
        &["--spec", &spec.to_string_lossy()],
        Data::Measured,
    );
    let mut compared = 0;
    for table in ["kurt_9_1.csv", "kurt_9_2.csv"] {
        let new = csv_map(&std::fs::read_to_string(out.join(table)).unwrap());
        let path = committed.join(table);
        let old = csv_map(
            &std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display())),
        );
        for (key, row) in &new {
            let old_row = old
                .get(key)
                .unwrap_or_else(|| panic!("{table}: row `{key}` not committed"));
            for (col, v) in row {
                let (Ok(a), Some(Ok(b))) =
                    (v.parse::<f64>(), old_row.get(col).map(|s| s.parse::<f64>()))
                else {
                    continue;
                };
                assert!(
                    (a - b).abs() <= 1e-6 * b.abs().max(1e-12),
                    "{table} `{key}` `{col}`: rerun {a}, committed {b}"
                );
                compared += 1;
            }
        }
    }
    assert!(compared >= 30, "only {compared} values compared");
    std::fs::remove_dir_all(&dir).unwrap();
}
