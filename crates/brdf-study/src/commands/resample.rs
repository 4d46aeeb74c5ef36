//! `brdf resample --from PATH --to merl|sopp-grid|csv OUT`: convert. Dense
//! sources (MERL) and saved models (`--from model.json`) are evaluated at
//! the target's nodes (a model written as CSV: at the nodes of Sopp's
//! grid); scattered sources can only be written as CSV
//! samples (resampling scattered data would need an interpolation the
//! project does not invent).

use std::path::PathBuf;

use brdf_core::Brdf;

use crate::StudyError;

/// Arguments of `brdf resample`.
#[derive(Debug, clap::Args)]
pub struct ResampleArgs {
    /// Source: a data file, or a model saved by `brdf fit --save` (`.json`).
    #[arg(long)]
    pub from: String,
    /// Target: merl, sopp-grid or csv.
    #[arg(long)]
    pub to: String,
    /// Output file.
    pub out: PathBuf,
}

/// Run `brdf resample`.
pub fn run(args: &ResampleArgs) -> Result<(), StudyError> {
    let from_model = args.from.ends_with(".json");
    let dense: Option<Box<dyn Brdf>> = if from_model {
        let m = crate::saved_model::SavedModel::load(std::path::Path::new(&args.from))?.build()?;
        Some(Box::new(ModelBrdf(m)))
    } else {
        crate::data::load_dense(&args.from)?
    };
    let (path, _) = crate::data::split_sample(&args.from);
    let rgl = !from_model && crate::data::format_of(&path)? == crate::data::Format::Rgl;
    match (args.to.as_str(), dense) {
        // RGL onto MERL: bins beyond the measured incidence are invalid
        // (see brdf_io::rgl::MeasuredRange).
        ("merl", Some(_)) if rgl => {
            let m = brdf_io::rgl::Rgl::read(&path)?;
            let merl = brdf_io::merl::Merl::resample(&brdf_io::rgl::MeasuredRange(&m));
            brdf_io::merl::write(&args.out, &merl)?;
            say!(
                "note: bins with theta_i or theta_o above {:.2} deg (the largest measured incidence) are marked invalid (-1)",
                m.measured_theta_max().to_degrees()
            )?;
        }
        ("merl", Some(b)) => {
            brdf_io::merl::write(&args.out, &brdf_io::merl::Merl::resample(b.as_ref()))?
        }
        ("sopp-grid", Some(b)) => brdf_io::sopp_grid::write(
            &args.out,
            &brdf_io::sopp_grid::SoppGrid::resample(b.as_ref()),
        )?,
        // A model has no samples of its own: it is written at the nodes of
        // Sopp's goniometric grid (cell weights).
        ("csv", Some(b)) if from_model => {
            let g = brdf_io::sopp_grid::SoppGrid::resample(b.as_ref());
            let name = std::path::Path::new(&args.from)
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default();
            let s = g.to_samples(&format!("model#{name}"), 90.0, true);
            brdf_io::csv_samples::write(&args.out, &s)?
        }
        ("csv", _) => {
            let s = crate::data::load(&args.from)?;
            brdf_io::csv_samples::write(&args.out, &s)?
        }
        ("merl" | "sopp-grid", None) => {
            return Err(StudyError::Usage(format!(
                "{}: scattered data cannot be resampled onto a grid without an interpolation; use --to csv, or fit a model and resample the saved model",
                args.from
            )));
        }
        (other, _) => {
            return Err(StudyError::Usage(format!(
                "--to {other}: expected merl, sopp-grid or csv"
            )));
        }
    }
    say!("wrote {}", args.out.display())?;
    Ok(())
}

/// A parametric model as a plain BRDF.
struct ModelBrdf(Box<dyn brdf_core::Parametric>);

impl Brdf for ModelBrdf {
    fn channels(&self) -> usize {
        self.0.channels()
    }
    fn eval(&self, l: &nalgebra::Vector3<f64>, v: &nalgebra::Vector3<f64>, out: &mut [f64]) {
        self.0.eval(l, v, out)
    }
}
