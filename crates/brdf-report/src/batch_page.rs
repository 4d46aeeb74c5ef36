//! The index of a batch: one row per material x model of `DIR/fits.jsonl`
//! (what `brdf batch` writes), with thumbnails of the measured and fitted
//! spheres where the data are evaluable, the errors and how each fit
//! ended; sortable by any column; each row links to its fit page, written
//! beside the index. A row whose page cannot be made (data moved, a model
//! that cannot be rebuilt) says why instead of failing the index.

use std::path::{Path, PathBuf};

use brdf_models::saved_model::{SCHEMA, SavedModel, VERSION};
use serde::Serialize;
use serde_json::{Value, json};

use crate::fit_page::{Analyser, FitInput, RunInfo, render};
use crate::{ReportError, templates};

/// What was written.
#[derive(Clone, Debug)]
pub struct BatchReport {
    /// the index page
    pub index: PathBuf,
    /// fit pages written
    pub pages: usize,
    /// rows without a page, with the reason
    pub skipped: Vec<String>,
}

#[derive(Serialize, Default)]
struct Row {
    data: String,
    model: String,
    ngan_l2: f64,
    flip: Option<f64>,
    delta_e: Option<f64>,
    seconds: f64,
    termination: String,
    note: String,
    page: Option<String>,
    measured: Option<String>,
    fitted: Option<String>,
}

/// The data file of a `fits.jsonl` name: as written when it exists, else
/// the first of `dirs` holding it, else under `$BRDF_DATA` (where `brdf
/// batch` shortens names to). `brdf batch` writes a file outside
/// `$BRDF_DATA` by its file name only (never an absolute machine path), so
/// its folder must be given again here. An error naming the places looked
/// in and the fix when none holds it.
pub fn resolve_data(name: &str, dirs: &[PathBuf]) -> Result<String, ReportError> {
    let exists = |spec: &str| brdf_io::split_sample(spec).0.exists();
    if exists(name) {
        return Ok(name.to_string());
    }
    let root = std::env::var_os("BRDF_DATA").map(PathBuf::from);
    dirs.iter()
        .chain(root.as_ref())
        .map(|d| d.join(name).display().to_string())
        .find(|spec| exists(spec))
        .ok_or_else(|| ReportError::Input {
            path: name.to_string(),
            reason: format!(
                "data not found in the working directory, {} folder(s) given with --data-dir, or $BRDF_DATA{}: give the folder that holds it with --data-dir DIR",
                dirs.len(),
                if root.is_some() { "" } else { " (not set)" }
            ),
        })
}

/// The saved model of a `fits.jsonl` line (3 channels, else 1).
pub fn saved_model(line: &Value, what: &str) -> Result<SavedModel, ReportError> {
    let fit = &line["fit"];
    let mut last = String::new();
    for channels in [3, 1] {
        let v = json!({
            "schema": SCHEMA, "version": VERSION, "model": line["model"],
            "structure": { "channels": channels }, "parameters": fit["parameters"],
            "provenance": {
                "data": line["data"], "samples_used": line["samples_used"],
                "samples_present": line["samples_present"], "objective": fit["objective"],
                "limit_deg": line["limit_deg"], "error": fit["error"],
                "solver": fit["solver"], "software": "brdf batch",
            },
        });
        match SavedModel::from_json(&v.to_string(), what) {
            Ok(s) if s.build().is_ok() => return Ok(s),
            Ok(_) => last = "the parameters do not rebuild the model".into(),
            Err(e) => last = e.to_string(),
        }
    }
    Err(ReportError::Model {
        what: what.into(),
        reason: last,
    })
}

fn page_name(data: &str, model: &str) -> String {
    let clean = |s: &str| -> String {
        s.chars()
            .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
            .collect()
    };
    format!("{}__{}.html", clean(data), clean(model))
}

/// How the fit of a `fits.jsonl` line ran: the whole fit's seconds (the
/// line's, as the batch summary gives them; older lines have only the kept
/// solve's) and how its kept solve ended.
fn run_info(line: &Value) -> RunInfo {
    let fit = &line["fit"];
    RunInfo {
        seconds: line["seconds"]
            .as_f64()
            .or_else(|| fit["seconds"].as_f64())
            .unwrap_or(f64::NAN),
        termination: fit["termination"].as_str().unwrap_or("not recorded").into(),
        ended: fit["termination"].as_str().and_then(|t| t.parse().ok()),
        iterations: fit["iterations"].as_u64().map(|n| n as usize),
    }
}

