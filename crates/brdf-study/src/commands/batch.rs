//! `brdf batch`: fit every material x model of a database.
//!
//! A `--data` PATH is a folder (every file of a known format in it), a data
//! file, or a CUReT `abrdf.dat` without `#N` (every sample). Every fit is one
//! JSON line in `OUT/fits.jsonl`, appended as it finishes; a rerun skips the
//! fits already there, so a killed run resumes. `--shard I/N` takes the
//! `I`-th of `N` deterministic shares of the sorted material x model list,
//! so the same command runs as a Slurm job array or under GNU parallel;
//! `brdf batch --merge DIR... --out DIR` joins the shards. The summary
//! (`summary.csv`, `summary.md`) is sorted by material and model, so it is
//! the same for any thread count, shard split or completion order.

use std::collections::BTreeMap;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use brdf_fit::{Channels, Fit};
use rayon::prelude::*;
use serde_json::Value;

use crate::StudyError;
use crate::report::{Cell, Table, data_name};

/// Arguments of `brdf batch`.
#[derive(Debug, clap::Args)]
pub struct BatchArgs {
    /// Data: folders, files, or a CUReT `abrdf.dat` (every sample).
    #[arg(long, num_args = 1..)]
    pub data: Vec<String>,
    /// Models, comma-separated (catalogue names, forgiving).
    #[arg(long, value_delimiter = ',')]
    pub models: Vec<String>,
    /// Output folder (fits.jsonl, summary.csv, summary.md).
    #[arg(long)]
    pub out: PathBuf,
    /// The `I`-th of `N` shares (`1/4` ... `4/4`).
    #[arg(long)]
    pub shard: Option<String>,
    /// Join the `fits.jsonl` of these folders into `--out` instead of fitting.
    #[arg(long, num_args = 1..)]
    pub merge: Vec<PathBuf>,
    /// grey (mean of the channels) or rgb.
    #[arg(long, default_value = "rgb")]
    pub channels: String,
    /// Angle limit (degrees).
    #[arg(long, default_value_t = 80.0)]
    pub limit: f64,
    /// Multi-start count.
    #[arg(long, default_value_t = 12)]
    pub starts: usize,
}

const FITS: &str = "fits.jsonl";

fn io_err(path: &Path) -> impl FnOnce(std::io::Error) -> StudyError + '_ {
    move |source| StudyError::Io {
        path: path.display().to_string(),
        source,
    }
}

/// Run `brdf batch`.
pub fn run(args: &BatchArgs) -> Result<(), StudyError> {
    std::fs::create_dir_all(&args.out).map_err(io_err(&args.out))?;
    if !args.merge.is_empty() {
        let mut all = BTreeMap::new();
        for dir in &args.merge {
            all.extend(read_fits(&dir.join(FITS))?);
        }
        let text: String = all.values().map(|v| format!("{v}\n")).collect();
        let path = args.out.join(FITS);
        std::fs::write(&path, text).map_err(io_err(&path))?;
        return write_summary(&args.out, &all);
    }
    if args.models.is_empty() || args.data.is_empty() {
        return Err(StudyError::Usage(
            "brdf batch needs --data PATH... and --models A,B,... (or --merge DIR...)".into(),
        ));
    }
    let models: Vec<&'static str> = args
        .models
        .iter()
        .map(|m| brdf_fit::resolve(m).map(|e| e.name))
        .collect::<Result<_, _>>()?;
    let channels = match args.channels.as_str() {
        "rgb" => Channels::All,
        "grey" => Channels::Grey,
        other => {
            return Err(StudyError::Usage(format!(
                "--channels {other}: expected grey or rgb"
            )));
        }
    };
    let (shard, shards) = parse_shard(args.shard.as_deref())?;
    let mut materials = Vec::new();
    for d in &args.data {
        materials.extend(brdf_io::materials(d)?);
    }
    materials.sort();
    materials.dedup();
    let items: Vec<(String, &str)> = materials
        .iter()
        .flat_map(|m| models.iter().map(move |x| (m.clone(), *x)))
        .enumerate()
        .filter(|(k, _)| k % shards == shard)
        .map(|(_, it)| it)
        .collect();
    let path = args.out.join(FITS);
    let done = read_fits(&path)?;
    let todo: Vec<&(String, &str)> = items
        .iter()
        .filter(|(m, x)| !done.contains_key(&(data_name(m), x.to_string())))
        .collect();
    eprintln!(
        "brdf batch: {} fits in this share, {} already in {}, {} to run",
        items.len(),
        items.len() - todo.len(),
        path.display(),
        todo.len()
    );
    let file = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(&path)
        .map_err(io_err(&path))?;
    // A killed run may have left half a line: end it, so the next line
    // starts on its own (the half line is ignored when read).
    let ends_open = std::fs::read(&path)
        .map(|b| b.last().is_some_and(|c| *c != b'\n'))
        .unwrap_or(false);
    let mut file = file;
    if ends_open {
        writeln!(file).map_err(io_err(&path))?;
    }
    let out = Mutex::new(file);
    let bar = indicatif::ProgressBar::new(todo.len() as u64);
    // Materials in parallel; each one loaded once for all its models.
    let mut by_material: BTreeMap<&str, Vec<&str>> = BTreeMap::new();
    for (m, x) in &todo {
        by_material.entry(m.as_str()).or_default().push(x);
    }
    let failures: Vec<String> = by_material
        .par_iter()
        .flat_map_iter(|(material, models)| {
            let samples = brdf_io::load(material);
            let lines: Vec<Result<Value, String>> = models
                .iter()
                .map(|model| {
                    let r = match &samples {
                        Ok(s) => fit_one(s, material, model, channels, args),
                        Err(e) => Err(e.to_string()),
                    };
                    bar.inc(1);
                    r
                })
                .collect();
            lines
        })
        .filter_map(|r| match r {
            Ok(v) => match out.lock() {
                Ok(mut f) => writeln!(f, "{v}").err().map(|e| e.to_string()),
                Err(_) => Some("output lock poisoned".into()),
            },
            Err(e) => Some(e),
        })
        .collect();
    bar.finish_and_clear();
    for f in &failures {
        eprintln!("brdf batch: {f}");
    }
    write_summary(&args.out, &read_fits(&path)?)?;
    if failures.is_empty() {
        Ok(())
    } else {
        Err(StudyError::Usage(format!(
            "{} of {} fits failed (listed above); the others are in {}",
            failures.len(),
            todo.len(),
            path.display()
        )))
    }
}

