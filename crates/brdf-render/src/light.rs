//! Named light sets: what lights the judge sphere. Each gives, for a surface
//! point seen from a direction `v`, a list of weighted incident directions
//! (world, unit, towards the light) with RGB weights (the environments'
//! directions are cells of half-vector space about the point's normal,
//! the mirror direction at their centre: [`crate::quadrature`]), so that the pixel radiance is
//! `L_c = sum_k w_kc f_c(v, l_k) max(0, n . l_k)` (the camera's direction first, as
//! renderers evaluate: [`crate::shading`]).
//!
//! - `directional`: one distant light of irradiance 1 (the study's light,
//!   `(0.5, 0.5, 0.707)` normalised, unless another direction is given);
//! - `sky`: Mitsuba's `sunsky` (Hosek-Wilkie sky dome plus a sun), tabulated
//!   from Mitsuba ([`crate::sky`]);
//! - `studio`: a constant surround of radiance 0.05 plus a 1.2 x 1.2 square
//!   light of radiance 12 at `(3, 3, 4)` facing the sphere
//!   ([`crate::area_light`], 8 x 8 points). The square's occlusion of the
//!   surround (0.06 sr at radiance 0.05) is neglected.
//!
//! Why: the appearance spec judges fits under `sky` and `studio`; the
//! directional light keeps the study's figures comparable.

use nalgebra::Vector3;

use crate::RenderError;
use crate::area_light::SquareLight;
use crate::environment::{EnvRadiance, Environment};
use crate::quadrature::Incident;
use crate::sky::SunSky;

/// The names [`LightSet::parse`] accepts.
pub const LIGHT_SET_NAMES: [&str; 3] = ["directional", "sky", "studio"];

/// A light set of the judge scene.
#[derive(Clone, Debug, PartialEq)]
pub enum LightSet {
    /// one directional light of irradiance 1 (RGB white) from `dir`
    Directional(Vector3<f64>),
    /// sky dome and sun
    Sky {
        /// the dome
        dome: Environment,
        /// the sun
        sun: Incident,
    },
    /// constant surround and a square area light
    Studio {
        /// the surround
        surround: Environment,
        /// the key light
        key: SquareLight,
    },
}

impl LightSet {
    /// One directional light of irradiance 1 from `dir` (normalised).
    pub fn directional(dir: Vector3<f64>) -> Result<LightSet, RenderError> {
        dir.try_normalize(1e-12)
            .map(LightSet::Directional)
            .ok_or_else(|| {
                RenderError::Invalid("directional: dir is zero: give a light direction".into())
            })
    }

    /// The study's directional light, `(0.5, 0.5, 0.707)` normalised.
    pub fn study_directional() -> LightSet {
        LightSet::Directional(Vector3::new(0.5, 0.5, 0.707).normalize())
    }

    /// The judge's sky set.
    pub fn sky() -> LightSet {
        let sky = SunSky::judge();
        LightSet::Sky {
            dome: Environment::new(EnvRadiance::SunSky(sky)),
            sun: sky.sun_light(),
        }
    }

    /// The judge's studio set.
    pub fn studio() -> LightSet {
        let key = SquareLight::look_at(
            Vector3::new(3.0, 3.0, 4.0),
            Vector3::zeros(),
            Vector3::y(),
            1.2,
            [12.0; 3],
            8,
        );
        LightSet::Studio {
            surround: Environment::constant([0.05; 3]),
            key,
        }
    }

    /// The light set called `name` (one of [`LIGHT_SET_NAMES`];
    /// `directional` is the study's light).
    pub fn parse(name: &str) -> Result<LightSet, RenderError> {
        match name {
            "directional" => Ok(LightSet::study_directional()),
            "sky" => Ok(LightSet::sky()),
            "studio" => Ok(LightSet::studio()),
            _ => Err(RenderError::UnknownLightSet {
                name: name.to_string(),
                choices: LIGHT_SET_NAMES.join(", "),
            }),
        }
    }

