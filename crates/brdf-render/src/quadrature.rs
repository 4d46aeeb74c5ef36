//! The quadrature of environment light at one surface point: cells of
//! half-vector space about the normal, fine near it and coarse far from it.
//!
//! A pixel's environment term is `∫ L(l) f(v, l) cos+(n . l) dl`. It is
//! discretised as `sum_cells f(v, l_cell) W_cell` with
//! `W_cell = ∫_cell L(l) cos+(n . l) dl` (integrated finely, once per
//! point: it does not depend on the BRDF). The only approximation is `f`
//! constant over a cell, so the cells must be small where a glossy `f`
//! varies fast. A microfacet lobe is a function of the half vector
//! `h = (l + v) / |l + v|` and is round about the normal there whatever
//! the view, where in the incident direction it is a thin band at grazing
//! views; so the cells are laid out in half-vector space and mapped to
//! incident directions by the reflection `l = 2 (v . h) h - v`, whose
//! Jacobian is `dl = 4 (v . h) dh`. Rings about the normal have angular
//! radii growing geometrically from [`INNER_RADIUS`] by [`RING_GROWTH`] up
//! to `pi / 2`, each split into [`SECTORS`] azimuthal sectors, the azimuth
//! measured from the view's tangent (the cells are symmetric about the
//! plane of incidence). The cap holds the mirror direction. A cell is
//! evaluated at the `W`-weighted mean of its sub-cells' polar angles (each
//! the geometric mean of its radii, where a lobe's `rho^-4` tail equals
//! its mean over the ring) and azimuths: a point of the ring, where a
//! direction centroid would fall inside it.
//!
//! What the layout resolves (the unit tests, against a fine integration in
//! the lobe's own variable): GGX lobes from `alpha = 0.001` (the narrowest
//! the renderer models allow) to 0.4 within 2% to a 60-degree view and 4%
//! to 88 degrees; an anisotropic lobe of aspect 5 within 8%; a constant
//! environment's irradiance within 0.2%. About 360 cells above the
//! horizon.
//!
//! Why not cells about the mirror direction in the incident directions
//! (this module until issue 23's second follow-up, after a spherical
//! Fibonacci set of 512 directions): their cap of 0.005 rad was wider than
//! a sharp lobe, which it then counted at its peak over the whole cap:
//! `alpha = 0.001` came out 6 to 36 times too bright. The image objective
//! found that error (paper_white refined to a faint mirror of metallic
//! 0.004 that brdf-render showed as a coat of gloss), and the judge
//! ranked paper_white's Ngan fit (`roughness` 0.05) at sky FLIP 0.085
//! where Mitsuba renders it at 0.053. At grazing views the rings resolved
//! a lobe coarsely (0.82 of it at 88 degrees).
//!
//! `W_cell` is the sum over sub-cells no wider than [`SUB_CELL`] radians
//! of half-vector space, each at its solid-angle centroid; the sub-cells
//! whose incident direction is below the point's horizon (or whose half
//! vector faces away from the view) are skipped before the radiance is
//! looked up. The sub-cells are laid out once, about `+z`
//! ([`HalfVectorCells::get`]); a point only rotates them.

use std::f64::consts::{FRAC_PI_2, PI};
use std::sync::OnceLock;

use nalgebra::Vector3;

use crate::environment::Incident;

/// Angular radius (radians, in half-vector space) of the cap about the
/// normal that is one cell: a third of the narrowest GGX width the
/// renderer models allow (`alpha = 0.001`).
pub const INNER_RADIUS: f64 = 3e-4;
/// Ratio of consecutive ring radii.
pub const RING_GROWTH: f64 = 1.3;
/// Azimuthal sectors of every ring but the cap.
pub const SECTORS: usize = 12;
/// Largest angular extent (radians, half-vector space) of a sub-cell of
/// `W`'s sums: at most twice that in the incident direction.
pub const SUB_CELL: f64 = 0.05;

