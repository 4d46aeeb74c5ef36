//! The resumable, shardable batch runner behind `brdf batch`: fit every
//! material x model of a database.
//!
//! Every fit is one JSON line in `OUT/fits.jsonl`, appended as it
//! finishes, the whole line in one write; a rerun skips the fits already
//! there, so a killed run resumes. A torn last line (a run killed while
//! writing it) is dropped on resume, reported in
//! [`BatchOutcome::dropped_torn_line`], and its fit redone. A batch that
//! fails before any fit is written leaves no output folder behind. A [`Shard`] `I/N` takes the `I`-th of `N` deterministic shares
//! of the sorted material x model list, so the same command runs as a
//! Slurm job array or under GNU parallel; [`merge`] joins the shards. The
//! summary (`summary.csv`, `summary.md`) is sorted by material and model,
//! so it is the same for any thread count, shard split or completion
//! order.
//!
//! Each fit is what `brdf fit` runs on the same file with the same
//! `--metric` (a [`FitRequest`]): renderer models are
//! fitted for appearance on data that can be rendered (RGL, MERL), and
//! every fit of such data carries its image errors (the sphere under the
//! sky and studio light sets at [`REPORT_SIZE`] pixels: FLIP, PSNR, mean
//! colour CIEDE2000) in its line and the summary; scattered data (CUReT,
//! Cornell, CSV) carry the note why none can be formed. The judge's terms
//! are computed once per batch and each material's renders once for all
//! its models.

use std::collections::BTreeMap;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, OnceLock};

use brdf_core::progress::{Progress, Task};
use rayon::prelude::*;
use serde_json::Value;

use crate::table::{Cell, Table};
use crate::{ChannelMode, FitError, FitRequest, Material, Metric, data_name};
use brdf_render::judge::{Judge, REPORT_SIZE};

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
        let bad = || FitError::InvalidOption {
            option: "--shard",
            value: s.to_string(),
            expected: "I/N with 1 <= I <= N",
        };
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
    /// Channels fitted (RGB or grey: a batch row is one model).
    pub channels: ChannelMode,
    /// Angle limit (degrees).
    pub limit_deg: f64,
    /// Multi-start count.
    pub starts: usize,
    /// What each fit minimises, as `brdf fit --metric`.
    pub metric: Metric,
    /// End each fit for appearance with the search on its render's FLIP
    /// ([`crate::Fit::polish_on_flip`]); other fits ignore it.
    pub polish: bool,
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
    /// The torn last line of `fits.jsonl` (a killed run) that was dropped.
    pub dropped_torn_line: Option<String>,
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
        materials.extend(brdf_io::materials(&resolved(d)?)?);
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

/// A data spec with its path looked up as [`brdf_io::load::resolve_spec`]
/// does (the working directory, then `BRDF_DATA`).
fn resolved(spec: &str) -> Result<String, FitError> {
    let (path, sample) = brdf_io::load::resolve_spec(spec)?;
    let path = path.display().to_string();
    Ok(match sample {
        Some(s) => format!("{path}#{s}"),
        None => path,
    })
}

/// Drop a torn last line (no newline: a run killed while writing it) from
/// `fits.jsonl`; returns it.
fn drop_torn_line(path: &Path) -> Result<Option<String>, FitError> {
    let bytes = match std::fs::read(path) {
        Ok(b) => b,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(io_err(path)(e)),
    };
    if bytes.last().is_none_or(|c| *c == b'\n') {
        return Ok(None);
    }
    let keep = bytes.iter().rposition(|c| *c == b'\n').map_or(0, |i| i + 1);
    let file = std::fs::OpenOptions::new()
        .write(true)
        .open(path)
        .map_err(io_err(path))?;
    file.set_len(keep as u64).map_err(io_err(path))?;
    file.sync_all().map_err(io_err(path))?;
    Ok(Some(String::from_utf8_lossy(&bytes[keep..]).into_owned()))
}

/// `fits.jsonl` opened for appending.
fn open_fits(path: &Path) -> Result<std::fs::File, FitError> {
    std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(path)
        .map_err(io_err(path))
}

/// Append one fit as a whole line: one write of the line with its newline,
/// then a flush, so a kill leaves at most one torn last line.
fn append_line(out: &Mutex<std::fs::File>, v: &Value) -> Option<String> {
    let line = format!("{v}\n");
    match out.lock() {
        Ok(mut f) => f
            .write_all(line.as_bytes())
            .and_then(|()| f.flush())
            .err()
            .map(|e| e.to_string()),
        Err(_) => Some("output lock poisoned".into()),
    }
}

/// The models, resolved and without repeats (`ggx,GGX` is one model), in
/// the order given.
fn resolve_models(names: &[String]) -> Result<Vec<&'static str>, FitError> {
    let mut out: Vec<&'static str> = Vec::new();
    for m in names {
        let name = crate::names::resolve(m)?.name;
        if !out.contains(&name) {
            out.push(name);
        }
    }
    Ok(out)
}

