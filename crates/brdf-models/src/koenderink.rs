//! Koenderink, van Doorn & Stavridis (1996), "Bidirectional reflection
//! distribution function expressed in terms of surface scattering modes"
//! (ECCV): an isotropic BRDF expanded in products of Zernike polynomials of
//! the two directions, linear in all its coefficients.
//!
//! Each hemisphere is mapped to the unit disk by `rho = sqrt(2) sin(theta/2)`
//! (`= sqrt(1 - cos theta)`). Zernike radial polynomials:
//!
//! `R_n^m(rho) = sum_{k=0}^{(n-m)/2} (-1)^k (n-k)! / (k! ((n+m)/2-k)! ((n-m)/2-k)!) rho^(n-2k)`.
//!
//! The basis of order `N` has, for every `m >= 0` and every pair `n <= n'`
//! with `m <= n`, `n' <= N` and `n = n' = m (mod 2)`, the function
//!
//! `K = [R_n^m(rho_i) R_n'^m(rho_o) + R_n'^m(rho_i) R_n^m(rho_o)] cos(m (phi_i - phi_o))`
//!
//! (a single product when `n = n'`), and `f = max(0, sum_K c_K K)`.
//! Orders 0, 2, 4 and 8 give 1, 5, 14 and 55 functions; order 0 is Lambert
//! (`K = 1`, `c = kd/pi`).
//!
//! | parameter | meaning | default box | linear |
//! | --- | --- | --- | --- |
//! | `c0`, `c1`, ... (per channel) | coefficient of the `k`-th basis function, in the order `m`, then `n`, then `n'` ascending ([`Koenderink::basis_indices`]) | `(-inf, inf)` | yes |
//!
//! Properties: reciprocal by construction (every `K` is symmetric in the two
//! directions). Not non-negative by construction: evaluation clamps the sum at
//! 0 (documented; the parameter derivatives are then 0), and fits use the
//! unclamped basis ([`Koenderink::basis`]). Energy conservation depends on the
//! coefficients and is checked on fitted results. The paper's normalisation
//! constants are absorbed into the coefficients.
//!
//! ```
//! use brdf_core::{Brdf, Parametric};
//! use brdf_models::Koenderink;
//! use nalgebra::Vector3;
//! assert_eq!(Koenderink::new(8, 1).unwrap().n_params(), 55);
//! // Order 0 with c0 = 0.5/pi is Lambert with kd = 0.5.
//! let mut m = Koenderink::new(0, 1).unwrap();
//! m.set_params(&[0.5 / std::f64::consts::PI]).unwrap();
//! let mut f = [0.0];
//! m.eval(&Vector3::z(), &Vector3::x().lerp(&Vector3::z(), 0.5).normalize(), &mut f);
//! assert!((f[0] - 0.5 / std::f64::consts::PI).abs() < 1e-15);
//! ```

use brdf_core::params::channel_param_name;
use brdf_core::trig::cos_dphi;
use brdf_core::{ParamError, ParamSpec, Parametric, impl_brdf_via_params};
use nalgebra::Vector3;

/// Zernike radial polynomial `R_n^m(rho)` (0 unless `n - m` is even and
/// non-negative).
pub fn zernike_radial(n: usize, m: usize, rho: f64) -> f64 {
    if m > n || !(n - m).is_multiple_of(2) {
        return 0.0;
    }
    let fact = |k: usize| (1..=k).fold(1.0f64, |a, b| a * b as f64);
    let mut s = 0.0;
    for k in 0..=(n - m) / 2 {
        let c = fact(n - k) / (fact(k) * fact((n + m) / 2 - k) * fact((n - m) / 2 - k));
        let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
        s += sign * c * rho.powi((n - 2 * k) as i32);
    }
    s
}

/// Koenderink's expansion of order `N`.
#[derive(Clone, Debug, PartialEq)]
pub struct Koenderink {
    channels: usize,
    order: usize,
    /// `(m, n, n')` of every basis function.
    indices: Vec<(usize, usize, usize)>,
    /// Coefficients of `R_n^m`: `radial[(n * (N+1) + m) * (N/2+1) + k]` is the
    /// coefficient of `rho^(n-2k)` (computed once; evaluation is then a few
    /// multiplications per polynomial).
    radial: Vec<f64>,
    specs: Vec<ParamSpec>,
    params: Vec<f64>,
}

impl Koenderink {
    /// Name in the catalogue.
    pub const NAME: &'static str = "koenderink";

    /// `(m, n, n')` of the basis functions of order `order`, in parameter order.
    pub fn basis_indices(order: usize) -> Vec<(usize, usize, usize)> {
        let mut v = Vec::new();
        for m in 0..=order {
            for n in (m..=order).step_by(2) {
                for n2 in (n..=order).step_by(2) {
                    v.push((m, n, n2));
                }
            }
        }
        v
    }

