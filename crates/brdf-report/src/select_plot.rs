//! The selection section: the candidates of `brdf select --json` as two
//! plots and a table, the chosen one marked.
//!
//! A selection is made one of two ways, and the section shows each by the
//! number it chose by:
//!
//! - by Ngan's L2 (`--by-l2`, and every selection of scattered data): each
//!   candidate's error against its stored numbers and its seconds, the
//!   candidates screened out on the coarse subsample (whose error is the
//!   coarse one) drawn apart;
//! - by image error (the default on RGL and MERL data, and `--for
//!   RENDERER`): each candidate's mean HDR-FLIP over the judge's light sets
//!   (128 px) against its parameters and its seconds, with the samples each
//!   fit used of those present.
//!
//! A file that is neither, or a candidate without the number its kind is
//! chosen by, is refused with the field named, never drawn as nothing.

use brdf_render::plot::{Plot, Series};
use serde::Serialize;
use serde_json::Value;

use crate::ReportError;

/// The section of a selection: its plots and its table.
#[derive(Debug, Serialize)]
pub struct Selection {
    /// What the choice was made by, in words.
    pub by: String,
    /// Two SVG plots (against the model's size, against seconds).
    pub svgs: Vec<String>,
    /// Column headings of the table.
    pub header: Vec<String>,
    /// One row per candidate, in the selection's order.
    pub rows: Vec<SelectionRow>,
}

/// One candidate of the table.
#[derive(Debug, Serialize)]
pub struct SelectionRow {
    /// Whether it is the choice.
    pub chosen: bool,
    /// The cells, as the header names them.
    pub cells: Vec<String>,
}

/// The two ways a selection chooses.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Kind {
    L2,
    Image,
}

/// The selection `v` read from `path` (the output of `brdf select
/// --json`) of the report's data `data` (a selection that names another
/// file is refused).
pub fn selection(v: &Value, path: &str, data: &str) -> Result<Selection, ReportError> {
    let bad = |reason: String| ReportError::Input {
        path: path.into(),
        reason: format!("{reason}; pass the output of `brdf select --json`"),
    };
    // The material's name: a selection names its data by file
    // (`paper_white_rgb.bsdf`) or by format and name (`rgl#paper_white_rgb`),
    // the report by the path it was given.
    let name = |s: &str| {
        let last = s.rsplit(['/', '\\']).next().unwrap_or(s);
        let last = last.rsplit('#').next().unwrap_or(last);
        let stem = std::path::Path::new(last).file_stem();
        stem.map(|f| f.to_string_lossy().into_owned())
    };
    if let Some(selected) = v["data"].as_str()
        && name(selected) != name(data)
    {
        return Err(bad(format!(
            "a selection on `{selected}`, not on the report's data `{data}`"
        )));
    }
    let rows = v["candidates"]
        .as_array()
        .filter(|r| !r.is_empty())
        .ok_or_else(|| bad("no `candidates` list".into()))?;
    let chosen = v["choice"]["label"]
        .as_str()
        .ok_or_else(|| bad("no `choice.label`".into()))?;
    let kind = if rows[0].get("image").is_some() {
        Kind::Image
    } else {
        Kind::L2
    };
    let candidates = rows
        .iter()
        .enumerate()
        .map(|(k, r)| {
            Candidate::read(r, kind)
                .map_err(|field| bad(format!("candidate {k}: no number `{field}`")))
        })
        .collect::<Result<Vec<_>, _>>()?;
    if !candidates.iter().any(|c| c.label == chosen) {
        return Err(bad(format!(
            "the choice `{chosen}` is not among the candidates"
        )));
    }
    let svgs = plots(&candidates, chosen, kind)?;
    let (by, header) = match kind {
        Kind::L2 => (
            "Ngan's L2 over the samples (the least error within the tolerance, fewest stored numbers first)",
            vec![
                "model",
                "error",
                "stored numbers",
                "seconds",
                "samples",
                "screened out",
            ],
        ),
        Kind::Image => (
            "image error: each model fitted for appearance, rendered by the judge at 128 px under each light set; the least mean HDR-FLIP",
            vec![
                "model",
                "objective",
                "HDR-FLIP (mean)",
                "HDR-FLIP per light",
                "CIEDE2000 (max)",
                "parameters",
                "seconds",
                "samples used of present",
            ],
        ),
    };
    Ok(Selection {
        by: by.to_string(),
        svgs,
        header: header.into_iter().map(String::from).collect(),
        rows: candidates
            .iter()
            .map(|c| SelectionRow {
                chosen: c.label == chosen,
                cells: c.cells.clone(),
            })
            .collect(),
    })
}

