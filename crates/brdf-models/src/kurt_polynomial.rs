//! Kurt's polynomial (PCA response-surface) model (Kurt 2007, "A new
//! illumination model in computer graphics", MSc thesis, Ege University,
//! chapter 7).
//!
//! Isotropic variant: the two features `W1 = ux vx + uy vy` and `W2 = uz vz`
//! (`u = L`, `v = V`) are centred by their mean over the fitted sample set and
//! rotated onto their principal axes (eigenvectors of the 2x2 covariance,
//! ordered by decreasing eigenvalue), giving uncorrelated scores `Z1, Z2`.
//! The model of degree `p` is
//!
//! `f = b0 + sum_{k=1..p} (b_{2k-1} Z1^k + b_{2k} Z2^k)`,
//!
//! `2p + 1` coefficients per channel, no cross terms. The anisotropic variant
//! uses `X1 = ux vx`, `X2 = uy vy`, `X3 = uz vz` and three scores:
//! `3p + 1` coefficients.
//!
//! | parameter | meaning | default box | linear |
//! | --- | --- | --- | --- |
//! | `b0`, `b1`, ... (per channel) | polynomial coefficients in the order above | `(-inf, inf)` | yes |
//!
//! Sign rule (for reproducible fits): each eigenvector is flipped so that its
//! component of largest magnitude is positive (the first such component on a
//! tie).
//!
//! Stored numbers: the coefficients of every channel, plus the PCA mean
//! (`d` numbers) and axes (`d^2`), `d = 2` or `3`
//! ([`KurtPolynomial::stored_numbers`]). Kurt's tables count `2p + 5` for the
//! isotropic model: the `2p + 1` coefficients and the four entries of the 2x2
//! rotation, without the mean ([`KurtPolynomial::kurt_stored_numbers`]).
//!
//! Properties: reciprocal by construction (`W` and `X` are symmetric in `u`
//! and `v`). Not non-negative by construction: evaluation clamps the
//! polynomial at 0 (so its parameter derivatives are 0 where the clamp is
//! active; fits use the unclamped design row, [`KurtPolynomial::design_row`]).
//! Energy conservation is not guaranteed and is checked on fitted results.
//! Kurt: good for diffuse and glossy materials; specular ones need a degree
//! so high that the model stops being practical.
//!
//! ```
//! use brdf_core::{Brdf, Parametric};
//! use brdf_models::kurt_polynomial::{KurtPolynomial, Pca, PolyVariant};
//! use nalgebra::Vector3;
//! // Degree 1, identity PCA: f = b0 + b1 W1 + b2 W2.
//! let mut m = KurtPolynomial::new(PolyVariant::Isotropic, 1, 1, Pca::identity(2)).unwrap();
//! m.set_params(&[0.1, 0.0, 0.2]).unwrap();
//! let mut f = [0.0];
//! m.eval(&Vector3::z(), &Vector3::z(), &mut f); // W2 = 1
//! assert!((f[0] - 0.3).abs() < 1e-15);
//! assert_eq!(m.n_params(), 3);
//! ```

use brdf_core::params::channel_param_name;
use brdf_core::{DirPairs, ParamError, ParamSpec, Parametric, impl_brdf_via_params};
use nalgebra::{Matrix2, Matrix3, Vector3};

/// Which features the polynomial is built on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum PolyVariant {
    /// `W1 = ux vx + uy vy`, `W2 = uz vz`.
    Isotropic,
    /// `X1 = ux vx`, `X2 = uy vy`, `X3 = uz vz`.
    Anisotropic,
}

impl PolyVariant {
    /// Number of features (2 or 3).
    pub fn dim(self) -> usize {
        match self {
            PolyVariant::Isotropic => 2,
            PolyVariant::Anisotropic => 3,
        }
    }

    /// The raw features of a direction pair.
    #[inline]
    pub fn features(self, l: &Vector3<f64>, v: &Vector3<f64>) -> [f64; 3] {
        match self {
            PolyVariant::Isotropic => [l.x * v.x + l.y * v.y, l.z * v.z, 0.0],
            PolyVariant::Anisotropic => [l.x * v.x, l.y * v.y, l.z * v.z],
        }
    }
}

/// A principal-component transform `Z = A (W - mean)`: `axes[i]` is the
/// `i`-th principal axis (row `i` of `A`), ordered by decreasing variance.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Pca {
    /// Feature means over the fitted sample set.
    pub mean: Vec<f64>,
    /// Principal axes, row-major `d x d`.
    pub axes: Vec<f64>,
    /// Variances along the axes (eigenvalues), decreasing.
    pub variances: Vec<f64>,
}

