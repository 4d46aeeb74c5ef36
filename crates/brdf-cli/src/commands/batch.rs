//! `brdf batch`: fit every material x model of a database, resumable
//! and shardable; the runner is [`brdf_fit::batch`] (see there for
//! `fits.jsonl`, shards and merging).

use std::path::{Path, PathBuf};

use brdf_fit::batch::{BatchOptions, Shard};

use crate::error::CliError;
use crate::opts::{ChannelsArg, MetricArg};
use crate::progress::Bars;

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
    #[arg(long, value_enum, default_value = "rgb")]
    pub channels: ChannelsArg,
    /// Angle limit (degrees).
    #[arg(long, default_value_t = 80.0, allow_negative_numbers = true)]
    pub limit: f64,
    /// Multi-start count.
    #[arg(long, default_value_t = 12)]
    pub starts: usize,
    /// Objective and metric, as `brdf fit --metric`: auto (for appearance
    /// when the model is a renderer's and the data can be rendered, else
    /// ngan), appearance, or one objective.
    #[arg(long, value_enum, default_value = "auto")]
    pub metric: MetricArg,
    /// End each fit for appearance with a search on the mean HDR-FLIP of
    /// its renders, as `brdf fit --polish` (other fits are unchanged).
    #[arg(long)]
    pub polish: bool,
    /// Also write an HTML index of the fits and one page per fit into
    /// OUT/report/.
    #[arg(long)]
    pub report: bool,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
}

/// Run `brdf batch`.
pub fn run(args: &BatchArgs) -> Result<(), CliError> {
    if !args.merge.is_empty() {
        brdf_fit::batch::merge(&args.merge, &args.out)?;
        return report(args);
    }
    if args.models.is_empty() || args.data.is_empty() {
        return Err(CliError::Usage(
            "brdf batch needs --data PATH... and --models A,B,... (or --merge DIR...)".into(),
        ));
    }
    if args.channels == ChannelsArg::PerChannel {
        return Err(CliError::Usage(
            "--channels per-channel: a batch row is one model; expected grey or rgb".into(),
        ));
    }
    let opts = BatchOptions {
        data: args.data.clone(),
        models: args.models.clone(),
        out: args.out.clone(),
        shard: args.shard.as_deref().map_or(Ok(Shard::ALL), Shard::parse)?,
        channels: args.channels.mode()?,
        limit_deg: args.limit,
        starts: args.starts,
        metric: args.metric.metric()?,
        polish: args.polish,
    };
    let fits = opts.out.join(brdf_fit::batch::FITS);
    let started = |todo: usize, in_share: usize| {
        eprintln!(
            "brdf batch: {in_share} fits in this share, {} already in {}, {todo} to run",
            in_share - todo,
            fits.display()
        );
    };
    let done = brdf_fit::batch::run(&opts, started, &Bars::new(args.quiet))?;
    if let Some(line) = &done.dropped_torn_line {
        eprintln!(
            "brdf batch: dropped the torn last line of {} (a killed run; {} bytes); its fit was redone",
            done.fits_path.display(),
            line.len()
        );
    }
    for f in &done.failures {
        eprintln!("brdf batch: {f}");
    }
    report(args)?;
    if done.failures.is_empty() {
        return Ok(());
    }
    Err(CliError::Usage(format!(
        "{} of {} fits failed (listed above); the others are in {}",
        done.failures.len(),
        done.in_share - done.already_done,
        done.fits_path.display()
    )))
}

/// `--report`: the index and fit pages in `OUT/report/`, the data found
/// where this batch read them ([`data_dirs`]).
fn report(args: &BatchArgs) -> Result<(), CliError> {
    if !args.report {
        return Ok(());
    }
    let out = args.out.join("report").join("index.html");
    let dirs = data_dirs(&args.data);
    crate::commands::report::batch_report(&args.out, &out, &dirs, args.quiet)
}

/// The folders of the batch's `--data`: a folder itself, a file's parent.
/// The fits name a file outside `$BRDF_DATA` by its file name only, so
/// the report looks for it there.
fn data_dirs(data: &[String]) -> Vec<PathBuf> {
    data.iter()
        .map(|spec| brdf_io::split_sample(spec).0)
        .filter_map(|p| {
            if p.is_dir() {
                Some(p)
            } else {
                p.parent().map(Path::to_path_buf)
            }
        })
        .collect()
}
