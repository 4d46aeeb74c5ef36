//! Kurt's Table 9.1: the polynomial's error against its degree, for the
//! Cornell paint `cayman` (RGB) and CUReT quarry tile (grey), by OLS and by
//! Kurt's robust IRLS, up to the degree where more terms stop paying.

use brdf_core::SampleSet;
use brdf_fit::FitSummary;
use brdf_models::ModelConfig;
use rayon::prelude::*;

use super::common::err;
use crate::StudyError;
use crate::context::models::{FitHow, fit_model};
use crate::context::{Study, progress};
use crate::report::{Cell, Table};
use brdf_render::plot::{Plot, Series};

/// Kurt's Table 9.1 (RGB, degrees 1..6): cayman, quarry tile.
const KURT: [[f64; 6]; 2] = [
    [2.199, 2.198, 2.198, 2.198, 2.198, 2.198],
    [0.041, 0.027, 0.015, 0.011, 0.011, 0.010],
];

/// Relative improvement below which one more degree does not pay.
const PAYS: f64 = 0.01;

fn materials(study: &mut Study) -> Result<Vec<(usize, SampleSet)>, StudyError> {
    let limit = study.variant.limit.to_radians();
    let mut out = Vec::new();
    if study.spec.has_material("cornell cayman") {
        let cayman = if let Some(dir) = &study.data {
            let path = dir.join("cornell/cayman.brdf");
            let set = brdf_io::cornell::read(&path, brdf_io::cornell::CornellColour::Rgb)?;
            set.filter_invalid(false).0
        } else {
            let pairs = crate::synthetic::scattered_pairs(205, 80f64.to_radians());
            let m = crate::synthetic::MATERIALS
                .iter()
                .find(|m| m.name.starts_with("cayman"))
                .ok_or_else(|| StudyError::Usage("no synthetic cayman".into()))?;
            crate::synthetic::sample(m, &pairs, 1)?
        };
        out.push((0, cayman.filter_angle_limit(limit).0));
    }
    if let Some(q) = study
        .curet()?
        .into_iter()
        .find(|s| crate::context::sample_number(s) == Some(25) || s.name.starts_with("quarry tile"))
    {
        out.push((1, q));
    }
    Ok(out)
}

/// The degree after which one more degree improves the error by less than
/// [`PAYS`] (relative), if any within the degrees run.
fn stops_paying(degrees: &[usize], errors: &[f64]) -> Option<usize> {
    (1..errors.len())
        .find(|k| errors[*k] > errors[k - 1] * (1.0 - PAYS))
        .map(|k| degrees[k - 1])
}

