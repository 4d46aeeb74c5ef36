//! Environment lights: distant radiance by direction, discretised per
//! surface point by the half-vector cells of [`crate::quadrature`].
//!
//! Why per point: the sky dome and the studio's constant surround are the
//! same for every shading point, but a glossy BRDF samples them around each
//! point's mirror direction; cells laid out about the normal in half-vector
//! space (the mirror direction at their centre) render the reflection of a
//! smooth environment smoothly (see [`crate::quadrature`]).
//! Cells whose radiance is zero (below the horizon of the sky) are left out.

use nalgebra::Vector3;

use crate::quadrature::{EnvironmentCells, Incident};
use crate::sky::SunSky;

/// The radiance of a distant environment by direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum EnvRadiance {
    /// the same RGB radiance from every direction
    Constant([f64; 3]),
    /// Mitsuba's `sunsky` sky dome without the sun ([`SunSky`])
    SunSky(SunSky),
}

impl EnvRadiance {
    /// RGB radiance arriving from world direction `dir` (unit).
    pub fn radiance(&self, dir: &Vector3<f64>) -> [f64; 3] {
        match self {
            EnvRadiance::Constant(rgb) => *rgb,
            EnvRadiance::SunSky(sky) => sky.radiance(dir),
        }
    }
}

/// A distant environment: its radiance by direction.
#[derive(Clone, Debug, PartialEq)]
pub struct Environment {
    /// the radiance by direction (what a camera ray that misses sees)
    pub radiance: EnvRadiance,
}

impl Environment {
    /// The environment of `radiance`.
    pub fn new(radiance: EnvRadiance) -> Environment {
        Environment { radiance }
    }

    /// A constant environment of radiance `rgb` from every direction.
    pub fn constant(rgb: [f64; 3]) -> Environment {
        Environment::new(EnvRadiance::Constant(rgb))
    }

    /// Append the environment's incident directions and weights at a point
    /// of unit normal `n` seen from unit direction `v` (world): the cells of
    /// [`EnvironmentCells`] about the point's normal in half-vector space.
    pub fn incident_at(&self, n: &Vector3<f64>, v: &Vector3<f64>, out: &mut Vec<Incident>) {
        EnvironmentCells::get().incident_at(n, v, |d| self.radiance.radiance(d), out);
    }
}
