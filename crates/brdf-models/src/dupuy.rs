//! Tabulated microfacet model extracted from data (Dupuy, Heitz, Iehl,
//! Poulin & Ostromoukhov 2015, "Extracting Microfacet-based BRDF Parameters
//! from Arbitrary Materials with Power Iterations", Computer Graphics Forum
//! 34(4)).
//!
//! In the back-scattering configuration `L = V = w` the half vector is `w`
//! and masking and shadowing are fully correlated (`G(w, w) = G1(w)`), so a
//! microfacet BRDF `f = F D G / (4 (N.L)(N.V))` with a constant Fresnel
//! factor gives, with Smith's `G1(w) = cos(theta) / sigma(w)` and the
//! projected area `sigma(w) = integral <w, m>+ D(m) dm`,
//!
//! `rho(w) = f(w, w) = F D(w) / (4 cos(theta) sigma(w))`, so
//! `D(w) = (4 / F) rho(w) cos(theta) sigma(w)[D]`:
//!
//! `D` is the positive eigenvector of the linear operator
//! `D -> rho cos(theta) sigma[D]`, with eigenvalue `F / 4`. Power iteration
//! (apply, normalise `integral D cos dm = 1`, repeat) finds it; no model of
//! `D` is assumed. The extraction is exact (to the quadrature's error) for
//! data of that form, as the tests check on GGX and Beckmann data
//! (derivation in `docs/derivations/fitted_microfacet_models.md`).
//!
//! [`TabulatedNdf`] holds the isotropic `D(theta)` at nodes
//! `theta_j = theta_max (j / (n - 1))^2` (dense near the pole, where sharp
//! lobes live), linearly interpolated; `theta_max = (pi/2)(1 - 1e-4)`, `D`
//! constant beyond (and integrated so). `sigma` is a matrix applied to the node values: the
//! azimuthal integral of `<w, m>+` in closed form, the polar one by
//! Simpson's rule on four sub-steps per table interval. Its GGX and
//! Beckmann widths are read off by least squares on `D cos sin`
//! ([`TabulatedNdf::fit_ggx_alpha`], [`TabulatedNdf::fit_beckmann_alpha`]).
//!
//! [`TabulatedMicrofacet`] is the BRDF
//! `f_c = F_c D(H) G(L, V) / (4 (N.L)(N.V))` with Smith's `G1` computed from
//! the table and `G = min(G1(L), G1(V))` (masking and shadowing fully
//! correlated: Heitz 2014's direction-correlated form at its limit, the
//! form under which `G(w, w) = G1(w)`, the extraction's assumption). Its
//! parameters are the per-channel factors `F_c` (linear, `[0, inf)`), the
//! product of Fresnel and scale (a Fresnel curve in `V.H` cannot be read
//! from back-scattering, where `V.H = 1`). It implements [`Parametric`] in
//! the `F_c` so a solver can refine them on the full data.
//!
//! [`Dupuy`] is the catalogue's model (`dupuy`): the table extracted from
//! the samples it is fitted to (the catalogue's data-dependent build,
//! [`ModelEntry::from_samples`](crate::ModelEntry::from_samples)), with
//! the free parameters a fit then solves, all linear:
//!
//! `f_c = kd_c / pi + (F_c + S_c (1 - V.H)^5) D(H) G(L, V) / (4 (N.L)(N.V))`,
//!
//! | parameter (per channel) | meaning | default box | linear |
//! | --- | --- | --- | --- |
//! | `kd` | diffuse albedo | `[0, 1]` | yes |
//! | `F` | Fresnel factor and scale at normal incidence (`V.H = 1`) | `[0, inf)` | yes |
//! | `S` | Schlick's grazing Fresnel rise, `(1 - F0) scale` | `[0, inf)` | yes |
//!
//! `F_c + S_c (1 - x)^5` is Schlick's `scale (F0 + (1 - F0)(1 - x)^5)`
//! written linearly; at back-scattering (`x = 1`) it is `F_c`, so the
//! extraction stays exact: for data of the assumed form the fit returns
//! `kd = S = 0` and the extracted `F_c`. The table (256 nodes) is part of
//! the model: its stored numbers are the parameters and the table, which
//! it hands to a saved model through
//! [`Parametric::data_table`] (the saved-model schema's version 2 holds it,
//! `saved_model`) and is rebuilt from by
//! [`Dupuy::from_saved_table`], evaluating as before to the last bit.
//! Data without back-scattering samples (CUReT's and Cornell's scattered
//! measurements) cannot give a table: [`ParamError::Data`], naming the
//! data set and the models to fit instead.
//! Before data the catalogue builds it with the table of a GGX `D`
//! (`alpha = 0.3`).
//!
//! Properties: reciprocal; non-negative; finite above the horizon. Energy:
//! `D` normalised, `G <= G1`, so the albedo of [`TabulatedMicrofacet`] is
//! at most `max F_c`, and that of [`Dupuy`] at most `kd_c + F_c + S_c`
//! (energy conserving where that sum is at most 1).
//!
//! ```
//! use brdf_core::Brdf;
//! use brdf_models::dupuy::{TabulatedMicrofacet, TabulatedNdf};
//! use nalgebra::Vector3;
//! // A table of a GGX D (alpha = 0.3), its microfacet BRDF with F = 0.5.
//! let a2 = 0.09f64;
//! let ndf = TabulatedNdf::from_fn(256, |t| {
//!     let c2 = t.cos() * t.cos();
//!     a2 / (std::f64::consts::PI * (c2 * (a2 - 1.0) + 1.0).powi(2))
//! }).unwrap();
//! let m = TabulatedMicrofacet::new(ndf, &[0.5]).unwrap();
//! let mut f = [0.0];
//! m.eval(&Vector3::z(), &Vector3::z(), &mut f);
//! // Pole: D = 1/(pi alpha^2), G = 1: f = F / (4 pi alpha^2), to the
//! // table's normalisation by quadrature (O(h^2), 1e-4 at 256 nodes).
//! let expect = 0.5 / (4.0 * std::f64::consts::PI * a2);
//! assert!((f[0] - expect).abs() < 2e-4 * expect);
//! ```

