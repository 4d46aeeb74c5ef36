//! `brdf select --data PATH [--tolerance REL] [--models A,B] [--max-parameters N] [--exhaustive] [--json]`:
//! fit the candidate models (coarse to fine, or every one to all samples
//! with `--exhaustive`) and choose the smallest one within the tolerance
//! of the best; on data that can be rendered, choose by image error
//! (`--for RENDERER`: among the models that renderer renders exactly).

use brdf_fit::judged::SCATTERED_NOTE;
use brdf_fit::report_text::image_error_lines;
use brdf_fit::select::{Among, Search};
use brdf_fit::{Material, SelectBy, SelectOutcome, SelectRequest};

use crate::error::CliError;
use crate::opts::TargetArg;
use crate::progress::Bars;

/// Arguments of `brdf select`.
#[derive(Debug, clap::Args)]
pub struct SelectArgs {
    /// Data set: `PATH` or `PATH#SAMPLE`.
    #[arg(long)]
    pub data: String,
    /// Accept errors up to (1 + REL) times the best (a selection by L2;
    /// default 0.1).
    #[arg(long, value_name = "REL", allow_negative_numbers = true)]
    pub tolerance: Option<f64>,
    /// Drop samples with theta_i or theta_o above this angle (degrees).
    #[arg(long, default_value_t = 80.0, allow_negative_numbers = true)]
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
    /// the standard light sets. The default on data that can be rendered
    /// (RGL, MERL); refused on scattered data.
    #[arg(long, conflicts_with = "by_l2")]
    pub by_image: bool,
    /// Choose the smallest model within the tolerance of the best Ngan L2
    /// (the default on scattered data: CUReT, Cornell, CSV).
    #[arg(long)]
    pub by_l2: bool,
    /// With a choice by image: end each model's fit with a search on the
    /// mean HDR-FLIP of its renders, as `brdf fit --polish`.
    #[arg(long)]
    pub polish: bool,
    /// Choose among the models RENDERER renders exactly, by image error
    /// (what `brdf fit --for RENDERER` fits and writes).
    #[arg(long = "for", value_enum, value_name = "RENDERER", conflicts_with_all = ["by_l2", "models", "max_parameters", "grey", "tolerance", "exhaustive"])]
    pub for_renderer: Option<TargetArg>,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
}

/// Run `brdf select`: a [`SelectRequest`] built from the arguments, its
/// outcome printed.
pub fn run(args: &SelectArgs) -> Result<(), CliError> {
    let material = Material::load(&args.data)?;
    for n in &material.samples().notes {
        eprintln!("note: {n}");
    }
    if args.polish && (args.by_l2 || !material.is_renderable()) {
        return Err(CliError::Usage(
            "--polish refines fits for appearance: use it with --by-image (renderer models on RGL `.bsdf` or MERL `.binary` data)".into(),
        ));
    }
    if args.by_image && !material.is_renderable() {
        return Err(CliError::Usage(format!(
            "--by-image: `{}` holds scattered samples that cannot be rendered; use RGL `.bsdf` or MERL `.binary` data, or select without --by-image",
            args.data
        )));
    }
    let bars = Bars::new(args.quiet);
    if let Some(target) = args.for_renderer {
        return select_for(args, &material, target, &bars);
    }
    let by = match (args.by_image, args.by_l2) {
        (true, _) => SelectBy::Image,
        (_, true) => SelectBy::L2,
        _ => SelectBy::Auto,
    };
    if by == SelectBy::Image || (by == SelectBy::Auto && material.is_renderable()) {
        refuse_l2_options(args)?;
    }
    let request = SelectRequest {
        by,
        tolerance: args.tolerance.unwrap_or(DEFAULT_TOLERANCE),
        limit_deg: args.limit,
        grey: args.grey,
        among: Among {
            models: args.models.clone(),
            max_parameters: args.max_parameters,
        },
        search: if args.exhaustive {
            Search::Exhaustive
        } else {
            Search::CoarseToFine
        },
        polish: args.polish,
        progress: &bars,
        ..SelectRequest::new(&material)
    };
    let outcome = request.run()?;
    if args.json {
        return say!("{}", serde_json::to_string_pretty(&outcome.json()?)?);
    }
    match &outcome {
        SelectOutcome::L2 {
            data,
            tolerance,
            rows,
            choice,
            image,
            ..
        } => print_by_l2(&data.name, rows, *choice, *tolerance, image.as_ref()),
        SelectOutcome::Image { rows, choice, .. } => {
            print_by_image(rows, *choice)?;
            print_samples(&rows[*choice])
        }
    }
}