/// One fit as a JSON line.
fn fit_one(
    samples: &brdf_core::SampleSet,
    material: &str,
    model: &str,
    channels: Channels,
    args: &BatchArgs,
) -> Result<Value, String> {
    let name = data_name(material);
    let rep = Fit::model(model)
        .and_then(|f| {
            f.channels(channels)
                .limit_deg(args.limit)
                .starts(args.starts)
                .run(samples)
        })
        .map_err(|e| format!("{name} x {model}: {e}"))?;
    Ok(serde_json::json!({
        "data": name,
        "model": model,
        "samples_used": rep.summary.samples,
        "samples_present": rep.samples_present,
        "limit_deg": args.limit,
        "fit": rep.summary,
    }))
}

/// `I/N` (1-based) as `(I - 1, N)`.
fn parse_shard(s: Option<&str>) -> Result<(usize, usize), StudyError> {
    let Some(s) = s else { return Ok((0, 1)) };
    let bad = || StudyError::Usage(format!("--shard {s}: expected I/N with 1 <= I <= N"));
    let (i, n) = s.split_once('/').ok_or_else(bad)?;
    let (i, n): (usize, usize) = (
        i.trim().parse().map_err(|_| bad())?,
        n.trim().parse().map_err(|_| bad())?,
    );
    if i == 0 || i > n {
        return Err(bad());
    }
    Ok((i - 1, n))
}

/// The fits already in a `fits.jsonl`, keyed by (data, model); a
/// truncated last line (a killed run) is ignored.
fn read_fits(path: &Path) -> Result<BTreeMap<(String, String), Value>, StudyError> {
    let mut out = BTreeMap::new();
    let text = match std::fs::read_to_string(path) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(out),
        Err(e) => return Err(io_err(path)(e)),
    };
    for line in text.lines() {
        let Ok(v) = serde_json::from_str::<Value>(line) else {
            continue;
        };
        let key = (
            v["data"].as_str().unwrap_or_default().to_string(),
            v["model"].as_str().unwrap_or_default().to_string(),
        );
        out.insert(key, v);
    }
    Ok(out)
}

fn write_summary(dir: &Path, fits: &BTreeMap<(String, String), Value>) -> Result<(), StudyError> {
    let mut t = Table::new(
        "brdf batch: every material x model fit",
        &[
            "data",
            "model",
            "samples used",
            "samples present",
            "Ngan L2",
            "termination",
            "seconds",
        ],
    );
    for ((data, model), v) in fits {
        let f = &v["fit"];
        let num = |x: &Value, d| Cell::Num(x.as_f64().unwrap_or(f64::NAN), d);
        t.rows.push(vec![
            Cell::Text(data.clone()),
            Cell::Text(model.clone()),
            Cell::Text(v["samples_used"].to_string()),
            Cell::Text(v["samples_present"].to_string()),
            num(&f["ngan_l2"], 6),
            Cell::Text(f["termination"].as_str().unwrap_or_default().to_string()),
            num(&f["seconds"], 3),
        ]);
    }
    t.write(dir, "summary")
}
