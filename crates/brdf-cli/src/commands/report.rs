//! `brdf report`: a self-contained HTML page of a saved fit against its
//! data (`--data DATA --fit FIT.json`), or the index of a batch with one
//! page per fit (`--batch DIR`); the pages come from [`brdf_report`].

use std::path::{Path, PathBuf};

use brdf_models::saved_model::SavedModel;

use brdf_core::progress::Progress;

use crate::error::CliError;
use crate::progress::Bars;

/// Arguments of `brdf report`.
#[derive(Debug, clap::Args)]
pub struct ReportArgs {
    /// Data set the model was fitted to: `PATH` or `PATH#SAMPLE`.
    #[arg(long, requires = "fit")]
    pub data: Option<String>,
    /// A model saved by `brdf fit --save`.
    #[arg(long, requires = "data")]
    pub fit: Option<PathBuf>,
    /// The output of `brdf select --json` (or `brdf select --for RENDERER
    /// --json`) for the same data: adds the selection's plots and table.
    #[arg(long)]
    pub select: Option<PathBuf>,
    /// A `brdf batch --out` folder: write its index and one page per fit.
    #[arg(long, conflicts_with_all = ["data", "fit"])]
    pub batch: Option<PathBuf>,
    /// With --batch: folders holding the batch's data, for the files it
    /// names by file name only (data outside `$BRDF_DATA` given by an
    /// absolute path).
    #[arg(long, num_args = 1.., requires = "batch")]
    pub data_dir: Vec<PathBuf>,
    /// The HTML file (default: report.html, or DIR/report/index.html
    /// with --batch).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
}

/// Run `brdf report`.
pub fn run(args: &ReportArgs) -> Result<(), CliError> {
    if let Some(dir) = &args.batch {
        let out = args
            .out
            .clone()
            .unwrap_or_else(|| dir.join("report").join("index.html"));
        return batch_report(dir, &out, &args.data_dir, args.quiet);
    }
    let (Some(data), Some(fit)) = (&args.data, &args.fit) else {
        return Err(CliError::Usage(
            "brdf report needs --data DATA --fit FIT.json, or --batch DIR".into(),
        ));
    };
    let saved = SavedModel::load(fit)?;
    let selection = match &args.select {
        Some(p) => Some(read_json(p)?),
        None => None,
    };
    let out = args.out.clone().unwrap_or_else(|| "report.html".into());
    let select_name = args.select.as_ref().map(|p| p.display().to_string());
    let input = brdf_report::FitInput {
        data,
        saved: &saved,
        fit_source: &fit.display().to_string(),
        run: None,
        selection: selection.as_ref().zip(select_name.as_deref()),
    };
    let mut analyser = brdf_report::Analyser::new(brdf_render::judge::REPORT_SIZE);
    fit_report(&input, &out, args.quiet, &mut analyser)
}

fn read_json(path: &Path) -> Result<serde_json::Value, CliError> {
    let text = std::fs::read_to_string(path).map_err(|source| CliError::Io {
        path: path.display().to_string(),
        source,
    })?;
    serde_json::from_str(&text).map_err(|e| {
        CliError::Usage(format!(
            "{}: not JSON ({e}); pass the output of `brdf select --json`",
            path.display()
        ))
    })
}

/// Write the page of one fit to `out` (shared with `brdf fit --report`).
pub fn fit_report(
    input: &brdf_report::FitInput,
    out: &Path,
    quiet: bool,
    analyser: &mut brdf_report::Analyser,
) -> Result<(), CliError> {
    let task = Bars::new(quiet).task("report", 1);
    task.item(&format!("{} on {}", input.saved.model, input.data));
    brdf_report::write_fit_page_with(input, out, analyser)?;
    task.finish();
    eprintln!("brdf report: wrote {}", out.display());
    Ok(())
}

/// Write the index of a batch folder and its fit pages, the data looked up
/// in `data_dirs` too (shared with `brdf batch --report`).
pub fn batch_report(
    dir: &Path,
    out: &Path,
    data_dirs: &[PathBuf],
    quiet: bool,
) -> Result<(), CliError> {
    let task = Bars::new(quiet).task("report", 0);
    let mut seen = 0;
    let mut tick = |done: usize, total: usize, current: &str| {
        task.set_total(total);
        task.item(current);
        task.advance(done.saturating_sub(seen));
        seen = seen.max(done);
    };
    let done = brdf_report::write_batch_report(dir, out, data_dirs, &mut tick)?;
    task.finish();
    for s in &done.skipped {
        eprintln!("brdf report: no page for {s}");
    }
    eprintln!(
        "brdf report: wrote {} and {} fit pages beside it",
        done.index.display(),
        done.pages
    );
    Ok(())
}
