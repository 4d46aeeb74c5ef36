//! `results/README.md`, written by the command from the list of files it
//! wrote: every file, what it holds, and the data, metric, angle limit,
//! software version and commit behind it.

use std::fmt::Write as _;
use std::path::Path;
use std::process::Command;

use super::Study;
use crate::StudyError;

/// The commit of the work tree holding `dir`, with a mark when the code
/// (outside the output folder) has uncommitted changes; "unknown" outside
/// a git work tree.
pub fn commit_of(dir: &Path) -> String {
    let git = |args: &[&str]| {
        Command::new("git")
            .arg("-C")
            .arg(dir)
            .args(args)
            .output()
            .ok()
            .filter(|o| o.status.success())
            .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
    };
    let Some(head) = git(&["rev-parse", "HEAD"]) else {
        return "unknown (not run inside a git work tree)".into();
    };
    let dirty = git(&[
        "status",
        "--porcelain",
        "--untracked-files=no",
        "--",
        ":/crates",
        ":/Cargo.toml",
        ":/Cargo.lock",
    ])
    .is_some_and(|s| !s.is_empty());
    if dirty {
        format!("{head} plus uncommitted changes to the code")
    } else {
        head
    }
}

/// Write `README.md` into the output folder.
pub fn write(study: &Study, command: &str) -> Result<(), StudyError> {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "# {}\n",
        study
            .out
            .file_name()
            .map_or("results".into(), |f| f.to_string_lossy().into_owned())
            + "/"
    );
    let _ = writeln!(
        s,
        "Written by `{command}` — this file too. Every number here comes from that run; the thesis values printed beside them are the targets from `spec/study.md`. Rerunning the command rewrites everything; only measured times (`kurt_9_4_times`, `error_vs_time`) change between runs.\n"
    );
    let _ = writeln!(s, "- software: brdf-study {}", env!("CARGO_PKG_VERSION"));
    let _ = writeln!(s, "- commit: {}", commit_of(&study.out));
    let data = if study.synthetic() {
        "BUILT-IN SYNTHETIC DATA (no measured data: BRDF_DATA unset and no --data)".to_string()
    } else {
        "measured data under `$BRDF_DATA` (paths below are relative to it)".to_string()
    };
    let _ = writeln!(s, "- data: {data}");
    let tables = if study.spec.tables.is_empty() {
        "all".to_string()
    } else {
        study.spec.tables.join(", ")
    };
    let _ = writeln!(s, "- parts run: {tables}\n");
    let _ = writeln!(s, "| file | what it holds | data | metric | angle limit |");
    let _ = writeln!(s, "| --- | --- | --- | --- | --- |");
    for w in &study.written {
        let _ = writeln!(
            s,
            "| `{}` | {} | {} | {} | {} |",
            w.file, w.what, w.data, w.metric, w.limit
        );
    }
    if !study.skipped.is_empty() {
        let _ = writeln!(s, "\nParts not run:\n");
        for (part, why) in &study.skipped {
            let _ = writeln!(s, "- `{part}`: {why}");
        }
    }
    let path = study.out.join("README.md");
    std::fs::write(&path, s).map_err(|e| StudyError::Io {
        path: path.display().to_string(),
        source: e,
    })
}
