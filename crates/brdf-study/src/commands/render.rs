//! `brdf render`: a labelled sphere of a saved model (`--model FILE`) or of
//! dense measured data (`--data PATH`, MERL or RGL), or both side by side
//! with their difference when both are given. Lit by one directional light
//! (`--light THETA,PHI` in degrees), seen from `+z`, tone mapped with the
//! exposure stated in the image.

use std::path::PathBuf;

use brdf_core::Brdf;
use nalgebra::Vector3;

use crate::StudyError;
use crate::report::{data_name, fmt_sig};
use brdf_render::grid::{Grid, Tile, Tone, difference_scale, exposure_for};
use brdf_render::{Image, render_sphere};

/// Arguments of `brdf render`.
#[derive(Debug, clap::Args)]
pub struct RenderArgs {
    /// A model saved by `brdf fit --save FILE`.
    #[arg(long)]
    pub model: Option<PathBuf>,
    /// Dense measured data (MERL `.binary`, RGL `.bsdf`).
    #[arg(long)]
    pub data: Option<String>,
    /// Light direction `THETA,PHI` in degrees (polar angle from the view axis).
    #[arg(long, default_value = "45,45", allow_hyphen_values = true)]
    pub light: String,
    /// Sphere size in pixels (16 to 2048).
    #[arg(long, default_value_t = 256)]
    pub size: usize,
    /// Output PNG.
    pub out: PathBuf,
}

fn light(s: &str) -> Result<Vector3<f64>, StudyError> {
    let d = crate::commands::eval::parse_direction(s, true, "--light")?;
    if d.vector().z <= 0.0 {
        return Err(StudyError::Usage(format!(
            "--light {s}: the light must be above the horizon (THETA < 90)"
        )));
    }
    Ok(*d.vector())
}

fn sphere(b: &(impl Brdf + ?Sized), size: usize, l: &Vector3<f64>) -> Image {
    render_sphere(b, size, l, &Vector3::z(), false)
}

/// Run `brdf render`.
pub fn run(args: &RenderArgs) -> Result<(), StudyError> {
    if !(16..=2048).contains(&args.size) {
        return Err(StudyError::Usage(format!(
            "--size {}: must be 16 to 2048 pixels",
            args.size
        )));
    }
    let l = light(&args.light)?;
    let mut tiles = Vec::new();
    let mut columns = Vec::new();
    let mut title = Vec::new();
    if let Some(spec) = &args.data {
        let Some(dense) = brdf_io::load_dense(spec)? else {
            return Err(StudyError::Usage(format!(
                "--data {}: scattered samples cannot be rendered without interpolating them; give a dense file (MERL .binary, RGL .bsdf)",
                data_name(spec)
            )));
        };
        tiles.push(sphere(dense.as_ref(), args.size, &l));
        columns.push(format!("measured: {}", data_name(spec)));
        title.push(data_name(spec));
    }
    if let Some(path) = &args.model {
        let m = crate::saved_model::SavedModel::load(path)?.build()?;
        tiles.push(sphere(m.as_ref(), args.size, &l));
        columns.push(format!("model: {}", m.name()));
        title.push(format!(
            "{} ({})",
            m.name(),
            data_name(&path.display().to_string())
        ));
    }
    if tiles.is_empty() {
        return Err(StudyError::Usage(
            "give --model FILE, --data PATH or both".into(),
        ));
    }
    let exposure = exposure_for(&tiles[0], 0.95);
    let mut row: Vec<Option<Tile>> = tiles
        .iter()
        .map(|i| {
            Some(Tile {
                image: i.clone(),
                tone: Tone::Exposure(exposure),
            })
        })
        .collect();
    if tiles.len() == 2 {
        let d = tiles[0].abs_difference(&tiles[1]);
        let max = difference_scale(std::slice::from_ref(&d));
        row.push(Some(Tile {
            image: d,
            tone: Tone::Difference(max),
        }));
        columns.push("|model - measured|".into());
    }
    let grid = Grid {
        title: title.join(" vs "),
        columns,
        rows: vec![format!("light {}\nexposure x{}", args.light, fmt_sig(exposure, 3))],
        tiles: vec![row],
        footer: vec![
            format!("Sphere {} px seen from +z, directional light at (theta, phi) = ({}) deg, pixel = f(L, V) cos(theta_i).", args.size, args.light),
            "Tone mapping: linear x exposure (95th percentile of the first sphere's non-zero values -> 0.8), clamped, gamma 2.2; difference in Viridis from 0 to the bar's maximum (99th percentile of the differences; larger ones saturate).".into(),
        ],
    };
    grid.write_png(&args.out)?;
    say!("wrote {}", args.out.display())
}