use std::f64::consts::{FRAC_PI_2, PI};

use brdf_core::params::per_channel_specs;
use brdf_core::{Brdf, ParamError, ParamSpec, Parametric, SampleSet};
use nalgebra::Vector3;

/// Catalogue name of [`Dupuy`].
pub const NAME: &str = "dupuy";
/// Name of the bare [`TabulatedMicrofacet`] (not a catalogue model: its
/// parameters are only the `F_c`).
const TABLE_NAME: &str = "dupuy-table";
/// Largest tabulated angle: `D = rho cos(theta) sigma` vanishes at `pi/2`.
const THETA_MAX: f64 = FRAC_PI_2 * (1.0 - 1e-4);
/// Simpson sub-steps per table interval.
const SUB: usize = 4;
/// Distinct back-scattering angles below which [`TabulatedMicrofacet::from_samples`]
/// widens its search to near-back-scattering pairs.
pub const MIN_BACK_SAMPLES: usize = 8;

fn config_error(reason: String) -> ParamError {
    ParamError::Config {
        model: NAME.into(),
        reason,
    }
}

/// `integral_0^{2 pi} max(0, cos a cos b + sin a sin b cos phi) dphi`.
fn azimuthal(theta_v: f64, theta_m: f64) -> f64 {
    let a = theta_v.cos() * theta_m.cos();
    let b = theta_v.sin() * theta_m.sin();
    if b <= a.abs() {
        return if a > 0.0 { 2.0 * PI * a } else { 0.0 };
    }
    let p0 = (-a / b).clamp(-1.0, 1.0).acos();
    2.0 * (a * p0 + b * p0.sin())
}

/// A tabulated isotropic normal distribution `D(theta)` (see the module doc).
#[derive(Clone, Debug, PartialEq)]
pub struct TabulatedNdf {
    /// Node angles.
    theta: Vec<f64>,
    /// `D` at the nodes.
    d: Vec<f64>,
}

impl TabulatedNdf {
    fn nodes(n: usize) -> Result<Vec<f64>, ParamError> {
        if n < 8 {
            return Err(config_error(format!(
                "a table needs at least 8 nodes, got {n}"
            )));
        }
        Ok((0..n)
            .map(|j| {
                let u = j as f64 / (n - 1) as f64;
                THETA_MAX * u * u
            })
            .collect())
    }

    /// The table of `d(theta)` at `n` nodes, normalised to
    /// `integral D cos dm = 1`; an error for a negative or non-finite value.
    pub fn from_fn(n: usize, d: impl Fn(f64) -> f64) -> Result<Self, ParamError> {
        let theta = Self::nodes(n)?;
        let d: Vec<f64> = theta.iter().map(|&t| d(t)).collect();
        Self::from_values(theta, d)
    }

