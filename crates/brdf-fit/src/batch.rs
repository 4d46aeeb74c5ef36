//! The resumable, shardable batch runner behind `brdf batch`: fit every
//! material x model of a database.
//!
//! Every fit is one JSON line in `OUT/fits.jsonl`, appended as it
//! finishes; a rerun skips the fits already there, so a killed run
//! resumes. A [`Shard`] `I/N` takes the `I`-th of `N` deterministic shares
//! of the sorted material x model list, so the same command runs as a
//! Slurm job array or under GNU parallel; [`merge`] joins the shards. The
//! summary (`summary.csv`, `summary.md`) is sorted by material and model,
//! so it is the same for any thread count, shard split or completion
//! order.

use std::collections::BTreeMap;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use rayon::prelude::*;
use serde_json::Value;

use crate::table::{Cell, Table};
use crate::{Channels, Fit, FitError, data_name};

/// The file of fits in a batch folder.
pub const FITS: &str = "fits.jsonl";

/// Fits keyed by (data name, model name).
pub type Fits = BTreeMap<(String, String), Value>;

/// One share of the material x model list: `index` of `count` (0-based).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// Which share (0-based).
    pub index: usize,
    /// How many shares.
    pub count: usize,
}

impl Shard {
    /// Everything: one share.
    pub const ALL: Shard = Shard { index: 0, count: 1 };

    /// Parse `I/N` (1-based, `1 <= I <= N`).
    pub fn parse(s: &str) -> Result<Shard, FitError> {
        let bad = || FitError::Usage(format!("--shard {s}: expected I/N with 1 <= I <= N"));
        let (i, n) = s.split_once('/').ok_or_else(bad)?;
        let i: usize = i.trim().parse().map_err(|_| bad())?;
        let n: usize = n.trim().parse().map_err(|_| bad())?;
        if i == 0 || i > n {
            return Err(bad());
        }
        Ok(Shard {
            index: i - 1,
            count: n,
        })
    }
}

/// What a batch fits and how.
#[derive(Clone, Debug)]
pub struct BatchOptions {
    /// Data: folders, files, or a CUReT `abrdf.dat` (every sample).
    pub data: Vec<String>,
    /// Models (forgiving names, resolved by [`crate::names::resolve`]).
    pub models: Vec<String>,
    /// Output folder (`fits.jsonl`, `summary.csv`, `summary.md`).
    pub out: PathBuf,
    /// The share of the list this run fits.
    pub shard: Shard,
    /// Channels fitted.
    pub channels: Channels,
    /// Angle limit (degrees).
    pub limit_deg: f64,
    /// Multi-start count.
    pub starts: usize,
}

/// How a batch went.
#[derive(Clone, Debug)]
pub struct BatchOutcome {
    /// Fits in this share.
    pub in_share: usize,
    /// Of them, already in `fits.jsonl` before this run.
    pub already_done: usize,
    /// One line per fit that failed (`data x model: why`).
    pub failures: Vec<String>,
    /// The `fits.jsonl` written.
    pub fits_path: PathBuf,
}

fn io_err(path: &Path) -> impl FnOnce(std::io::Error) -> FitError + '_ {
    move |source| FitError::Io {
        path: path.display().to_string(),
        source,
    }
}

/// Join the `fits.jsonl` of `dirs` into `out` and write its summary.
pub fn merge(dirs: &[PathBuf], out: &Path) -> Result<(), FitError> {
    std::fs::create_dir_all(out).map_err(io_err(out))?;
    let mut all = BTreeMap::new();
    for dir in dirs {
        all.extend(read_fits(&dir.join(FITS))?);
    }
    let text: String = all.values().map(|v| format!("{v}\n")).collect();
    let path = out.join(FITS);
    std::fs::write(&path, text).map_err(io_err(&path))?;
    write_summary(out, &all)
}

