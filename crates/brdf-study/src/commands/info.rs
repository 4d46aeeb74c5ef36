//! `brdf info PATH [--json]`: what a data file holds — format, sample
//! count, channels, invalid count, value range, angle ranges.

use brdf_core::cartesian_to_spherical;
use serde::Serialize;

use crate::StudyError;

/// Arguments of `brdf info`.
#[derive(Debug, clap::Args)]
pub struct InfoArgs {
    /// Data file (`PATH` or `PATH#SAMPLE`).
    pub path: String,
    /// Machine-readable output.
    #[arg(long)]
    pub json: bool,
}

#[derive(Serialize)]
struct Info {
    name: String,
    format: crate::data::Format,
    samples: usize,
    channels: Vec<String>,
    negative: usize,
    non_finite: usize,
    value_range: Option<(f64, f64)>,
    theta_i_deg: (f64, f64),
    theta_o_deg: (f64, f64),
    phi_i_deg: (f64, f64),
    phi_o_deg: (f64, f64),
    /// RGL: the largest measured incidence (degrees); resampled onto MERL,
    /// bins beyond it are invalid.
    #[serde(skip_serializing_if = "Option::is_none")]
    measured_theta_max_deg: Option<f64>,
}

fn range(v: impl Iterator<Item = f64>) -> (f64, f64) {
    v.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
        (a.min(x), b.max(x))
    })
}

/// Run `brdf info`.
pub fn run(args: &InfoArgs) -> Result<(), StudyError> {
    let (path, _) = crate::data::split_sample(&args.path);
    let format = crate::data::format_of(&path)?;
    let spec = if format == crate::data::Format::Curet && !args.path.contains('#') {
        format!("{}#1", args.path)
    } else {
        args.path.clone()
    };
    let s = crate::data::load(&spec)?;
    let p = s.pairs();
    let sph: Vec<((f64, f64), (f64, f64))> = (0..s.len())
        .map(|j| {
            (
                cartesian_to_spherical(&p.l(j)),
                cartesian_to_spherical(&p.v(j)),
            )
        })
        .collect();
    let info = Info {
        name: s.name.clone(),
        format,
        samples: s.len(),
        channels: s.channel_names.clone(),
        negative: s.count_negative(),
        non_finite: s.count_non_finite(),
        value_range: s.value_range(),
        theta_i_deg: range(sph.iter().map(|a| a.0.0.to_degrees())),
        theta_o_deg: range(sph.iter().map(|a| a.1.0.to_degrees())),
        phi_i_deg: range(sph.iter().map(|a| a.0.1.to_degrees())),
        phi_o_deg: range(sph.iter().map(|a| a.1.1.to_degrees())),
        measured_theta_max_deg: if format == crate::data::Format::Rgl {
            Some(
                brdf_io::rgl::Rgl::read(&path)?
                    .measured_theta_max()
                    .to_degrees(),
            )
        } else {
            None
        },
    };
    if args.json {
        say!("{}", serde_json::to_string_pretty(&info)?)?;
    } else {
        say!(
            "{} ({:?}): {} samples, channels {}",
            info.name,
            info.format,
            info.samples,
            info.channels.join(",")
        )?;
        say!(
            "  negative values {}, non-finite {}",
            info.negative,
            info.non_finite
        )?;
        if let Some((a, b)) = info.value_range {
            say!("  values [{a:.6e}, {b:.6e}] 1/sr")?;
        }
        say!(
            "  theta_i [{:.2}, {:.2}] deg, theta_o [{:.2}, {:.2}] deg, phi_i [{:.2}, {:.2}], phi_o [{:.2}, {:.2}]",
            info.theta_i_deg.0,
            info.theta_i_deg.1,
            info.theta_o_deg.0,
            info.theta_o_deg.1,
            info.phi_i_deg.0,
            info.phi_i_deg.1,
            info.phi_o_deg.0,
            info.phi_o_deg.1
        )?;
        if let Some(t) = info.measured_theta_max_deg {
            say!(
                "  measured incidence up to {t:.2} deg (the 90 deg node is not a measurement): `brdf resample --to merl` marks bins beyond it invalid (-1); near the horizon f = stored / cos theta_o grows without bound"
            )?;
        }
        if format == crate::data::Format::Curet && !args.path.contains('#') {
            say!("  (CUReT holds 61 samples; shown: sample 1; name one as PATH#N)")?;
        }
    }
    Ok(())
}