    fn from_values(theta: Vec<f64>, d: Vec<f64>) -> Result<Self, ParamError> {
        if let Some((j, x)) = d
            .iter()
            .enumerate()
            .find(|(_, x)| !(x.is_finite() && **x >= 0.0))
        {
            return Err(config_error(format!(
                "D at node {j} (theta {}) is {x}; it must be finite and >= 0",
                theta[j]
            )));
        }
        let mut t = Self { theta, d };
        let norm = dot(&t.normalisation_weights(), &t.d);
        if !(norm > 0.0) {
            return Err(config_error("D is zero everywhere".into()));
        }
        t.d.iter_mut().for_each(|x| *x /= norm);
        Ok(t)
    }

    /// Node angles and `D` values.
    pub fn table(&self) -> (&[f64], &[f64]) {
        (&self.theta, &self.d)
    }

    /// A table as [`TabulatedNdf::table`] gave it (a saved model's): the
    /// node angles must be the grid of `d.len()` nodes (the lookup in
    /// [`TabulatedNdf::eval`] assumes it) and `D` normalised
    /// (`integral D cos dm = 1` to 1e-9); the values are kept as given, so
    /// a saved and reloaded model evaluates as the saved one did.
    pub fn from_table(theta: &[f64], d: &[f64]) -> Result<Self, ParamError> {
        let grid = Self::nodes(d.len())?;
        if theta.len() != d.len() {
            return Err(config_error(format!(
                "the table has {} angles and {} values of D; they must pair up",
                theta.len(),
                d.len()
            )));
        }
        if let Some((j, (a, b))) = theta
            .iter()
            .zip(&grid)
            .enumerate()
            .find(|(_, (a, b))| !((*a - *b).abs() <= 1e-12))
        {
            return Err(config_error(format!(
                "table angle {j} is {a}, the grid of {} nodes has {b} there (theta_max (j / (n - 1))^2)",
                d.len()
            )));
        }
        let t = Self::from_values(grid, d.to_vec())?;
        let norm = dot(&t.normalisation_weights(), d);
        if !((norm - 1.0).abs() <= 1e-9) {
            return Err(config_error(format!(
                "the table's D integrates to {norm} against cos, not 1: it is not a saved table"
            )));
        }
        Ok(Self {
            theta: t.theta,
            d: d.to_vec(),
        })
    }

    /// Simpson points over `[0, theta_max]` in `u = sqrt(theta/theta_max)`
    /// and over `[theta_max, pi/2]` in `theta`, where `D` is the last node's
    /// (as in [`TabulatedNdf::eval`]; rough distributions have normals
    /// there, which shadow grazing directions):
    /// `(theta_k, weight_k * dtheta/du, node i, fraction t)`.
    fn quadrature(&self) -> Vec<(f64, f64, usize, f64)> {
        let n = self.theta.len();
        let m = SUB * (n - 1);
        let h = 1.0 / m as f64;
        let tail = FRAC_PI_2 - THETA_MAX;
        let last = [(0.5, 4.0), (1.0, 1.0)]
            .map(|(x, w)| (THETA_MAX + x * tail, w * tail / 6.0, n - 2, 1.0));
        let mut q: Vec<_> = (0..=m)
            .map(|k| {
                let u = k as f64 * h;
                let w = if k == 0 || k == m {
                    1.0
                } else if k % 2 == 1 {
                    4.0
                } else {
                    2.0
                };
                let i = (k / SUB).min(n - 2);
                let t = (k - i * SUB) as f64 / SUB as f64;
                (THETA_MAX * u * u, w * h / 3.0 * 2.0 * THETA_MAX * u, i, t)
            })
            .collect();
        // The tail's first Simpson point is theta_max itself.
        q[m].1 += tail / 6.0;
        q.extend(last);
        q
    }

    /// Weights `c` with `integral D cos dm = c . D` (2 pi cos sin dtheta).
    fn normalisation_weights(&self) -> Vec<f64> {
        let mut c = vec![0.0; self.theta.len()];
        for (th, w, i, t) in self.quadrature() {
            let x = w * 2.0 * PI * th.cos() * th.sin();
            c[i] += x * (1.0 - t);
            c[i + 1] += x * t;
        }
        c
    }