/// One fit to run: (material, model).
type Item = (String, &'static str);

/// The items of this share that are not yet fitted, and the size of the
/// share.
fn plan(opts: &BatchOptions, models: &[&'static str]) -> Result<(Vec<Item>, usize), FitError> {
    let mut materials = Vec::new();
    for d in &opts.data {
        materials.extend(brdf_io::materials(d)?);
    }
    materials.sort();
    materials.dedup();
    let items: Vec<Item> = materials
        .iter()
        .flat_map(|m| models.iter().map(move |x| (m.clone(), *x)))
        .enumerate()
        .filter(|(k, _)| k % opts.shard.count == opts.shard.index)
        .map(|(_, it)| it)
        .collect();
    let done = read_fits(&opts.out.join(FITS))?;
    let n = items.len();
    let todo = items
        .into_iter()
        .filter(|(m, x)| !done.contains_key(&(data_name(m), x.to_string())))
        .collect();
    Ok((todo, n))
}

/// `fits.jsonl` opened for appending; a half line a killed run left is
/// ended, so the next line starts on its own (the half line is ignored
/// when read).
fn open_fits(path: &Path) -> Result<std::fs::File, FitError> {
    let ends_open = std::fs::read(path)
        .map(|b| b.last().is_some_and(|c| *c != b'\n'))
        .unwrap_or(false);
    let mut file = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(path)
        .map_err(io_err(path))?;
    if ends_open {
        writeln!(file).map_err(io_err(path))?;
    }
    Ok(file)
}

/// Run a batch: fit what this share still lacks, append each fit to
/// `fits.jsonl`, write the summary. `started(todo, in_share)` is called
/// once the work is known, `progress()` after every fit (a progress bar).
pub fn run(
    opts: &BatchOptions,
    started: impl FnOnce(usize, usize),
    progress: &(dyn Fn() + Sync),
) -> Result<BatchOutcome, FitError> {
    std::fs::create_dir_all(&opts.out).map_err(io_err(&opts.out))?;
    let models: Vec<&'static str> = opts
        .models
        .iter()
        .map(|m| crate::names::resolve(m).map(|e| e.name))
        .collect::<Result<_, _>>()?;
    let (todo, in_share) = plan(opts, &models)?;
    started(todo.len(), in_share);
    let path = opts.out.join(FITS);
    let out = Mutex::new(open_fits(&path)?);
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
                        Ok(s) => fit_one(s, material, model, opts),
                        Err(e) => Err(e.to_string()),
                    };
                    progress();
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
    write_summary(&opts.out, &read_fits(&path)?)?;
    Ok(BatchOutcome {
        in_share,
        already_done: in_share - todo.len(),
        failures,
        fits_path: path,
    })
}

/// One fit as a JSON line.
fn fit_one(
    samples: &brdf_core::SampleSet,
    material: &str,
    model: &str,
    opts: &BatchOptions,
) -> Result<Value, String> {
    let name = data_name(material);
    let rep = Fit::model(model)
        .and_then(|f| {
            f.channels(opts.channels)
                .limit_deg(opts.limit_deg)
                .starts(opts.starts)
                .run(samples)
        })
        .map_err(|e| format!("{name} x {model}: {e}"))?;
    Ok(serde_json::json!({
        "data": name,
        "model": model,
        "samples_used": rep.summary.samples,
        "samples_present": rep.samples_present,
        "limit_deg": opts.limit_deg,
        "fit": rep.summary,
    }))
}

/// The fits already in a `fits.jsonl`, keyed by (data, model); a
/// truncated last line (a killed run) is ignored.
pub fn read_fits(path: &Path) -> Result<Fits, FitError> {
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

/// `summary.csv` and `summary.md`, sorted by material and model.
pub fn write_summary(dir: &Path, fits: &Fits) -> Result<(), FitError> {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_are_one_based_and_bounded() {
        assert_eq!(Shard::parse("2/4").ok(), Some(Shard { index: 1, count: 4 }));
        assert!(Shard::parse("0/4").is_err());
        assert!(Shard::parse("5/4").is_err());
        assert!(Shard::parse("x").is_err());
    }
}
