//! Fit starts of the thin-film model from a scan of its thickness.
//!
//! The film's colour repeats about every 150 nm of thickness, so a local
//! solver started at one thickness finds the fringe nearest to it, not the
//! best one. Each point of a grid of thicknesses (0 to
//! [`THICKNESS_MAX`] every [`THICKNESS_STEP`] nm), film indices and GGX
//! widths is scored by the weighted least squares of the samples with the
//! linear parameters (diffuse colour, film weight) solved exactly; the
//! film's colour is tabulated once per thickness and index over the cosine
//! `V.H` and read per sample by linear interpolation. The best points, at
//! least one fringe apart, become the solver's starts.
//!
//! Residuals are weighted by `cos_i` (the radiance a sample contributes)
//! so that the near-grazing samples, whose values are largest and least
//! certain, do not decide the thickness alone.

use brdf_core::{Parametric, SampleSet};
use nalgebra::{DMatrix, DVector};

use super::airy::film_colour;
use super::model::THICKNESS_MAX;
use crate::coloured_lobes::geometry::LobeGeometry;
use crate::ggx::Masking;

/// Thickness step of the scan, in nm: a fifteenth of a fringe.
pub const THICKNESS_STEP: f64 = 10.0;
/// Film indices the scan tries (the base's is fixed at 1.5).
const FILM_INDICES: [f64; 4] = [1.35, 1.6, 1.9, 2.3];
/// GGX widths the scan tries.
const WIDTHS: [f64; 6] = [0.01, 0.025, 0.05, 0.1, 0.2, 0.4];
/// Base index of every start.
const BASE_INDEX: f64 = 1.5;
/// Coat of every start (index, width), when the model has one.
const COAT: (f64, f64) = (1.5, 0.03);
/// Samples the scan reads at most (every k-th of the data).
const SCAN_SAMPLES: usize = 4000;
/// Nodes of the colour table over `V.H` in `[0, 1]`.
const TABLE: usize = 129;
/// Starts returned.
const STARTS: usize = 6;
/// Least thickness between two returned starts of one film index, in nm.
const APART: f64 = 60.0;

/// What the scan reads of one sample.
struct Row {
    mu: f64,
    q: f64,
    y: Vec<f64>,
    s: [f64; WIDTHS.len()],
    coat: f64,
}

fn rows(model: &dyn Parametric, data: &SampleSet, coat: bool) -> Vec<Row> {
    let nc = model.channels();
    let every = data.len().div_ceil(SCAN_SAMPLES).max(1);
    let pairs = data.pairs();
    (0..data.len())
        .step_by(every)
        .filter_map(|j| {
            let (l, v) = (pairs.l(j), pairs.v(j));
            let geo = LobeGeometry::new(&l, &v)?;
            let y: Vec<f64> = (0..nc).map(|c| data.channel(c)[j]).collect();
            if y.iter().any(|x| !x.is_finite()) {
                return None;
            }
            let s = WIDTHS.map(|a| geo.lobe(a, Masking::HeightCorrelated).0);
            let coat = if coat {
                let f = brdf_core::fresnel::fresnel_dielectric(geo.cos_d, COAT.0);
                f * geo.lobe(COAT.1, Masking::HeightCorrelated).0
            } else {
                0.0
            };
            Some(Row {
                mu: geo.cos_d,
                q: data.weights()[j] * l.z * l.z,
                y,
                s,
                coat,
            })
        })
        .collect()
}

/// The film's colour per channel on [`TABLE`] nodes of `V.H`.
fn colour_table(d: f64, n2: f64, nc: usize) -> Vec<[f64; 3]> {
    (0..TABLE)
        .map(|i| film_colour(i as f64 / (TABLE - 1) as f64, d, n2, BASE_INDEX, nc).value)
        .collect()
}

fn lookup(table: &[[f64; 3]], mu: f64, c: usize) -> f64 {
    let x = mu.clamp(0.0, 1.0) * (TABLE - 1) as f64;
    let i = (x as usize).min(TABLE - 2);
    let t = x - i as f64;
    table[i][c] * (1.0 - t) + table[i + 1][c] * t
}

/// Weighted squared error of the best linear parameters `(kd_c, w)`
/// (clamped to their box) for one table and width; and those parameters.
fn score(rows: &[Row], table: &[[f64; 3]], width: usize, nc: usize) -> (f64, Vec<f64>) {
    let m = nc + 1;
    let inv_pi = std::f64::consts::FRAC_1_PI;
    let (mut g, mut b, mut yy) = (DMatrix::<f64>::zeros(m, m), DVector::<f64>::zeros(m), 0.0);
    for r in rows {
        for c in 0..nc {
            let f = lookup(table, r.mu, c) * r.s[width];
            let y = r.y[c] - r.coat;
            g[(c, c)] += r.q * inv_pi * inv_pi;
            g[(c, nc)] += r.q * inv_pi * f;
            g[(nc, nc)] += r.q * f * f;
            b[c] += r.q * inv_pi * y;
            b[nc] += r.q * f * y;
            yy += r.q * y * y;
        }
    }
    for c in 0..nc {
        g[(nc, c)] = g[(c, nc)];
    }
    let x = match g.clone().lu().solve(&b) {
        Some(x) => x.map(|v| v.clamp(0.0, 1.0)),
        None => return (f64::INFINITY, vec![0.0; m]),
    };
    let cost = yy - 2.0 * x.dot(&b) + x.dot(&(&g * &x));
    (cost, x.iter().copied().collect())
}

/// One scored grid point.
struct Point {
    cost: f64,
    d: f64,
    n2: f64,
    width: f64,
    linear: Vec<f64>,
}

/// Starts for the thin-film `model` fitted to `data`: the best points of
/// the scan, as full parameter vectors in the model's order.
pub fn screened_starts(model: &dyn Parametric, data: &SampleSet) -> Vec<Vec<f64>> {
    let nc = model.channels();
    let np = model.n_params();
    let coat = np == nc + 7;
    if data.channels() != nc || !(np == nc + 5 || coat) || data.is_empty() {
        return Vec::new();
    }
    let rows = rows(model, data, coat);
    let steps = (THICKNESS_MAX / THICKNESS_STEP).round() as usize;
    let mut points = Vec::with_capacity(FILM_INDICES.len() * (steps + 1));
    for n2 in FILM_INDICES {
        for i in 0..=steps {
            let d = i as f64 * THICKNESS_STEP;
            let table = colour_table(d, n2, nc);
            let best = (0..WIDTHS.len())
                .map(|k| (k, score(&rows, &table, k, nc)))
                .min_by(|a, b| a.1.0.total_cmp(&b.1.0));
            if let Some((k, (cost, linear))) = best {
                points.push(Point {
                    cost,
                    d,
                    n2,
                    width: WIDTHS[k],
                    linear,
                });
            }
        }
    }
    points.sort_by(|a, b| a.cost.total_cmp(&b.cost));
    let mut chosen: Vec<&Point> = Vec::with_capacity(STARTS);
    for p in &points {
        let near = chosen
            .iter()
            .any(|c| c.n2 == p.n2 && (c.d - p.d).abs() < APART);
        if p.cost.is_finite() && !near {
            chosen.push(p);
        }
        if chosen.len() == STARTS {
            break;
        }
    }
    chosen
        .iter()
        .map(|p| {
            let mut v = p.linear.clone();
            v.extend([p.width, p.d, p.n2, BASE_INDEX]);
            if coat {
                v.extend([COAT.0, COAT.1]);
            }
            v
        })
        .collect()
}