    /// Rows `K_v` with `sigma(theta_v) = K_v . D` for each angle in `views`.
    fn sigma_matrix(&self, views: &[f64]) -> Vec<Vec<f64>> {
        let quad = self.quadrature();
        views
            .iter()
            .map(|&tv| {
                let mut row = vec![0.0; self.theta.len()];
                for &(th, w, i, t) in &quad {
                    let x = w * th.sin() * azimuthal(tv, th);
                    row[i] += x * (1.0 - t);
                    row[i + 1] += x * t;
                }
                row
            })
            .collect()
    }

    /// `D` at a half vector with `N.H = cos_theta`.
    pub fn eval(&self, cos_theta: f64) -> f64 {
        let th = cos_theta.clamp(-1.0, 1.0).acos().min(THETA_MAX);
        let n = self.theta.len();
        let x = (th / THETA_MAX).sqrt() * (n - 1) as f64;
        let i = (x.floor() as usize).min(n - 2);
        let t = x - i as f64;
        self.d[i] * (1.0 - t) + self.d[i + 1] * t
    }

    /// Smith's `G1(theta) = cos(theta) / sigma(theta)` at the given angles.
    pub fn smith_g1(&self, views: &[f64]) -> Vec<f64> {
        self.sigma_matrix(views)
            .iter()
            .zip(views)
            .map(|(row, &tv)| {
                let s = dot(row, &self.d);
                if s > 0.0 {
                    (tv.cos() / s).min(1.0)
                } else {
                    0.0
                }
            })
            .collect()
    }