/// A candidate read from the JSON: its label, the number it is judged by,
/// its size and seconds, and its table cells.
struct Candidate {
    label: String,
    error: f64,
    size: f64,
    seconds: f64,
    screened_out: bool,
    cells: Vec<String>,
}

impl Candidate {
    /// Candidate `r` of a selection of `kind`, or the field it lacks.
    fn read(r: &Value, kind: Kind) -> Result<Self, &'static str> {
        let num = |field: &'static str| r[field].as_f64().filter(|x| x.is_finite()).ok_or(field);
        let label = r["label"].as_str().ok_or("label")?.to_string();
        let seconds = num("seconds")?;
        let sig = |x: f64| brdf_core::format::number(x, 4);
        match kind {
            Kind::L2 => {
                let (error, size) = (num("error")?, num("stored_numbers")?);
                let screened_out = r["screened_out"].as_bool() == Some(true);
                let cells = vec![
                    label.clone(),
                    sig(error),
                    format!("{size}"),
                    format!("{seconds:.2}"),
                    r["samples"]
                        .as_u64()
                        .map_or_else(String::new, |n| n.to_string()),
                    if screened_out {
                        "yes (coarse error)"
                    } else {
                        ""
                    }
                    .to_string(),
                ];
                Ok(Candidate {
                    label,
                    error,
                    size,
                    seconds,
                    screened_out,
                    cells,
                })
            }
            Kind::Image => {
                let lights = r["image"]["lights"]
                    .as_array()
                    .filter(|l| !l.is_empty())
                    .ok_or("image.lights")?;
                let mut flips = Vec::new();
                let (mut sum, mut delta_e) = (0.0, 0.0_f64);
                for l in lights {
                    let flip = l["flip"]
                        .as_f64()
                        .filter(|x| x.is_finite())
                        .ok_or("image.lights.flip")?;
                    sum += flip;
                    flips.push(format!("{} {flip:.4}", l["light"].as_str().unwrap_or("?")));
                    delta_e = delta_e.max(l["delta_e"].as_f64().ok_or("image.lights.delta_e")?);
                }
                let error = sum / lights.len() as f64;
                let size = num("parameters")?;
                let (used, present) = (num("samples")?, num("samples_present")?);
                let cells = vec![
                    label.clone(),
                    r["objective"].as_str().unwrap_or_default().to_string(),
                    format!("{error:.4}"),
                    flips.join(", "),
                    format!("{delta_e:.2}"),
                    format!("{size}"),
                    format!("{seconds:.1}"),
                    format!("{used} of {present}"),
                ];
                Ok(Candidate {
                    label,
                    error,
                    size,
                    seconds,
                    screened_out: false,
                    cells,
                })
            }
        }
    }
}