/// One sub-cell of half-vector space, about `+z` (the normal), azimuth
/// measured from `+x` (towards the view's tangent).
#[derive(Clone, Copy, Debug)]
struct SubCell {
    /// unit half vector at the sub-cell's solid-angle centroid
    dir: Vector3<f64>,
    /// its polar angle and azimuth
    rho: f64,
    phi: f64,
    /// its solid angle in half-vector space
    solid_angle: f64,
    cell: usize,
}

/// The cells of half-vector space about the normal and their sub-cells
/// (see the module doc).
#[derive(Debug)]
pub struct HalfVectorCells {
    subs: Vec<SubCell>,
    cells: usize,
}

/// Per-cell sums of one point: `W` per channel, and the `W`-weighted sums
/// of the sub-cells' polar angle and azimuth (the evaluation point).
#[derive(Clone, Copy, Default)]
struct CellSum {
    w: [f64; 3],
    weight: f64,
    rho: f64,
    phi: f64,
}

impl HalfVectorCells {
    /// The layout of the module's constants, made once.
    pub fn get() -> &'static HalfVectorCells {
        static CELLS: OnceLock<HalfVectorCells> = OnceLock::new();
        CELLS.get_or_init(|| HalfVectorCells::layout(INNER_RADIUS, RING_GROWTH, SECTORS))
    }

    /// Rings about `+z` from `inner` growing by `growth` up to `pi / 2`,
    /// each but the cap split into `sectors`, each cell into sub-cells no
    /// wider than [`SUB_CELL`].
    fn layout(inner: f64, growth: f64, sectors: usize) -> HalfVectorCells {
        let mut edges = vec![0.0, inner];
        while edges[edges.len() - 1] < FRAC_PI_2 {
            let next = (edges[edges.len() - 1] * growth).min(FRAC_PI_2);
            edges.push(next);
        }
        let mut subs = Vec::new();
        for (ring, ab) in edges.windows(2).enumerate() {
            let (a, b) = (ab[0], ab[1]);
            let n_sectors = if ring == 0 { 1 } else { sectors };
            let sector = 2.0 * PI / n_sectors as f64;
            let n_rho = ((b - a) / SUB_CELL).ceil().max(1.0) as usize;
            let n_phi = (b.sin() * sector / SUB_CELL).ceil().max(1.0) as usize;
            for s in 0..n_sectors {
                let cell = 1 + (ring.max(1) - 1) * sectors + s - usize::from(ring == 0);
                for i in 0..n_rho {
                    let r0 = a + (b - a) * i as f64 / n_rho as f64;
                    let r1 = a + (b - a) * (i + 1) as f64 / n_rho as f64;
                    let (c0, c1) = (r0.cos(), r1.cos());
                    // The solid-angle centroid in rho: mean of cos(rho).
                    let cz = 0.5 * (c0 + c1);
                    let sz = (1.0 - cz * cz).max(0.0).sqrt();
                    for j in 0..n_phi {
                        let phi = sector * (s as f64 + (j as f64 + 0.5) / n_phi as f64);
                        subs.push(SubCell {
                            dir: Vector3::new(sz * phi.cos(), sz * phi.sin(), cz),
                            // The geometric mean of the sub-cell's radii:
                            // where a lobe's tail `rho^-4` equals its mean
                            // over the ring.
                            rho: (r0 * r1).sqrt(),
                            phi,
                            solid_angle: (c0 - c1) * sector / n_phi as f64,
                            cell,
                        });
                    }
                }
            }
        }
        let cells = 1 + (edges.len() - 2) * sectors;
        HalfVectorCells { subs, cells }
    }

    /// Append to `out` the cells of the environment `radiance` at a point
    /// of unit normal `n` seen from unit direction `v` (both world, `v`
    /// above the surface): each cell with non-zero `W` as an [`Incident`]
    /// at its evaluation point, of weight `W / cos(n . w_cell)` (an
    /// irradiance at normal incidence, as [`Incident`] holds; the
    /// receiver's cosine is applied by the caller).
    pub fn incident_at(
        &self,
        n: &Vector3<f64>,
        v: &Vector3<f64>,
        radiance: impl Fn(&Vector3<f64>) -> [f64; 3],
        out: &mut Vec<Incident>,
    ) {
        let (t1, t2) = view_frame(n, v);
        let to_world = |h: &Vector3<f64>| t1 * h.x + t2 * h.y + n * h.z;
        let mut sums = vec![CellSum::default(); self.cells];
        for s in &self.subs {
            let h = to_world(&s.dir);
            let vh = v.dot(&h);
            if vh <= 0.0 {
                continue;
            }
            let l = 2.0 * vh * h - v;
            let cos = n.dot(&l);
            if cos <= 0.0 {
                continue;
            }
            let rad = radiance(&l);
            // dw_l = 4 (v . h) dw_h: the Jacobian of the reflection map.
            let k = cos * 4.0 * vh * s.solid_angle;
            let sum = &mut sums[s.cell];
            for c in 0..3 {
                sum.w[c] += rad[c] * k;
            }
            let m = (rad[0] + rad[1] + rad[2]) * k;
            sum.weight += m;
            sum.rho += s.rho * m;
            sum.phi += s.phi * m;
        }
        for (cell, sum) in sums.iter().enumerate() {
            if !(sum.weight > 0.0) {
                continue;
            }
            // The cap is evaluated at the normal; a ring's cell at the
            // W-weighted mean of its polar angle and azimuth (a point of
            // the ring: a cell's direction centroid would fall inside it).
            let h = if cell == 0 {
                *n
            } else {
                let (rho, phi) = (sum.rho / sum.weight, sum.phi / sum.weight);
                to_world(&Vector3::new(
                    rho.sin() * phi.cos(),
                    rho.sin() * phi.sin(),
                    rho.cos(),
                ))
            };
            let l = 2.0 * v.dot(&h) * h - v;
            let cos = n.dot(&l);
            if !(cos > 0.0) {
                continue;
            }
            out.push(Incident {
                dir: l,
                weight: sum.w.map(|x| x / cos),
            });
        }
    }
}

