//! The expected bias of a degree-p polynomial fit against a "true" model
//! (Kurt 2007, eq. 7.8-7.10, in the response-surface form of Box & Draper,
//! "Empirical Model-Building and Response Surfaces", 1987, ch. 13).
//!
//! With the design `X` of the degree-p model at the sample directions and
//! the true values `eta` there, the least-squares coefficients have the
//! expectation `E[b] = (X^T X)^-1 X^T eta` (the noise averages out), so the
//! expected prediction at a direction pair `x` is `x_p(x)^T E[b]` and its
//! bias is
//!
//! `B(x) = x_p(x)^T (X^T X)^-1 X^T eta - eta(x)`.
//!
//! When the true model is itself a polynomial with extra terms `X2 beta2`
//! this is the classical `x_p^T A beta2 - x_2^T beta2` with the alias matrix
//! `A = (X^T X)^-1 X^T X2`. The maximum expected bias is `max_x |B(x)|` over
//! the sample space (the evaluation pairs); the RMS over them is reported
//! too. `(X^T X)^-1 X^T eta` is computed by pivoted QR, not by inverting.

use brdf_core::{DirPairs, Parametric};
use brdf_models::KurtPolynomial;
use brdf_models::kurt_polynomial::{Pca, PolyVariant};
use brdf_solve::{LstsqMethod, lstsq};
use faer::Mat;
use serde::Serialize;

use crate::StudyError;

/// Bias of a degree-p fit.
#[derive(Clone, Debug, Serialize)]
pub struct Bias {
    /// Degree `p`.
    pub degree: usize,
    /// `max_x |B(x)|` over the evaluation pairs (channel 0).
    pub max_abs: f64,
    /// RMS of `B(x)` over the evaluation pairs.
    pub rms: f64,
    /// Index of the evaluation pair where the maximum is reached.
    pub at: usize,
}

/// Expected bias of Kurt's isotropic polynomial of `degree` fitted at
/// `design` to the one-channel `truth`, evaluated over `space`.
pub fn expected_bias(
    truth: &dyn Parametric,
    degree: usize,
    design: &DirPairs,
    space: &DirPairs,
) -> Result<Bias, StudyError> {
    if truth.channels() != 1 {
        return Err(StudyError::Usage(
            "the bias analysis takes a one-channel true model".into(),
        ));
    }
    let pca = Pca::from_pairs(PolyVariant::Isotropic, design)?;
    let poly = KurtPolynomial::new(PolyVariant::Isotropic, degree, 1, pca)?;
    let k = poly.coefficients_per_channel();
    let n = design.len();
    if n <= k {
        return Err(StudyError::Usage(format!(
            "{n} design pairs for {k} coefficients"
        )));
    }
    let mut row = vec![0.0; k];
    let mut x = Mat::<f64>::zeros(n, k);
    let mut eta = Mat::<f64>::zeros(n, 1);
    let mut f = [0.0];
    for j in 0..n {
        let (l, v) = (design.l(j), design.v(j));
        poly.design_row(&l, &v, &mut row);
        for c in 0..k {
            x[(j, c)] = row[c];
        }
        truth.eval(&l, &v, &mut f);
        eta[(j, 0)] = f[0];
    }
    let b = lstsq(x.as_ref(), eta.as_ref(), None, LstsqMethod::PivotedQr)?;
    let (mut max_abs, mut at, mut ss) = (0.0f64, 0, 0.0);
    for j in 0..space.len() {
        let (l, v) = (space.l(j), space.v(j));
        poly.design_row(&l, &v, &mut row);
        let pred: f64 = (0..k).map(|c| row[c] * b.x[(c, 0)]).sum();
        truth.eval(&l, &v, &mut f);
        let bias = pred - f[0];
        ss += bias * bias;
        if bias.abs() > max_abs {
            max_abs = bias.abs();
            at = j;
        }
    }
    Ok(Bias {
        degree,
        max_abs,
        rms: (ss / space.len().max(1) as f64).sqrt(),
        at,
    })
}