    /// The set's name.
    pub fn name(&self) -> &'static str {
        match self {
            LightSet::Directional(_) => "directional",
            LightSet::Sky { .. } => "sky",
            LightSet::Studio { .. } => "studio",
        }
    }

    /// Whether every light of the set has one colour, white (equal RGB
    /// channels): renders under it keep each value's hue
    /// ([`crate::colour_plane`]). The study's light and `studio` are; the
    /// sky is not.
    pub fn is_white(&self) -> bool {
        let grey = |c: &[f64; 3]| c[0] == c[1] && c[1] == c[2];
        match self {
            LightSet::Directional(_) => true,
            LightSet::Sky { .. } => false,
            LightSet::Studio { surround, key } => {
                matches!(&surround.radiance, EnvRadiance::Constant(c) if grey(c))
                    && grey(&key.radiance)
            }
        }
    }

    /// RGB radiance a camera ray that misses the sphere sees in world
    /// direction `dir` (the environment; the directional light, the sun and
    /// the key light are not seen: they are out of the judge camera's view).
    pub fn background(&self, dir: &Vector3<f64>) -> [f64; 3] {
        match self {
            LightSet::Directional(_) => [0.0; 3],
            LightSet::Sky { dome, .. } => dome.radiance.radiance(dir),
            LightSet::Studio { surround, .. } => surround.radiance.radiance(dir),
        }
    }

    /// Append the incident directions and weights at the unit-sphere point
    /// `p` (also its normal), seen from unit direction `v` (towards the
    /// camera), to `out` (the receiver's cosine is not applied; the
    /// environments' directions depend on `v`: [`crate::quadrature`]).
    pub fn incident_at(&self, p: &Vector3<f64>, v: &Vector3<f64>, out: &mut Vec<Incident>) {
        match self {
            LightSet::Directional(dir) => out.push(Incident {
                dir: *dir,
                weight: [1.0; 3],
            }),
            LightSet::Sky { dome, sun } => {
                dome.incident_at(p, v, out);
                out.push(*sun);
            }
            LightSet::Studio { surround, key } => {
                surround.incident_at(p, v, out);
                key.incident_at(p, out);
            }
        }
    }
}

impl std::str::FromStr for LightSet {
    type Err = RenderError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        LightSet::parse(s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_name_parses_and_unknown_names_list_the_choices() {
        for name in LIGHT_SET_NAMES {
            assert_eq!(LightSet::parse(name).map(|l| l.name()).ok(), Some(name));
        }
        match LightSet::parse("sunset") {
            Err(e @ RenderError::UnknownLightSet { .. }) => {
                let msg = e.to_string();
                assert!(
                    msg.contains("sunset") && msg.contains("directional, sky, studio"),
                    "{msg}"
                );
            }
            other => panic!("expected UnknownLightSet, got {other:?}"),
        }
    }

    #[test]
    fn the_study_light_and_studio_are_white_the_sky_is_not() {
        assert!(LightSet::study_directional().is_white());
        assert!(LightSet::studio().is_white());
        assert!(!LightSet::sky().is_white());
    }

    /// Irradiance at the sphere point nearest the key light against the
    /// analytic irradiance of a parallel square centred on the normal:
    /// `E = 4 L (A/sqrt(1+A^2) atan(B/sqrt(1+A^2)) + B/sqrt(1+B^2) atan(A/sqrt(1+B^2))) / 2`
    /// with `A = B = (side/2) / d` (four corner rectangles; the form factor of
    /// a corner rectangle, Howell's catalogue C-11, times `pi L`).
    #[test]
    fn studio_key_irradiance_matches_the_square_formula() {
        let LightSet::Studio { key, .. } = LightSet::studio() else {
            panic!("studio is not a Studio set");
        };
        let n = key.centre.normalize();
        let d = key.centre.norm() - 1.0;
        let a = 0.6 / d;
        let s = (1.0 + a * a).sqrt();
        let corner = (a / s * (a / s).atan() * 2.0) / 2.0;
        let expect = 4.0 * 12.0 * corner;
        let mut inc = Vec::new();
        key.incident_at(&n, &mut inc);
        assert_eq!(inc.len(), 64);
        let e: f64 = inc
            .iter()
            .map(|i| i.weight[0] * n.dot(&i.dir).max(0.0))
            .sum();
        assert!((e / expect - 1.0).abs() < 1e-3, "{e} vs {expect}");
    }
}