    /// The width `alpha` of the distribution `model(theta, alpha)` closest
    /// to the table in `integral (D - D_alpha)^2 cos sin dtheta` (trapezoid
    /// rule on the nodes, where the table holds its values without
    /// interpolation), by golden section over `ln alpha` in `[ln 1e-3, ln 2]`.
    fn fit_width(&self, model: impl Fn(f64, f64) -> f64) -> f64 {
        let th = &self.theta;
        let n = th.len();
        let w: Vec<f64> = (0..n)
            .map(|j| {
                0.5 * (th[(j + 1).min(n - 1)] - th[j.saturating_sub(1)]) * th[j].cos() * th[j].sin()
            })
            .collect();
        let err = |la: f64| {
            let a = la.exp();
            (0..n)
                .map(|j| {
                    let r = self.d[j] - model(th[j], a);
                    w[j] * r * r
                })
                .sum::<f64>()
        };
        let (mut lo, mut hi) = (1e-3f64.ln(), 2f64.ln());
        let g = 0.5 * (5f64.sqrt() - 1.0);
        let (mut x1, mut x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
        let (mut f1, mut f2) = (err(x1), err(x2));
        for _ in 0..120 {
            if f1 < f2 {
                hi = x2;
                (x2, f2) = (x1, f1);
                x1 = hi - g * (hi - lo);
                f1 = err(x1);
            } else {
                lo = x1;
                (x1, f1) = (x2, f2);
                x2 = lo + g * (hi - lo);
                f2 = err(x2);
            }
        }
        (0.5 * (lo + hi)).exp()
    }

    /// GGX width read off the table.
    pub fn fit_ggx_alpha(&self) -> f64 {
        self.fit_width(|th, a| {
            let c2 = th.cos().powi(2);
            let a2 = a * a;
            a2 / (PI * (c2 * (a2 - 1.0) + 1.0).powi(2))
        })
    }

    /// Beckmann width read off the table.
    pub fn fit_beckmann_alpha(&self) -> f64 {
        self.fit_width(|th, a| {
            let c2 = th.cos().powi(2);
            let t2 = (1.0 - c2) / c2;
            (-t2 / (a * a)).exp() / (PI * a * a * c2 * c2)
        })
    }
}

/// The error for a data set without back-scattering samples (CUReT's and
/// Cornell's scattered measurements): it names the file and the models
/// that need no such samples.
fn no_back_scattering(samples: &SampleSet, found: usize) -> ParamError {
    let data = if samples.provenance.is_empty() {
        samples.name.clone()
    } else {
        format!("{} ({})", samples.name, samples.provenance)
    };
    ParamError::Data {
        model: NAME.into(),
        data,
        reason: format!(
            "its normal distribution is read off back-scattering samples (L = V, or within 5 deg of it), and the data set has {found} of the 2 needed"
        ),
        fix: "fit a closed-form microfacet model instead (`--model std`, `--model ggx` or `--model sgd`)".into(),
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Options of the extraction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExtractOptions {
    /// Table nodes.
    pub nodes: usize,
    /// Most power iterations.
    pub max_iterations: usize,
    /// Stop when no node changes by more than this times the largest `D`.
    pub tolerance: f64,
}

impl Default for ExtractOptions {
    fn default() -> Self {
        Self {
            nodes: 256,
            max_iterations: 2000,
            tolerance: 1e-13,
        }
    }
}

/// Result of an extraction: the model and how the iteration ended.
#[derive(Clone, Debug)]
pub struct Extraction {
    /// The tabulated BRDF.
    pub model: TabulatedMicrofacet,
    /// Power iterations done.
    pub iterations: usize,
    /// Whether the change fell below the tolerance.
    pub converged: bool,
}

/// The tabulated microfacet BRDF (see the module doc).
#[derive(Clone, Debug, PartialEq)]
pub struct TabulatedMicrofacet {
    ndf: TabulatedNdf,
    /// `G1` on a uniform grid of `G1_NODES` angles over `[0, pi/2]`.
    g1: Vec<f64>,
    specs: Vec<ParamSpec>,
    params: Vec<f64>,
}

const G1_NODES: usize = 1025;

impl TabulatedMicrofacet {
    /// The model of a table with per-channel factors `F_c >= 0`.
    pub fn new(ndf: TabulatedNdf, scales: &[f64]) -> Result<Self, ParamError> {
        if scales.is_empty() {
            return Err(config_error("a model needs at least one channel".into()));
        }
        let views: Vec<f64> = (0..G1_NODES)
            .map(|j| FRAC_PI_2 * j as f64 / (G1_NODES - 1) as f64)
            .collect();
        let mut g1 = ndf.smith_g1(&views);
        // At pi/2 G1 is 0 (cos = 0); the quadrature gives it exactly.
        g1[G1_NODES - 1] = 0.0;
        let specs = per_channel_specs(
            "F",
            "Fresnel factor and scale",
            scales.len(),
            0.0,
            f64::INFINITY,
            1.0,
        );
        let mut m = Self {
            ndf,
            g1,
            specs,
            params: vec![1.0; scales.len()],
        };
        m.set_params(scales)?;
        Ok(m)
    }

    /// The normal distribution.
    pub fn ndf(&self) -> &TabulatedNdf {
        &self.ndf
    }

    /// Extract from back-scattering values `rho[c][j]` at the nodes of an
    /// `opts.nodes` table (`rho` per channel; `D` from their mean).
    fn extract(
        theta: Vec<f64>,
        rho: &[Vec<f64>],
        opts: &ExtractOptions,
    ) -> Result<Extraction, ParamError> {
        let n = theta.len();
        let nc = rho.len();
        let grey: Vec<f64> = (0..n)
            .map(|j| rho.iter().map(|r| r[j]).sum::<f64>() / nc as f64)
            .collect();
        if let Some((j, x)) = grey
            .iter()
            .enumerate()
            .find(|(_, x)| !(x.is_finite() && **x >= 0.0))
        {
            return Err(config_error(format!(
                "back-scattering value {x} at theta {} is not >= 0",
                theta[j]
            )));
        }
        let mut table = TabulatedNdf::from_values(theta.clone(), vec![1.0 / PI; n])?;
        let k = table.sigma_matrix(&theta);
        let c = table.normalisation_weights();
        let (mut iterations, mut converged) = (0, false);
        while iterations < opts.max_iterations && !converged {
            let next: Vec<f64> = (0..n)
                .map(|j| grey[j] * theta[j].cos() * dot(&k[j], &table.d))
                .collect();
            let norm = dot(&c, &next);
            if !(norm > 0.0) {
                return Err(config_error("the back-scattering values are zero".into()));
            }
            let dmax = next.iter().fold(0.0f64, |a, &x| a.max(x / norm));
            let change = next
                .iter()
                .zip(&table.d)
                .fold(0.0f64, |a, (x, y)| a.max((x / norm - y).abs()));
            table.d = next.iter().map(|x| x / norm).collect();
            converged = change <= opts.tolerance * dmax;
            iterations += 1;
        }
        // rho_c = F_c s with s = D / (4 cos sigma): least squares per channel.
        let s: Vec<f64> = (0..n)
            .map(|j| {
                let sig = theta[j].cos() * dot(&k[j], &table.d);
                if sig > 0.0 {
                    table.d[j] / (4.0 * sig)
                } else {
                    0.0
                }
            })
            .collect();
        let ss = dot(&s, &s);
        let scales: Vec<f64> = rho.iter().map(|r| (dot(r, &s) / ss).max(0.0)).collect();
        Ok(Extraction {
            model: Self::new(table, &scales)?,
            iterations,
            converged,
        })
    }

    /// Extract from any BRDF evaluated at back-scattering directions
    /// (`phi = 0`) at the table nodes.
    pub fn from_brdf(brdf: &dyn Brdf, opts: &ExtractOptions) -> Result<Extraction, ParamError> {
        let theta = TabulatedNdf::nodes(opts.nodes)?;
        let nc = brdf.channels();
        let mut rho = vec![vec![0.0; theta.len()]; nc];
        let mut f = vec![0.0; nc];
        for (j, &t) in theta.iter().enumerate() {
            let w = Vector3::new(t.sin(), 0.0, t.cos());
            brdf.eval(&w, &w, &mut f);
            for c in 0..nc {
                rho[c][j] = f[c];
            }
        }
        Self::extract(theta, &rho, opts)
    }

    /// Extract from the back-scattering samples of a sample set:
    /// those with `|L - V| <= 1e-6` (gridded data, Sopp's grid, synthetic
    /// sets), or, where fewer than [`MIN_BACK_SAMPLES`] are exact
    /// (scattered measurements), those within 2 deg of it, then within
    /// 5 deg, at the polar angle of their half vector. Samples are averaged
    /// in groups spanning at most `1e-9` rad (exact) or 0.5 deg (near),
    /// and interpolated linearly in `theta` onto the nodes (constant beyond
    /// the measured range).
    pub fn from_samples(
        samples: &SampleSet,
        opts: &ExtractOptions,
    ) -> Result<Extraction, ParamError> {
        let exact = back_scattering(samples, 0.0);
        let back = if exact.len() >= MIN_BACK_SAMPLES {
            exact
        } else {
            [2.0f64, 5.0]
                .iter()
                .map(|a| back_scattering(samples, a.to_radians()))
                .find(|b| b.len() >= MIN_BACK_SAMPLES)
                .unwrap_or(exact)
        };
        if back.len() < 2 {
            return Err(no_back_scattering(samples, back.len()));
        }
        let theta = TabulatedNdf::nodes(opts.nodes)?;
        let rho = onto_nodes(&back, &theta, samples.channels());
        Self::extract(theta, &rho, opts)
    }

    fn g1(&self, w: &Vector3<f64>) -> f64 {
        let th = w.x.hypot(w.y).atan2(w.z).clamp(0.0, FRAC_PI_2);
        let x = th / FRAC_PI_2 * (G1_NODES - 1) as f64;
        let i = (x.floor() as usize).min(G1_NODES - 2);
        let t = x - i as f64;
        self.g1[i] * (1.0 - t) + self.g1[i + 1] * t
    }

    /// `D G / (4 N.L N.V)`, the shape every channel scales.
    fn shape(&self, l: &Vector3<f64>, v: &Vector3<f64>) -> f64 {
        let s = l + v;
        let len = s.norm();
        if !(len > 0.0 && l.z > 0.0 && v.z > 0.0) {
            return 0.0;
        }
        let g = self.g1(l).min(self.g1(v));
        self.ndf.eval(s.z / len) * g / (4.0 * l.z * v.z)
    }
}

impl Brdf for TabulatedMicrofacet {
    fn channels(&self) -> usize {
        self.params.len()
    }
    fn eval(&self, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        self.eval_at(&self.params, l, v, out)
    }
}

impl Parametric for TabulatedMicrofacet {
    brdf_core::param_accessors!();
    fn name(&self) -> &str {
        TABLE_NAME
    }
    fn eval_at(&self, p: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        let s = self.shape(l, v);
        for (o, f) in out.iter_mut().zip(p) {
            *o = f * s;
        }
    }
    fn eval_grad_at(
        &self,
        p: &[f64],
        l: &Vector3<f64>,
        v: &Vector3<f64>,
        out: &mut [f64],
        grad: &mut [f64],
    ) {
        let s = self.shape(l, v);
        let nc = p.len();
        grad[..nc * nc].fill(0.0);
        for c in 0..nc {
            out[c] = p[c] * s;
            grad[c * nc + c] = s;
        }
    }
}

/// Nodes of the catalogue model's table.
pub const DUPUY_NODES: usize = 256;

/// Dupuy et al.'s model as the catalogue fits it (see the module doc): the
/// table extracted from the data, `kd_c`, `F_c` and `S_c` per channel.
#[derive(Clone, Debug, PartialEq)]
pub struct Dupuy {
    table: TabulatedMicrofacet,
    specs: Vec<ParamSpec>,
    params: Vec<f64>,
}

impl Dupuy {
    fn from_table(table: TabulatedMicrofacet) -> Result<Self, ParamError> {
        let nc = table.channels();
        let mut specs = per_channel_specs("kd", "diffuse albedo", nc, 0.0, 1.0, 0.0);
        specs.extend(per_channel_specs(
            "F",
            "Fresnel factor and scale at normal incidence",
            nc,
            0.0,
            f64::INFINITY,
            1.0,
        ));
        specs.extend(per_channel_specs(
            "S",
            "Schlick's grazing Fresnel rise",
            nc,
            0.0,
            f64::INFINITY,
            0.0,
        ));
        let mut params: Vec<f64> = specs.iter().map(|s| s.default).collect();
        params[nc..2 * nc].copy_from_slice(table.params());
        Ok(Self {
            table,
            specs,
            params,
        })
    }

    /// The model before data: the table of a GGX `D` with `alpha = 0.3`,
    /// `kd = S = 0`, `F = 1`.
    pub fn with_channels(channels: usize) -> Result<Self, ParamError> {
        let a2 = 0.09;
        let ndf = TabulatedNdf::from_fn(DUPUY_NODES, |t| {
            let c2 = t.cos() * t.cos();
            a2 / (PI * (c2 * (a2 - 1.0) + 1.0).powi(2))
        })?;
        Self::from_table(TabulatedMicrofacet::new(ndf, &vec![1.0; channels])?)
    }

    /// The model for `samples`: its table extracted from their
    /// back-scattering ([`TabulatedMicrofacet::from_samples`], 256 nodes),
    /// `F_c` the extraction's, `kd = S = 0`; the error of the extraction
    /// (too few back-scattering samples), or one for a channel count other
    /// than `channels`, or an iteration that did not converge.
    pub fn from_samples(channels: usize, samples: &SampleSet) -> Result<Self, ParamError> {
        if samples.channels() != channels {
            return Err(config_error(format!(
                "`{}` has {} channels, the model {channels}",
                samples.name,
                samples.channels()
            )));
        }
        let opts = ExtractOptions {
            nodes: DUPUY_NODES,
            ..ExtractOptions::default()
        };
        let ex = TabulatedMicrofacet::from_samples(samples, &opts)?;
        if !ex.converged {
            return Err(config_error(format!(
                "the power iteration on `{}` did not converge in {} iterations",
                samples.name, ex.iterations
            )));
        }
        Self::from_table(ex.model)
    }

    /// The model of a saved table ([`TabulatedNdf::from_table`]) at its
    /// default parameters (`kd = S = 0`, `F = 1`); the saved parameters
    /// are set after.
    pub fn from_saved_table(channels: usize, theta: &[f64], d: &[f64]) -> Result<Self, ParamError> {
        let ndf = TabulatedNdf::from_table(theta, d)?;
        Self::from_table(TabulatedMicrofacet::new(ndf, &vec![1.0; channels])?)
    }

    /// The tabulated microfacet part (table and `G1`).
    pub fn table(&self) -> &TabulatedMicrofacet {
        &self.table
    }
}

impl Brdf for Dupuy {
    fn channels(&self) -> usize {
        self.table.channels()
    }
    fn eval(&self, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        self.eval_at(&self.params, l, v, out)
    }
}

/// The back-scattering samples of `samples` (`L` within `max_angle` of
/// `V`; 0: `|L - V| <= 1e-6`) as `(theta_h, values)`, sorted by
/// `theta_h` and averaged in groups spanning at most `1e-9` rad (exact)
/// or 0.5 deg (near).
fn back_scattering(samples: &SampleSet, max_angle: f64) -> Vec<(f64, Vec<f64>)> {
    let pairs = samples.pairs();
    let nc = samples.channels();
    let chord = if max_angle == 0.0 {
        1e-6
    } else {
        2.0 * (0.5 * max_angle).sin()
    };
    let mut back: Vec<(f64, Vec<f64>)> = (0..samples.len())
        .filter(|&j| {
            let (l, v) = (pairs.l(j), pairs.v(j));
            (l - v).norm() <= chord && l.z > 0.0 && v.z > 0.0
        })
        .map(|j| {
            let h = (pairs.l(j) + pairs.v(j)).normalize();
            (
                h.x.hypot(h.y).atan2(h.z),
                (0..nc).map(|c| samples.channel(c)[j]).collect(),
            )
        })
        .collect();
    back.sort_by(|a, b| a.0.total_cmp(&b.0));
    let width = if max_angle == 0.0 {
        1e-9
    } else {
        0.5f64.to_radians()
    };
    merge_groups(back, width)
}

/// Sorted `(theta, values)` averaged in groups spanning at most `width`
/// from each group's first angle (running means, in order).
fn merge_groups(back: Vec<(f64, Vec<f64>)>, width: f64) -> Vec<(f64, Vec<f64>)> {
    let mut merged: Vec<(f64, Vec<f64>)> = Vec::new();
    let mut count = 0usize;
    let mut first = f64::NEG_INFINITY;
    for (t, vals) in back {
        match merged.last_mut() {
            Some(m) if t - first <= width => {
                count += 1;
                let w = 1.0 / count as f64;
                m.0 += (t - m.0) * w;
                for (a, b) in m.1.iter_mut().zip(&vals) {
                    *a += (b - *a) * w;
                }
            }
            _ => {
                first = t;
                count = 1;
                merged.push((t, vals));
            }
        }
    }
    merged
}

/// The `nc` channels of `back` (at least two angles, sorted) interpolated
/// linearly in `theta` onto the nodes `theta` (constant beyond the
/// measured range): one row per channel.
fn onto_nodes(back: &[(f64, Vec<f64>)], theta: &[f64], nc: usize) -> Vec<Vec<f64>> {
    let mut rho = vec![vec![0.0; theta.len()]; nc];
    for (j, &t) in theta.iter().enumerate() {
        let k = back.partition_point(|b| b.0 < t).clamp(1, back.len() - 1);
        let (a, b) = (&back[k - 1], &back[k]);
        let w = if b.0 > a.0 {
            ((t - a.0) / (b.0 - a.0)).clamp(0.0, 1.0)
        } else {
            0.5
        };
        for c in 0..nc {
            rho[c][j] = a.1[c] * (1.0 - w) + b.1[c] * w;
        }
    }
    rho
}

/// `(D G / (4 N.L N.V), (1 - V.H)^5)`, both 0 below the horizon.
fn dupuy_terms(t: &TabulatedMicrofacet, l: &Vector3<f64>, v: &Vector3<f64>) -> (f64, f64) {
    let s = t.shape(l, v);
    if s == 0.0 {
        return (0.0, 0.0);
    }
    let h = (l + v).normalize();
    (s, (1.0 - v.dot(&h)).clamp(0.0, 1.0).powi(5))
}

impl Parametric for Dupuy {
    brdf_core::param_accessors!();
    fn name(&self) -> &str {
        NAME
    }
    fn data_table(&self) -> Option<(&[f64], &[f64])> {
        Some(self.table.ndf().table())
    }
    fn eval_at(&self, p: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        let nc = self.table.channels();
        if !(l.z > 0.0 && v.z > 0.0) {
            out[..nc].fill(0.0);
            return;
        }
        let (s, x) = dupuy_terms(&self.table, l, v);
        for c in 0..nc {
            out[c] = p[c] / PI + (p[nc + c] + p[2 * nc + c] * x) * s;
        }
    }
    fn eval_grad_at(
        &self,
        p: &[f64],
        l: &Vector3<f64>,
        v: &Vector3<f64>,
        out: &mut [f64],
        grad: &mut [f64],
    ) {
        let nc = self.table.channels();
        let np = 3 * nc;
        grad[..nc * np].fill(0.0);
        if !(l.z > 0.0 && v.z > 0.0) {
            out[..nc].fill(0.0);
            return;
        }
        let (s, x) = dupuy_terms(&self.table, l, v);
        for c in 0..nc {
            out[c] = p[c] / PI + (p[nc + c] + p[2 * nc + c] * x) * s;
            let row = &mut grad[c * np..(c + 1) * np];
            row[c] = 1.0 / PI;
            row[nc + c] = s;
            row[2 * nc + c] = s * x;
        }
    }
}
