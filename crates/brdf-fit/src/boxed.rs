//! A model seen by the solver through other parameter boxes than its own.
//!
//! Two fits need this: a fit of data divided by a value scale moves the
//! linear parameters' boxes with the data ([`BoxedModel::scaled`], see
//! [`crate::scaling`]), and a study may fit a catalogue model in a
//! narrower box than the catalogue allows ([`BoxedModel::narrowed`], Kurt's
//! box for Lafortune's lobes). In both cases the function is the inner
//! model's: evaluation and derivatives are delegated at the wrapper's own
//! parameters, which are validated against the wrapper's boxes only (the
//! scaled boxes need not lie inside the inner ones).

use brdf_core::nalgebra::Vector3;
use brdf_core::{Brdf, DirPairs, ParamError, ParamSpec, Parametric, SharedBasis};

/// A model with its parameter boxes replaced; everything else is delegated.
#[derive(Clone)]
pub struct BoxedModel {
    inner: Box<dyn Parametric>,
    specs: Vec<ParamSpec>,
    params: Vec<f64>,
}

impl BoxedModel {
    /// Wrap `inner` with the boxes `specs` (one per parameter, same order)
    /// at the parameters `params`, each moved into its new box.
    fn with_specs(inner: Box<dyn Parametric>, specs: Vec<ParamSpec>, params: &[f64]) -> Self {
        let params = params
            .iter()
            .zip(&specs)
            .map(|(x, s)| x.clamp(s.lower, s.upper))
            .collect();
        BoxedModel {
            inner,
            specs,
            params,
        }
    }

    /// Wrap `inner`, dividing its linear parameters' boxes (and current
    /// values) by `scale`: the same function, fitted to data divided by
    /// `scale`.
    pub fn scaled(inner: Box<dyn Parametric>, scale: f64) -> Self {
        let specs: Vec<ParamSpec> = inner
            .param_specs()
            .iter()
            .map(|s| {
                let mut s = s.clone();
                if s.linear {
                    s.lower /= scale;
                    s.upper /= scale;
                    s.default /= scale;
                }
                s
            })
            .collect();
        let params: Vec<f64> = inner
            .params()
            .iter()
            .zip(&specs)
            .map(|(x, s)| if s.linear { x / scale } else { *x })
            .collect();
        Self::with_specs(inner, specs, &params)
    }

    /// Narrow the boxes of `inner`: for every `(prefix, lower, upper)`,
    /// parameters whose name is `prefix` followed by nothing or a lobe
    /// number get the box `[lower, upper]` intersected with their own (and
    /// their default moved into it). The current parameters are moved into
    /// the new box. An error if a box and its parameter's own do not meet,
    /// or a current parameter is not finite.
    pub fn narrowed(
        inner: Box<dyn Parametric>,
        boxes: &[(&str, f64, f64)],
    ) -> Result<Self, ParamError> {
        let mut specs = inner.param_specs().to_vec();
        for s in &mut specs {
            for (prefix, lo, hi) in boxes {
                let rest = s.name.strip_prefix(prefix);
                if rest.is_some_and(|r| r.chars().all(|c| c.is_ascii_digit())) {
                    narrow(inner.name(), s, *lo, *hi)?;
                }
            }
        }
        let params = inner.params().to_vec();
        let boxed = Self::with_specs(inner, specs, &params);
        brdf_core::params::validate(boxed.inner.name(), &boxed.specs, &boxed.params)?;
        Ok(boxed)
    }

    /// The wrapped model (at its own parameters, not the wrapper's).
    pub fn into_inner(self) -> Box<dyn Parametric> {
        self.inner
    }
}

/// Intersect the box of `spec` with `[lo, hi]` and move its default into
/// the result; an error (rather than a panic of `clamp`) if they do not meet.
/// A box open below stays open only where its own bound is the binding one:
/// `(0, 1]` narrowed to `[0.1, 0.1]` is `[0.1, 0.1]` (a parameter held at
/// 0.1), not the empty `(0.1, 0.1]`.
fn narrow(model: &str, spec: &mut ParamSpec, lo: f64, hi: f64) -> Result<(), ParamError> {
    let (lower, upper) = (spec.lower.max(lo), spec.upper.min(hi));
    let lower_open = spec.lower_open && spec.lower >= lo;
    if lower.is_nan() || upper.is_nan() || lower > upper || (lower_open && lower == upper) {
        return Err(ParamError::Config {
            model: model.to_string(),
            reason: format!(
                "the box [{lo}, {hi}] does not meet the box {} of `{}`",
                spec.box_string(),
                spec.name
            ),
        });
    }
    spec.lower = lower;
    spec.lower_open = lower_open;
    spec.upper = upper;
    spec.default = spec.default.clamp(lower, upper);
    Ok(())
}

