//! The selection plot: each candidate of `brdf select --json` by its error
//! against stored numbers and against seconds, the chosen one marked and
//! the candidates screened out on the coarse subsample (whose error is the
//! coarse one) drawn apart.

use brdf_render::plot::{Plot, Series};
use serde_json::Value;

use crate::ReportError;

/// Two SVG plots (error vs. parameter count, error vs. time) of the
/// selection `v` read from `path`.
pub fn svgs(v: &Value, path: &str) -> Result<Vec<String>, ReportError> {
    let bad = |reason: &str| ReportError::Input {
        path: path.into(),
        reason: format!("{reason}; pass the output of `brdf select --json`"),
    };
    let rows = v["candidates"]
        .as_array()
        .ok_or_else(|| bad("no `candidates` list"))?;
    let chosen = v["choice"]["label"].as_str().unwrap_or_default();
    let get = |r: &Value, k: &str| r[k].as_f64().unwrap_or(f64::NAN);
    let mut out = Vec::new();
    for (x_key, x_label, log_x) in [
        ("stored_numbers", "stored numbers", false),
        ("seconds", "seconds", true),
    ] {
        let (mut others, mut best, mut screened) = (Vec::new(), Vec::new(), Vec::new());
        for r in rows {
            let p = (get(r, x_key), get(r, "error"));
            if r["label"].as_str() == Some(chosen) {
                best.push(p);
            } else if r["screened_out"].as_bool() == Some(true) {
                screened.push(p);
            } else {
                others.push(p);
            }
        }
        let mut chosen_series = Series::points(&format!("chosen: {chosen}"), 3, best);
        chosen_series.marker = 7;
        let plot = Plot {
            title: format!("candidates: error against {x_label}"),
            x_label: x_label.into(),
            y_label: "error".into(),
            series: vec![
                Series::points("candidates (all samples)", 0, others),
                Series::points("screened out (coarse error)", 1, screened),
                chosen_series,
            ],
            log_x,
            log_y: true,
            ..Plot::default()
        };
        out.push(brdf_render::plot::svg(&plot, (620, 380))?);
    }
    Ok(out)
}
