//! The judge's "sky": Mitsuba 3.9.1's `sunsky` emitter with
//! `sun_direction = [0.5, 0.64, 0.58]` and its other parameters at their
//! defaults (Hosek-Wilkie sky, turbidity 3, ground albedo 0.3, a uniform sun
//! disc of 0.5358 degrees), as a table made by Mitsuba itself.
//!
//! Why a table: the appearance judge renders fits in Mitsuba, and the image
//! objective of the fit pipeline renders them here; both must show the same
//! sky, or the objective optimises for a light the judge never uses. The
//! Hosek-Wilkie model rests on large fitted datasets; rather than
//! reimplement them, `data/make_sunsky.py` evaluates Mitsuba's emitter
//! (`Emitter.eval`) and writes `data/sunsky_table.rs`, which is compiled in
//! (no Python at run time). Regenerate it with the judge's venv:
//! `python crates/brdf-render/data/make_sunsky.py`.
//!
//! What the table holds:
//! - the sky without the sun: RGB radiance on a grid over the upper
//!   hemisphere, [`table::ROWS`] rows uniform in
//!   `x = 1 - sqrt(1 - theta / (pi / 2))` (`theta` the zenith angle; rows
//!   are finer towards the bright horizon) and [`table::COLS`] columns
//!   uniform in the azimuth from the sun's, `dphi` in `[0, pi]` (the sky is
//!   symmetric about the sun's vertical plane; the script checks it).
//!   [`SunSky::radiance`] interpolates bilinearly in `(x, dphi)`; against
//!   Mitsuba at random directions the relative error is 8e-4 on average and
//!   below 1% everywhere (the script prints it into the table's header);
//! - the sun: its direction and its RGB irradiance at normal incidence (the
//!   disc's radiance times its solid angle). The sun is a directional light
//!   here: its 0.27-degree radius is far below the width of any highlight
//!   of the fitted materials.
//!
//! Conventions, found by evaluating Mitsuba: the zenith is world `+z`, and
//! nothing comes from below the `z = 0` plane (the ground is black). The
//! judge camera at `(0, 0, 6)` therefore looks straight down at the sphere:
//! the sky lights the side the camera sees, the background is black, and
//! the sun stands 35.5 degrees above the horizon. Radiances are Mitsuba's
//! own (absolute) values.

use std::f64::consts::{FRAC_PI_2, PI};

use nalgebra::Vector3;

use crate::quadrature::Incident;

/// The table written by `data/make_sunsky.py` (generated; see the module
/// doc). Measured values: some happen to be close to named constants.
#[allow(clippy::approx_constant)]
pub mod table {
    include!("../data/sunsky_table.rs");
}

/// The judge's sun direction (world, unnormalised as `docs/appearance.md` gives it).
pub const SUN_DIRECTION: [f64; 3] = [0.5, 0.64, 0.58];

/// Mitsuba's sky (sun excluded) for the judge's sun, from [`table`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SunSky {
    /// unit sun direction (world, zenith `+z`)
    pub sun: Vector3<f64>,
    /// azimuth of the sun, `atan2(sun.y, sun.x)`
    phi_sun: f64,
}

impl Default for SunSky {
    fn default() -> Self {
        SunSky::judge()
    }
}

impl SunSky {
    /// The judge's sky (the only one tabulated).
    pub fn judge() -> SunSky {
        let sun = Vector3::from(table::SUN_DIRECTION);
        SunSky {
            sun,
            phi_sun: sun.y.atan2(sun.x),
        }
    }