impl Pca {
    /// The identity transform (no centring, no rotation).
    pub fn identity(dim: usize) -> Self {
        let mut axes = vec![0.0; dim * dim];
        for i in 0..dim {
            axes[i * dim + i] = 1.0;
        }
        Pca {
            mean: vec![0.0; dim],
            axes,
            variances: vec![1.0; dim],
        }
    }

    /// The PCA of the features of `pairs`: centre by the mean, eigen-decompose
    /// the covariance (nalgebra's symmetric eigensolver), order by decreasing
    /// eigenvalue, and fix signs by the rule in the module doc.
    pub fn from_pairs(variant: PolyVariant, pairs: &DirPairs) -> Result<Self, ParamError> {
        let d = variant.dim();
        let n = pairs.len();
        if n < 2 {
            return Err(ParamError::Config {
                model: KurtPolynomial::NAME.into(),
                reason: format!("PCA needs at least 2 samples, got {n}"),
            });
        }
        let mut mean = [0.0; 3];
        for j in 0..n {
            let w = variant.features(&pairs.l(j), &pairs.v(j));
            for i in 0..d {
                mean[i] += w[i];
            }
        }
        mean.iter_mut().for_each(|m| *m /= n as f64);
        let mut cov = Matrix3::<f64>::zeros();
        for j in 0..n {
            let w = variant.features(&pairs.l(j), &pairs.v(j));
            for a in 0..d {
                for b in 0..d {
                    cov[(a, b)] += (w[a] - mean[a]) * (w[b] - mean[b]);
                }
            }
        }
        cov /= (n - 1) as f64;
        let (values, vectors): (Vec<f64>, Vec<Vec<f64>>) = if d == 2 {
            let c2 = Matrix2::new(cov[(0, 0)], cov[(0, 1)], cov[(1, 0)], cov[(1, 1)]);
            let e = c2.symmetric_eigen();
            (
                e.eigenvalues.iter().copied().collect(),
                (0..2)
                    .map(|i| e.eigenvectors.column(i).iter().copied().collect())
                    .collect(),
            )
        } else {
            let e = cov.symmetric_eigen();
            (
                e.eigenvalues.iter().copied().collect(),
                (0..3)
                    .map(|i| e.eigenvectors.column(i).iter().copied().collect())
                    .collect(),
            )
        };
        let mut order: Vec<usize> = (0..d).collect();
        order.sort_by(|&a, &b| values[b].total_cmp(&values[a]));
        let mut axes = Vec::with_capacity(d * d);
        let mut variances = Vec::with_capacity(d);
        for &i in &order {
            let mut v = vectors[i].clone();
            let big = (0..d).fold(0, |best, k| {
                if v[k].abs() > v[best].abs() + 1e-12 {
                    k
                } else {
                    best
                }
            });
            if v[big] < 0.0 {
                v.iter_mut().for_each(|x| *x = -*x);
            }
            axes.extend_from_slice(&v);
            variances.push(values[i].max(0.0));
        }
        Ok(Pca {
            mean: mean[..d].to_vec(),
            axes,
            variances,
        })
    }

    /// Scores `Z = A (W - mean)` of a direction pair.
    #[inline]
    pub fn scores(&self, variant: PolyVariant, l: &Vector3<f64>, v: &Vector3<f64>) -> [f64; 3] {
        let d = variant.dim();
        let w = variant.features(l, v);
        let mut z = [0.0; 3];
        for i in 0..d {
            let mut s = 0.0;
            for k in 0..d {
                s += self.axes[i * d + k] * (w[k] - self.mean[k]);
            }
            z[i] = s;
        }
        z
    }
}

/// Kurt's polynomial model of degree `p` (see the module doc).
#[derive(Clone, Debug, PartialEq)]
pub struct KurtPolynomial {
    channels: usize,
    variant: PolyVariant,
    degree: usize,
    pca: Pca,
    specs: Vec<ParamSpec>,
    params: Vec<f64>,
}

impl KurtPolynomial {
    /// Name in the catalogue (isotropic).
    pub const NAME: &'static str = "polynomial";
    /// Name in the catalogue (anisotropic).
    pub const NAME_ANISO: &'static str = "polynomial-aniso";

