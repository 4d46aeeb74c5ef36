//! The shape Kurt's Figures 9.4 and 9.5 share: several models' errors on
//! every CUReT material, the materials ranked by one model's error, written
//! as a table (rank, material, one column per model) and a log-scale plot
//! (one point series per model, x the rank).

use brdf_core::SampleSet;
use brdf_fit::FitSummary;

use super::common::err;
use crate::StudyError;
use crate::context::Study;
use crate::report::{Cell, Table};
use brdf_render::plot::{Plot, Series};

/// One ranked figure: what it shows and how it is labelled.
pub struct RankedFigure<'a> {
    /// File stem before the variant suffix (`kurt_9_4`).
    pub stem: &'a str,
    /// Table title.
    pub caption: String,
    /// Note under the table.
    pub note: String,
    /// Plot title (before [`Study::title`] marks synthetic data).
    pub plot_title: String,
    /// Plot x label.
    pub x_label: String,
    /// Name of the error metric (the y label is `{metric} error`).
    pub metric: &'a str,
    /// Model labels, one per entry of `results`.
    pub labels: &'a [&'a str],
    /// `results[k][s]`: model `k` fitted to set `s`.
    pub results: &'a [Vec<FitSummary>],
    /// The model whose error ranks the materials.
    pub rank_by: usize,
    /// What the files are, for `results/README.md`.
    pub what: &'a str,
}

/// Write `fig` for `sets` into the study's output folder and record it.
pub fn write(study: &mut Study, sets: &[SampleSet], fig: RankedFigure) -> Result<(), StudyError> {
    let results = fig.results;
    let mut order: Vec<usize> = (0..sets.len()).collect();
    let by = &results[fig.rank_by];
    order.sort_by(|a, b| err(&by[*a]).total_cmp(&err(&by[*b])));
    let mut hdr = vec!["rank", "material"];
    hdr.extend(fig.labels.iter());
    let mut table = Table::new(&fig.caption, &hdr);
    table.note = fig.note;
    let mut plot = Plot {
        title: study.title(fig.plot_title),
        x_label: fig.x_label,
        y_label: format!("{} error", fig.metric),
        log_y: true,
        integer_x: true,
        ..Plot::default()
    };
    for (i, s) in order.iter().enumerate() {
        let mut r = vec![
            Cell::Text((i + 1).to_string()),
            Cell::Text(sets[*s].name.clone()),
        ];
        r.extend(results.iter().map(|m| Cell::Num(err(&m[*s]), 4)));
        table.rows.push(r);
    }
    for (k, label) in fig.labels.iter().enumerate() {
        let pts = order
            .iter()
            .enumerate()
            .map(|(i, s)| ((i + 1) as f64, err(&results[k][*s])))
            .collect();
        plot.series.push(Series::points(label, k, pts));
    }
    let stem = study.stem(fig.stem);
    table.write(&study.out, &stem)?;
    brdf_render::plot::write(&plot, &study.out, &stem)?;
    study.wrote(
        format!("{stem}.{{csv,md,svg,png}}"),
        fig.what,
        "`curet/abrdf.dat` (grey, isotropic samples)",
    );
    Ok(())
}
