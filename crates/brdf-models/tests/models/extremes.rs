//! Analytic parameter derivatives at the extremes fitting reaches
//! (spec/fitting.md): exponents at their upper bound `1e6` and half of it,
//! roughness `1e-3` and `1e-4` (near the open lower bound 0). The direction
//! pairs sit where such a lobe is neither 0 nor at its peak: `V` at angle
//! `alpha` from the mirror direction with `cos alpha = 1 - 1/n` (mirror
//! lobes), the half vector at `tan delta = m` (facet lobes), and the same
//! for the other family (where the lobe underflows to 0 and the derivatives
//! must be 0, not NaN). Compared with central differences whose step is
//! relative to the parameter (`1e-6 |p|`, one-sided second order at a
//! bound): the library's `fd_step` is absolute below 1, far too coarse
//! for a roughness of `1e-3`.
//!
//! Lafortune's lobe is taken at `-Cxy = Cz = 1` (a Phong lobe, so it is not
//! 0 at the test pairs); there the normaliser `max(|Cxy|, |Cz|)` has a kink
//! (two weights tie), so the axis-weight derivatives are one-sided and only
//! `ks`, `kd` and the exponent are compared.

use brdf_core::Parametric;
use brdf_models::{ModelConfig, build};
use nalgebra::{Rotation3, Unit, Vector3};

fn dir(theta: f64, phi: f64) -> Vector3<f64> {
    Vector3::new(
        theta.sin() * phi.cos(),
        theta.sin() * phi.sin(),
        theta.cos(),
    )
}

/// `L` at 40 deg and `V` at angle `alpha` from `L`'s mirror direction.
fn mirror_pair(alpha: f64) -> (Vector3<f64>, Vector3<f64>) {
    let l = dir(40f64.to_radians(), 0.4);
    let r = Vector3::new(-l.x, -l.y, l.z);
    let axis = Unit::new_normalize(r.cross(&Vector3::z()));
    (l, Rotation3::from_axis_angle(&axis, alpha) * r)
}

/// The half vector at `delta` from the normal, `L` and `V` at 30 deg from it.
fn half_pair(delta: f64) -> (Vector3<f64>, Vector3<f64>) {
    let h = dir(delta, 1.1);
    let axis = Unit::new_normalize(h.cross(&Vector3::x()));
    let l = Rotation3::from_axis_angle(&axis, 30f64.to_radians()) * h;
    let v = 2.0 * l.dot(&h) * h - l;
    (l, v)
}

/// `(model, lobes, parameter overrides by name)`: every other parameter at
/// its default.
/// `(model, lobes, parameter overrides)`.
type Case = (&'static str, usize, Vec<(&'static str, f64)>);

fn cases() -> Vec<Case> {
    let mut v = Vec::new();
    for n in [1e6, 5e5] {
        v.push(("phong", 1, vec![("n", n)]));
        v.push(("blinn-phong", 1, vec![("n", n)]));
        v.push(("phong-fresnel", 1, vec![("ns", n)]));
        v.push(("as-paint", 1, vec![("ns", n)]));
        v.push(("clear-coat", 1, vec![("ns", n)]));
        v.push(("ashikhmin-shirley", 1, vec![("n", n)]));
        v.push((
            "ashikhmin-shirley-coupled",
            1,
            vec![("n", n), ("f0", 0.999)],
        ));
        v.push(("ashikhmin-shirley-aniso", 1, vec![("nu", n), ("nv", 1e3)]));
        v.push((
            "lafortune",
            1,
            vec![("cxy1", -1.0), ("cz1", 1.0), ("n1", n)],
        ));
        v.push((
            "lafortune-aniso",
            2,
            vec![
                ("cx1", -1.0),
                ("cy1", -1.0),
                ("cz1", 1.0),
                ("n1", n),
                ("n2", 3.0),
            ],
        ));
    }
    for m in [1e-3, 1e-4] {
        v.push(("ward", 1, vec![("a", m)]));
        v.push(("ward-duer", 1, vec![("a", m)]));
        v.push(("ward-aniso", 1, vec![("ax", m), ("ay", 10.0 * m)]));
        v.push(("torrance-sparrow", 1, vec![("m", m)]));
        v.push(("cook-torrance", 1, vec![("m1", m)]));
        v.push((
            "cook-torrance",
            2,
            vec![("m1", m), ("m2", 0.3), ("f0_2", 0.999)],
        ));
        v.push(("oren-nayar", 1, vec![("sigma", m)]));
    }
    v
}