/// Tangents of the view's frame: `t1` along the view's projection onto
/// the surface (any tangent at normal view), `t2 = n x t1`.
fn view_frame(n: &Vector3<f64>, v: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let along = v - n * n.dot(v);
    let t1 = if along.norm() > 1e-9 {
        along.normalize()
    } else {
        let a = if n.x.abs() < 0.9 {
            Vector3::x()
        } else {
            Vector3::y()
        };
        (a - n * a.dot(n)).normalize()
    };
    (t1, n.cross(&t1))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn irradiance(
        n: &Vector3<f64>,
        v: &Vector3<f64>,
        l: impl Fn(&Vector3<f64>) -> [f64; 3],
    ) -> f64 {
        let mut out = Vec::new();
        HalfVectorCells::get().incident_at(n, v, l, &mut out);
        out.iter().map(|i| i.weight[0] * n.dot(&i.dir)).sum()
    }

    /// The sub-cells tile the hemisphere of half vectors: their solid
    /// angles sum to `2 pi`.
    #[test]
    fn sub_cells_cover_the_hemisphere() {
        let cells = HalfVectorCells::get();
        let total: f64 = cells.subs.iter().map(|s| s.solid_angle).sum();
        assert!((total / (2.0 * PI) - 1.0).abs() < 1e-12, "{total}");
        assert!(
            cells
                .subs
                .iter()
                .all(|s| (s.dir.norm() - 1.0).abs() < 1e-12 && s.dir.z >= 0.0)
        );
    }

    /// A constant environment of radiance 1 gives irradiance `pi` at any
    /// point and view (the cosine integral over the hemisphere), through
    /// the reflection map's Jacobian `4 (v . h)`.
    #[test]
    fn constant_radiance_gives_irradiance_pi() {
        for (n, v) in [
            (Vector3::z(), Vector3::z()),
            (Vector3::z(), Vector3::new(0.6, 0.0, 0.8)),
            (
                Vector3::new(0.3, -0.5, 0.2).normalize(),
                Vector3::new(0.1, 0.0, 1.0).normalize(),
            ),
            (Vector3::z(), Vector3::new(0.999, 0.0, 0.0447).normalize()),
        ] {
            let e = irradiance(&n, &v, |_| [1.0; 3]);
            assert!((e / PI - 1.0).abs() < 2e-3, "n {n:?} v {v:?}: {e}");
        }
    }

    /// Radiance `max(0, w . a)` from direction `a`: irradiance at normal `n`
    /// is `∫ (w.a)+ (w.n)+ dw`, for `a = n` equal to `2 pi / 3`.
    #[test]
    fn cosine_lobe_radiance_gives_two_pi_over_three() {
        let n = Vector3::new(0.2, 0.3, 0.9).normalize();
        let v = Vector3::new(-0.4, 0.1, 0.9).normalize();
        let e = irradiance(&n, &v, |w| [w.dot(&n).max(0.0); 3]);
        assert!((e / (2.0 * PI / 3.0) - 1.0).abs() < 2e-3, "{e}");
    }

    /// The first cell is the cap about the normal in half-vector space:
    /// the mirror direction, of weight `4 (v . n)` times the cap's solid
    /// angle (the reflection map's Jacobian at `h = n`).
    #[test]
    fn the_first_cell_is_the_mirror_direction() {
        let n = Vector3::z();
        let v = Vector3::new(0.5, 0.2, 0.8).normalize();
        let r = 2.0 * n.dot(&v) * n - v;
        let mut out = Vec::new();
        HalfVectorCells::get().incident_at(&n, &v, |_| [1.0; 3], &mut out);
        assert!((out[0].dir - r).norm() < 1e-12);
        let cap = 2.0 * PI * (1.0 - INNER_RADIUS.cos());
        let expect = 4.0 * v.z * cap;
        assert!(
            (out[0].weight[0] / expect - 1.0).abs() < 1e-3,
            "{:?}",
            out[0]
        );
    }

    /// An anisotropic GGX lobe (widths `ax` along the tangent `x`, `ay`),
    /// separable Smith masking, Fresnel 1.
    fn ggx(ax: f64, ay: f64) -> impl Fn(&Vector3<f64>, &Vector3<f64>) -> f64 {
        move |l, v| {
            if l.z <= 0.0 || v.z <= 0.0 {
                return 0.0;
            }
            let h = (l + v).normalize();
            let e = (h.x / ax).powi(2) + (h.y / ay).powi(2) + h.z * h.z;
            let d = 1.0 / (PI * ax * ay * e * e);
            let g1 = |w: &Vector3<f64>| {
                let t2 = ((w.x * ax).powi(2) + (w.y * ay).powi(2)) / (w.z * w.z);
                2.0 / (1.0 + (1.0 + t2).sqrt())
            };
            d * g1(l) * g1(v) / (4.0 * l.z * v.z)
        }
    }

    /// `∫ f(l, v) L(l) cos+(l) dl` at normal `+z` by the cells.
    fn by_cells(
        f: &impl Fn(&Vector3<f64>, &Vector3<f64>) -> f64,
        v: &Vector3<f64>,
        radiance: &impl Fn(&Vector3<f64>) -> f64,
    ) -> f64 {
        let mut out = Vec::new();
        HalfVectorCells::get().incident_at(&Vector3::z(), v, |w| [radiance(w); 3], &mut out);
        out.iter()
            .map(|i| f(&i.dir, v) * i.weight[0] * i.dir.z)
            .sum()
    }

    /// The same integral on a fine grid of half vectors,
    /// `theta_h = atan(alpha tan u)` with `u` uniform (the GGX lobe's
    /// own variable: its density in `u` is smooth for every width), the
    /// azimuth uniform; `dl = 4 (v . h) dh`.
    fn fine(
        f: &impl Fn(&Vector3<f64>, &Vector3<f64>) -> f64,
        alpha: f64,
        v: &Vector3<f64>,
        radiance: &impl Fn(&Vector3<f64>) -> f64,
    ) -> f64 {
        let u_max = ((0.99999 * FRAC_PI_2).tan() / alpha).atan();
        let (nu, np) = (3000, 2400);
        let du = u_max / nu as f64;
        let mut sum = 0.0;
        for i in 0..nu {
            let u = (i as f64 + 0.5) * du;
            let th = (alpha * u.tan()).atan();
            let dth = alpha / (u.cos().powi(2) * (1.0 + (alpha * u.tan()).powi(2))) * du;
            for j in 0..np {
                let p = 2.0 * PI * (j as f64 + 0.5) / np as f64;
                let h = Vector3::new(th.sin() * p.cos(), th.sin() * p.sin(), th.cos());
                let vh = v.dot(&h);
                let l = 2.0 * vh * h - v;
                if vh <= 0.0 || l.z <= 0.0 {
                    continue;
                }
                let dl = 4.0 * vh * th.sin() * dth * 2.0 * PI / np as f64;
                sum += f(&l, v) * radiance(&l) * l.z * dl;
            }
        }
        sum
    }

    fn view(deg: f64) -> Vector3<f64> {
        let t = deg.to_radians();
        Vector3::new(t.sin(), 0.0, t.cos())
    }

    /// GGX lobes from the narrowest width the renderer models allow
    /// (`alpha = 0.001`) to a broad one, at views from the pole to 88 deg
    /// (the sphere's outermost pixels), against [`fine`]: within 2% to
    /// 60 deg, 4% beyond (measured: 0.997-1.019 to 60 deg, 0.967 for
    /// `alpha = 0.4` at 88 deg). Under the mirror-direction rings this
    /// module had before (cap 0.005 rad), `alpha = 0.001` came out 6.4
    /// times too bright at the pole and 36 times at 80 deg, and
    /// `alpha = 0.05` 15% too dark at 80 deg.
    #[test]
    fn ggx_lobes_of_every_width_match_a_fine_integration() {
        let one = |_: &Vector3<f64>| 1.0;
        for alpha in [0.001, 0.004, 0.02, 0.1, 0.4] {
            let f = ggx(alpha, alpha);
            for (deg, tol) in [
                (0.0, 0.02),
                (30.0, 0.02),
                (60.0, 0.02),
                (80.0, 0.04),
                (88.0, 0.04),
            ] {
                let v = view(deg);
                let (c, r) = (by_cells(&f, &v, &one), fine(&f, alpha, &v, &one));
                assert!(
                    (c / r - 1.0).abs() < tol,
                    "alpha {alpha} view {deg}: {c} vs {r}"
                );
            }
        }
    }

    /// An anisotropic lobe (widths 0.03 and 0.15, turned 40 deg from the
    /// plane of incidence) under a non-constant environment: within 10%
    /// (measured 1.035-1.081: a sector of 30 deg is coarse for a lobe of
    /// aspect 5; 16 sectors would give 0.99 at a third more terms, 8
    /// sectors 0.73).
    #[test]
    fn an_anisotropic_lobe_under_a_varying_sky_matches() {
        let (ax, ay, turn) = (0.03, 0.15, 40f64.to_radians());
        let g = ggx(ax, ay);
        let (c, s) = (turn.cos(), turn.sin());
        let f = |l: &Vector3<f64>, v: &Vector3<f64>| {
            let rot = |w: &Vector3<f64>| Vector3::new(c * w.x + s * w.y, -s * w.x + c * w.y, w.z);
            g(&rot(l), &rot(v))
        };
        let sky = |w: &Vector3<f64>| 1.0 + 0.8 * w.x + 0.5 * w.y.max(0.0) + 2.0 * w.z * w.z;
        for deg in [0.0, 45.0, 75.0] {
            let v = view(deg);
            let (c, r) = (by_cells(&f, &v, &sky), fine(&f, ax, &v, &sky));
            assert!((c / r - 1.0).abs() < 0.1, "view {deg}: {c} vs {r}");
        }
    }
}
