//! The image errors of a fit: per light set HDR-FLIP, PSNR and the
//! CIEDE2000 difference of the mean sphere colours ([`LightError`]), over
//! the judge's light sets with the data's distance from every colour plane
//! ([`ImageError`]), and the plain-words warnings a report gives when a fit
//! will not look like the data.
//!
//! Thresholds of the warnings ([`ImageError::warnings`]): mean-colour
//! CIEDE2000 above [`DELTA_E_WARN`] (a colour difference an observer names
//! at a glance; 2.3 is a just-noticeable difference) and HDR-FLIP above
//! [`FLIP_WARN`] (two renders of the same measurement with different noise
//! differ by 0.02-0.05; the films' default fits before the appearance fit
//! were at 0.3-0.6).

use serde::Serialize;

/// Mean-colour CIEDE2000 above which a report warns.
pub const DELTA_E_WARN: f64 = 5.0;
/// HDR-FLIP above which a report warns.
pub const FLIP_WARN: f64 = 0.15;

/// The image errors of a fit (or any test render) under one light set,
/// against the data's (the reference's) render.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct LightError {
    /// Light set name.
    pub light: String,
    /// Mean HDR-FLIP over the image (0: identical).
    pub flip: f64,
    /// PSNR (dB) after the data's exposure, clip, gamma 2.2.
    pub psnr: f64,
    /// CIEDE2000 between the mean sphere colours.
    pub delta_e: f64,
    /// Mean linear RGB of the data's sphere.
    pub mean_colour_data: [f64; 3],
    /// Mean linear RGB of the fit's sphere.
    pub mean_colour_fit: [f64; 3],
    /// Exposure `1 / p99` of the data's render.
    pub exposure: f64,
}

/// The image errors of a fit under the standard light sets.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct ImageError {
    /// Image size (pixels per side).
    pub size: usize,
    /// One entry per light set.
    pub lights: Vec<LightError>,
    /// The data's colours against the planes of white and one colour,
    /// under the first white light set ([`DataColourPlane`]); `None` when
    /// no light set is white or the data's render is black.
    pub colour_plane: Option<DataColourPlane>,
}

/// How far the data's render under a white light set lies from every
/// plane of white and one colour ([`crate::colour_plane`]): no fit
/// of a model that colours every lobe white or by its one base colour
/// (`principled`, `gltf`) renders closer to it than `outside`.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct DataColourPlane {
    /// The white light set it was measured under.
    pub light: String,
    /// The closest plane's colour (linear RGB, largest channel 1).
    pub colour: [f64; 3],
    /// RMS distance of the data's sphere colours from that plane over
    /// their RMS (linear RGB): the least relative RMS difference any render
    /// of a single-colour model can have.
    pub outside: f64,
}

impl ImageError {
    /// Mean FLIP over the light sets (the ranking of candidates).
    pub fn mean_flip(&self) -> f64 {
        self.lights.iter().map(|l| l.flip).sum::<f64>() / self.lights.len().max(1) as f64
    }

    /// Largest HDR-FLIP over the light sets.
    pub fn max_flip(&self) -> f64 {
        self.lights.iter().map(|l| l.flip).fold(0.0, f64::max)
    }

    /// Largest mean-colour difference over the light sets.
    pub fn max_delta_e(&self) -> f64 {
        self.lights.iter().map(|l| l.delta_e).fold(0.0, f64::max)
    }

    /// Plain-words warnings when the fit will not look like the data.
    pub fn warnings(&self) -> Vec<String> {
        let mut out = Vec::new();
        for l in &self.lights {
            if l.delta_e > DELTA_E_WARN {
                out.push(format!(
                    "under the {} light the fit's colour differs visibly from the data's (CIEDE2000 {:.1} > {DELTA_E_WARN}): data mean RGB {}, fit {}",
                    l.light,
                    l.delta_e,
                    rgb(l.mean_colour_data, l.exposure),
                    rgb(l.mean_colour_fit, l.exposure)
                ));
            }
            if l.flip > FLIP_WARN {
                out.push(format!(
                    "under the {} light the fit renders unlike the data (FLIP {:.3} > {FLIP_WARN})",
                    l.light, l.flip
                ));
            }
        }
        out
    }
}

fn rgb(c: [f64; 3], exposure: f64) -> String {
    format!(
        "({:.2}, {:.2}, {:.2})",
        c[0] * exposure,
        c[1] * exposure,
        c[2] * exposure
    )
}
