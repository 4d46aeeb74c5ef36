//! The default finite-difference derivatives of `Parametric`, against a
//! model with known derivatives, inside the box and at its ends.

use brdf_core::params::validate;
use brdf_core::{ParamError, ParamSpec, Parametric, impl_brdf_via_params};
use nalgebra::Vector3;

/// `f = a exp(b cos_i) + c^3` on one channel; `b` in `(0, 2]`, `c` in `[0, 1]`.
#[derive(Clone)]
struct Toy {
    channels: usize,
    specs: Vec<ParamSpec>,
    params: Vec<f64>,
}

impl Toy {
    fn new() -> Self {
        Toy {
            channels: 1,
            specs: vec![
                ParamSpec::new("a", "scale", 0.0, 10.0, 1.0, true),
                ParamSpec::new("b", "rate", 0.0, 2.0, 1.0, false).open_below(),
                ParamSpec::new("c", "offset", 0.0, 1.0, 0.5, false),
            ],
            params: vec![1.0, 1.0, 0.5],
        }
    }
}

impl Parametric for Toy {
    fn name(&self) -> &str {
        "toy"
    }
    fn param_specs(&self) -> &[ParamSpec] {
        &self.specs
    }
    fn params(&self) -> &[f64] {
        &self.params
    }
    fn set_params(&mut self, p: &[f64]) -> Result<(), ParamError> {
        validate("toy", &self.specs, p)?;
        self.params.copy_from_slice(p);
        Ok(())
    }
    fn eval_at(&self, p: &[f64], l: &Vector3<f64>, _v: &Vector3<f64>, out: &mut [f64]) {
        assert!(
            p[1] > 0.0 && p[2] >= 0.0 && p[2] <= 1.0,
            "evaluated outside the box: {p:?}"
        );
        out[0] = p[0] * (p[1] * l.z).exp() + p[2].powi(3);
    }
    fn clone_box(&self) -> Box<dyn Parametric> {
        Box::new(self.clone())
    }
}
impl_brdf_via_params!(Toy);

fn exact(p: &[f64], cz: f64) -> [f64; 3] {
    let e = (p[1] * cz).exp();
    [e, p[0] * cz * e, 3.0 * p[2] * p[2]]
}

#[test]
fn default_gradient_matches_the_analytic_one_inside_and_at_the_bounds() {
    let m = Toy::new();
    let l = Vector3::new(0.6, 0.0, 0.8);
    // Inside, at c's lower bound (one-sided upward), at c's upper bound
    // (one-sided downward), and b next to its open lower end.
    for p in [
        [1.0, 1.0, 0.5],
        [2.0, 0.5, 0.0],
        [0.3, 1.7, 1.0],
        [1.0, 1e-7, 0.4],
    ] {
        let (mut out, mut g) = ([0.0], [0.0; 3]);
        m.eval_grad_at(&p, &l, &Vector3::z(), &mut out, &mut g);
        let e = exact(&p, l.z);
        for k in 0..3 {
            assert!(
                (g[k] - e[k]).abs() < 1e-8 * (1.0 + e[k].abs()),
                "p {p:?} k {k}: {} vs {}",
                g[k],
                e[k]
            );
        }
        assert_eq!(out[0], p[0] * (p[1] * l.z).exp() + p[2].powi(3));
    }
}

#[test]
fn batch_defaults_use_channel_major_layout() {
    let m = Toy::new();
    let mut pairs = brdf_core::DirPairs::default();
    pairs.push(&Vector3::z(), &Vector3::z());
    pairs.push(&Vector3::new(0.6, 0.0, 0.8), &Vector3::z());
    let p = [1.0, 1.0, 0.5];
    let (mut out, mut jac) = (vec![0.0; 2], vec![0.0; 6]);
    m.eval_grad_batch_at(&p, &pairs, &mut out, &mut jac);
    let e = exact(&p, 0.8);
    for k in 0..3 {
        assert!((jac[3 + k] - e[k]).abs() < 1e-8 * (1.0 + e[k].abs()));
    }
    let mut vals = vec![0.0; 2];
    m.eval_batch_at(&p, &pairs, &mut vals);
    assert_eq!(vals, out);
}