/// The row of a `fits.jsonl` line before its page is made.
fn base_row(line: &Value) -> Row {
    let run = run_info(line);
    Row {
        data: line["data"].as_str().unwrap_or_default().to_string(),
        model: line["model"].as_str().unwrap_or_default().to_string(),
        ngan_l2: line["fit"]["ngan_l2"].as_f64().unwrap_or(f64::NAN),
        seconds: run.seconds,
        termination: run.termination,
        ..Row::default()
    }
}

/// Make the fit page of `line` in `dir` (its thumbnails and errors go into
/// `r`); the page's file name.
fn page(
    line: &Value,
    r: &mut Row,
    dir: &Path,
    back: &str,
    data_dirs: &[PathBuf],
    analyser: &mut Analyser,
) -> Result<String, ReportError> {
    let what = format!("{} x {}", r.data, r.model);
    let saved = saved_model(line, &what)?;
    let spec = resolve_data(&r.data, data_dirs)?;
    let input = FitInput {
        data: &spec,
        saved: &saved,
        fit_source: "fits.jsonl",
        run: Some(run_info(line)),
        selection: None,
    };
    let a = analyser.analyse(&input)?;
    r.flip = a.image.as_ref().map(|i| i.mean_flip());
    r.delta_e = a.image.as_ref().map(|i| i.max_delta_e());
    r.measured = a.spheres.first().and_then(|s| s.measured.clone());
    r.fitted = a.spheres.first().map(|s| s.fitted.clone());
    // The index holds a word and the worst figure; the reasons in full
    // are on the fit's page.
    r.note = short_verdict(a.verdict.good, a.image.as_ref());
    let html = render(&input, &a, Some(back))?;
    let name = page_name(&r.data, &r.model);
    let path = dir.join(&name);
    std::fs::write(&path, html).map_err(ReportError::io(&path))?;
    Ok(name)
}

/// Write the index of `batch_dir/fits.jsonl` to `out` and every fit page
/// beside it, finding each line's data as [`resolve_data`] does in
/// `data_dirs`; `progress(done, total, current)` before each fit.
pub fn write_batch_report(
    batch_dir: &Path,
    out: &Path,
    data_dirs: &[PathBuf],
    progress: &mut dyn FnMut(usize, usize, &str),
) -> Result<BatchReport, ReportError> {
    let fits_path = batch_dir.join(brdf_fit::batch::FITS);
    let fits = brdf_fit::batch::read_fits(&fits_path)?;
    if fits.is_empty() {
        return Err(ReportError::Input {
            path: fits_path.display().to_string(),
            reason: "no fits; run `brdf batch --out DIR` first".into(),
        });
    }
    let dir = out
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir).map_err(ReportError::io(dir))?;
    let back = out
        .file_name()
        .map_or("index.html".into(), |n| n.to_string_lossy().to_string());
    let (mut rows, mut skipped) = (Vec::new(), Vec::new());
    // The judge's terms made once for the index, each material rendered
    // once for all its models; at the judge's size, so a page's image
    // errors are the ones `brdf batch` wrote for its line.
    let mut analyser = Analyser::new(brdf_render::judge::REPORT_SIZE);
    for (k, ((data, model), line)) in fits.iter().enumerate() {
        progress(k, fits.len(), &format!("{data} x {model}"));
        let mut r = base_row(line);
        match page(line, &mut r, dir, &back, data_dirs, &mut analyser) {
            Ok(name) => r.page = Some(name),
            Err(e) => {
                r.note = format!("{data} x {model}: {e}");
                skipped.push(r.note.clone());
            }
        }
        rows.push(r);
    }
    progress(fits.len(), fits.len(), "index");
    let columns = [
        ("material", "text"),
        ("model", "text"),
        ("Ngan L2", "num"),
        ("FLIP", "num"),
        ("ΔE (max)", "num"),
        ("seconds", "num"),
        ("how it ended", "text"),
        ("verdict", "text"),
    ];
    let ctx = minijinja::context! {
        title => "brdf batch: every material x model fit",
        source => fits_path.display().to_string(), rows, columns,
    };
    let html = templates::render("index.html", ctx)?;
    std::fs::write(out, html).map_err(ReportError::io(out))?;
    Ok(BatchReport {
        index: out.to_path_buf(),
        pages: fits.len() - skipped.len(),
        skipped,
    })
}

/// A verdict in a word and the worst image error: `ok` or `off`, and the
/// largest FLIP over the light sets with its light.
fn short_verdict(good: bool, image: Option<&brdf_render::ImageError>) -> String {
    let word = if good { "ok" } else { "off" };
    let worst = image.and_then(|i| i.lights.iter().max_by(|a, b| a.flip.total_cmp(&b.flip)));
    match worst {
        Some(l) => format!("{word}: FLIP {:.3} ({})", l.flip, l.light),
        None => word.to_string(),
    }
}