    /// All coefficients 0; `order` up to 20 (factorials stay exact in f64).
    pub fn new(order: usize, channels: usize) -> Result<Self, ParamError> {
        let cfg = |reason: String| ParamError::Config {
            model: Self::NAME.into(),
            reason,
        };
        if channels == 0 {
            return Err(cfg("a model needs at least one channel".into()));
        }
        if order > 20 {
            return Err(cfg(format!("order {order} is above the supported 20")));
        }
        let indices = Self::basis_indices(order);
        let per = indices.len();
        let mut specs = Vec::with_capacity(per * channels);
        for c in 0..channels {
            for (k, (m, n, n2)) in indices.iter().enumerate() {
                specs.push(ParamSpec::new(
                    channel_param_name(&format!("c{k}"), c, channels),
                    format!("coefficient of K(m={m}, n={n}, n'={n2}) (channel {c})"),
                    f64::NEG_INFINITY,
                    f64::INFINITY,
                    0.0,
                    true,
                ));
            }
        }
        let stride = order / 2 + 1;
        let mut radial = vec![0.0; (order + 1) * (order + 1) * stride];
        let fact = |k: usize| (1..=k).fold(1.0f64, |a, b| a * b as f64);
        for n in 0..=order {
            for m in (n % 2..=n).step_by(2) {
                for k in 0..=(n - m) / 2 {
                    let c = fact(n - k) / (fact(k) * fact((n + m) / 2 - k) * fact((n - m) / 2 - k));
                    radial[(n * (order + 1) + m) * stride + k] = if k % 2 == 0 { c } else { -c };
                }
            }
        }
        Ok(Koenderink {
            channels,
            order,
            indices,
            radial,
            params: vec![0.0; specs.len()],
            specs,
        })
    }

    /// Expansion order `N`.
    pub fn order(&self) -> usize {
        self.order
    }

    /// Basis functions per channel.
    pub fn basis_len(&self) -> usize {
        self.indices.len()
    }

    /// The unclamped basis values `K` of a pair (0 below the horizon).
    pub fn basis(&self, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        if !(l.z > 0.0 && v.z > 0.0) {
            out[..self.indices.len()].iter_mut().for_each(|x| *x = 0.0);
            return;
        }
        let ri = (1.0 - l.z.min(1.0)).sqrt();
        let ro = (1.0 - v.z.min(1.0)).sqrt();
        let c1 = cos_dphi(l, v);
        // cos(m dphi) by the Chebyshev recurrence T_{m+1} = 2 c T_m - T_{m-1}.
        let mut cos_m = [0.0; 21];
        cos_m[0] = 1.0;
        if self.order >= 1 {
            cos_m[1] = c1;
        }
        for m in 2..=self.order {
            cos_m[m] = 2.0 * c1 * cos_m[m - 1] - cos_m[m - 2];
        }
        // All R_n^m at rho_i and rho_o once, from the precomputed coefficients.
        let n1 = self.order + 1;
        let stride = self.order / 2 + 1;
        let mut pi = [0.0; 21];
        let mut po = [0.0; 21];
        pi[0] = 1.0;
        po[0] = 1.0;
        for k in 1..n1 {
            pi[k] = pi[k - 1] * ri;
            po[k] = po[k - 1] * ro;
        }
        let mut ri_tab = [0.0; 21 * 21];
        let mut ro_tab = [0.0; 21 * 21];
        for n in 0..n1 {
            for m in (n % 2..=n).step_by(2) {
                let (mut a, mut b) = (0.0, 0.0);
                for k in 0..=(n - m) / 2 {
                    let c = self.radial[(n * n1 + m) * stride + k];
                    a += c * pi[n - 2 * k];
                    b += c * po[n - 2 * k];
                }
                ri_tab[n * n1 + m] = a;
                ro_tab[n * n1 + m] = b;
            }
        }
        for (k, &(m, n, n2)) in self.indices.iter().enumerate() {
            let a = ri_tab[n * n1 + m] * ro_tab[n2 * n1 + m];
            let s = if n == n2 {
                a
            } else {
                a + ri_tab[n2 * n1 + m] * ro_tab[n * n1 + m]
            };
            out[k] = s * cos_m[m];
        }
    }
}

impl Parametric for Koenderink {
    brdf_core::param_accessors!();
    fn name(&self) -> &str {
        Self::NAME
    }
    fn eval_at(&self, p: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        let mut grad = Vec::new();
        self.value_and_grad(p, l, v, out, &mut grad, false);
    }
    fn eval_grad_at(
        &self,
        p: &[f64],
        l: &Vector3<f64>,
        v: &Vector3<f64>,
        out: &mut [f64],
        grad: &mut [f64],
    ) {
        self.value_and_grad(p, l, v, out, grad, true);
    }
}

impl Koenderink {
    fn value_and_grad(
        &self,
        p: &[f64],
        l: &Vector3<f64>,
        v: &Vector3<f64>,
        out: &mut [f64],
        grad: &mut [f64],
        with_grad: bool,
    ) {
        let per = self.indices.len();
        let np = per * self.channels;
        let mut basis = [0.0; 64];
        let mut heap = Vec::new();
        let b: &mut [f64] = if per <= 64 {
            &mut basis[..per]
        } else {
            heap.resize(per, 0.0);
            &mut heap
        };
        self.basis(l, v, b);
        if with_grad {
            grad[..self.channels * np].iter_mut().for_each(|g| *g = 0.0);
        }
        for c in 0..self.channels {
            let s: f64 = b
                .iter()
                .zip(&p[c * per..(c + 1) * per])
                .map(|(x, y)| x * y)
                .sum();
            out[c] = s.max(0.0);
            if with_grad {
                grad[c * np + c * per..c * np + (c + 1) * per].copy_from_slice(b);
            }
        }
    }
}

impl_brdf_via_params!(Koenderink);
