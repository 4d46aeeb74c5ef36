//! `results/README.md`, written by the command from the list of files it
//! wrote: every file, what it holds, and the data, metric, angle limit,
//! software version and commit behind it.

use std::fmt::Write as _;
use std::path::Path;
use std::process::Command;

use crate::StudyError;
use crate::context::Study;

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

/// Rows of an earlier README in `dir` (file name, whole line), kept when a
/// partial run (`--only`) does not rewrite their files.
fn earlier_rows(path: &Path) -> Vec<(String, String)> {
    let Ok(text) = std::fs::read_to_string(path) else {
        return Vec::new();
    };
    text.lines()
        .filter_map(|l| {
            let rest = l.strip_prefix("| `")?;
            let (file, _) = rest.split_once('`')?;
            Some((file.to_string(), l.to_string()))
        })
        .collect()
}

/// Write `README.md` into the output folder: this run's files, then those
/// of earlier runs that this run did not rewrite (each row names the
/// version and commit that wrote it).
pub fn write(study: &Study, command: &str) -> Result<(), StudyError> {
    let path = study.out.join("README.md");
    let earlier = earlier_rows(&path);
    let version = format!("{} @ {}", env!("CARGO_PKG_VERSION"), commit_of(&study.out));
    let mut s = String::new();
    preamble(&mut s, study, command, &version);
    file_rows(&mut s, study, &earlier, &version);
    let others = unlisted(study, &earlier);
    if !others.is_empty() {
        let _ = writeln!(
            s,
            "\nOther files and folders here, not written by `brdf reproduce`:\n"
        );
        for f in others {
            let _ = writeln!(s, "- `{f}`: {}", other_file(&f));
        }
    }
    if !study.skipped.is_empty() {
        let _ = writeln!(s, "\nParts of the last run that wrote nothing:\n");
        for (part, why) in &study.skipped {
            let _ = writeln!(s, "- `{part}`: {why}");
        }
    }
    std::fs::write(&path, s).map_err(|e| StudyError::Io {
        path: path.display().to_string(),
        source: e,
    })
}

/// The README's title, what wrote the folder (command, software `version`,
/// data) and the header of the table of files.
fn preamble(s: &mut String, study: &Study, command: &str, version: &str) {
    let name = study
        .out
        .file_name()
        .map_or("results".into(), |f| f.to_string_lossy().into_owned());
    let _ = writeln!(s, "# {name}/\n");
    let _ = writeln!(
        s,
        "Written by `brdf reproduce` — this file too. Every number in this folder comes from a run of that command on the data named below; the thesis values printed beside ours are the targets, from Kurt (2007) and Sopp (2017). Rerunning it rewrites the files; only measured fit times (`kurt_9_4_times`, `error_vs_time`) change between runs. A run of selected parts (`--only`, `--spec`) rewrites their rows and keeps the others.\n"
    );
    let _ = writeln!(s, "- last run: `{command}`");
    let _ = writeln!(s, "- software: brdf-study {version}");
    let data = if study.synthetic() {
        "BUILT-IN SYNTHETIC DATA (no measured data: BRDF_DATA unset and no --data)"
    } else {
        "measured data under `$BRDF_DATA` (paths below are relative to it)"
    };
    let _ = writeln!(s, "- data: {data}\n");
    let _ = writeln!(
        s,
        "| file | what it holds | data | metric | angle limit | version @ commit |"
    );
    let _ = writeln!(s, "| --- | --- | --- | --- | --- | --- |");
}

/// The table's rows: this run's files (written by `version`), then the
/// `earlier` rows of files this run did not rewrite, as they were.
fn file_rows(s: &mut String, study: &Study, earlier: &[(String, String)], version: &str) {
    for w in &study.written {
        let _ = writeln!(
            s,
            "| `{}` | {} | {} | {} | {} | {version} |",
            w.file, w.what, w.data, w.metric, w.limit
        );
    }
    for (file, line) in earlier {
        if !study.written.iter().any(|w| &w.file == file) && line.matches(" | ").count() >= 5 {
            let _ = writeln!(s, "{line}");
        }
    }
}

/// Files and folders of the output folder that this run did not write
/// and no earlier run's row names, sorted; folders end in `/`.
fn unlisted(study: &Study, earlier: &[(String, String)]) -> Vec<String> {
    let listed = |f: &str| {
        let stem = f.split('.').next().unwrap_or(f);
        study
            .written
            .iter()
            .any(|w| w.file.split('.').next() == Some(stem))
            || earlier
                .iter()
                .any(|(e, _)| e.split('.').next() == Some(stem))
            || f == "README.md"
    };
    let mut others: Vec<String> = std::fs::read_dir(&study.out)
        .map(|d| {
            d.filter_map(|e| e.ok())
                .filter_map(|e| {
                    let name = e.file_name().to_string_lossy().into_owned();
                    let path = e.path();
                    if path.is_dir() {
                        Some(format!("{name}/"))
                    } else if path.is_file() && !listed(&name) {
                        Some(name)
                    } else {
                        None
                    }
                })
                .collect()
        })
        .unwrap_or_default();
    others.sort();
    others
}

/// What a file or folder of `results/` that `brdf reproduce` does not
/// write holds, and the command that writes it.
fn other_file(name: &str) -> &'static str {
    match name {
        "performance.md" => "the peer comparison, written by `benches/peers/run.sh`",
        "quickstart.md" => {
            "the README's quick start timed, each command run as written, written by `bash benches/readme/quickstart.sh` (which also writes the README's table)"
        }
        "setup.md" => {
            "the README's two set-up commands timed in a fresh clone without data, written by `bash benches/readme/setup.sh` (which also writes the README's table)"
        }
        "performance_renderer_models.md" => {
            "the renderer models' fit times before and after their fitting kernels were sped up (commit `9779d66` against `d3d78b3`; tables from `benches/peers/renderer_models.sh`)"
        }
        "render_fidelity.md" => {
            "fits judged by their render in Mitsuba 3, written by `bash benches/judge/regenerate.sh` (every configuration; `render_fidelity.py` for some) (its renders and `table.json` in `render_fidelity/`)"
        }
        "render_fidelity/" => {
            "the Mitsuba 3 renders behind `render_fidelity.md` (one PNG per material, fit and light set), its `table.json`, and the peer's rows `peer.json` (`python benches/judge/peer_inverse.py`; `--rejudge` judges its parameters again)"
        }
        "for_stages.jsonl" => {
            "where `brdf fit --for` spends its time, model by model (BRDF-space stages and image refinements, seconds and FLIP), written by `python benches/peers/for_stages.py target/release/brdf cc_ibiza_sunset_rgb.bsdf`"
        }
        "colour_planes.md" => {
            "what colour alone costs a renderer model with one base colour (principled, glTF) on each RGL measurement, written by `python benches/judge/colour_planes.py`"
        }
        "renderers/" => {
            "one RGL film fitted `--for mitsuba`, `--for blender` and `--for materialx`, rendered by Mitsuba 3, Blender Cycles and MaterialX's GLSL renderer beside its measurement: its fits, materials, renders and `renderers.md`, written by `bash results/renderers/make.sh` (with `figure.py`)"
        }
        "synthetic/" => {
            "the study on the built-in synthetic materials (`brdf reproduce` without measured data), with its own README.md"
        }
        _ => "not from this command (check where it came from)",
    }
}