/// Run the part.
pub fn run(study: &mut Study) -> Result<(), StudyError> {
    let sets = materials(study)?;
    let mut degrees = study.spec.degrees.clone();
    degrees.sort_unstable();
    degrees.dedup();
    let objective = study.variant.objective()?;
    let jobs: Vec<(usize, usize, bool)> = (0..sets.len())
        .flat_map(|m| {
            degrees
                .iter()
                .flat_map(move |d| [(m, *d, true), (m, *d, false)])
        })
        .collect();
    let bar = progress::bar(jobs.len(), "Table 9.1");
    let fits: Vec<Result<FitSummary, StudyError>> = jobs
        .par_iter()
        .map(|(m, d, ols)| {
            let set = &sets[*m].1;
            let config = ModelConfig {
                channels: set.channels(),
                degree: *d,
                ..ModelConfig::default()
            };
            let how = FitHow {
                objective,
                ols: *ols,
                ..FitHow::default()
            };
            let r = fit_model("polynomial", config, set, how).map(|r| r.1);
            bar.inc(1);
            r
        })
        .collect();
    bar.finish_and_clear();
    let fits = fits.into_iter().collect::<Result<Vec<_>, _>>()?;
    let at = |m: usize, k: usize, ols: bool| &fits[(m * degrees.len() + k) * 2 + usize::from(!ols)];
    let mut cols = vec![
        "degree p".to_string(),
        "stored numbers per channel (2p+5)".to_string(),
    ];
    for (_, s) in &sets {
        cols.push(format!("{} OLS", s.name));
        cols.push(format!("{} IRLS", s.name));
        cols.push(format!("{} Kurt 2007 (RGB)", s.name));
    }
    let hdr: Vec<&str> = cols.iter().map(String::as_str).collect();
    let mut t = Table::new(
        "Kurt Table 9.1: error against polynomial degree (cayman, quarry tile)",
        &hdr,
    );
    let mut plot = Plot {
        title: study.title("Kurt Table 9.1: polynomial error against degree"),
        x_label: "degree p".into(),
        y_label: format!("{} error", objective.name()),
        log_y: true,
        integer_x: true,
        ..Plot::default()
    };
    let mut verdicts = Vec::new();
    for (i, (which, s)) in sets.iter().enumerate() {
        let ols: Vec<f64> = (0..degrees.len()).map(|k| err(at(i, k, true))).collect();
        let irls: Vec<f64> = (0..degrees.len()).map(|k| err(at(i, k, false))).collect();
        verdicts.push(match stops_paying(&degrees, &ols) {
            Some(p) => format!(
                "`{}`: beyond p = {p} one more degree gains less than {}% (OLS)",
                s.name,
                PAYS * 100.0
            ),
            None => format!(
                "`{}`: every degree run still gains at least {}%",
                s.name,
                PAYS * 100.0
            ),
        });
        let pts = |v: &[f64]| {
            degrees
                .iter()
                .map(|d| *d as f64)
                .zip(v.iter().copied())
                .collect()
        };
        let mut a = Series::points(&format!("{} OLS", s.name), 2 * i, pts(&ols));
        a.line = true;
        let mut b = Series::points(&format!("{} IRLS", s.name), 2 * i + 1, pts(&irls));
        b.line = true;
        let kurt = (1..=6).map(|d| (d as f64, KURT[*which][d - 1])).collect();
        plot.series.extend([
            a,
            b,
            Series::points(&format!("{} Kurt (RGB)", s.name), 8 + i, kurt),
        ]);
    }
    for (k, d) in degrees.iter().enumerate() {
        let mut row = vec![
            Cell::Text(d.to_string()),
            Cell::Text((2 * d + 5).to_string()),
        ];
        for (i, (which, _)) in sets.iter().enumerate() {
            row.push(Cell::Num(err(at(i, k, true)), 4));
            row.push(Cell::Num(err(at(i, k, false)), 4));
            row.push(
                KURT[*which]
                    .get(d - 1)
                    .map_or(Cell::Empty, |v| Cell::Num(*v, 4)),
            );
        }
        t.rows.push(row);
    }
    t.note = format!(
        "Data: cayman = `cornell/cayman.brdf` (RGB, angle limit {} deg){}; quarry tile from {}. Kurt fitted RGB data; our quarry tile is grey, so compare the shape of the curves, not the values. OLS: column-pivoted least squares; IRLS: Kurt's robust fit (bisquare). Where more terms stop paying: {}. Generated by `brdf reproduce`.",
        study.variant.limit,
        if study.synthetic() {
            " — here BUILT-IN SYNTHETIC cayman"
        } else {
            ""
        },
        study.curet_source(),
        verdicts.join("; ")
    );
    let stem = study.stem("kurt_9_1");
    t.write(&study.out, &stem)?;
    brdf_render::plot::write(&plot, &study.out, &stem)?;
    let data = if study.synthetic() {
        "built-in synthetic"
    } else {
        "`cornell/cayman.brdf`, `curet/abrdf.dat` #25"
    };
    study.wrote(
        format!("{stem}.{{csv,md,svg,png}}"),
        "Table 9.1: polynomial error against degree, OLS and IRLS, Kurt's values beside; plot",
        data,
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn more_terms_stop_paying_at_the_first_gain_below_one_percent() {
        let d = [1, 2, 3, 4];
        assert_eq!(stops_paying(&d, &[1.0, 0.5, 0.499, 0.3]), Some(2));
        assert_eq!(stops_paying(&d, &[1.0, 0.5, 0.4, 0.3]), None);
    }
}