impl Brdf for BoxedModel {
    fn channels(&self) -> usize {
        self.inner.channels()
    }
    fn eval(&self, l: &Vector3<f64>, v: &Vector3<f64>, out: &mut [f64]) {
        self.inner.eval_at(&self.params, l, v, out)
    }
    fn eval_pairs(&self, pairs: &DirPairs, out: &mut [f64]) {
        self.inner.eval_batch_at(&self.params, pairs, out)
    }
}

impl Parametric for BoxedModel {
    fn name(&self) -> &str {
        self.inner.name()
    }
    fn param_specs(&self) -> &[ParamSpec] {
        &self.specs
    }
    fn params(&self) -> &[f64] {
        &self.params
    }
    fn set_params(&mut self, p: &[f64]) -> Result<(), ParamError> {
        brdf_core::params::validate(self.inner.name(), &self.specs, p)?;
        self.params = p.to_vec();
        Ok(())
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
    fn data_table(&self) -> Option<(&[f64], &[f64])> {
        self.inner.data_table()
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
    use brdf_models::Ward;

    /// Ward with `kd = 0.5`, `ks = 0.25` (boxes `[0, 1]`), `a = 0.2` (box `(0, 0.5]`).
    fn ward() -> Box<dyn Parametric> {
        Box::new(Ward::new(&[0.5], &[0.25], &[0.2]).unwrap())
    }

    fn boxes(m: &dyn Parametric) -> Vec<(f64, f64)> {
        m.param_specs().iter().map(|s| (s.lower, s.upper)).collect()
    }

    #[test]
    fn scaled_divides_only_the_linear_boxes_and_values() {
        let m = BoxedModel::scaled(ward(), 4.0);
        assert_eq!(boxes(&m), [(0.0, 0.25), (0.0, 0.25), (0.0, 0.5)]);
        assert_eq!(m.params(), [0.125, 0.0625, 0.2]);
        // Ward is linear in (kd, ks): at the divided values the wrapper is
        // the model divided by 4.
        let (l, v) = (
            Vector3::new(0.3, 0.1, 0.9).normalize(),
            Vector3::new(-0.2, 0.4, 0.8).normalize(),
        );
        let (mut a, mut b) = ([0.0], [0.0]);
        m.eval(&l, &v, &mut a);
        ward().eval(&l, &v, &mut b);
        assert!((a[0] - b[0] / 4.0).abs() <= 1e-15 * b[0], "{a:?} {b:?}");
        // The scaled values are valid in the wrapper's box, not the model's.
        let mut m = m;
        assert!(m.set_params(&[0.25, 0.25, 0.3]).is_ok());
        assert!(m.set_params(&[0.5, 0.25, 0.3]).is_err());
        assert_eq!(m.into_inner().params(), [0.5, 0.25, 0.2]);
    }

    #[test]
    fn narrowed_matches_prefix_and_lobe_numbers_and_clamps() {
        let m = BoxedModel::narrowed(ward(), &[("ks", 0.0, 0.1), ("k", 0.0, 0.01)]).unwrap();
        // `k` is not `kd` or `ks` (a prefix followed by letters).
        assert_eq!(boxes(&m), [(0.0, 1.0), (0.0, 0.1), (0.0, 0.5)]);
        assert_eq!(m.params(), [0.5, 0.1, 0.2]);
        assert_eq!(
            m.param_specs()[1].default.clamp(0.0, 0.1),
            m.param_specs()[1].default
        );
    }

    /// Ward's `a` has the box `(0, 0.5]`: held at 0.1 it is `[0.1, 0.1]`
    /// (closed: the held value is in it); narrowed to `[0, 0.3]` its own
    /// open bound still binds; `[0, 0]` meets `(0, 0.5]` nowhere.
    #[test]
    fn narrowing_an_open_bound_closes_it_where_the_new_bound_binds() {
        let m = BoxedModel::narrowed(ward(), &[("a", 0.1, 0.1)]).unwrap();
        let a = &m.param_specs()[2];
        assert_eq!((a.lower, a.upper, a.lower_open), (0.1, 0.1, false));
        assert_eq!(m.params()[2], 0.1);
        let m = BoxedModel::narrowed(ward(), &[("a", 0.0, 0.3)]).unwrap();
        let a = &m.param_specs()[2];
        assert_eq!((a.lower, a.upper, a.lower_open), (0.0, 0.3, true));
        assert!(BoxedModel::narrowed(ward(), &[("a", 0.0, 0.0)]).is_err());
    }

    #[test]
    fn narrowed_to_a_box_outside_the_own_is_an_error() {
        let e = BoxedModel::narrowed(ward(), &[("a", 0.6, 0.9)]).err();
        assert!(
            matches!(&e, Some(ParamError::Config { reason, .. }) if reason.contains("`a`")),
            "{e:?}"
        );
    }
}