    /// A model with all coefficients 0 and the given transform. `degree >= 1`.
    pub fn new(
        variant: PolyVariant,
        degree: usize,
        channels: usize,
        pca: Pca,
    ) -> Result<Self, ParamError> {
        let name = match variant {
            PolyVariant::Isotropic => Self::NAME,
            PolyVariant::Anisotropic => Self::NAME_ANISO,
        };
        let cfg = |reason: String| ParamError::Config {
            model: name.into(),
            reason,
        };
        if channels == 0 {
            return Err(cfg("a model needs at least one channel".into()));
        }
        if degree == 0 {
            return Err(cfg("the polynomial degree must be at least 1".into()));
        }
        let d = variant.dim();
        if pca.mean.len() != d || pca.axes.len() != d * d || pca.variances.len() != d {
            return Err(cfg(format!("the PCA transform must be {d}-dimensional")));
        }
        if pca.mean.iter().chain(&pca.axes).any(|x| !x.is_finite()) {
            return Err(cfg("the PCA transform must be finite".into()));
        }
        let per = d * degree + 1;
        let mut specs = Vec::with_capacity(per * channels);
        for c in 0..channels {
            for k in 0..per {
                let meaning = if k == 0 {
                    "constant term".to_string()
                } else {
                    format!("coefficient of Z{}^{}", (k - 1) % d + 1, (k - 1) / d + 1)
                };
                specs.push(ParamSpec::new(
                    channel_param_name(&format!("b{k}"), c, channels),
                    format!("{meaning} (channel {c})"),
                    f64::NEG_INFINITY,
                    f64::INFINITY,
                    0.0,
                    true,
                ));
            }
        }
        let params = vec![0.0; specs.len()];
        Ok(KurtPolynomial {
            channels,
            variant,
            degree,
            pca,
            specs,
            params,
        })
    }

    /// Variant.
    pub fn variant(&self) -> PolyVariant {
        self.variant
    }

    /// Degree `p`.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The PCA transform.
    pub fn pca(&self) -> &Pca {
        &self.pca
    }

    /// Coefficients per channel: `2p + 1` (isotropic) or `3p + 1`.
    pub fn coefficients_per_channel(&self) -> usize {
        self.variant.dim() * self.degree + 1
    }

    /// Numbers needed to evaluate the model: all channels' coefficients, the
    /// PCA mean and the PCA axes.
    pub fn stored_numbers(&self) -> usize {
        let d = self.variant.dim();
        self.coefficients_per_channel() * self.channels + d + d * d
    }

    /// Kurt's count for one channel: coefficients plus the `d x d` axes
    /// (`2p + 5` isotropic).
    pub fn kurt_stored_numbers(&self) -> usize {
        let d = self.variant.dim();
        self.coefficients_per_channel() + d * d
    }

    /// The unclamped basis `[1, Z1, Z2, Z1^2, Z2^2, ...]` of a pair: one row
    /// of the linear design matrix (the same for every channel).
    #[inline]
    pub fn design_row(&self, l: &Vector3<f64>, v: &Vector3<f64>, row: &mut [f64]) {
        let d = self.variant.dim();
        let z = self.pca.scores(self.variant, l, v);
        row[0] = 1.0;
        let mut pw = [1.0; 3];
        for k in 0..self.degree {
            for i in 0..d {
                pw[i] *= z[i];
                row[1 + k * d + i] = pw[i];
            }
        }
    }

    #[inline]
    fn unclamped(&self, p: &[f64], c: usize, row: &[f64]) -> f64 {
        let per = row.len();
        row.iter()
            .zip(&p[c * per..(c + 1) * per])
            .map(|(a, b)| a * b)
            .sum()
    }
}

impl Parametric for KurtPolynomial {
    brdf_core::param_accessors!();
    fn name(&self) -> &str {
        match self.variant {
            PolyVariant::Isotropic => Self::NAME,
            PolyVariant::Anisotropic => Self::NAME_ANISO,
        }
    }
    fn eval_at(&self, p: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        if !(l.z > 0.0 && v.z > 0.0) {
            out[..self.channels].iter_mut().for_each(|x| *x = 0.0);
            return;
        }
        let mut row = [0.0; 64];
        let per = self.coefficients_per_channel();
        let mut heap = Vec::new();
        let row: &mut [f64] = if per <= 64 {
            &mut row[..per]
        } else {
            heap.resize(per, 0.0);
            &mut heap
        };
        self.design_row(l, v, row);
        for c in 0..self.channels {
            out[c] = self.unclamped(p, c, row).max(0.0);
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
        let np = self.specs.len();
        grad[..self.channels * np].iter_mut().for_each(|g| *g = 0.0);
        if !(l.z > 0.0 && v.z > 0.0) {
            out[..self.channels].iter_mut().for_each(|x| *x = 0.0);
            return;
        }
        let per = self.coefficients_per_channel();
        let mut row = vec![0.0; per];
        self.design_row(l, v, &mut row);
        for c in 0..self.channels {
            let s = self.unclamped(p, c, &row);
            out[c] = s.max(0.0);
            grad[c * np + c * per..c * np + (c + 1) * per].copy_from_slice(&row);
        }
    }
}

impl_brdf_via_params!(KurtPolynomial);