/// The two plots: the judged number against the model's size and against
/// seconds.
fn plots(candidates: &[Candidate], chosen: &str, kind: Kind) -> Result<Vec<String>, ReportError> {
    let (y_label, size_label) = match kind {
        Kind::L2 => ("error", "stored numbers"),
        Kind::Image => ("mean HDR-FLIP (128 px)", "parameters"),
    };
    let mut out = Vec::new();
    for (x_label, log_x) in [(size_label, false), ("seconds", true)] {
        let (mut others, mut best, mut screened) = (Vec::new(), Vec::new(), Vec::new());
        for c in candidates {
            let x = if log_x { c.seconds } else { c.size };
            let p = (x, c.error);
            if c.label == chosen {
                best.push(p);
            } else if c.screened_out {
                screened.push(p);
            } else {
                others.push(p);
            }
        }
        let mut chosen_series = Series::points(&format!("chosen: {chosen}"), 3, best);
        chosen_series.marker = 7;
        let mut series = match kind {
            Kind::L2 => vec![
                Series::points("candidates (all samples)", 0, others),
                Series::points("screened out (coarse error)", 1, screened),
            ],
            Kind::Image => vec![Series::points("candidates", 0, others)],
        };
        series.push(chosen_series);
        let plot = Plot {
            title: format!("candidates: {y_label} against {x_label}"),
            x_label: x_label.into(),
            y_label: y_label.into(),
            series,
            log_x,
            log_y: kind == Kind::L2,
            ..Plot::default()
        };
        out.push(brdf_render::plot::svg(&plot, (620, 380))?);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use serde_json::json;

    use super::*;

    const DATA: &str = "rgl/paper_white_rgb.bsdf";

    fn by_image() -> Value {
        let row = |label: &str, sky: f64, studio: f64| {
            json!({
                "label": label, "model": label, "objective": "image", "lobes": [],
                "image": {"size": 128, "lights": [
                    {"light": "sky", "flip": sky, "delta_e": 1.5, "psnr": 30.0},
                    {"light": "studio", "flip": studio, "delta_e": 2.5, "psnr": 31.0}]},
                "ngan_l2": 0.1, "parameters": 7, "seconds": 2.0,
                "samples": 18000, "samples_present": 20196,
                "dropped_invalid": 0, "dropped_angle": 2196, "limit_deg": 80.0
            })
        };
        json!({
            "data": "rgl#paper_white_rgb",
            "candidates": [row("gltf", 0.06, 0.04), row("gltf-ext", 0.05, 0.03)],
            "choice": row("gltf-ext", 0.05, 0.03),
        })
    }

    #[test]
    fn a_selection_by_image_shows_each_candidates_image_error() {
        let s = selection(&by_image(), "sel.json", DATA).expect("a selection by image");
        assert!(s.by.starts_with("image error"), "{}", s.by);
        assert_eq!(s.rows.len(), 2);
        assert!(s.rows[1].chosen && !s.rows[0].chosen);
        // The mean of sky and studio, the lights named, samples of present.
        assert_eq!(s.rows[0].cells[2], "0.0500");
        assert_eq!(s.rows[1].cells[3], "sky 0.0500, studio 0.0300");
        assert_eq!(s.rows[1].cells[4], "2.50");
        assert_eq!(s.rows[1].cells[7], "18000 of 20196");
        assert!(s.svgs.iter().all(|svg| svg.contains("chosen: gltf-ext")));
        assert!(s.svgs[0].contains("mean HDR-FLIP (128 px)"));
        // `--for` names the data by its file.
        let mut v = by_image();
        v["data"] = json!("paper_white_rgb.bsdf");
        assert!(selection(&v, "sel.json", DATA).is_ok());
    }

    #[test]
    fn a_selection_by_l2_keeps_its_error_and_stored_numbers() {
        let row = |label: &str, error: f64, screened: bool| {
            json!({"label": label, "model": label, "stored_numbers": 3, "error": error,
                   "seconds": 0.5, "samples": 2020, "screened_out": screened})
        };
        let v = json!({
            "candidates": [row("lambert", 0.3, true), row("ggx", 0.1, false)],
            "choice": row("ggx", 0.1, false),
        });
        let s = selection(&v, "sel.json", DATA).expect("a selection by L2");
        assert_eq!(s.header[1], "error");
        assert_eq!(s.rows[0].cells[5], "yes (coarse error)");
        assert!(s.rows[1].chosen);
        assert!(s.svgs[0].contains("screened out"));
    }

    #[test]
    fn a_candidate_without_its_number_is_refused_with_the_field_named() {
        let mut v = by_image();
        v["candidates"][0]["image"]["lights"][1]["flip"] = Value::Null;
        let e = selection(&v, "sel.json", DATA)
            .expect_err("no FLIP")
            .to_string();
        assert!(
            e.starts_with("sel.json: candidate 0: no number `image.lights.flip`"),
            "{e}"
        );
        let mut v = by_image();
        v["choice"]["label"] = json!("principled");
        let e = selection(&v, "sel.json", DATA)
            .expect_err("choice elsewhere")
            .to_string();
        assert!(
            e.contains("`principled` is not among the candidates"),
            "{e}"
        );
        let e = selection(&by_image(), "sel.json", "rgl/cc_iris_purple_gem_rgb.bsdf")
            .expect_err("another file")
            .to_string();
        assert!(e.contains("a selection on `rgl#paper_white_rgb`"), "{e}");
        let e = selection(&json!({"rows": []}), "x.json", DATA).expect_err("not a selection");
        assert!(e.to_string().contains("brdf select --json"), "{e}");
    }
}