    /// RGB radiance of the sky (without the sun's disc) from world direction
    /// `d` (unit); 0 below the horizon.
    pub fn radiance(&self, d: &Vector3<f64>) -> [f64; 3] {
        if !(d.z >= 0.0) {
            return [0.0; 3];
        }
        let theta = d.z.min(1.0).acos();
        let x = (1.0 - (1.0 - theta / FRAC_PI_2).max(0.0).sqrt()) * (table::ROWS - 1) as f64;
        let mut dphi = (d.y.atan2(d.x) - self.phi_sun).rem_euclid(2.0 * PI);
        if dphi > PI {
            dphi = 2.0 * PI - dphi;
        }
        let y = dphi / PI * (table::COLS - 1) as f64;
        // Cell indices (a non-finite `x` or `y` saturates to 0).
        // `as usize` saturates below at 0 and truncates: the floor of
        // `x, y >= 0` (0 for NaN or below 0, as before) without a call to
        // `floor`.
        let i = (x as usize).min(table::ROWS - 2);
        let j = (y as usize).min(table::COLS - 2);
        let (fx, fy) = (x - i as f64, y - j as f64);
        let at = |r: usize, c: usize| table::SKY[r * table::COLS + c];
        let (a, b, c, e) = (at(i, j), at(i + 1, j), at(i, j + 1), at(i + 1, j + 1));
        std::array::from_fn(|k| {
            a[k] * (1.0 - fx) * (1.0 - fy)
                + b[k] * fx * (1.0 - fy)
                + c[k] * (1.0 - fx) * fy
                + e[k] * fx * fy
        })
    }

    /// The sun as a directional light: its direction and RGB irradiance at
    /// normal incidence.
    pub fn sun_light(&self) -> Incident {
        Incident {
            dir: self.sun,
            weight: table::SUN_IRRADIANCE,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_reproduces_mitsuba_at_the_check_directions() {
        let sky = SunSky::judge();
        for (d, rgb) in table::CHECKS.iter() {
            let l = sky.radiance(&Vector3::from(*d));
            for c in 0..3 {
                assert!(
                    (l[c] / rgb[c] - 1.0).abs() < 0.01,
                    "{d:?}: {l:?} vs Mitsuba {rgb:?}"
                );
            }
        }
    }

    #[test]
    fn sky_is_black_below_the_horizon_blue_at_the_zenith_and_the_sun_is_the_spec_s() {
        let sky = SunSky::judge();
        assert_eq!(sky.radiance(&-Vector3::z()), [0.0; 3]);
        assert_eq!(
            sky.radiance(&Vector3::new(0.6, 0.0, -0.8)),
            [0.0; 3],
            "below the horizon"
        );
        let zenith = sky.radiance(&Vector3::z());
        assert!(zenith[2] > zenith[1] && zenith[1] > zenith[0] && zenith[0] > 0.0);
        // Brighter towards the horizon, and symmetric about the sun's plane.
        let horizon = sky.radiance(&Vector3::new(-0.5, -0.64, 0.05).normalize());
        assert!(horizon[1] > 2.0 * zenith[1]);
        let m = Vector3::new(0.3, -0.2, 0.6).normalize();
        let h = Vector3::new(sky.sun.x, sky.sun.y, 0.0).normalize();
        let mirrored =
            2.0 * m.dot(&h) * h - Vector3::new(m.x, m.y, 0.0) + Vector3::new(0.0, 0.0, m.z);
        let (a, b) = (sky.radiance(&m), sky.radiance(&mirrored));
        for c in 0..3 {
            assert!((a[c] - b[c]).abs() < 1e-12 * a[c].max(1.0));
        }
        assert!((sky.sun - Vector3::from(SUN_DIRECTION).normalize()).norm() < 1e-6);
        // The sun's irradiance is its disc radiance times the disc's solid angle.
        let half = (table::SUN_APERTURE_DEG / 2.0).to_radians();
        let omega = 2.0 * PI * (1.0 - half.cos());
        let sun = SunSky::judge().sun_light();
        for c in 0..3 {
            let e = table::SUN_RADIANCE[c] * omega;
            assert!((sun.weight[c] / e - 1.0).abs() < 1e-5, "{c}");
        }
        assert_eq!(table::MITSUBA_VERSION, "3.9.1");
    }
}
