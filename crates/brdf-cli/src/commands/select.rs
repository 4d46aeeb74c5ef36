//! `brdf select --data PATH [--tolerance REL] [--models A,B] [--max-parameters N] [--exhaustive] [--json]`:
//! fit the candidate models (coarse to fine, or every one to all samples
//! with `--exhaustive`) and choose the smallest one within the tolerance
//! of the best.

use crate::error::CliError;
use brdf_fit::FitOptions;
use brdf_fit::judged::SCATTERED_NOTE;
use brdf_fit::report_text::image_error_lines;

/// Arguments of `brdf select`.
#[derive(Debug, clap::Args)]
pub struct SelectArgs {
    /// Data set: `PATH` or `PATH#SAMPLE`.
    #[arg(long)]
    pub data: String,
    /// Accept errors up to (1 + REL) times the best.
    #[arg(long, default_value_t = 0.1)]
    pub tolerance: f64,
    /// Drop samples with theta_i or theta_o above this angle (degrees).
    #[arg(long, default_value_t = 80.0)]
    pub limit: f64,
    /// Fit the mean of the channels (grey) instead of every channel.
    #[arg(long)]
    pub grey: bool,
    /// Only these models (comma-separated, forgiving names; repeats count once).
    #[arg(long, value_delimiter = ',')]
    pub models: Vec<String>,
    /// Only candidates with at most N stored numbers.
    #[arg(long, value_name = "N")]
    pub max_parameters: Option<usize>,
    /// Fit every candidate to all samples. By default all candidates are
    /// fitted to a shared subsample of about 2048 samples and only those
    /// near the best again to all samples; the others are reported with
    /// their coarse error, screened out.
    #[arg(long)]
    pub exhaustive: bool,
    /// Machine-readable output.
    #[arg(long)]
    pub json: bool,
    /// Choose among the renderer models (principled, glTF, glTF + KHR, GGX;
    /// or those of --models) by their image error against the data under
    /// the standard light sets (data that can be rendered: RGL, MERL).
    #[arg(long)]
    pub by_image: bool,
    /// With --by-image: end each model's fit with a search on the mean
    /// HDR-FLIP of its renders, as `brdf fit --polish`.
    #[arg(long)]
    pub polish: bool,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
}

/// Run `brdf select`.
pub fn run(args: &SelectArgs) -> Result<(), CliError> {
    if args.by_image {
        return by_image(args);
    }
    if args.polish {
        return Err(CliError::Usage(
            "--polish refines fits for appearance: use it with --by-image (renderer models on RGL `.bsdf` or MERL `.binary` data)".into(),
        ));
    }
    let data = brdf_io::load(&args.data)?;
    let data = brdf_fit::select::prepare(&data, args.limit, args.grey)?;
    brdf_study::context::progress::set_quiet(args.quiet);
    let bar = brdf_study::context::progress::bar(1, "select");
    let n = brdf_fit::select::candidates(data.channels()).len();
    bar.set_message(format!("fitting up to {n} candidates to {}", data.name));
    let among = brdf_fit::select::Among {
        models: args.models.clone(),
        max_parameters: args.max_parameters,
    };
    let search = if args.exhaustive {
        brdf_fit::select::Search::Exhaustive
    } else {
        brdf_fit::select::Search::CoarseToFine
    };
    let dense = brdf_io::load_dense(&args.data)?;
    let (selection, image) = brdf_fit::judged::select_judged(
        &data,
        dense.as_deref(),
        args.tolerance,
        &FitOptions::default(),
        &among,
        search,
    )?;
    let (rows, choice) = (selection.rows, selection.choice);
    bar.finish_and_clear();
    if args.json {
        let v =
            brdf_fit::select_json(&data, args.tolerance, search, &rows, choice, image.as_ref())?;
        return say!("{}", serde_json::to_string_pretty(&v)?);
    }
    let table = brdf_fit::select::table(&data.name, &rows, choice, args.tolerance);
    say_raw!("{}", table.markdown())?;
    match &image {
        Some(e) => {
            say_raw!(
                "\nThe choice, {}:\n{}",
                rows[choice].label,
                image_error_lines(e)
            )?;
            for w in e.warnings() {
                say!("warning: {w}")?;
            }
            Ok(())
        }
        None => say!("\n{SCATTERED_NOTE}"),
    }
}

/// `brdf select --by-image`: a thin layer over
/// [`brdf_fit::select_by_image::select_by_image`].
fn by_image(args: &SelectArgs) -> Result<(), CliError> {
    let samples = brdf_io::load(&args.data)?;
    let Some(dense) = brdf_io::load_dense(&args.data)? else {
        return Err(CliError::Usage(format!(
            "--by-image: `{}` holds scattered samples that cannot be rendered; use RGL `.bsdf` or MERL `.binary` data, or select without --by-image",
            args.data
        )));
    };
    let names: Vec<&str> = if args.models.is_empty() {
        brdf_models::by_image_models()
    } else {
        args.models.iter().map(String::as_str).collect()
    };
    let (rows, choice) =
        brdf_fit::select_by_image::select_by_image(&names, &samples, dense.as_ref(), args.polish)?;
    if args.json {
        let v = brdf_fit::select_by_image_json(&samples.name, &rows, choice)?;
        return say!("{}", serde_json::to_string_pretty(&v)?);
    }
    for (i, r) in rows.iter().enumerate() {
        let flips: Vec<String> = r
            .image
            .lights
            .iter()
            .map(|l| format!("{} {:.3}", l.light, l.flip))
            .collect();
        say!(
            "{} {:<11} {:<9} lobes [{}]: FLIP {}, CIEDE2000 {:.1}, Ngan L2 {:.4e}, {} parameters, {:.1} s",
            if i == choice { "*" } else { " " },
            r.model,
            r.objective,
            r.lobes.join(", "),
            flips.join(", "),
            r.image.max_delta_e(),
            r.ngan_l2,
            r.parameters,
            r.seconds
        )?;
    }
    Ok(())
}