/// The tolerance of a selection by L2 when `--tolerance` is not given.
const DEFAULT_TOLERANCE: f64 = 0.1;

/// The options only a selection by L2 reads, refused (not ignored) when
/// the choice is made by image.
fn refuse_l2_options(args: &SelectArgs) -> Result<(), CliError> {
    let given = [
        ("--tolerance", args.tolerance.is_some()),
        ("--grey", args.grey),
        ("--exhaustive", args.exhaustive),
        ("--max-parameters", args.max_parameters.is_some()),
    ];
    match given.iter().find(|(_, on)| *on) {
        Some((option, _)) => Err(CliError::Usage(format!(
            "{option} applies to a selection by L2, and `{}` can be rendered, so select chooses by image (every renderer model fitted for appearance on all channels): add --by-l2, or leave {option} out",
            args.data
        ))),
        None => Ok(()),
    }
}

/// The samples the choice used, of those present.
pub(crate) fn print_samples(row: &brdf_fit::select_by_image::ImageChoice) -> Result<(), CliError> {
    say!(
        "samples: {} of {} used (dropped {} invalid, {} beyond {} deg; the image objective sees the whole render)",
        row.samples,
        row.samples_present,
        row.dropped_invalid,
        row.dropped_angle,
        row.limit_deg
    )
}

/// `brdf select --for RENDERER`: the models the renderer renders exactly,
/// fitted for appearance, the closest chosen.
fn select_for(
    args: &SelectArgs,
    material: &Material,
    target: TargetArg,
    bars: &Bars,
) -> Result<(), CliError> {
    if !material.is_renderable() {
        return Err(CliError::Usage(format!(
            "--for: `{}` holds scattered samples that cannot be rendered, so no choice by image error can be made; use RGL `.bsdf` or MERL `.binary` data",
            args.data
        )));
    }
    let request = SelectRequest {
        limit_deg: args.limit,
        polish: args.polish,
        progress: bars,
        ..SelectRequest::new(material)
    };
    let s = brdf_export::for_renderer::select_for(&request, target.target())?;
    if args.json {
        let v = brdf_fit::select_by_image_json(&material.samples().name, &s.rows, s.choice)?;
        return say!("{}", serde_json::to_string_pretty(&v)?);
    }
    print_by_image(&s.rows, s.choice)?;
    print_samples(&s.rows[s.choice])?;
    say!(
        "`{}` renders exactly in {}: write it with `brdf fit --data {} --for {} --out FILE`",
        s.rows[s.choice].label,
        target.target(),
        args.data,
        target.target()
    )
}

/// The table of candidates and the choice's image errors.
fn print_by_l2(
    name: &str,
    rows: &[brdf_fit::select::SelectRow],
    choice: usize,
    tolerance: f64,
    image: Option<&brdf_render::ImageError>,
) -> Result<(), CliError> {
    let table = brdf_fit::select::table(name, rows, choice, tolerance);
    say_raw!("{}", table.markdown())?;
    match image {
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

/// One line per renderer model, the choice starred.
pub(crate) fn print_by_image(
    rows: &[brdf_fit::select_by_image::ImageChoice],
    choice: usize,
) -> Result<(), CliError> {
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
            r.label,
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