/// Run a batch: fit what this share still lacks, append each fit to
/// `fits.jsonl`, write the summary. `started(todo, in_share)` is called
/// once the work is known; `progress` hears of every fit, started and
/// done.
pub fn run(
    opts: &BatchOptions,
    started: impl FnOnce(usize, usize),
    progress: &dyn Progress,
) -> Result<BatchOutcome, FitError> {
    let models = resolve_models(&opts.models)?;
    let path = opts.out.join(FITS);
    let dropped_torn_line = drop_torn_line(&path)?;
    let (todo, in_share) = plan(opts, &models)?;
    let created = !opts.out.exists();
    std::fs::create_dir_all(&opts.out).map_err(io_err(&opts.out))?;
    started(todo.len(), in_share);
    let task = progress.task("batch", todo.len());
    let result = fit_all(opts, &todo, &path, task.as_ref());
    task.finish();
    let fitted = read_fits(&path).map(|f| !f.is_empty()).unwrap_or(false);
    if created && !fitted {
        // Nothing to keep: leave no empty output folder behind.
        let _ = std::fs::remove_dir_all(&opts.out);
    }
    let failures = result?;
    if fitted || !created {
        write_summary(&opts.out, &read_fits(&path)?)?;
    }
    Ok(BatchOutcome {
        in_share,
        already_done: in_share - todo.len(),
        failures,
        fits_path: path,
        dropped_torn_line,
    })
}

/// Fit every item, appending each fit to `path`; the failures.
fn fit_all(
    opts: &BatchOptions,
    todo: &[Item],
    path: &Path,
    task: &dyn Task,
) -> Result<Vec<String>, FitError> {
    let out = Mutex::new(open_fits(path)?);
    // Each material loaded once for all its models.
    let mut by_material: BTreeMap<&str, Vec<&str>> = BTreeMap::new();
    for (m, x) in todo {
        by_material.entry(m.as_str()).or_default().push(x);
    }
    // The judge's terms, computed once for every renderable material (the
    // first one builds them).
    let terms: OnceLock<Judge> = OnceLock::new();
    // Materials in parallel, and each material's models in parallel too
    // (a few materials would otherwise leave cores idle).
    let failures: Vec<String> = by_material
        .par_iter()
        .flat_map_iter(|(material, models)| {
            let loaded = load(material, &terms);
            let lines: Vec<Result<Value, String>> = models
                .par_iter()
                .map(|model| {
                    task.item(&format!("{} x {model}", data_name(material)));
                    let r = match &loaded {
                        Ok(m) => fit_one(m, material, model, opts),
                        Err(e) => Err(e.to_string()),
                    };
                    task.advance(1);
                    r
                })
                .collect();
            lines
        })
        .filter_map(|r| match r {
            Ok(v) => append_line(&out, &v),
            Err(e) => Some(e),
        })
        .collect();
    Ok(failures)
}

/// Load `material`; render it on the judge's `terms` when it can be.
fn load(material: &str, terms: &OnceLock<Judge>) -> Result<Material, FitError> {
    Material::load_on(material, || terms.get_or_init(|| Judge::new(REPORT_SIZE)))
}

/// One fit as a JSON line.
fn fit_one(
    material: &Material,
    spec: &str,
    model: &str,
    opts: &BatchOptions,
) -> Result<Value, String> {
    let name = data_name(spec);
    let run = || {
        FitRequest {
            metric: opts.metric,
            channels: opts.channels,
            limit_deg: opts.limit_deg,
            starts: opts.starts,
            polish: opts.polish,
            ..FitRequest::new(material, crate::names::resolve(model)?)
        }
        .run()
    };
    let outcome = run().map_err(|e| format!("{name} x {model}: {e}"))?;
    let seconds = outcome.seconds;
    let rep = outcome
        .into_report()
        .map_err(|e| format!("{name} x {model}: {e}"))?;
    let chosen = rep.candidates.iter().find(|c| c.chosen);
    Ok(serde_json::json!({
        "data": name,
        "model": model,
        "samples_used": rep.summary.samples,
        "samples_present": rep.samples_present,
        "limit_deg": opts.limit_deg,
        "fit": rep.summary,
        // The whole fit: for appearance every candidate and the image
        // errors (the summary's `seconds` is the kept solve's alone).
        "seconds": seconds,
        "for_appearance": chosen.map(|c| serde_json::json!({
            "objective": c.objective,
            "lobes": c.lobes,
            "candidates": rep.candidates.len(),
        })),
        "image_error": rep.image_error,
        "image_note": rep.image_note,
        "notes": rep.notes,
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
            "FLIP sky",
            "FLIP studio",
            "dE2000 (max)",
            "termination",
            "seconds",
        ],
    );
    for ((data, model), v) in fits {
        let f = &v["fit"];
        let num = |x: &Value, d| Cell::Num(x.as_f64().unwrap_or(f64::NAN), d);
        // Image errors: "-" for scattered data (and lines of older runs).
        let lights = v["image_error"]["lights"].as_array();
        let light = |name: &str, key: &str| {
            lights
                .and_then(|ls| ls.iter().find(|l| l["light"] == name))
                .and_then(|l| l[key].as_f64())
        };
        let image = |x: Option<f64>, d| x.map_or(Cell::Text("-".into()), |x| Cell::Num(x, d));
        let de = lights
            .into_iter()
            .flatten()
            .filter_map(|l| l["delta_e"].as_f64())
            .reduce(f64::max);
        t.rows.push(vec![
            Cell::Text(data.clone()),
            Cell::Text(model.clone()),
            Cell::Text(v["samples_used"].to_string()),
            Cell::Text(v["samples_present"].to_string()),
            num(&f["ngan_l2"], 6),
            image(light("sky", "flip"), 3),
            image(light("studio", "flip"), 3),
            image(de, 2),
            Cell::Text(f["termination"].as_str().unwrap_or_default().to_string()),
            // Lines of older runs have only the solve's seconds.
            num(v.get("seconds").unwrap_or(&f["seconds"]), 3),
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
