//! A square area light at finite distance (Mitsuba's `rectangle` emitter),
//! discretised into a fixed grid of points.
//!
//! Why: the studio set's key light is close enough that its direction and
//! strength change over the sphere, so its incident directions depend on the
//! shading point. The square is split into `grid x grid` equal cells; the
//! cell centre `q` lights point `p` from `l = (q - p) / |q - p|` with weight
//! `L_e (A / n) cos_light / |q - p|^2` (the solid angle of the cell seen
//! from `p`), `cos_light = max(0, -n_light . l)`. The light emits on the side
//! its normal points to. Occlusion of the light by the sphere itself is the
//! receiver's `n . l <= 0` test (the sphere is convex).

use nalgebra::Vector3;

use crate::quadrature::Incident;

/// A square emitter: centre, in-plane unit axes, emitting normal, side
/// length, RGB radiance and the quadrature grid.
#[derive(Clone, Debug, PartialEq)]
pub struct SquareLight {
    /// centre (world)
    pub centre: Vector3<f64>,
    /// first in-plane unit axis
    pub u: Vector3<f64>,
    /// second in-plane unit axis
    pub v: Vector3<f64>,
    /// unit normal, the side that emits
    pub normal: Vector3<f64>,
    /// side length
    pub side: f64,
    /// RGB radiance `L_e`
    pub radiance: [f64; 3],
    /// cells per side of the quadrature grid
    pub grid: usize,
}

impl SquareLight {
    /// A square of `side` and `radiance` centred at `origin`, facing
    /// `target` (Mitsuba's `look_at(origin, target, up)` then a scale of
    /// `side / 2` applied to the `[-1, 1]^2` rectangle).
    pub fn look_at(
        origin: Vector3<f64>,
        target: Vector3<f64>,
        up: Vector3<f64>,
        side: f64,
        radiance: [f64; 3],
        grid: usize,
    ) -> SquareLight {
        let normal = (target - origin).normalize();
        let u = up.cross(&normal).normalize();
        let v = normal.cross(&u);
        SquareLight {
            centre: origin,
            u,
            v,
            normal,
            side,
            radiance,
            grid,
        }
    }

    /// The grid's incident directions and weights at the surface point `p`
    /// (cells behind the light's emitting side are left out).
    pub fn incident_at(&self, p: &Vector3<f64>, out: &mut Vec<Incident>) {
        let n = self.grid * self.grid;
        let cell_area = self.side * self.side / n as f64;
        for i in 0..self.grid {
            for j in 0..self.grid {
                let a = ((i as f64 + 0.5) / self.grid as f64 - 0.5) * self.side;
                let b = ((j as f64 + 0.5) / self.grid as f64 - 0.5) * self.side;
                let q = self.centre + self.u * a + self.v * b;
                let d = q - p;
                let dist2 = d.norm_squared();
                let l = d / dist2.sqrt();
                let cos_light = -self.normal.dot(&l);
                if cos_light <= 0.0 {
                    continue;
                }
                let g = cell_area * cos_light / dist2;
                out.push(Incident {
                    dir: l,
                    weight: self.radiance.map(|x| x * g),
                });
            }
        }
    }
}
