//! `brdf render`: a labelled sphere of a saved model (`--model FILE`) or of
//! dense measured data (`--data PATH`, MERL or RGL), or both side by side
//! with their difference when both are given. By default the judge's
//! sphere under the studio light set at the reports' size, the sphere the
//! reports, the image errors and Python's `Model.render()` show; `--light`
//! names another light set or one directional light (`THETA,PHI` in
//! degrees, sphere seen from `+z`). Tone mapped with the exposure stated in
//! the image.

use std::path::PathBuf;

use brdf_fit::data_name;
use brdf_models::saved_model::SavedModel;
use brdf_render::side_by_side::{Side, SideBySide, SphereLight};

use crate::error::CliError;
use crate::opts::parse_direction;

/// Arguments of `brdf render`.
#[derive(Debug, clap::Args)]
pub struct RenderArgs {
    /// A model saved by `brdf fit --save FILE`.
    #[arg(long)]
    pub model: Option<PathBuf>,
    /// Dense measured data (MERL `.binary`, RGL `.bsdf`).
    #[arg(long)]
    pub data: Option<String>,
    /// A light set (studio, sky, directional: the judge's camera) or one
    /// directional light `THETA,PHI` in degrees (polar angle from the view
    /// axis; the sphere seen from +z).
    #[arg(long, default_value = "studio", allow_hyphen_values = true)]
    pub light: String,
    /// Sphere size in pixels (16 to 2048).
    #[arg(long, default_value_t = brdf_render::judge::REPORT_SIZE)]
    pub size: usize,
    /// Output image: `.png` (labelled, tone mapped) or `.exr` (linear
    /// radiance of the spheres, side by side).
    pub out: PathBuf,
}

fn light(s: &str) -> Result<SphereLight, CliError> {
    if let Ok(set) = brdf_render::LightSet::parse(s) {
        return Ok(SphereLight::Set(set));
    }
    if !s.contains(',') {
        return Err(CliError::Usage(format!(
            "--light {s}: expected a light set ({}) or a direction THETA,PHI in degrees",
            brdf_render::light::LIGHT_SET_NAMES.join(", ")
        )));
    }
    let d = parse_direction(s, true, "--light")?;
    if d.vector().z <= 0.0 {
        return Err(CliError::Usage(format!(
            "--light {s}: the light must be above the horizon (THETA < 90)"
        )));
    }
    Ok(SphereLight::Directional(*d.vector()))
}

/// The image formats `brdf render` writes, chosen by the extension.
#[derive(Clone, Copy, Debug)]
enum ImageFormat {
    Png,
    Exr,
}

impl ImageFormat {
    fn of(out: &std::path::Path) -> Result<Self, CliError> {
        let ext = out.extension().and_then(|e| e.to_str()).unwrap_or("");
        match ext.to_ascii_lowercase().as_str() {
            "png" => Ok(ImageFormat::Png),
            "exr" => Ok(ImageFormat::Exr),
            _ => Err(CliError::Usage(format!(
                "`{}`: cannot write .{ext} images; name the output .png (labelled) or .exr (linear radiance)",
                out.display()
            ))),
        }
    }
}

/// The spheres of the picture (and their difference), side by side, as
/// linear OpenEXR.
fn write_exr(picture: &SideBySide, out: &std::path::Path) -> Result<(), CliError> {
    let grid = picture.grid()?;
    let tiles: Vec<&brdf_render::Image> = grid
        .tiles
        .iter()
        .flatten()
        .flatten()
        .map(|t| &t.image)
        .collect();
    brdf_render::Image::hstack(&tiles).write_exr(out)?;
    Ok(())
}

/// Run `brdf render`: load what was named, let
/// [`brdf_render::side_by_side`] render and lay it out.
pub fn run(args: &RenderArgs) -> Result<(), CliError> {
    let format = ImageFormat::of(&args.out)?;
    if !(16..=2048).contains(&args.size) {
        return Err(CliError::Usage(format!(
            "--size {}: must be 16 to 2048 pixels",
            args.size
        )));
    }
    if args.data.is_none() && args.model.is_none() {
        return Err(CliError::Usage(
            "give --model FILE, --data PATH or both".into(),
        ));
    }
    let light = light(&args.light)?;
    let dense = match &args.data {
        Some(spec) => match brdf_io::load_dense(spec)? {
            Some(d) => Some((data_name(spec), d)),
            None => {
                return Err(CliError::Usage(format!(
                    "--data {}: scattered samples cannot be rendered without interpolating them; give a dense file (MERL .binary, RGL .bsdf)",
                    data_name(spec)
                )));
            }
        },
        None => None,
    };
    let model = match &args.model {
        Some(path) => Some((path, SavedModel::load(path)?.build()?)),
        None => None,
    };
    let picture = SideBySide {
        measured: dense.as_ref().map(|(name, d)| Side {
            brdf: d.as_ref(),
            column: format!("measured: {name}"),
            title: name.clone(),
        }),
        model: model.as_ref().map(|(path, m)| Side {
            brdf: m.as_ref(),
            column: format!("model: {}", m.name()),
            title: format!("{} ({})", m.name(), data_name(&path.display().to_string())),
        }),
        light,
        light_label: args.light.clone(),
        size: args.size,
    };
    match format {
        ImageFormat::Png => picture.write_png(&args.out)?,
        ImageFormat::Exr => write_exr(&picture, &args.out)?,
    }
    say!("wrote {}", args.out.display())
}
