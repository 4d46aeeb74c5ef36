//! What a data file holds — format, sample count, channels, invalid
//! values, value range, angle ranges — for `brdf info`.

use brdf_core::cartesian_to_spherical;

use crate::{Format, IoError, format_of, load, rgl, split_sample};

/// A data file described.
#[derive(Clone, Debug)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Description {
    /// The data set's name.
    pub name: String,
    /// Its format.
    pub format: Format,
    /// Sample count.
    pub samples: usize,
    /// Channel names.
    pub channels: Vec<String>,
    /// Negative values.
    pub negative: usize,
    /// NaN or infinite values.
    pub non_finite: usize,
    /// Smallest and largest finite value (1/sr).
    pub value_range: Option<(f64, f64)>,
    /// Range of the incident polar angle (degrees).
    pub theta_i_deg: (f64, f64),
    /// Range of the outgoing polar angle (degrees).
    pub theta_o_deg: (f64, f64),
    /// Range of the incident azimuth (degrees).
    pub phi_i_deg: (f64, f64),
    /// Range of the outgoing azimuth (degrees).
    pub phi_o_deg: (f64, f64),
    /// RGL: the largest measured incidence (degrees); resampled onto MERL,
    /// bins beyond it are invalid.
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "Option::is_none"))]
    pub measured_theta_max_deg: Option<f64>,
    /// CUReT without `#N`: only sample 1 is described (the file holds 61).
    #[cfg_attr(feature = "serde", serde(skip))]
    pub first_of_many: bool,
}

fn range(v: impl Iterator<Item = f64>) -> (f64, f64) {
    v.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
        (a.min(x), b.max(x))
    })
}

/// Describe `spec` (`PATH` or `PATH#SAMPLE`; a CUReT file without `#N`:
/// its first sample).
pub fn describe(spec: &str) -> Result<Description, IoError> {
    let (path, _) = split_sample(spec);
    let format = format_of(&path)?;
    let first_of_many = format == Format::Curet && !spec.contains('#');
    let s = if first_of_many {
        load(&format!("{spec}#1"))?
    } else {
        load(spec)?
    };
    let p = s.pairs();
    let sph: Vec<((f64, f64), (f64, f64))> = (0..s.len())
        .map(|j| {
            (
                cartesian_to_spherical(&p.l(j)),
                cartesian_to_spherical(&p.v(j)),
            )
        })
        .collect();
    let measured_theta_max_deg = if format == Format::Rgl {
        Some(rgl::Rgl::read(&path)?.measured_theta_max().to_degrees())
    } else {
        None
    };
    Ok(Description {
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
        measured_theta_max_deg,
        first_of_many,
    })
}

impl std::fmt::Display for Description {
    /// The readable description, several lines.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (name, format, samples) = (&self.name, self.format, self.samples);
        writeln!(
            f,
            "{name} ({format:?}): {samples} samples, channels {}",
            self.channels.join(",")
        )?;
        writeln!(
            f,
            "  negative values {}, non-finite {}",
            self.negative, self.non_finite
        )?;
        if let Some((a, b)) = self.value_range {
            writeln!(f, "  values [{a:.6e}, {b:.6e}] 1/sr")?;
        }
        let (ti, to, pi, po) = (
            self.theta_i_deg,
            self.theta_o_deg,
            self.phi_i_deg,
            self.phi_o_deg,
        );
        writeln!(
            f,
            "  theta_i [{:.2}, {:.2}] deg, theta_o [{:.2}, {:.2}] deg, phi_i [{:.2}, {:.2}], phi_o [{:.2}, {:.2}]",
            ti.0, ti.1, to.0, to.1, pi.0, pi.1, po.0, po.1
        )?;
        if let Some(t) = self.measured_theta_max_deg {
            writeln!(
                f,
                "  measured incidence up to {t:.2} deg (the 90 deg node is not a measurement): `brdf resample --to merl` marks bins beyond it invalid (-1); near the horizon f = stored / cos theta_o grows without bound"
            )?;
        }
        if self.first_of_many {
            writeln!(
                f,
                "  (CUReT holds 61 samples; shown: sample 1; name one as PATH#N)"
            )?;
        }
        Ok(())
    }
}
