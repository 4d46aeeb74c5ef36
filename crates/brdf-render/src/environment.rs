//! Environment lights discretised by the fixed [`crate::quadrature`]: a
//! list of world directions, each carrying the RGB radiance arriving from it
//! times the solid angle it represents.
//!
//! Why: the sky dome and the studio's constant surround are distant lights
//! that are the same for every shading point, so their directions and
//! weights are computed once. Directions whose radiance is zero (below the
//! horizon of the sky) are left out.

use nalgebra::Vector3;

use crate::quadrature::fibonacci_sphere;
use crate::sky::SunSky;

/// Number of quadrature directions over the whole sphere (about half of them
/// light a given surface point).
pub const ENV_DIRECTIONS: usize = 512;

/// One incident direction (world, unit, pointing away from the surface
/// towards the light) and the RGB irradiance it carries at normal incidence
/// (radiance times solid angle; the receiver's cosine is applied later).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Incident {
    /// unit world direction towards the light
    pub dir: Vector3<f64>,
    /// RGB weight `w_c` (irradiance at normal incidence)
    pub weight: [f64; 3],
}

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

/// A distant environment: its radiance and the fixed list of weighted
/// directions that discretises it.
#[derive(Clone, Debug, PartialEq)]
pub struct Environment {
    /// the radiance by direction (what a camera ray that misses sees)
    pub radiance: EnvRadiance,
    /// the directions with non-zero radiance and their weights
    pub incident: Vec<Incident>,
}

impl Environment {
    /// The environment of `radiance`, discretised by [`ENV_DIRECTIONS`]
    /// Fibonacci directions.
    pub fn new(radiance: EnvRadiance) -> Environment {
        Environment {
            radiance,
            incident: discretise(|d| radiance.radiance(d)),
        }
    }

    /// A constant environment of radiance `rgb` from every direction.
    pub fn constant(rgb: [f64; 3]) -> Environment {
        Environment::new(EnvRadiance::Constant(rgb))
    }
}

/// The Fibonacci directions with non-zero `radiance(dir)` and their weights
/// `radiance * 4 pi / n`.
fn discretise(radiance: impl Fn(&Vector3<f64>) -> [f64; 3]) -> Vec<Incident> {
    let d_omega = 4.0 * std::f64::consts::PI / ENV_DIRECTIONS as f64;
    fibonacci_sphere(ENV_DIRECTIONS)
        .into_iter()
        .filter_map(|dir| {
            let l = radiance(&dir);
            (l.iter().any(|&x| x != 0.0)).then(|| Incident {
                dir,
                weight: l.map(|x| x * d_omega),
            })
        })
        .collect()
}
