//! Every hint the default fit prints is a command that, run as printed,
//! does what the hint says: on every shared RGL file the default
//! `principled` fit's hints are run, and each renders at least as close to
//! the data as the fit it advises against (a second-colour model strictly
//! closer, a selection by image never worse).

use crate::common;

use std::path::PathBuf;
use std::process::Command;

use common::mean_flip;
use serde_json::Value;

fn brdf(args: &[String]) -> Value {
    let out = Command::new(env!("CARGO_BIN_EXE_brdf"))
        .args(args)
        .output()
        .expect("brdf runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "brdf {}: {err}", args.join(" "));
    serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("brdf {}: {e}", args.join(" ")))
}

/// The RGL files of the shared data.
fn rgl_files() -> Vec<PathBuf> {
    let root = std::env::var_os("BRDF_DATA").expect("BRDF_DATA must name the measured data");
    let dir = PathBuf::from(root).join("rgl");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "bsdf"))
        .collect();
    files.sort();
    assert!(!files.is_empty(), "no RGL file in {}", dir.display());
    files
}

#[test]
#[ignore = "needs BRDF_DATA"]
fn every_hint_of_the_default_fit_renders_closer() {
    let mut ran = 0;
    for file in rgl_files() {
        let data = file.display().to_string();
        let args =
            |extra: &[&str]| -> Vec<String> { extra.iter().map(|s| s.to_string()).collect() };
        let fit = brdf(&args(&[
            "fit",
            "--data",
            &data,
            "--model",
            "principled",
            "--json",
            "--quiet",
        ]));
        let base = mean_flip(&fit["image_errors"][0]);
        let notes = fit["notes"][0].as_array().expect("notes");
        for hint in notes
            .iter()
            .filter_map(Value::as_str)
            .filter(|n| n.starts_with("hint: `"))
        {
            let command = hint
                .trim_start_matches("hint: `")
                .split('`')
                .next()
                .expect("a command in backticks");
            let mut words: Vec<String> = command.split_whitespace().map(String::from).collect();
            assert_eq!(words.first().map(String::as_str), Some("brdf"), "{hint}");
            words.remove(0);
            words.extend(["--json".to_string(), "--quiet".to_string()]);
            let v = brdf(&words);
            let (flip, strict) = match words[0].as_str() {
                "fit" => (mean_flip(&v["image_errors"][0]), true),
                "select" => (mean_flip(&v["choice"]["image"]), false),
                other => panic!("a hint of an unexpected command `{other}`: {hint}"),
            };
            if strict {
                assert!(
                    flip < base,
                    "{data}: `{command}` renders at {flip}, the fit at {base}"
                );
            } else {
                assert!(
                    flip <= base + 1e-12,
                    "{data}: `{command}` renders at {flip}, the fit at {base}"
                );
            }
            ran += 1;
        }
    }
    // The films' hues leave every plane of white and one colour: their
    // default fits carry at least the second-colour hint.
    assert!(
        ran >= 2,
        "only {ran} hints were printed on the shared RGL files"
    );
}
