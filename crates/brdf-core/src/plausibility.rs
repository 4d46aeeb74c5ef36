//! Physical-plausibility checks usable on any [`Brdf`]: reciprocity,
//! non-negativity and energy conservation over a deterministic set of
//! directions that includes the pole and near-grazing angles.

use nalgebra::Vector3;

use crate::quadrature::{AlbedoFrame, QuadratureOptions, directional_albedo};
use crate::{Brdf, spherical_to_cartesian};

/// A deterministic set of directions above the horizon: `n_theta` polar angles
/// from the pole (0) to `pi/2 - grazing` inclusive, times `n_phi` azimuths
/// (one at the pole).
pub fn hemisphere_directions(n_theta: usize, n_phi: usize, grazing: f64) -> Vec<Vector3<f64>> {
    let mut out = vec![Vector3::z()];
    let top = std::f64::consts::FRAC_PI_2 - grazing;
    for i in 1..n_theta.max(2) {
        let theta = top * i as f64 / (n_theta.max(2) - 1) as f64;
        for j in 0..n_phi.max(1) {
            let phi = 2.0 * std::f64::consts::PI * (j as f64 + 0.25) / n_phi.max(1) as f64;
            out.push(spherical_to_cartesian(theta, phi));
        }
    }
    out
}

/// The worst reciprocity violation found.
#[derive(Clone, Debug, PartialEq)]
pub struct ReciprocityReport {
    /// `max |f(L,V) - f(V,L)|` over pairs and channels.
    pub max_abs: f64,
    /// `max |f(L,V) - f(V,L)| / max(|f(L,V)|, |f(V,L)|)` (0 where both are 0).
    pub max_rel: f64,
    /// Pairs examined.
    pub pairs: usize,
}

/// Maximum deviation from `f(L, V) = f(V, L)` over all pairs of `dirs`.
pub fn reciprocity_deviation(
    brdf: &(impl Brdf + ?Sized),
    dirs: &[Vector3<f64>],
) -> ReciprocityReport {
    let nc = brdf.channels();
    let (mut a, mut b) = (vec![0.0; nc], vec![0.0; nc]);
    let mut rep = ReciprocityReport {
        max_abs: 0.0,
        max_rel: 0.0,
        pairs: 0,
    };
    for (i, l) in dirs.iter().enumerate() {
        for v in &dirs[i..] {
            brdf.eval(l, v, &mut a);
            brdf.eval(v, l, &mut b);
            rep.pairs += 1;
            for c in 0..nc {
                let d = (a[c] - b[c]).abs();
                let m = a[c].abs().max(b[c].abs());
                rep.max_abs = rep.max_abs.max(d);
                if m > 0.0 {
                    rep.max_rel = rep.max_rel.max(d / m);
                }
            }
        }
    }
    rep
}

/// Result of a non-negativity (and finiteness) scan.
#[derive(Clone, Debug, PartialEq)]
pub struct NonNegativityReport {
    /// Smallest value seen over all pairs and channels.
    pub min_value: f64,
    /// The pair where it was seen.
    pub at: (Vector3<f64>, Vector3<f64>),
    /// Values below zero.
    pub negative: usize,
    /// Values that were NaN or infinite.
    pub non_finite: usize,
    /// Values examined.
    pub values: usize,
}

/// Scan all ordered pairs of `dirs` for negative and non-finite values.
pub fn nonnegativity_scan(
    brdf: &(impl Brdf + ?Sized),
    dirs: &[Vector3<f64>],
) -> NonNegativityReport {
    let nc = brdf.channels();
    let mut a = vec![0.0; nc];
    let mut rep = NonNegativityReport {
        min_value: f64::INFINITY,
        at: (Vector3::z(), Vector3::z()),
        negative: 0,
        non_finite: 0,
        values: 0,
    };
    for l in dirs {
        for v in dirs {
            brdf.eval(l, v, &mut a);
            for &x in &a {
                rep.values += 1;
                if !x.is_finite() {
                    rep.non_finite += 1;
                } else {
                    if x < 0.0 {
                        rep.negative += 1;
                    }
                    if x < rep.min_value {
                        rep.min_value = x;
                        rep.at = (*l, *v);
                    }
                }
            }
        }
    }
    rep
}

/// The largest directional albedo (value plus its error estimate) over the
/// given incident directions, per channel, with the direction where it occurs.
#[derive(Clone, Debug, PartialEq)]
pub struct EnergyReport {
    /// `max_L a_c(L)` per channel.
    pub max_albedo: Vec<f64>,
    /// Error estimate of that albedo.
    pub error: Vec<f64>,
    /// The incident direction of the maximum, per channel.
    pub at: Vec<Vector3<f64>>,
}

impl EnergyReport {
    /// True when `a + error <= 1` in every channel.
    pub fn conserves_energy(&self) -> bool {
        self.max_albedo
            .iter()
            .zip(&self.error)
            .all(|(a, e)| a + e <= 1.0)
    }
}

/// Largest directional albedo over the incident directions `dirs`.
pub fn energy_scan(
    brdf: &(impl Brdf + ?Sized),
    dirs: &[Vector3<f64>],
    frame: AlbedoFrame,
    opts: &QuadratureOptions,
) -> EnergyReport {
    let nc = brdf.channels();
    let mut rep = EnergyReport {
        max_albedo: vec![f64::NEG_INFINITY; nc],
        error: vec![0.0; nc],
        at: vec![Vector3::z(); nc],
    };
    for l in dirs {
        let a = directional_albedo(brdf, l, frame, opts);
        for c in 0..nc {
            if a.value[c] > rep.max_albedo[c] {
                rep.max_albedo[c] = a.value[c];
                rep.error[c] = a.error[c];
                rep.at[c] = *l;
            }
        }
    }
    rep
}