/// Finite differences with step `1e-6 |p_k|`, inside the box.
fn relative_fd(
    model: &dyn Parametric,
    p: &[f64],
    l: &Vector3<f64>,
    v: &Vector3<f64>,
    fd: &mut [f64],
) {
    let specs = model.param_specs();
    let at = |k: usize, d: f64| {
        let mut q = p.to_vec();
        q[k] += d;
        let mut f = [0.0];
        model.eval_at(&q, l, v, &mut f);
        f[0]
    };
    for k in 0..p.len() {
        let h = 1e-6 * p[k].abs().max(1e-3);
        let s = &specs[k];
        fd[k] = if p[k] + h > s.upper {
            (3.0 * at(k, 0.0) - 4.0 * at(k, -h) + at(k, -2.0 * h)) / (2.0 * h)
        } else if p[k] - h <= s.lower {
            (-3.0 * at(k, 0.0) + 4.0 * at(k, h) - at(k, 2.0 * h)) / (2.0 * h)
        } else {
            (at(k, h) - at(k, -h)) / (2.0 * h)
        };
    }
}

#[test]
fn derivatives_at_extreme_exponents_and_roughness_match_finite_differences() {
    for (name, lobes, overrides) in cases() {
        let config = ModelConfig {
            lobes,
            ..ModelConfig::default()
        };
        let mut model = build(name, &config).unwrap();
        let specs = model.param_specs().to_vec();
        let mut p = model.params().to_vec();
        for (pn, val) in &overrides {
            let k = specs
                .iter()
                .position(|s| s.name == *pn)
                .unwrap_or_else(|| panic!("{name} has no parameter {pn}"));
            p[k] = *val;
        }
        model.set_params(&p).unwrap();
        // The lobe's scale: exponent n or roughness m of the first override.
        let x = overrides[0].1;
        let (alpha, delta) = if x > 1.0 {
            ((1.0 - 1.0 / x).acos(), (1.0 - 1.0 / x).acos())
        } else {
            (x, (1.5 * x).atan())
        };
        let pairs = [
            mirror_pair(alpha),
            half_pair(delta),
            mirror_pair(2.0 * alpha),
            half_pair(0.0),
            mirror_pair(0.3),
        ];
        let np = p.len();
        for (l, v) in pairs {
            let mut f = [0.0];
            let mut g = vec![0.0; np];
            let mut fd = vec![0.0; np];
            model.eval_grad_at(&p, &l, &v, &mut f, &mut g);
            relative_fd(model.as_ref(), &p, &l, &v, &mut fd);
            assert!(
                f[0].is_finite() && f[0] >= 0.0,
                "{name} {overrides:?}: f = {}",
                f[0]
            );
            for k in 0..np {
                assert!(
                    g[k].is_finite(),
                    "{name} {overrides:?} d/d{} = {}",
                    specs[k].name,
                    g[k]
                );
                if name.starts_with("lafortune") && specs[k].name.starts_with('c') {
                    continue;
                }
                // Relative 1e-4, plus the difference quotient's rounding
                // (about 1e4 eps f / h, h = 1e-6 |p|).
                let h = 1e-6 * p[k].abs().max(1e-3);
                let tol = 1e-4 * g[k].abs().max(fd[k].abs()) + 1e-7 + 1e-12 * f[0] / h;
                assert!(
                    (g[k] - fd[k]).abs() <= tol,
                    "{name} {overrides:?} at l {l:?} v {v:?}: d/d{} analytic {} vs fd {} (f = {})",
                    specs[k].name,
                    g[k],
                    fd[k],
                    f[0]
                );
            }
        }
    }
}
