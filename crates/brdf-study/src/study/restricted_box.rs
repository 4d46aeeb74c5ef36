//! A catalogue model fitted in a narrower parameter box than its own: Kurt
//! fitted Lafortune's lobe with `Cxy` in `[-1, 0]` and `Cz` in `[0, 1]`
//! (every value of his Appendix 3 lies there), while the catalogue allows
//! `[-1, 1]` for both. The wrapper changes only the boxes the solver sees
//! (and validates against); evaluation and derivatives are the inner
//! model's, so a fit in the narrow box is the same model, constrained.

use brdf_core::{Brdf, DirPairs, ParamError, ParamSpec, Parametric, SharedBasis};
use nalgebra::Vector3;

/// A model with some parameter boxes narrowed.
#[derive(Clone)]
pub struct Restricted {
    inner: Box<dyn Parametric>,
    specs: Vec<ParamSpec>,
}

impl Restricted {
    /// Narrow the boxes of `inner`: for every `(prefix, lower, upper)`,
    /// parameters whose name is `prefix` followed by nothing or a lobe number
    /// get the box `[lower, upper]` (intersected with their own). The
    /// current parameters are moved into the new box.
    pub fn new(
        mut inner: Box<dyn Parametric>,
        boxes: &[(&str, f64, f64)],
    ) -> Result<Self, ParamError> {
        let mut specs = inner.param_specs().to_vec();
        for s in &mut specs {
            for (prefix, lo, hi) in boxes {
                let rest = s.name.strip_prefix(prefix);
                if rest.is_some_and(|r| r.chars().all(|c| c.is_ascii_digit())) {
                    s.lower = s.lower.max(*lo);
                    s.upper = s.upper.min(*hi);
                    s.default = s.default.clamp(s.lower, s.upper);
                }
            }
        }
        let p: Vec<f64> = inner
            .params()
            .iter()
            .zip(&specs)
            .map(|(v, s)| v.clamp(s.lower, s.upper))
            .collect();
        inner.set_params(&p)?;
        Ok(Restricted { inner, specs })
    }

    /// Kurt's box for Lafortune's lobes: `Cxy` in `[-1, 0]`, `Cz` in `[0, 1]`.
    pub fn kurt_lafortune(inner: Box<dyn Parametric>) -> Result<Self, ParamError> {
        Self::new(inner, &[("cxy", -1.0, 0.0), ("cz", 0.0, 1.0)])
    }
}

impl Brdf for Restricted {
    fn channels(&self) -> usize {
        self.inner.channels()
    }
    fn eval(&self, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        self.inner.eval(l, v, out)
    }
}

impl Parametric for Restricted {
    fn name(&self) -> &str {
        self.inner.name()
    }
    fn param_specs(&self) -> &[ParamSpec] {
        &self.specs
    }
    fn params(&self) -> &[f64] {
        self.inner.params()
    }
    fn set_params(&mut self, p: &[f64]) -> Result<(), ParamError> {
        brdf_core::params::validate(self.inner.name(), &self.specs, p)?;
        self.inner.set_params(p)
    }
    fn eval_at(&self, p: &[f64], l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        self.inner.eval_at(p, l, v, out)
    }
    fn eval_grad_at(
        &self,
        p: &[f64],
        l: &Vector3<f64>,
        v: &Vector3<f64>,
        out: &mut [f64],
        grad: &mut [f64],
    ) {
        self.inner.eval_grad_at(p, l, v, out, grad)
    }
    fn eval_batch_at(&self, p: &[f64], pairs: &DirPairs, out: &mut [f64]) {
        self.inner.eval_batch_at(p, pairs, out)
    }
    fn eval_grad_batch_at(&self, p: &[f64], pairs: &DirPairs, out: &mut [f64], jac: &mut [f64]) {
        self.inner.eval_grad_batch_at(p, pairs, out, jac)
    }
    fn shared_basis(&self) -> Option<&dyn SharedBasis> {
        self.inner.shared_basis()
    }
    fn clone_box(&self) -> Box<dyn Parametric> {
        Box::new(self.clone())
    }
    fn is_reciprocal(&self) -> bool {
        self.inner.is_reciprocal()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use brdf_models::{ModelConfig, build};

    #[test]
    fn kurt_box_narrows_only_the_axis_weights_and_evaluates_the_same() {
        let inner = build("lafortune", &ModelConfig::default()).unwrap();
        let m = Restricted::kurt_lafortune(inner.clone_box()).unwrap();
        for s in m.param_specs() {
            let (lo, hi) = match s.name.as_str() {
                "cxy1" => (-1.0, 0.0),
                "cz1" => (0.0, 1.0),
                _ => {
                    let o = inner
                        .param_specs()
                        .iter()
                        .find(|o| o.name == s.name)
                        .unwrap();
                    (o.lower, o.upper)
                }
            };
            assert_eq!((s.lower, s.upper), (lo, hi), "{}", s.name);
        }
        let (l, v) = (
            Vector3::new(0.3, 0.1, 0.9).normalize(),
            Vector3::new(-0.2, 0.4, 0.8).normalize(),
        );
        let (mut a, mut b) = ([0.0], [0.0]);
        m.eval(&l, &v, &mut a);
        inner.eval(&l, &v, &mut b);
        assert_eq!(a, b);
        // A back-scattering lobe (Cxy > 0) is outside Kurt's box.
        let mut m = m;
        let mut p = m.params().to_vec();
        let k = m
            .param_specs()
            .iter()
            .position(|s| s.name == "cxy1")
            .unwrap();
        p[k] = 0.5;
        assert!(m.set_params(&p).is_err());
    }
}
